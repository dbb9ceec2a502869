/* Texture lookups with glTF's samplers: nearest or bilinear filtering of RGBA8 texels, decoded to
 * linear before filtering (sRGB colour or linear data), wrapped by repeat, clamp to edge or
 * mirrored repeat per axis. Plain C for OpenCL C 1.2 and host C++.
 *
 * Texel centres lie at ((i + 0.5) / width, (j + 0.5) / height); (0, 0) is the top-left corner of
 * the first row. The sRGB decode is a table (IEC 61966-2-1, computed in double precision and
 * rounded to float), so host and device decode identically and no pow runs per lookup. */
#ifndef COHORT_TEXTURE_H
#define COHORT_TEXTURE_H

#include "common/core/types.h"
#include "common/core/vec.h"

#if !defined(__OPENCL_VERSION__) && !defined(__CUDACC__)
using std::floor;
#endif
CO_CONSTANT_DATA float co_srgb_to_linear[256] = {
    0.0f, 0.000303526991f, 0.000607053982f, 0.000910580973f, 0.00121410796f, 0.00151763496f,
    0.00182116195f, 0.00212468882f, 0.00242821593f, 0.0027317428f, 0.00303526991f, 0.00334653584f,
    0.00367650739f, 0.00402471703f, 0.00439144205f, 0.00477695325f, 0.00518151652f, 0.00560539169f,
    0.00604883302f, 0.00651209056f, 0.00699541019f, 0.00749903219f, 0.00802319311f, 0.00856812578f,
    0.00913405884f, 0.00972121768f, 0.010329823f, 0.0109600937f, 0.0116122449f, 0.012286488f,
    0.0129830325f, 0.0137020834f, 0.0144438436f, 0.0152085144f, 0.0159962941f, 0.0168073755f,
    0.0176419541f, 0.01850022f, 0.0193823613f, 0.0202885624f, 0.0212190095f, 0.0221738853f,
    0.0231533665f, 0.0241576321f, 0.0251868591f, 0.0262412224f, 0.0273208916f, 0.02842604f,
    0.0295568351f, 0.0307134446f, 0.0318960324f, 0.0331047662f, 0.0343398079f, 0.0356013142f,
    0.0368894488f, 0.0382043719f, 0.0395462364f, 0.0409151986f, 0.0423114114f, 0.043735031f,
    0.045186203f, 0.0466650873f, 0.0481718257f, 0.0497065671f, 0.0512694567f, 0.0528606474f,
    0.054480277f, 0.0561284907f, 0.0578054301f, 0.0595112368f, 0.0612460524f, 0.0630100146f,
    0.064803265f, 0.0666259378f, 0.0684781671f, 0.0703600943f, 0.0722718537f, 0.0742135718f,
    0.0761853829f, 0.078187421f, 0.0802198201f, 0.0822827071f, 0.0843762085f, 0.0865004584f,
    0.0886555836f, 0.0908417106f, 0.0930589661f, 0.0953074694f, 0.097587347f, 0.0998987257f,
    0.102241732f, 0.104616486f, 0.107023105f, 0.10946171f, 0.111932427f, 0.114435375f,
    0.116970666f, 0.119538426f, 0.122138776f, 0.124771819f, 0.127437681f, 0.130136475f,
    0.13286832f, 0.135633335f, 0.138431609f, 0.141263291f, 0.144128472f, 0.147027269f,
    0.149959788f, 0.152926147f, 0.155926466f, 0.158960834f, 0.162029371f, 0.165132195f,
    0.168269396f, 0.171441108f, 0.174647406f, 0.177888423f, 0.18116425f, 0.18447499f,
    0.187820777f, 0.191201687f, 0.194617838f, 0.198069319f, 0.20155625f, 0.205078736f,
    0.208636865f, 0.212230757f, 0.215860501f, 0.219526201f, 0.223227963f, 0.226965874f,
    0.230740055f, 0.23455058f, 0.238397568f, 0.242281124f, 0.246201321f, 0.25015828f,
    0.254152089f, 0.258182853f, 0.262250662f, 0.266355604f, 0.270497799f, 0.274677306f,
    0.278894275f, 0.283148736f, 0.287440836f, 0.291770637f, 0.296138257f, 0.300543785f,
    0.304987311f, 0.309468925f, 0.313988715f, 0.318546772f, 0.323143214f, 0.327778101f,
    0.332451522f, 0.337163627f, 0.341914415f, 0.346704066f, 0.351532608f, 0.356400132f,
    0.361306787f, 0.366252601f, 0.371237695f, 0.376262128f, 0.38132602f, 0.386429429f,
    0.391572475f, 0.396755219f, 0.401977777f, 0.407240212f, 0.412542611f, 0.417885065f,
    0.423267663f, 0.428690493f, 0.434153646f, 0.439657182f, 0.445201188f, 0.450785786f,
    0.456411034f, 0.462076992f, 0.467783809f, 0.473531485f, 0.479320168f, 0.48514995f,
    0.491020858f, 0.496932983f, 0.502886474f, 0.50888133f, 0.514917672f, 0.520995557f,
    0.527115107f, 0.533276379f, 0.539479494f, 0.545724452f, 0.55201143f, 0.558340371f,
    0.564711511f, 0.571124852f, 0.577580452f, 0.584078431f, 0.590618849f, 0.597201765f,
    0.603827357f, 0.610495567f, 0.617206573f, 0.623960376f, 0.630757153f, 0.637596846f,
    0.644479692f, 0.651405632f, 0.658374846f, 0.665387273f, 0.672443151f, 0.679542482f,
    0.686685324f, 0.693871737f, 0.701101899f, 0.708375752f, 0.715693474f, 0.723055124f,
    0.730460763f, 0.73791039f, 0.745404184f, 0.752942204f, 0.760524511f, 0.768151164f,
    0.775822222f, 0.783537805f, 0.791297913f, 0.799102724f, 0.806952238f, 0.814846575f,
    0.822785735f, 0.830769897f, 0.838799f, 0.846873224f, 0.854992628f, 0.863157213f,
    0.871367097f, 0.8796224f, 0.887923121f, 0.896269381f, 0.904661179f, 0.913098633f,
    0.921581864f, 0.930110872f, 0.938685715f, 0.947306514f, 0.955973327f, 0.964686275f,
    0.973445296f, 0.982250571f, 0.991102099f, 1.0f,
};

