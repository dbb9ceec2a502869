/* Structs shared by host and device. Every layout is checked on the host with static_asserts;
 * change one field and both sides change with it. */
#ifndef COHORT_TYPES_H
#define COHORT_TYPES_H

#include "common/core/port.h"

/* ---- KD-tree, 8 bytes per node --------------------------------------------------------------
 * Children of an inner node are adjacent (left at `child`, right at `child + 1`) and nodes are in
 * breadth-first order, so the top L levels of the tree are a prefix of the node array (what the
 * PTH subtree in local memory needs).
 *   word0 bits 0-1 : split axis 0..2, or KD_LEAF (3)
 *   word0 bits 2-31: inner -> index of the left child; leaf -> number of triangles
 *   word1          : inner -> split position (float bits); leaf -> first entry in the leaf index list */
#define KD_LEAF 3u
#define KD_MAX_INDEX ((1u << 30) - 1u)
typedef struct KdNode {
  uint32_t word0;
  uint32_t word1;
} KdNode;
CO_STATIC_ASSERT(sizeof(KdNode) == 8, "KdNode must stay 8 bytes");

CO_INLINE uint32_t kd_axis(KdNode n) { return n.word0 & 3u; }
CO_INLINE int kd_is_leaf(KdNode n) { return (n.word0 & 3u) == KD_LEAF; }
CO_INLINE uint32_t kd_left_child(KdNode n) { return n.word0 >> 2; }
CO_INLINE uint32_t kd_leaf_count(KdNode n) { return n.word0 >> 2; }
CO_INLINE uint32_t kd_leaf_first(KdNode n) { return n.word1; }

/* ---- 4-wide BVH, 128 bytes per node (--tree bvh4, the default where the method allows) -------
 * Each node holds its four children's boxes lane by lane (lane i is child i), so one ray tests
 * all four with one SIMD operation per slab. A child reference is an inner node's index, or a
 * leaf: BVH4_LEAF, the triangle count less one in bits 27-30 and the first entry of the leaf lists
 * in bits 0-26. An unused lane has BVH4_EMPTY and a box at +infinity that no ray enters. */
#define BVH4_LEAF 0x80000000u
#define BVH4_EMPTY 0xffffffffu
#define BVH4_LEAF_MAX 16u
#define BVH4_LEAF_FIRST_MAX ((1u << 27) - 1u)
/* The levels the builder lays out breadth first at the front of the node array (1,365 nodes at
 * most, 171 KiB): more than any device's local memory holds for the PTH walk. */
#define BVH4_TOP_LEVELS 6u
typedef struct Bvh4Node {
  co_float4 lo_x, hi_x, lo_y, hi_y, lo_z, hi_z;
  co_uint4 child;
  co_uint4 reserved; /* zero; pads the node to two 64-byte cache lines */
} Bvh4Node;
CO_STATIC_ASSERT(sizeof(Bvh4Node) == 128, "Bvh4Node must stay 128 bytes");

CO_INLINE int bvh4_is_leaf(uint32_t ref) { return (ref & BVH4_LEAF) != 0u; }
CO_INLINE uint32_t bvh4_leaf_first(uint32_t ref) { return ref & BVH4_LEAF_FIRST_MAX; }
CO_INLINE uint32_t bvh4_leaf_count(uint32_t ref) { return ((ref >> 27) & 15u) + 1u; }
CO_INLINE uint32_t bvh4_leaf_ref(uint32_t first, uint32_t count) { return BVH4_LEAF | ((count - 1u) << 27) | first; }

/* ---- Compressed 8-wide BVH, 80 bytes per node (--tree bvh8) -----------------------------------
 * Ylitie, Karras & Laine, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs"
 * (HPG 2017). A node holds up to eight children in slots 0-7; each child box is quantised to 8 bits
 * per plane against the node's origin and a power-of-two scale per axis: plane = origin + q * 2^e,
 * exact in float (the builder keeps every such value a float). Words:
 *   header: x y z the origin's bits; w the biased exponents e + 127 of x, y, z in bytes 0-2 and
 *           imask in byte 3 (bit s: slot s holds an inner node)
 *   index:  x the first child node (the inner children are consecutive, in slot order), y the first
 *           leaf triangle (the leaf children's triangles are consecutive), z w the meta bytes of
 *           slots 0-3 and 4-7: 0 for an unused slot; an inner node's 0x20 | (24 + s); a leaf's
 *           triangle count in unary in bits 5-7 (1, 3 or 7) and its first triangle's offset from
 *           index.y (0-23) in bits 0-4
 *   q:      the quantised planes, plane p (lo x, lo y, lo z, hi x, hi y, hi z) of slot s in byte
 *           s % 4 of word 2p + s / 4 (q[0].x is lo x of slots 0-3). */
