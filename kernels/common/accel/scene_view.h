/* Device view of a loaded scene: the KD-tree, per-triangle materials, the emitter table, the
 * textures (texture coordinates per triangle, descriptors, texels; read only when the program is
 * built with COHORT_FEATURE_TEXTURES, and one-element placeholders otherwise), vertex colours
 * (COHORT_FEATURE_VERTEX_COLORS), the environment map
 * (COHORT_FEATURE_ENVMAP) and the punctual lights (COHORT_FEATURE_PUNCTUAL), placeholders
 * likewise, and the materials' clearcoat, sheen and specular tables (COHORT_FEATURE_CLEARCOAT, _SHEEN,
 * _SPECULAR; parameters only of the programs built with them). With COHORT_FEATURE_ALPHA the traversal view also holds what alpha tests read
 * (alpha.h). */
#ifndef COHORT_SCENE_VIEW_H
#define COHORT_SCENE_VIEW_H

#include "common/shading/environment.h"
#include "common/accel/scene_accel.h"
#include "common/shading/punctual.h"
#include "common/core/sampling.h"
#include "common/shading/texture.h"
#include "common/accel/alpha.h"

typedef struct SceneView {
  SceneAccel tree;
  const CO_GLOBAL Triangle* triangles;         /* the kept triangles, for shading and lights */
  const CO_GLOBAL uint32_t* triangle_material; /* per kept triangle */
  const CO_GLOBAL Material* materials;
  const CO_GLOBAL EmitterEntry* emitters;      /* emissive triangles, cdf by power */
  const CO_GLOBAL TriangleUv* triangle_uvs;   /* per kept triangle */
  const CO_GLOBAL TextureDesc* textures;
  const CO_GLOBAL uint32_t* texels;           /* RGBA8 */
#ifdef COHORT_FEATURE_VERTEX_COLORS
  const CO_GLOBAL TriangleColor* triangle_colors; /* per kept triangle */
#endif
#ifdef COHORT_FEATURE_NORMAL_MAP
  const CO_GLOBAL TriangleFrame* triangle_frames; /* per kept triangle */
#endif
#ifdef COHORT_FEATURE_CLEARCOAT
  const CO_GLOBAL MaterialCoat* material_coats; /* per material (shading/clearcoat.h) */
#endif
#ifdef COHORT_FEATURE_SHEEN
  const CO_GLOBAL MaterialSheen* material_sheen; /* per material (shading/sheen.h) */
#endif
#ifdef COHORT_FEATURE_SPECULAR
  const CO_GLOBAL MaterialSpecular* material_specular; /* per material (shading/specular.h) */
#endif
  EnvironmentView env;
  const CO_GLOBAL PunctualLight* punctual_lights;
  uint32_t emitter_count;
  float emitter_power_total;
  uint32_t punctual_count;
  float pick_triangles, pick_environment, pick_punctual; /* NEE's choice of a kind of light */
} SceneView;

/* The clearcoat table, a parameter of the programs built with COHORT_FEATURE_CLEARCOAT only
 * (SCENE_CLEARCOAT_BUFFERS, kernel_params.h) */
#ifdef COHORT_FEATURE_CLEARCOAT
#define CO_CLEARCOAT_PARAM , const CO_GLOBAL MaterialCoat* material_coats
#define CO_CLEARCOAT_ARG(coats) , (coats)
#else
#define CO_CLEARCOAT_PARAM
#define CO_CLEARCOAT_ARG(coats)
#endif
/* The sheen table likewise, with COHORT_FEATURE_SHEEN only (SCENE_SHEEN_BUFFERS) */
#ifdef COHORT_FEATURE_SHEEN
#define CO_SHEEN_PARAM , const CO_GLOBAL MaterialSheen* material_sheen
#define CO_SHEEN_ARG(sheen) , (sheen)
#else
#define CO_SHEEN_PARAM
#define CO_SHEEN_ARG(sheen)
#endif
/* The specular table likewise, with COHORT_FEATURE_SPECULAR only (SCENE_SPECULAR_BUFFERS) */
#ifdef COHORT_FEATURE_SPECULAR
#define CO_SPECULAR_PARAM , const CO_GLOBAL MaterialSpecular* material_specular
#define CO_SPECULAR_ARG(specular) , (specular)
#else
#define CO_SPECULAR_PARAM
#define CO_SPECULAR_ARG(specular)
#endif