/* One texel's channels in linear terms: colour textures (base colour, emission) are sRGB-encoded,
 * data textures (metallic-roughness, normals) are stored linearly, so they divide by 255. */
CO_INLINE co_vec3 texel_linear(const CO_GLOBAL uint32_t* texels, uint32_t index, uint32_t sampler) {
  uint32_t t = texels[index];
  if (sampler & TEX_DATA)
    return v3((float)(t & 255u) * (1.0f / 255.0f), (float)((t >> 8) & 255u) * (1.0f / 255.0f),
              (float)((t >> 16) & 255u) * (1.0f / 255.0f));
  return v3(co_srgb_to_linear[t & 255u], co_srgb_to_linear[(t >> 8) & 255u], co_srgb_to_linear[(t >> 16) & 255u]);
}

/* Coordinate in [0, 1) for repeat wrapping; a non-finite or huge coordinate maps to 0. */
CO_INLINE float texture_wrap(float u) {
  if (!(u > -1e7f && u < 1e7f)) return 0.0f;
  float f = u - floor(u);
  return f < 1.0f ? f : 0.0f; /* u - floor(u) rounds to 1 for tiny negative u */
}

/* Coordinate in [0, 1] for a wrap mode: repeat as above, clamp to the edge, or mirrored repeat
 * (odd periods run backwards). Clamp and mirror then clamp their texel indices to the edge, which
 * is what OpenGL's and Mitsuba's integer wrapping gives for the same coordinate. */
CO_INLINE float texture_wrap_mode(float u, uint32_t mode) {
  if (mode == TEX_WRAP_REPEAT) return texture_wrap(u);
  if (!(u > -1e7f && u < 1e7f)) return 0.0f;
  if (mode == TEX_WRAP_CLAMP) return fmin(fmax(u, 0.0f), 1.0f);
  float f = u - 2.0f * floor(0.5f * u); /* [0, 2] */
  return f <= 1.0f ? f : fmax(2.0f - f, 0.0f);
}

/* Texel index in [0, n) for a position i in texels (rounded down) that may lie one beyond either end. */
CO_INLINE uint32_t texel_index(int32_t i, uint32_t n, uint32_t mode) {
  if (mode == TEX_WRAP_REPEAT) return i < 0 ? n - 1u : ((uint32_t)i >= n ? (uint32_t)i - n : (uint32_t)i);
  return i < 0 ? 0u : ((uint32_t)i >= n ? n - 1u : (uint32_t)i);
}

#ifdef COHORT_FEATURE_TEXTURE_TRANSFORM
/* (u, v) through the descriptor's KHR_texture_transform, where it has one. */
CO_INLINE void texture_transform_uv(const CO_GLOBAL TextureDesc* descs, uint32_t sampler, float* u, float* v) {
  if (!(sampler & TEX_TRANSFORM)) return;
  TextureTransform t = *(const CO_GLOBAL TextureTransform*)&descs[tex_transform_entry(sampler)];
  float tu = t.a * *u + t.b * *v + t.c;
  float tv = t.d * *u + t.e * *v + t.f;
  *u = tu;
  *v = tv;
}
#endif