#define BVH8_LEAF_MAX 3u
typedef struct Bvh8Node {
  co_uint4 header;
  co_uint4 index;
  co_uint4 q[3];
} Bvh8Node;
CO_STATIC_ASSERT(sizeof(Bvh8Node) == 80, "Bvh8Node must stay 80 bytes");

/* ---- 8-wide BVH with float planes, 256 bytes per node (--tree bvh8f, for CPUs) --------------
 * The 4-wide node's layout at twice the width: each plane of the eight child boxes is one row of
 * eight floats (child i in lane i), so one float8 load and one AVX operation per slab test all
 * eight. planes[p] is lo_x, hi_x, lo_y, hi_y, lo_z, hi_z for p = 0-5 (the 4-wide node's order);
 * child[i] is child i's reference as a 4-wide node's (an inner node's index, a bvh4_leaf_ref into
 * the leaf triangles, or BVH4_EMPTY with a box at +infinity). 64-byte aligned, four cache lines:
 * the planes in the first three, the references in the fourth. */
typedef struct CO_ALIGN(64) Bvh8fNode {
  float planes[6][8];
  uint32_t child[8];
  uint32_t reserved[8]; /* zero; pads the node to four 64-byte cache lines */
} Bvh8fNode;
CO_STATIC_ASSERT(sizeof(Bvh8fNode) == 256, "Bvh8fNode must stay 256 bytes");

/* ---- Triangles, stored for the watertight test of Woop, Benthin & Wald (JCGT 2013) -----------
 * The watertight test needs the vertices themselves; w components are padding. 48 bytes. */
typedef struct Triangle {
  co_float4 v0;
  co_float4 v1;
  co_float4 v2;
} Triangle;
CO_STATIC_ASSERT(sizeof(Triangle) == 48, "Triangle must stay 48 bytes");

/* ---- Four triangles of a leaf, lane by lane (the 8-wide BVH with float planes' leaves) -------
 * A leaf's triangles in blocks of four, each coordinate of each vertex one row of four floats
 * (triangle i in lane i), so the watertight test runs on all four in float4 operations
 * (intersect_triangle4); then the kept triangles' indices. A leaf of n triangles takes
 * ceil(n / 4) consecutive blocks; the unused lanes of its last block repeat its last triangle, and
 * the walk masks them off. 160 bytes. */
typedef struct Triangle4 {
  co_float4 v[3][3]; /* v[vertex][axis]: that coordinate of that vertex of each lane's triangle */
  uint32_t index[4];
} Triangle4;
CO_STATIC_ASSERT(sizeof(Triangle4) == 160, "Triangle4 must stay 160 bytes");

/* The blocks a leaf of `count` triangles takes. */
CO_INLINE uint32_t bvh8f_leaf_blocks(uint32_t count) { return (count + 3u) >> 2; }

/* ---- Materials ------------------------------------------------------------------------------
 * The glTF metallic-roughness parameters, mapped to a BSDF by bsdf_from_gltf (bsdf.h), and
 * emission as a one-sided (or two-sided) area light. Texture indices refer to the TextureDesc
 * table; the host sets them to -1 when the scene has no texture coordinates. A MAT_UV1_* flag
 * makes that texture read the triangle's second coordinate set (glTF TEXCOORD_1). */
#define MAT_TWO_SIDED_EMISSION 1u
#define MAT_UV1_BASE_COLOR 2u
#define MAT_UV1_METALLIC_ROUGHNESS 4u
#define MAT_UV1_EMISSION 8u
#define MAT_UV1_NORMAL 16u
/* glTF alphaMode (OPAQUE when neither is set): MASK cuts the surface out where its alpha is below
 * alpha_cutoff; BLEND lets a ray through with probability 1 - alpha (kernels/common/accel/alpha.h) */