/* The view of the scene that a rendering kernel's SCENE_PARAMS (kernel_params.h) make. */
CO_INLINE SceneView make_scene_view(const RenderParams* p, const CO_GLOBAL KdNode* nodes,
                                    const CO_GLOBAL uint32_t* leaf_triangles, const CO_GLOBAL Triangle* triangles,
                                    const CO_GLOBAL uint32_t* triangle_material, const CO_GLOBAL Material* materials,
                                    const CO_GLOBAL EmitterEntry* emitters, const CO_GLOBAL TriangleUv* triangle_uvs,
                                    const CO_GLOBAL TextureDesc* textures, const CO_GLOBAL uint32_t* texels,
                                    const CO_GLOBAL TriangleColor* triangle_colors,
                                    const CO_GLOBAL TriangleFrame* triangle_frames,
                                    const CO_GLOBAL co_float4* env_texels, const CO_GLOBAL float* env_tables,
                                    const CO_GLOBAL PunctualLight* punctual_lights CO_CLEARCOAT_PARAM CO_SHEEN_PARAM
                                        CO_SPECULAR_PARAM) {
  SceneView s;
  s.tree = make_scene_accel(nodes, leaf_triangles, triangles, p->scene_min, p->scene_max);
#if defined(COHORT_FEATURE_ALPHA)
  s.tree.alpha.triangle_material = triangle_material;
  s.tree.alpha.materials = materials;
  s.tree.alpha.triangle_uvs = triangle_uvs;
  s.tree.alpha.textures = textures;
  s.tree.alpha.texels = texels;
#ifdef COHORT_FEATURE_VERTEX_COLORS
  s.tree.alpha.triangle_colors = triangle_colors;
#endif
#endif
  s.triangles = triangles;
  s.triangle_material = triangle_material;
  s.materials = materials;
  s.emitters = emitters;
  s.triangle_uvs = triangle_uvs;
  s.textures = textures;
  s.texels = texels;
  /* a scene without vertex colours or normal maps keeps no pointer to them */
#ifdef COHORT_FEATURE_VERTEX_COLORS
  s.triangle_colors = triangle_colors;
#else
  (void)triangle_colors;
#endif
#ifdef COHORT_FEATURE_NORMAL_MAP
  s.triangle_frames = triangle_frames;
#else
  (void)triangle_frames;
#endif
#ifdef COHORT_FEATURE_SHEEN
  s.material_sheen = material_sheen;
#endif
#ifdef COHORT_FEATURE_SPECULAR
  s.material_specular = material_specular;
#endif
  s.env.texels = env_texels;
  s.env.tables = env_tables;
  s.env.width = p->env_width;
  s.env.height = p->env_height;
  s.punctual_lights = punctual_lights;
#ifdef COHORT_FEATURE_CLEARCOAT
  s.material_coats = material_coats;
#endif
  s.emitter_count = p->emitter_count;
  s.emitter_power_total = p->emitter_power_total;
  s.punctual_count = p->punctual_count;
  s.pick_triangles = p->pick_triangles;
  s.pick_environment = p->pick_environment;
  s.pick_punctual = p->pick_punctual;
  return s;
}
#define SCENE_VIEW(p)                                                                                \
  make_scene_view(&(p), nodes, leaf_triangles, triangles, triangle_material, materials, emitters, triangle_uvs, \
                  textures, texels, triangle_colors, triangle_frames, env_texels, env_tables,       \
                  punctual_lights CO_CLEARCOAT_ARG(material_coats) CO_SHEEN_ARG(material_sheen) \
                      CO_SPECULAR_ARG(material_specular))