/* Where a lookup of texture `index` at (u, v) reads: one texel (nearest) or four with their bilinear
 * weights, each axis wrapped by its own mode (after the slot's texture transform, with
 * COHORT_FEATURE_TEXTURE_TRANSFORM). The colour (texture_sample) and the alpha (alpha.h) lookups
 * share it, so they filter and wrap alike. */
typedef struct TexelFootprint {
  uint32_t row0, row1, x0, x1; /* nearest: the texel is row0 + x0 */
  float tx, ty;
  int nearest;
  uint32_t sampler;
} TexelFootprint;

CO_INLINE TexelFootprint texture_footprint(const CO_GLOBAL TextureDesc* descs, int32_t index, float u, float v) {
  TextureDesc d = descs[index];
  TexelFootprint f;
  f.sampler = d.sampler;
#ifdef COHORT_FEATURE_TEXTURE_TRANSFORM
  texture_transform_uv(descs, d.sampler, &u, &v);
#endif
  uint32_t wrap_s = tex_wrap_s(d.sampler), wrap_t = tex_wrap_t(d.sampler);
  float x = texture_wrap_mode(u, wrap_s) * (float)d.width;
  float y = texture_wrap_mode(v, wrap_t) * (float)d.height;
  f.nearest = (d.sampler & TEX_NEAREST) != 0u;
  if (f.nearest) {
    /* x in [0, width]: width itself (u = 1 when clamped or mirrored, or rounding) is the last column */
    f.x0 = co_umin((uint32_t)x, d.width - 1u);
    f.row0 = d.offset + co_umin((uint32_t)y, d.height - 1u) * d.width;
    f.x1 = f.x0;
    f.row1 = f.row0;
    f.tx = f.ty = 0.0f;
    return f;
  }
  x = x - 0.5f;
  y = y - 0.5f;
  float fx = floor(x), fy = floor(y);
  f.tx = x - fx;
  f.ty = y - fy;
  /* fx in [-1, width]: the neighbours beyond the edges wrap, or clamp to the edge */
  int32_t ix = (int32_t)fx, iy = (int32_t)fy;
  f.x0 = texel_index(ix, d.width, wrap_s);
  f.x1 = texel_index(ix + 1, d.width, wrap_s);
  f.row0 = d.offset + texel_index(iy, d.height, wrap_t) * d.width;
  f.row1 = d.offset + texel_index(iy + 1, d.height, wrap_t) * d.width;
  return f;
}

/* Linear RGB of texture `index` at (u, v) with its sampler: nearest texel or bilinear filtering. */
CO_INLINE co_vec3 texture_sample(const CO_GLOBAL TextureDesc* descs, const CO_GLOBAL uint32_t* texels, int32_t index,
                                 float u, float v) {
  TexelFootprint f = texture_footprint(descs, index, u, v);
  if (f.nearest) return texel_linear(texels, f.row0 + f.x0, f.sampler);
  co_vec3 a = v3_add(v3_scale(texel_linear(texels, f.row0 + f.x0, f.sampler), 1.0f - f.tx),
                     v3_scale(texel_linear(texels, f.row0 + f.x1, f.sampler), f.tx));
  co_vec3 b = v3_add(v3_scale(texel_linear(texels, f.row1 + f.x0, f.sampler), 1.0f - f.tx),
                     v3_scale(texel_linear(texels, f.row1 + f.x1, f.sampler), f.tx));
  return v3_add(v3_scale(a, 1.0f - f.ty), v3_scale(b, f.ty));
}

/* Texture coordinates at barycentric weights (b1, b2) of vertices 1 and 2. */
CO_INLINE void triangle_uv_at(const CO_GLOBAL TriangleUv* uvs, uint32_t triangle, float b1, float b2, float* u,
                              float* v) {
  TriangleUv t = uvs[triangle];
  float b0 = 1.0f - b1 - b2;
  *u = t.u0 * b0 + t.u1 * b1 + t.u2 * b2;
  *v = t.v0 * b0 + t.v1 * b1 + t.v2 * b2;
}

/* The coordinates a texture slot reads at (b1, b2) of kept triangle `triangle`: set 1 (TEXCOORD_1)
 * where `set1`, else set 0. Both sets are stored (two TriangleUv per triangle) only with
 * COHORT_FEATURE_TEXCOORD1; without it every slot reads set 0. */
CO_INLINE void slot_uv_at(const CO_GLOBAL TriangleUv* uvs, int set1, uint32_t triangle, float b1, float b2, float* u,
                          float* v) {
#ifdef COHORT_FEATURE_TEXCOORD1
  triangle_uv_at(uvs, 2u * triangle + (set1 ? 1u : 0u), b1, b2, u, v);
#else
  (void)set1;
  triangle_uv_at(uvs, triangle, b1, b2, u, v);
#endif
}

#endif