#define MAT_ALPHA_MASK 32u
#define MAT_ALPHA_BLEND 64u
typedef struct Material {
  co_float4 base_color;  /* rgb; a = alpha */
  co_float4 emission;    /* rgb radiance (factor x strength); a unused */
  float metallic;
  float roughness;
  float transmission;
  float ior;
  int32_t base_color_texture; /* -1: none; multiplies base_color */
  uint32_t flags;
  int32_t emission_texture;   /* -1: none; multiplies emission */
  int32_t metallic_roughness_texture; /* -1: none; B multiplies metallic, G roughness (linear data) */
  int32_t normal_texture;             /* -1: none; tangent-space normal map (COHORT_FEATURE_NORMAL_MAP) */
  float normal_scale;                 /* scales the map's x and y */
  float alpha_cutoff;                 /* MAT_ALPHA_MASK: alpha below it is cut out (glTF alphaCutoff) */
  uint32_t pad1;
  co_float4 absorption; /* rgb sigma_a per unit length of the interior (KHR_materials_volume; 0: none,
                         * COHORT_FEATURE_VOLUME, shading/medium.h); a unused */
} Material;
CO_STATIC_ASSERT(sizeof(Material) == 96, "Material must stay 96 bytes");

/* KHR_materials_clearcoat of one material, in a table of its own beside the materials (uploaded
 * and passed to the kernels only with COHORT_FEATURE_CLEARCOAT, so a scene without a coat neither
 * stores nor reads it, and its programs do not even declare it; shading/clearcoat.h). factor 0: no
 * coat. Texture indices as Material's. */
#define COAT_UV1_FACTOR 1u    /* the factor texture reads TEXCOORD_1 */
#define COAT_UV1_ROUGHNESS 2u /* the roughness texture reads TEXCOORD_1 */
#define COAT_UV1_NORMAL 4u    /* the normal texture reads TEXCOORD_1 */
#if defined(COHORT_FEATURE_CLEARCOAT) || !(defined(__OPENCL_VERSION__) || defined(__CUDACC__))
typedef struct MaterialCoat {
  float factor;              /* clearcoatFactor */
  float roughness;           /* clearcoatRoughnessFactor */
  int32_t factor_texture;    /* -1: none; R multiplies factor (linear data) */
  int32_t roughness_texture; /* -1: none; G multiplies roughness (linear data) */
  int32_t normal_texture;    /* -1: none; the coat's tangent-space normal map (COHORT_FEATURE_NORMAL_MAP) */
  float normal_scale;        /* scales the map's x and y */
  uint32_t flags;            /* COAT_UV1_* */
  uint32_t pad0;
} MaterialCoat;
CO_STATIC_ASSERT(sizeof(MaterialCoat) == 32, "MaterialCoat must stay 32 bytes");
#endif
/* glTF KHR_materials_sheen of each material, a table indexed like the materials; uploaded and passed
 * to the kernels only with COHORT_FEATURE_SHEEN, as the coat's, so Material keeps its size and the
 * programs of a scene without sheen do not declare it (shading/sheen.h). */
#define MAT_SHEEN_UV1_COLOR 1u     /* the colour texture reads TEXCOORD_1 */
#define MAT_SHEEN_UV1_ROUGHNESS 2u /* the roughness texture reads TEXCOORD_1 */
#if defined(COHORT_FEATURE_SHEEN) || !(defined(__OPENCL_VERSION__) || defined(__CUDACC__))
typedef struct MaterialSheen {
  co_float4 color_roughness; /* rgb sheenColorFactor (linear); w sheenRoughnessFactor; rgb 0: no sheen */
  int32_t color_texture;     /* -1: none; its RGB (sRGB colour) multiplies the colour */
  int32_t roughness_texture; /* -1: none; its A (linear data) multiplies the roughness */
  uint32_t flags;            /* MAT_SHEEN_UV1_* */
  uint32_t pad0;
} MaterialSheen;
CO_STATIC_ASSERT(sizeof(MaterialSheen) == 32, "MaterialSheen must stay 32 bytes");
#endif
/* glTF KHR_materials_specular of each material, a table indexed like the materials; uploaded and passed
 * to the kernels only with COHORT_FEATURE_SPECULAR, as the coat's and the sheen's (shading/specular.h).
 * A material without MAT_SPECULAR_LAYER (no extension, or one of default values and no texture) keeps
 * the opaque dielectric it has without the extension. */
