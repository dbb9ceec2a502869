/* Device view of a loaded scene: the KD-tree, per-triangle materials and the emitter table. */
#ifndef COHORT_SCENE_VIEW_H
#define COHORT_SCENE_VIEW_H

#include "common/kdtree_traverse.h"
#include "common/sampling.h"

typedef struct SceneView {
  KdTreeView tree;
  const CO_GLOBAL uint32_t* triangle_material; /* per kept triangle */
  const CO_GLOBAL Material* materials;
  const CO_GLOBAL EmitterEntry* emitters;      /* emissive triangles, cdf by power */
  uint32_t emitter_count;
  float emitter_power_total;
} SceneView;

/* The kernel arguments every rendering kernel takes, and the view they make. */
#define SCENE_KERNEL_PARAMS                                                                         \
  CO_CONSTANT RenderParams *params, CO_GLOBAL const KdNode *nodes, CO_GLOBAL const uint32_t *leaf_triangles, \
      CO_GLOBAL const Triangle *triangles, CO_GLOBAL const uint32_t *triangle_material,              \
      CO_GLOBAL const Material *materials, CO_GLOBAL const EmitterEntry *emitters

CO_INLINE SceneView make_scene_view(const RenderParams* p, const CO_GLOBAL KdNode* nodes,
                                    const CO_GLOBAL uint32_t* leaf_triangles, const CO_GLOBAL Triangle* triangles,
                                    const CO_GLOBAL uint32_t* triangle_material, const CO_GLOBAL Material* materials,
                                    const CO_GLOBAL EmitterEntry* emitters) {
  SceneView s;
  s.tree.nodes = nodes;
  s.tree.leaf_triangles = leaf_triangles;
  s.tree.triangles = triangles;
  s.tree.lo = v3_from4(p->scene_min);
  s.tree.hi = v3_from4(p->scene_max);
  s.triangle_material = triangle_material;
  s.materials = materials;
  s.emitters = emitters;
  s.emitter_count = p->emitter_count;
  s.emitter_power_total = p->emitter_power_total;
  return s;
}
#define SCENE_VIEW(p) make_scene_view(&(p), nodes, leaf_triangles, triangles, triangle_material, materials, emitters)

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

/* Solid-angle density of sampling point `p_light` (normal n_light, unit) from `p` by NEE. */
CO_INLINE float light_pdf_solid_angle(const SceneView* s, const CO_GLOBAL Material* m, float area, co_vec3 p,
                                      co_vec3 p_light, co_vec3 n_light) {
  co_vec3 d = v3_sub(p_light, p);
  float dist2 = v3_dot(d, d);
  float cos_l = fabs(v3_dot(n_light, d)) / sqrt(dist2);
  float pmf = emitter_power(v3_from4(m->emission), area, material_two_sided_emission(m)) / s->emitter_power_total;
  return pmf * dist2 / (area * cos_l);
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