CO_INLINE float luminance(co_vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* Unnormalised geometric normal; its length is twice the area. Counter-clockwise is the front. */
CO_INLINE co_vec3 triangle_cross(const CO_GLOBAL Triangle* t) {
  co_vec3 p0 = v3_from4(t->v0);
  return v3_cross(v3_sub(v3_from4(t->v1), p0), v3_sub(v3_from4(t->v2), p0));
}

CO_INLINE int material_two_sided_emission(const CO_GLOBAL Material* m) {
  return (m->flags & MAT_TWO_SIDED_EMISSION) != 0u;
}

/* Power used to pick an emissive triangle; the host computes the table with the same function. */
CO_INLINE float emitter_power(co_vec3 radiance, float area, int two_sided) {
  return luminance(radiance) * area * (two_sided ? 2.0f : 1.0f);
}

/* Radiance leaving an emitter towards a point on the side of `to_viewer`; 0 from its back. */
CO_INLINE co_vec3 emitted_radiance(const CO_GLOBAL Material* m, co_vec3 n_geo, co_vec3 to_viewer) {
  co_vec3 le = v3_from4(m->emission);
  if (!material_two_sided_emission(m) && v3_dot(n_geo, to_viewer) <= 0.0f) return v3_splat(0.0f);
  return le;
}

/* Texture `index` (colour channels) at barycentric weights (b1, b2) of `triangle`, read through the
 * coordinate set `set1` picks (slot_uv_at); 1 where there is no texture (index < 0). Without
 * COHORT_FEATURE_TEXTURES every texture is absent and no lookup is compiled. */
CO_INLINE co_vec3 slot_texture(const SceneView* s, int32_t index, int set1, uint32_t triangle, float b1, float b2) {
#ifdef COHORT_FEATURE_TEXTURES
  if (index >= 0) {
    float u, v;
    slot_uv_at(s->triangle_uvs, set1, triangle, b1, b2, &u, &v);
    return texture_sample(s->textures, s->texels, index, u, v);
  }
#else
  (void)s;
  (void)index;
  (void)set1;
  (void)triangle;
  (void)b1;
  (void)b2;
#endif
  return v3_splat(1.0f);
}

#if (defined(COHORT_FEATURE_SHEEN) || defined(COHORT_FEATURE_SPECULAR)) && defined(COHORT_FEATURE_TEXTURES)
/* Texture `index`'s alpha channel (linear, byte / 255) as slot_texture reads colour; 1 where there is
 * no texture, so a factor times it keeps its bits. The sheen's roughness and the specular factor. */
CO_INLINE float slot_alpha(const SceneView* s, int32_t index, int set1, uint32_t triangle, float b1, float b2) {
  float u, v;
  if (index < 0) return 1.0f;
  slot_uv_at(s->triangle_uvs, set1, triangle, b1, b2, &u, &v);
  return texture_sample_alpha(s->textures, s->texels, index, u, v);
}
#endif

/* A core slot of material `m`: TEXCOORD_1 where the material's `uv1_flag` is set. */
CO_INLINE co_vec3 material_texture(const SceneView* s, const CO_GLOBAL Material* m, int32_t index, uint32_t uv1_flag,
                                   uint32_t triangle, float b1, float b2) {
  return slot_texture(s, index, (m->flags & uv1_flag) != 0u, triangle, b1, b2);
}

/* The glTF metallic-roughness parameters at a surface point: factors times textures (base colour
 * also times COLOR_0), what bsdf_from_gltf takes. */
typedef struct SurfaceParams {
  co_vec3 base_color;
  float metallic;
  float roughness;
} SurfaceParams;

CO_INLINE SurfaceParams surface_params(const SceneView* s, const CO_GLOBAL Material* m, uint32_t triangle, float b1,
                                       float b2) {
  SurfaceParams p;
  p.base_color = v3_mul(v3_from4(m->base_color),
                        material_texture(s, m, m->base_color_texture, MAT_UV1_BASE_COLOR, triangle, b1, b2));
#ifdef COHORT_FEATURE_VERTEX_COLORS
  {
    TriangleColor c = s->triangle_colors[triangle];
    float b0 = 1.0f - b1 - b2;
    co_vec3 vc = v3_add(v3_add(v3_scale(v3_from4(c.c0), b0), v3_scale(v3_from4(c.c1), b1)), v3_scale(v3_from4(c.c2), b2));
    p.base_color = v3_mul(p.base_color, vc);
  }
#endif
  p.metallic = m->metallic;
  p.roughness = m->roughness;
#ifdef COHORT_FEATURE_TEXTURES
  if (m->metallic_roughness_texture >= 0) {
    co_vec3 mr = material_texture(s, m, m->metallic_roughness_texture, MAT_UV1_METALLIC_ROUGHNESS, triangle, b1, b2);
    p.metallic = p.metallic * mr.z;
    p.roughness = p.roughness * mr.y;
  }
#endif
  return p;
}

#ifdef COHORT_FEATURE_SHEEN
/* KHR_materials_sheen at a surface point: the factors times their textures (the colour texture's RGB,
 * sRGB-decoded; the roughness texture's A, linear), what bsdf_sheen_select takes. */
typedef struct SheenParams {
  co_vec3 color;
  float roughness;
} SheenParams;

CO_INLINE SheenParams sheen_params(const SceneView* s, uint32_t material, uint32_t triangle, float b1, float b2) {
  MaterialSheen ms = s->material_sheen[material];
  SheenParams p;
  p.color = v3_from4(ms.color_roughness);
  p.roughness = ms.color_roughness.w;
#ifdef COHORT_FEATURE_TEXTURES
  p.color = v3_mul(p.color, slot_texture(s, ms.color_texture, (ms.flags & MAT_SHEEN_UV1_COLOR) != 0u, triangle, b1, b2));
  p.roughness =
      p.roughness * slot_alpha(s, ms.roughness_texture, (ms.flags & MAT_SHEEN_UV1_ROUGHNESS) != 0u, triangle, b1, b2);
#else
  (void)triangle;
  (void)b1;
  (void)b2;
#endif
  return p;
}
#endif

#ifdef COHORT_FEATURE_SPECULAR
/* KHR_materials_specular at a surface point: the factors times their textures (the colour texture's
 * RGB, sRGB-decoded; the specular texture's A, linear), what bsdf_specular_layer takes; `layer` 0 for a
 * material that keeps its opaque dielectric (MAT_SPECULAR_LAYER unset). */
typedef struct SpecularParams {
  co_vec3 color;
  float factor;
  int layer;
} SpecularParams;

CO_INLINE SpecularParams specular_params(const SceneView* s, uint32_t material, uint32_t triangle, float b1, float b2) {
  MaterialSpecular ms = s->material_specular[material];
  SpecularParams p;
  p.layer = (ms.flags & MAT_SPECULAR_LAYER) != 0u;
  p.color = v3_from4(ms.color_factor);
  p.factor = ms.color_factor.w;
  if (!p.layer) return p;
#ifdef COHORT_FEATURE_TEXTURES
  p.color = v3_mul(p.color, slot_texture(s, ms.color_texture, (ms.flags & MAT_SPECULAR_UV1_COLOR) != 0u, triangle, b1, b2));
  p.factor = p.factor * slot_alpha(s, ms.factor_texture, (ms.flags & MAT_SPECULAR_UV1_FACTOR) != 0u, triangle, b1, b2);
#else
  (void)triangle;
  (void)b1;
  (void)b2;
#endif
  return p;
}
#endif

#ifdef COHORT_FEATURE_NORMAL_MAP
/* A tangent-space normal map's texel c at (b1, b2) as a world normal: (c * 2 - 1) with x and y times
 * `scale`, in the frame of the interpolated vertex normal and tangent (glTF's rule: bitangent =
 * cross(n, t) * w). n_geo where the frame or the result is degenerate. */
CO_INLINE co_vec3 tangent_space_normal(const SceneView* s, uint32_t triangle, float b1, float b2, co_vec3 n_geo,
                                       co_vec3 c, float scale) {
  TriangleFrame f = s->triangle_frames[triangle];
  float b0 = 1.0f - b1 - b2;
  co_vec3 n = v3_add(v3_add(v3_scale(v3_from4(f.n0), b0), v3_scale(v3_from4(f.n1), b1)), v3_scale(v3_from4(f.n2), b2));
  co_vec3 t = v3_add(v3_add(v3_scale(v3_from4(f.t0), b0), v3_scale(v3_from4(f.t1), b1)), v3_scale(v3_from4(f.t2), b2));
  float n_len = v3_length(n);
  n = n_len > 0.0f ? v3_scale(n, 1.0f / n_len) : n_geo; /* no vertex normals: the flat one */
  t = v3_sub(t, v3_scale(n, v3_dot(n, t)));             /* orthogonal to the interpolated normal */
  float t_len = v3_length(t);
  if (!(t_len > 0.0f)) return n_geo;
  t = v3_scale(t, 1.0f / t_len);
  co_vec3 b = v3_scale(v3_cross(n, t), f.t0.w < 0.0f ? -1.0f : 1.0f);
  float x = (2.0f * c.x - 1.0f) * scale, y = (2.0f * c.y - 1.0f) * scale, z = 2.0f * c.z - 1.0f;
  co_vec3 ns = v3_add(v3_add(v3_scale(t, x), v3_scale(b, y)), v3_scale(n, z));
  float len = v3_length(ns);
  if (!(len > 0.0f) || !v3_is_finite(ns)) return n_geo;
  return v3_scale(ns, 1.0f / len);
}

/* The normal a normal-mapped material shades with at (b1, b2); n_geo where the material has no map. */
CO_INLINE co_vec3 mapped_normal(const SceneView* s, const CO_GLOBAL Material* m, uint32_t triangle, float b1, float b2,
                                co_vec3 n_geo) {
  if (m->normal_texture < 0) return n_geo;
  co_vec3 c = material_texture(s, m, m->normal_texture, MAT_UV1_NORMAL, triangle, b1, b2);
  return tangent_space_normal(s, triangle, b1, b2, n_geo, c, m->normal_scale);
}
#endif

/* emitted_radiance times the emission texture at (b1, b2). The emitter table (host) and the
 * light pdf below use the untextured emission factor: NEE picks a textured emitter with a
 * probability that only approximates its power, which stays unbiased because the estimator
 * divides by the probability the table used, and the MIS weights on both sides use that same
 * light_pdf_solid_angle. */
CO_INLINE co_vec3 emitted_radiance_at(const SceneView* s, const CO_GLOBAL Material* m, uint32_t triangle, float b1,
                                      float b2, co_vec3 n_geo, co_vec3 to_viewer) {
  co_vec3 le = emitted_radiance(m, n_geo, to_viewer);
#ifdef COHORT_FEATURE_TEXTURES
  if (m->emission_texture >= 0 && v3_max_component(le) > 0.0f)
    le = v3_mul(le, material_texture(s, m, m->emission_texture, MAT_UV1_EMISSION, triangle, b1, b2));
#else
  (void)s;
  (void)triangle;
  (void)b1;
  (void)b2;
#endif
  return le;
}

/* Solid-angle density of sampling point `p_light` (normal n_light, unit) from `p` by NEE. */
CO_INLINE float light_pdf_solid_angle(const SceneView* s, const CO_GLOBAL Material* m, float area, co_vec3 p,
                                      co_vec3 p_light, co_vec3 n_light) {
  co_vec3 d = v3_sub(p_light, p);
  float dist2 = v3_dot(d, d);
  float cos_l = fabs(v3_dot(n_light, d)) / sqrt(dist2);
  float pmf = emitter_power(v3_from4(m->emission), area, material_two_sided_emission(m)) / s->emitter_power_total;
  /* pick_triangles is exactly 1 when emissive triangles are the only lights */
  return pmf * s->pick_triangles * dist2 / (area * cos_l);
}

/* Index of the emitter whose cdf interval holds u (binary search). */
CO_INLINE uint32_t pick_emitter(const SceneView* s, float u) {
  uint32_t lo = 0, hi = s->emitter_count - 1u;
  while (lo < hi) {
    uint32_t mid = (lo + hi) >> 1;
    if (u < s->emitters[mid].cdf) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

#endif