#define MAT_SPECULAR_UV1_FACTOR 1u /* the specular texture reads TEXCOORD_1 */
#define MAT_SPECULAR_UV1_COLOR 2u  /* the specular colour texture reads TEXCOORD_1 */
#define MAT_SPECULAR_LAYER 4u      /* the opaque dielectric is glTF's specular layering */
#if defined(COHORT_FEATURE_SPECULAR) || !(defined(__OPENCL_VERSION__) || defined(__CUDACC__))
typedef struct MaterialSpecular {
  co_float4 color_factor; /* rgb specularColorFactor (linear, >= 0); w specularFactor in [0, 1] */
  int32_t factor_texture; /* -1: none; its A (linear data) multiplies specularFactor */
  int32_t color_texture;  /* -1: none; its RGB (sRGB colour) multiplies specularColorFactor */
  uint32_t flags;         /* MAT_SPECULAR_* */
  uint32_t pad0;
} MaterialSpecular;
CO_STATIC_ASSERT(sizeof(MaterialSpecular) == 32, "MaterialSpecular must stay 32 bytes");
#endif

/* ---- Textures ---------------------------------------------------------------------------------
 * Every texture's texels live in one buffer of RGBA8 words (r in the low byte, as glTF stores
 * them, rows from the top: texture coordinate v = 0 is the first row); a descriptor per texture
 * says where and how it is sampled (glTF's sampler, and whether the texels are sRGB colour or
 * linear data). Texture coordinates are stored per kept triangle, 3 vertices; with
 * COHORT_FEATURE_TEXCOORD1 two sets per triangle, TEXCOORD_0's then TEXCOORD_1's. */
#define TEX_NEAREST 1u     /* nearest texel; else bilinear */
#define TEX_DATA 2u        /* linear data (metallic-roughness, normals); else sRGB-encoded colour */
#define TEX_WRAP_REPEAT 0u /* wrap modes, two bits each: along u in bits 2-3, along v in bits 4-5 */
#define TEX_WRAP_CLAMP 1u
#define TEX_WRAP_MIRROR 2u
#define TEX_TRANSFORM 64u  /* glTF KHR_texture_transform: the sampler's bits 8-31 index its TextureTransform */
typedef struct TextureDesc {
  uint32_t offset; /* first texel in the texel buffer */
  uint32_t width;
  uint32_t height;
  uint32_t sampler; /* TEX_* flags and wrap modes */
} TextureDesc;
CO_STATIC_ASSERT(sizeof(TextureDesc) == 16, "TextureDesc must stay 16 bytes");

/* KHR_texture_transform of one texture slot as the affine map (u, v) -> (a u + b v + c, d u + e v + f)
 * (glTF's T * R * S). Stored in the descriptor buffer after the descriptors, as two entries: a
 * descriptor with TEX_TRANSFORM finds it at entry tex_transform_entry(sampler)
 * (COHORT_FEATURE_TEXTURE_TRANSFORM; a scene without transforms stores none). */
typedef struct TextureTransform {
  float a, b, c;
  float d, e, f;
  float pad0, pad1;
} TextureTransform;
CO_STATIC_ASSERT(sizeof(TextureTransform) == 2 * sizeof(TextureDesc), "a TextureTransform fills two TextureDesc entries");
CO_INLINE uint32_t tex_transform_entry(uint32_t sampler) { return sampler >> 8; }

CO_INLINE uint32_t tex_wrap_s(uint32_t sampler) { return (sampler >> 2) & 3u; }
CO_INLINE uint32_t tex_wrap_t(uint32_t sampler) { return (sampler >> 4) & 3u; }
CO_INLINE uint32_t tex_sampler(uint32_t flags, uint32_t wrap_s, uint32_t wrap_t) {
  return flags | (wrap_s << 2) | (wrap_t << 4);
}

typedef struct TriangleUv {
  float u0, v0, u1, v1, u2, v2;
} TriangleUv;
CO_STATIC_ASSERT(sizeof(TriangleUv) == 24, "TriangleUv must stay 24 bytes");

/* glTF COLOR_0 at a kept triangle's 3 vertices, linear RGBA (COHORT_FEATURE_VERTEX_COLORS) */
typedef struct TriangleColor {
  co_float4 c0;
  co_float4 c1;
  co_float4 c2;
} TriangleColor;
CO_STATIC_ASSERT(sizeof(TriangleColor) == 48, "TriangleColor must stay 48 bytes");

/* The tangent frames of a kept triangle's 3 vertices, for normal maps (COHORT_FEATURE_NORMAL_MAP):
 * unit vertex normals n (w unused; zero where the file has none: the geometric normal stands in)
 * and unit tangents t with the bitangent's sign in w (glTF TANGENT: b = cross(n, t) * w). */
typedef struct TriangleFrame {
  co_float4 n0, n1, n2;
  co_float4 t0, t1, t2;
} TriangleFrame;
CO_STATIC_ASSERT(sizeof(TriangleFrame) == 96, "TriangleFrame must stay 96 bytes");

/* ---- Emissive triangles, sampled by power --------------------------------------------------- */
typedef struct EmitterEntry {
  uint32_t triangle;
  float cdf;   /* inclusive running sum of power, normalised to 1 at the last entry */
  float pmf;   /* probability of picking this triangle */
  float area;
} EmitterEntry;
CO_STATIC_ASSERT(sizeof(EmitterEntry) == 16, "EmitterEntry must stay 16 bytes");

/* ---- Camera and per-render constants -------------------------------------------------------- */
typedef struct CameraParams {
  co_float4 eye;
  co_float4 forward;  /* unit */
  co_float4 right;    /* unit, scaled by tan(fov/2) * aspect */
  co_float4 up;       /* unit, scaled by tan(fov/2) */
} CameraParams;
CO_STATIC_ASSERT(sizeof(CameraParams) == 64, "CameraParams must stay 64 bytes");

#define RENDER_FLAG_NEE 1u
#define RENDER_FLAG_MIS 2u
#define RENDER_FLAG_RUSSIAN_ROULETTE 4u
#define RENDER_FLAG_ENVIRONMENT 8u       /* constant environment `environment` on escaped rays */
#define RENDER_FLAG_ENVIRONMENT_MAP 16u  /* the environment map (COHORT_FEATURE_ENVMAP); replaces the constant */
typedef struct RenderParams {
  CameraParams camera;
  co_float4 environment;   /* constant environment radiance, rgb */
  co_float4 scene_min;     /* bounds of the KD-tree root; w unused */
  co_float4 scene_max;
  uint32_t width;
  uint32_t height;
  uint32_t max_depth;      /* path segments, as Mitsuba's max_depth; 0 = unbounded */
  uint32_t rr_depth;       /* first segment at which Russian roulette may end a path */
  uint32_t seed;
  uint32_t flags;
  uint32_t emitter_count;
  uint32_t sample_offset;  /* index of the first sample of this pass */
  uint32_t samples_per_pass;
  float emitter_power_total; /* sum of emitter_power() over emissive triangles */
  uint32_t pad3;             /* ray offsets come from error bounds (ray_offset.h), not from here */
  uint32_t env_width;        /* environment map texels per row (the grid has one more column) */
  uint32_t env_height;       /* rows, pole to pole; 0 without an environment map */
  uint32_t punctual_count;   /* KHR_lights_punctual lights */
  /* NEE first picks a kind of light with these probabilities (they sum to 1; see docs/lights.md) */
  float pick_triangles;
  float pick_environment;
  float pick_punctual;
  /* adaptive sampling (runtime/render/run/adaptive.h): this pass renders the first `active_pixels`
   * entries of its pixel list only; 0: every pixel, the list unused */
  uint32_t active_pixels;
  uint32_t pad1, pad2;
} RenderParams;
CO_STATIC_ASSERT(sizeof(RenderParams) == 192, "RenderParams must stay 192 bytes");

/* The pixels a pass renders (its work items per sample): every pixel, or the adaptive pass's
 * active ones. The kernels and the host's launch sizes both use it. */
CO_INLINE uint32_t pass_pixel_count(const RenderParams* p) {
  return p->active_pixels ? p->active_pixels : p->width * p->height;
}

/* The pixel of a pass's k-th work item where camera rays are launched in tiles (GPUs: port.h,
 * CO_PIXEL_TILES): the image in bands of PIXEL_TILE_H rows, each band in tiles of PIXEL_TILE_W
 * columns, a tile's pixels row by row, so that a warp's 32 camera rays cover an 8x4 patch rather
 * than 32 pixels of a row (a third of the perimeter: fewer warps split at an object's edge). The
 * last band and the last tile of a band are as high and as wide as the image leaves them, so it is
 * a permutation of the pixels for any size; which item renders a pixel changes nothing in its
 * samples (their random numbers come from the pixel and the sample). The host's bench traces the
 * protocol's rays in this order on such devices (runtime/bench/protocol_rays.h). */
#define PIXEL_TILE_W 8u
#define PIXEL_TILE_H 4u
CO_INLINE uint32_t tiled_pixel(uint32_t k, uint32_t width, uint32_t height) {
  uint32_t y0 = k / (width * PIXEL_TILE_H) * PIXEL_TILE_H;
  uint32_t rows = co_umin(PIXEL_TILE_H, height - y0);
  uint32_t in_band = k - y0 * width;
  uint32_t x0 = in_band / (PIXEL_TILE_W * rows) * PIXEL_TILE_W;
  uint32_t cols = co_umin(PIXEL_TILE_W, width - x0);
  uint32_t in_tile = in_band - x0 * rows; /* the band's tiles left of x0 are full */
  return (y0 + in_tile / cols) * width + x0 + in_tile % cols;
}

/* ---- KHR_lights_punctual: point and spot lights (delta lights, NEE only) ---------------------- */
#define PUNCTUAL_POINT 0u
#define PUNCTUAL_SPOT 1u
typedef struct PunctualLight {
  co_float4 position;   /* world; w unused */
  co_float4 direction;  /* spot: unit direction the light shines in; w = cos(outer cone angle) */
  co_float4 intensity;  /* rgb candela (colour x intensity); w = cos(inner cone angle) */
  uint32_t type;        /* PUNCTUAL_POINT or PUNCTUAL_SPOT */
  float cdf;            /* inclusive running sum of power, 1 at the last light */
  float pmf;            /* probability NEE picks this light among the punctual lights */
  float pad0;
} PunctualLight;
CO_STATIC_ASSERT(sizeof(PunctualLight) == 64, "PunctualLight must stay 64 bytes");

/* ---- Coherence code (Wang & Deng, section 3) -------------------------------------------------
 * A sort key of at most 64 bits (32-bit keys when key_bits <= 32) packing up to four parts; each
 * part's width and position are set on the host (`--code`). Origin, end point and direction cells
 * are Morton-interleaved so that nearby cells get nearby codes. */
typedef struct CodeParams {
  uint32_t origin_bits;      /* per axis, 0..10 */
  uint32_t origin_shift;
  uint32_t origin_adaptive;  /* 1: cells bounded by per-axis quantiles of triangle centroids */
  uint32_t pth_levels;       /* 2 bits per level, 0..16 */
  uint32_t pth_shift;
  uint32_t direction_bits;   /* per octahedral coordinate, 0..16 */
  uint32_t direction_shift;
  uint32_t key_bits;         /* bits the radix sort must look at: at most 32 means 32-bit keys */
  uint32_t end_bits;         /* per axis of the estimated end point (two-point key), 0..10 */
  uint32_t end_shift;
  uint32_t pad0;
  uint32_t pad1;
  co_float4 lo;              /* uniform origin grid, also the end point's */
  co_float4 hi;
} CodeParams;
CO_STATIC_ASSERT(sizeof(CodeParams) == 80, "CodeParams must stay 80 bytes");

/* ---- Rays and hits for the traversal-only kernels -------------------------------------------- */
typedef struct RayIn {
  co_float4 origin;  /* w = tmin */
  co_float4 dir;     /* w = tmax */
} RayIn;
CO_STATIC_ASSERT(sizeof(RayIn) == 32, "RayIn must stay 32 bytes");

#define HIT_NONE 0xffffffffu
typedef struct HitOut {
  float t;
  float u;
  float v;
  uint32_t triangle; /* HIT_NONE on a miss */
} HitOut;
CO_STATIC_ASSERT(sizeof(HitOut) == 16, "HitOut must stay 16 bytes");

/* No triangle (yet) for a ray in (tmin, tmax): where every traversal starts and what a miss returns. */
CO_INLINE HitOut hit_none(float tmax) {
  HitOut hit;
  hit.t = tmax; hit.u = 0.0f; hit.v = 0.0f; hit.triangle = HIT_NONE;
  return hit;
}

#endif
