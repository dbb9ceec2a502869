/* The reference estimator: unidirectional path tracing with next-event estimation on emissive
 * triangles, the environment map and punctual lights, and multiple importance sampling (power
 * heuristic; docs/lights.md), Russian roulette, and a depth
 * counted in path segments as Mitsuba's max_depth (1 = emitters seen directly). Surfaces shade
 * with the BSDFs of bsdf.h, mapped from the glTF material (docs/bsdf.md). The program is built
 * with the COHORT_FEATURE_* options of its scene, so only the BSDF families and the texture
 * lookups the scene needs are compiled. */
#ifndef COHORT_PATHTRACE_H
#define COHORT_PATHTRACE_H

/* the BSDF dispatch compiles only the families named by COHORT_FEATURE_* (see bsdf.h) */
#define COHORT_BSDF_SPECIALISED 1

#include "common/core/path_slot.h"
#include "common/shading/bsdf.h"
#include "common/shading/camera.h"
#include "common/accel/ray_offset.h"
#include "common/core/rng.h"
#include "common/accel/scene_view.h"
#if defined(COHORT_FEATURE_VOLUME) || defined(COHORT_FEATURE_SHEEN)
#include "common/shading/medium.h"
#endif
#if defined(COHORT_FEATURE_CLEARCOAT)
#include "common/shading/clearcoat.h"
#endif
#if defined(COHORT_FEATURE_SHEEN)
#include "common/shading/sheen.h"
#endif
#if defined(COHORT_FEATURE_SPECULAR)
#include "common/shading/specular.h"
#endif

/* A path between stages: what the megakernel keeps in registers and the wavefront kernels keep
 * in structure-of-arrays buffers. Every method runs these same functions in the same order per
 * path, so they all compute the same radiance bit for bit. */
#define PATH_ALIVE 0u       /* `org, dir` is the next ray to trace */
#define PATH_TERMINATED 1u  /* finished; its pending shadow ray may still add light */

/* PathState (org, dir, throughput, radiance, prev_pos, prev_bsdf_pdf, segment, status and, with
 * COHORT_FEATURE_ALPHA, alpha_seed: the seed of `dir`'s BLEND decisions, alpha.h; with
 * COHORT_FEATURE_VOLUME, medium: the absorbing volume `dir` travels in, shading/medium.h) is
 * generated from the path slot's list, PATH_SLOT in common/core/path_slot.h. */

/* A shadow ray whose `contribution` is added to the path's radiance when nothing occludes it. */
typedef struct ShadowRay {
  co_vec3 org, dir;
  float tmax;
  co_vec3 contribution;
  int valid;
#if defined(COHORT_FEATURE_ALPHA)
  uint32_t alpha_seed;
#endif
} ShadowRay;

/* The shadow ray of a light sample that passed every test: from `org` along the unit `dir` up to
 * `tmax`, adding `contribution` when nothing occludes it. */
CO_INLINE ShadowRay shadow_ray_towards(ShadowRay sr, co_vec3 org, co_vec3 dir, float tmax, co_vec3 contribution) {
  sr.org = org;
  sr.dir = dir;
  sr.tmax = tmax;
  sr.contribution = contribution;
  sr.valid = 1;
  return sr;
}

/* The pixels a pass renders: every pixel, or (adaptive sampling) the first p->active_pixels entries
 * of `pixel_list` (pass_pixel_count, types.h). Work item or item k of a pass stands for the pass's
 * k-th pixel: in 8x4 tiles on GPUs (tiled_pixel, types.h), row by row elsewhere. */
CO_INLINE uint32_t pass_pixel(uint32_t k, CO_GLOBAL const uint32_t* pixel_list, const RenderParams* p) {
#if defined(CO_PIXEL_TILES)
  return p->active_pixels ? pixel_list[k] : tiled_pixel(k, p->width, p->height);
#else
  return p->active_pixels ? pixel_list[k] : k;
#endif
}

/* The camera ray's direction of a pixel's sample: its jitter from the sample's camera stream. */
CO_INLINE co_vec3 path_camera_direction(const RenderParams* p, uint32_t pixel, uint32_t path_key) {
  Rng cam_rng = rng_at(path_key, 0u, RNG_CAMERA);
  float jx = rng_next(&cam_rng), jy = rng_next(&cam_rng);
  return camera_direction(&p->camera, p->width, p->height, pixel % p->width, pixel / p->width, jx, jy);
}

/* A path at the camera, about to trace the camera ray along `dir`. */
CO_INLINE PathState path_start_along(const RenderParams* p, uint32_t path_key, co_vec3 dir) {
  PathState st;
  st.org = v3_from4(p->camera.eye);
  st.dir = dir;
  st.throughput = v3_splat(1.0f);
  st.radiance = v3_splat(0.0f);
  st.prev_pos = st.org;
  st.prev_bsdf_pdf = 0.0f;
  st.segment = 1u;
  st.status = PATH_ALIVE;
#if defined(COHORT_FEATURE_ALPHA)
  st.alpha_seed = alpha_ray_seed(path_key, 1u, RNG_ALPHA);
#else
  (void)path_key;
#endif
#if defined(COHORT_FEATURE_VOLUME)
  st.medium = MEDIUM_NONE; /* the camera is outside every volume (docs/bsdf.md, "Volumes") */
#endif
  return st;
}

/* A path of `pixel` at the camera, its camera ray jittered from the path's streams (path_key:
 * rng_path_key of the pixel and sample, which the caller keeps for the path's later streams). */
CO_INLINE PathState path_start(const RenderParams* p, uint32_t pixel, uint32_t path_key) {
  return path_start_along(p, path_key, path_camera_direction(p, pixel, path_key));
}

/* path_start for PATH_START_BATCH consecutive samples of one pixel, from `sample`: the camera
 * directions first, lane by lane in loops of a fixed count over plain arrays, which a CPU compiler
 * can turn into one vector operation per step for all the samples (each lane runs
 * path_camera_direction's operations: the same bits). For CPUs, where each work item is scalar
 * code: one sample's camera ray alone is a chain of six dependent hashes, two divisions and a
 * square root. All eight are made even where the pass has fewer samples left: the fixed count is
 * what the compiler vectorises, and the caller uses only the ones it traces. Returns the mask of the
 * camera rays that miss the scene's box (bit l for sample + l), in the same vector loops:
 * intersect_box with the KD-tree's inverse is the test the KD-tree clips every ray with, so such a
 * ray hits nothing on any tree, and its walk (the ray's set-up, the root's box test) can be skipped. */
#define PATH_START_BATCH 8u
CO_INLINE uint32_t path_start_batch(const RenderParams* p, uint32_t pixel, uint32_t sample, PathState* out,
                                    uint32_t* keys) {
  float dx[PATH_START_BATCH], dy[PATH_START_BATCH], dz[PATH_START_BATCH];
  /* the keys in an array of the function's own, copied out at the end: stored through `keys` in the
   * loop below, which may alias *p, they kept the loop scalar (5-20 % slower renders, 2026-12-07) */
  uint32_t outside[PATH_START_BATCH], key[PATH_START_BATCH];
  for (uint32_t l = 0u; l < PATH_START_BATCH; ++l) {
    key[l] = rng_path_key(p->seed, pixel, sample + l);
    co_vec3 d = path_camera_direction(p, pixel, key[l]);
    dx[l] = d.x; dy[l] = d.y; dz[l] = d.z;
  }
  const co_vec3 eye = v3_from4(p->camera.eye), lo = v3_from4(p->scene_min), hi = v3_from4(p->scene_max);
  for (uint32_t l = 0u; l < PATH_START_BATCH; ++l) {
    float t0 = 0.0f, t1 = INFINITY;
    outside[l] = intersect_box(eye, kd_inverse(v3(dx[l], dy[l], dz[l])), lo, hi, &t0, &t1) ? 0u : 1u;
  }
  uint32_t mask = 0u;
  for (uint32_t l = 0u; l < PATH_START_BATCH; ++l) {
    out[l] = path_start_along(p, key[l], v3(dx[l], dy[l], dz[l]));
    keys[l] = key[l];
    mask |= outside[l] << l;
  }
  return mask;
}

/* Unit direction *dir and distance from `from` to `to`; 0 when they are not farther apart than
 * min_dist (or NaN). */
CO_INLINE int direction_to(co_vec3 from, co_vec3 to, float min_dist, co_vec3* dir, float* dist, float* dist2) {
  co_vec3 d = v3_sub(to, from);
  *dist2 = v3_dot(d, d);
  *dist = sqrt(*dist2);
  if (!(*dist > min_dist)) return 0;
  *dir = v3_scale(d, 1.0f / *dist);
  return 1;
}

/* Next-event estimation towards an emissive triangle picked by power with u_pick (the emitter
 * table's cdf). Returns the shadow ray with the MIS-weighted contribution it adds when unoccluded
 * (already times the throughput); see sample_direct_light. */
CO_INLINE ShadowRay nee_triangle(const SceneView* s, const RenderParams* p, float u_pick, float u1, float u2,
                                 co_vec3 pos, float offset, const ShadingFrame* frame, const Bsdf* b, co_vec3 wi,
                                 co_vec3 throughput) {
  ShadowRay sr;
  sr.valid = 0;
  uint32_t e = pick_emitter(s, u_pick);
  EmitterEntry entry = s->emitters[e];
  CO_GLOBAL const Triangle* tri = &s->triangles[entry.triangle];
  const CO_GLOBAL Material* m = &s->materials[s->triangle_material[entry.triangle]];
  float b1, b2, light_magnitude;
  sample_triangle(u1, u2, &b1, &b2);
  co_vec3 p0 = v3_from4(tri->v0), p1 = v3_from4(tri->v1), p2 = v3_from4(tri->v2);
  co_vec3 pl = triangle_point(p0, p1, p2, b1, b2, &light_magnitude);
  co_vec3 cross_l = v3_cross(v3_sub(p1, p0), v3_sub(p2, p0));
  co_vec3 nl = v3_normalize(cross_l);
  /* Both strategies of the MIS pair integrate over the directions seen from the ray origin, which
   * is offset from `pos` to the side the ray leaves from: NEE measures its direction, distance and
   * pdfs from the shadow ray's origin, as path_shade measures a BSDF sample's light pdf from the
   * origin of that ray (prev_pos). Measured from `pos` instead, the two weights of one light path
   * no longer sum to 1: the furnace lost ~0.05% of the direct light. The shadow ray stops short of
   * the light by the error bound of ray_offset.h, so neither the receiver's nor the light's own
   * triangle can occlude the sample. */
  float side = v3_dot(v3_sub(pl, pos), frame_geometric_normal(frame));
  if (!(side > 0.0f) && !(side < 0.0f)) return sr; /* in the plane, or NaN */
  co_vec3 origin = offset_origin(pos, frame_geometric_normal(frame), offset, side > 0.0f);
  co_vec3 wl;
  float dist, dist2;
  if (!direction_to(origin, pl, 0.0f, &wl, &dist, &dist2)) return sr;
  co_vec3 wl_local = frame_to_local(frame, wl);
  /* a light within the offset of the tangent plane, or (normal maps) on the other side of the
   * shading normal than of the surface */
  if (!(wl_local.z * side > 0.0f)) return sr;
  float cos_light = fabs(v3_dot(nl, wl));
  float tmax = shadow_tmax(dist, fmax(light_magnitude, v3_max_abs(origin)), triangle_edge_error(p0, p1, p2, cross_l),
                           cos_light);
  if (!(tmax > 0.0f)) return sr; /* closer to the light than its position is known */
  co_vec3 f = bsdf_eval(b, wi, wl_local); /* f |cos|; 0 on the wrong side of a reflector */
  if (!(v3_max_component(f) > 0.0f)) return sr;
  co_vec3 le = emitted_radiance_at(s, m, entry.triangle, b1, b2, nl, v3_neg(wl));
#if defined(COHORT_FEATURE_ALPHA)
  /* a cut-out point emits nothing; a BLEND emitter is met by a share alpha of the rays towards it */
  le = v3_scale(le, alpha_coverage(&s->tree.alpha, m, entry.triangle, b1, b2));
#endif
  if (v3_max_component(le) <= 0.0f) return sr;

  /* the light pdf of the MIS weight is the one path_shade uses when a BSDF sample hits the
   * emitter (the untextured power table), so the two weights sum to 1 */
  float pdf_light = light_pdf_solid_angle(s, m, entry.area, origin, pl, nl);
  float weight = (p->flags & RENDER_FLAG_MIS) ? mis_power(pdf_light, bsdf_pdf(b, wi, wl_local)) : 1.0f;
  /* estimator divides by the probability the table actually used to pick this triangle (times
   * the probability of picking a triangle at all, exactly 1 when they are the only lights) */
  float pdf_pick = entry.pmf * s->pick_triangles * dist2 / (entry.area * cos_light);
  float scale = weight / pdf_pick;
  return shadow_ray_towards(sr, origin, wl, tmax, v3_mul(throughput, v3_scale(v3_mul(f, le), scale)));
}

/* The shadow ray's origin for a light in the unit direction wl: `pos` offset along the normal to
 * the side wl leaves from (the side path_shade offsets a BSDF sample in that direction to). Returns
 * 0 when wl lies in the tangent plane. */
CO_INLINE int nee_origin(co_vec3 pos, float offset, const ShadingFrame* frame, co_vec3 wl, co_vec3 wl_local,
                         co_vec3* origin) {
  if (!(wl_local.z > 0.0f) && !(wl_local.z < 0.0f)) return 0;
#ifdef COHORT_FEATURE_NORMAL_MAP
  /* the shading normal must not send a shadow ray through the surface (docs/bsdf.md) */
  if (!(v3_dot(wl, frame_geometric_normal(frame)) * wl_local.z > 0.0f)) return 0;
#else
  (void)wl;
#endif
  *origin = offset_origin(pos, frame_geometric_normal(frame), offset, wl_local.z > 0.0f);
  return 1;
}

#ifdef COHORT_FEATURE_ENVMAP
/* Next-event estimation towards the environment map (environment.h), MIS-weighted against the
 * BSDF; pdf_pick is the probability of having chosen the environment. */
CO_INLINE ShadowRay nee_environment(const SceneView* s, const RenderParams* p, float pdf_pick, float u1, float u2,
                                    co_vec3 pos, float offset, const ShadingFrame* frame, const Bsdf* b, co_vec3 wi,
                                    co_vec3 throughput) {
  ShadowRay sr;
  sr.valid = 0;
  float pdf_env;
  co_vec3 wl = env_sample(&s->env, u1, u2, &pdf_env);
  if (!(pdf_env > 0.0f)) return sr;
  co_vec3 wl_local = frame_to_local(frame, wl);
  co_vec3 origin;
  if (!nee_origin(pos, offset, frame, wl, wl_local, &origin)) return sr;
  co_vec3 f = bsdf_eval(b, wi, wl_local);
  if (!(v3_max_component(f) > 0.0f)) return sr;
  co_vec3 le = env_eval(&s->env, wl);
  float pdf_light = pdf_pick * pdf_env;
  float weight = (p->flags & RENDER_FLAG_MIS) ? mis_power(pdf_light, bsdf_pdf(b, wi, wl_local)) : 1.0f;
  return shadow_ray_towards(sr, origin, wl, INFINITY, v3_mul(throughput, v3_scale(v3_mul(f, le), weight / pdf_light)));
}
#endif

#ifdef COHORT_FEATURE_PUNCTUAL
/* Next-event estimation towards a point or spot light picked by power with u_pick: a delta
 * light, so no MIS (no BSDF sample can reach it); pdf_pick is the probability of having chosen
 * the punctual lights. */
CO_INLINE ShadowRay nee_punctual(const SceneView* s, float pdf_pick, float u_pick, co_vec3 pos,
                                 float offset, const ShadingFrame* frame, const Bsdf* b, co_vec3 wi, co_vec3 throughput) {
  ShadowRay sr;
  sr.valid = 0;
  const CO_GLOBAL PunctualLight* l = &s->punctual_lights[pick_punctual(s->punctual_lights, s->punctual_count, u_pick)];
  co_vec3 pl = v3_from4(l->position);
  /* No MIS pairs this strategy with another, so the irradiance I cos / r^2 is measured from the
   * shading point itself; the shadow ray leaves from the offset origin and stops short of the
   * light by the error bound of ray_offset.h (a punctual light has no surface of its own, but may
   * sit on one). */
  co_vec3 wl;
  float dist, dist2;
  if (!direction_to(pos, pl, 0.0f, &wl, &dist, &dist2)) return sr;
  co_vec3 wl_local = frame_to_local(frame, wl);
  co_vec3 origin;
  if (!nee_origin(pos, offset, frame, wl, wl_local, &origin)) return sr;
  float tmax = shadow_tmax(v3_length(v3_sub(pl, origin)), fmax(v3_max_abs(pl), v3_max_abs(origin)), 0.0f, 1.0f);
  if (!(tmax > 0.0f)) return sr;
  co_vec3 f = bsdf_eval(b, wi, wl_local);
  if (!(v3_max_component(f) > 0.0f)) return sr;
  co_vec3 intensity = punctual_intensity(l, v3_neg(wl));
  if (!(v3_max_component(intensity) > 0.0f)) return sr;
  /* irradiance I / r^2 from the light's point; bsdf_eval already holds the cosine */
  float scale = 1.0f / (pdf_pick * l->pmf * dist2);
  return shadow_ray_towards(sr, origin, wl, tmax, v3_mul(throughput, v3_scale(v3_mul(f, intensity), scale)));
}
#endif

/* u in [lo, lo + width) mapped to [0, 1): the rest of a random number after a discrete choice. */
CO_INLINE float remap_unit(float u, float lo, float width) {
  return fmin(fmax((u - lo) / width, 0.0f), 0x1.fffffep-1f);
}

/* Next-event estimation at `pos` for the BSDF `b` chosen there (never a delta BSDF): picks a kind
 * of light (the environment map, the punctual lights or the emissive triangles, with the
 * host's pick_* probabilities; only triangles without those features, and then u_pick is used
 * as is) and one sample of it, and returns the shadow ray with the contribution it adds when
 * unoccluded (already times the throughput). `frame` is the shading frame of the stored
 * geometric normal and `wi` the local direction towards the previous vertex. */
CO_INLINE ShadowRay sample_direct_light(const SceneView* s, const RenderParams* p, Rng* rng, co_vec3 pos,
                                        float offset, const ShadingFrame* frame, const Bsdf* b, co_vec3 wi, co_vec3 throughput) {
  float u_pick = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
#ifdef COHORT_FEATURE_ENVMAP
  if (u_pick < s->pick_environment)
    return nee_environment(s, p, s->pick_environment, u1, u2, pos, offset, frame, b, wi, throughput);
#endif
#ifdef COHORT_FEATURE_PUNCTUAL
  if (u_pick < s->pick_environment + s->pick_punctual)
    return nee_punctual(s, s->pick_punctual, remap_unit(u_pick, s->pick_environment, s->pick_punctual), pos,
                        offset, frame, b, wi, throughput);
#endif
#if defined(COHORT_FEATURE_ENVMAP) || defined(COHORT_FEATURE_PUNCTUAL)
  u_pick = remap_unit(u_pick, 1.0f - s->pick_triangles, s->pick_triangles);
#endif
  return nee_triangle(s, p, u_pick, u1, u2, pos, offset, frame, b, wi, throughput);
}

/* Whether NEE has a light to sample. */
CO_INLINE int nee_enabled(const SceneView* s, const RenderParams* p) {
  if (!(p->flags & RENDER_FLAG_NEE)) return 0;
  int lights = s->emitter_count > 0u;
#ifdef COHORT_FEATURE_ENVMAP
  lights |= s->pick_environment > 0.0f;
#endif
#ifdef COHORT_FEATURE_PUNCTUAL
  lights |= s->pick_punctual > 0.0f;
#endif
  return lights;
}

/* Light from the environment along an escaped ray: the map, MIS-weighted against NEE after a
 * non-delta vertex, or the constant radiance. */
CO_INLINE void path_escape(const SceneView* s, const RenderParams* p, PathState* st) {
#ifdef COHORT_FEATURE_ENVMAP
  if (p->flags & RENDER_FLAG_ENVIRONMENT_MAP) {
    co_vec3 le = env_eval(&s->env, st->dir);
    float w = 1.0f;
    if (st->prev_bsdf_pdf > 0.0f && nee_enabled(s, p) && s->pick_environment > 0.0f) {
      w = (p->flags & RENDER_FLAG_MIS)
              ? mis_power(st->prev_bsdf_pdf, s->pick_environment * env_pdf(&s->env, st->dir))
              : 0.0f;
    }
    st->radiance = v3_add(st->radiance, v3_scale(v3_mul(st->throughput, le), w));
    return;
  }
#endif
  (void)s;
  if (p->flags & RENDER_FLAG_ENVIRONMENT)
    st->radiance = v3_add(st->radiance, v3_mul(st->throughput, v3_from4(p->environment)));
}

/* Everything that happens at the end of the segment `st->segment` given its closest hit:
 * emission, next-event estimation (returned as a shadow ray), Russian roulette and the next
 * direction. Leaves the path ALIVE with its next ray, or TERMINATED.
 *
 * Shading follows docs/bsdf.md: the frame of the geometric normal as stored (flat shading; the
 * front is the exterior, which dielectrics need), one BSDF chosen per vertex from the material
 * with u_select and used for both NEE and the continuation, the four numbers of the RNG_BSDF
 * stream (u_select, u_lobe, u1, u2), no NEE at delta BSDFs, and after a delta sample a
 * prev_bsdf_pdf of 0: the next emitter hit counts with weight 1. Every stream comes from the path's
 * path_key (rng_path_key), which a miss does not read. */
CO_INLINE ShadowRay path_shade(const SceneView* s, const RenderParams* p, PathState* st, HitOut hit,
                               uint32_t path_key) {
  ShadowRay none;
  none.valid = 0;
  if (hit.triangle == HIT_NONE) {
#if defined(COHORT_FEATURE_VOLUME)
    /* an infinite segment: an absorbing channel sends nothing back (only an open volume escapes) */
    if (st->medium != MEDIUM_NONE)
      st->throughput = v3_mul(st->throughput, medium_transmittance(v3_from4(s->materials[st->medium - 1u].absorption),
                                                                   INFINITY));
#endif
    path_escape(s, p, st);
    st->status = PATH_TERMINATED;
    return none;
  }
  uint32_t segment = st->segment;
  int nee = nee_enabled(s, p);
  CO_GLOBAL const Triangle* tri = &s->triangles[hit.triangle];
  const CO_GLOBAL Material* m = &s->materials[s->triangle_material[hit.triangle]];
  co_vec3 p0 = v3_from4(tri->v0), p1 = v3_from4(tri->v1), p2 = v3_from4(tri->v2);
  co_vec3 cross_n = triangle_cross(tri);
  co_vec3 n_geo = v3_normalize(cross_n);
  /* from the barycentrics rather than org + t dir: on the triangle to a few ulps of its vertices,
   * however far the ray came (ray_offset.h) */
  float magnitude;
  co_vec3 pos = triangle_point(p0, p1, p2, hit.u, hit.v, &magnitude);
  float offset = surface_offset(magnitude, triangle_edge_error(p0, p1, p2, cross_n));
#if defined(COHORT_FEATURE_VOLUME)
  /* Beer-Lambert over the segment, before the emission at its end: the length from the ray's origin
   * to the point on the triangle (its barycentrics, which every method and tree agree on bit for bit,
   * rather than the traversal's t) */
  if (st->medium != MEDIUM_NONE)
    st->throughput = v3_mul(st->throughput, medium_transmittance(v3_from4(s->materials[st->medium - 1u].absorption),
                                                                 v3_length(v3_sub(pos, st->org))));
#endif

  co_vec3 le = emitted_radiance_at(s, m, hit.triangle, hit.u, hit.v, n_geo, v3_neg(st->dir));
  if (v3_max_component(le) > 0.0f) {
    float w = 1.0f;
    if (st->prev_bsdf_pdf > 0.0f && nee) {
      if (p->flags & RENDER_FLAG_MIS) {
        float area = 0.5f * v3_length(cross_n);
        w = mis_power(st->prev_bsdf_pdf, light_pdf_solid_angle(s, m, area, st->prev_pos, pos, n_geo));
      } else {
        w = 0.0f; /* NEE alone accounts for emitters after a non-delta vertex */
      }
    }
    st->radiance = v3_add(st->radiance, v3_scale(v3_mul(st->throughput, le), w));
  }
  if (p->max_depth != 0u && segment >= p->max_depth) {
    st->status = PATH_TERMINATED;
    return none;
  }

  Rng bsdf_rng = rng_at(path_key, segment, RNG_BSDF);
  float u_select = rng_next(&bsdf_rng), u_lobe = rng_next(&bsdf_rng);
  float u1 = rng_next(&bsdf_rng), u2 = rng_next(&bsdf_rng);
  SurfaceParams sp = surface_params(s, m, hit.triangle, hit.u, hit.v);
#if defined(COHORT_FEATURE_CLEARCOAT)
  /* glTF's clearcoat lies over the base: it is chosen first, and the base from the rest of u_select */
  CoatChoice coat = coat_choose(s, s->triangle_material[hit.triangle], hit.triangle, hit.u, hit.v, n_geo, st->dir,
                                u_select);
  u_select = coat.u_rest;
#endif
#ifndef COHORT_FEATURE_SHEEN
  Bsdf b = bsdf_from_gltf(sp.base_color, sp.metallic, sp.roughness, m->transmission, m->ior, u_select);
#endif
  ShadingFrame frame = frame_from_normal(n_geo);
#ifdef COHORT_FEATURE_NORMAL_MAP
  {
    /* a mapped normal that puts the incoming direction on the other side than the surface does
     * is dropped for the flat one (docs/bsdf.md, "Normal maps") */
    co_vec3 ns = mapped_normal(s, m, hit.triangle, hit.u, hit.v, n_geo);
    if (v3_dot(ns, st->dir) * v3_dot(n_geo, st->dir) > 0.0f) {
      frame = frame_from_normal(ns);
      frame.ng = n_geo;
    }
  }
#endif
  co_vec3 wi = frame_to_local(&frame, v3_neg(st->dir));
#ifdef COHORT_FEATURE_SHEEN
  /* the sheen layer above the base, taken with a probability that depends on wi (bsdf_sheen_select;
   * docs/bsdf.md, "Sheen"); otherwise the base's choice with the remapped u_select */
  Bsdf b;
  {
    SheenParams sh = sheen_params(s, s->triangle_material[hit.triangle], hit.triangle, hit.u, hit.v);
    if (!bsdf_sheen_select(sh.color, sh.roughness, wi, &u_select, &b))
      b = bsdf_from_gltf(sp.base_color, sp.metallic, sp.roughness, m->transmission, m->ior, u_select);
  }
#endif
#if defined(COHORT_FEATURE_SPECULAR)
  /* KHR_materials_specular: the opaque dielectric that the rest of u_select chose becomes glTF's
   * layering, chosen from what remains of u_select (specular.h; docs/bsdf.md, "Specular") */
  if (b.type == BSDF_PLASTIC || b.type == BSDF_DIFFUSE) {
    SpecularParams sq = specular_params(s, s->triangle_material[hit.triangle], hit.triangle, hit.u, hit.v);
    if (sq.layer)
      b = bsdf_specular_base(b, sp.base_color, sp.metallic, sp.roughness, m->transmission, m->ior, sq.color,
                             sq.factor, wi, u_select);
  }
#endif
#if defined(COHORT_FEATURE_CLEARCOAT)
  /* the coat, chosen first, replaces whatever the rest of u_select chose below it */
  if (coat.chosen) {
    b = coat.bsdf;
    frame = coat.frame;
    wi = coat.wi;
  }
#endif

  ShadowRay shadow = none;
  if (nee && !bsdf_is_delta(&b)) {
    Rng light_rng = rng_at(path_key, segment, RNG_LIGHT);
    shadow = sample_direct_light(s, p, &light_rng, pos, offset, &frame, &b, wi, st->throughput);
#if defined(COHORT_FEATURE_ALPHA)
    shadow.alpha_seed = alpha_ray_seed(path_key, segment, RNG_ALPHA_SHADOW);
#endif
#if defined(COHORT_FEATURE_VOLUME)
    /* A shadow ray that stays inside a volume (from a vertex inside, or through a rough dielectric
     * into it) counts only if the light is inside too: the boundary occludes any other. Its light
     * is absorbed over the ray's length (tmax, short of the light by the offset bound; infinite
     * towards the environment). */
    if (shadow.valid) {
      float side_in = -v3_dot(st->dir, n_geo), side_out = v3_dot(shadow.dir, n_geo);
      uint32_t medium = medium_beyond(st->medium, m, s->triangle_material[hit.triangle],
                                      (side_in > 0.0f) != (side_out > 0.0f), side_out < 0.0f);
      if (medium != MEDIUM_NONE)
        shadow.contribution = v3_mul(shadow.contribution,
                                     medium_transmittance(v3_from4(s->materials[medium - 1u].absorption), shadow.tmax));
    }
#endif
  }
  if ((p->flags & RENDER_FLAG_RUSSIAN_ROULETTE) && segment >= p->rr_depth) {
    Rng rr_rng = rng_at(path_key, segment, RNG_ROULETTE);
    /* refraction may lift the throughput above 1 (the eta^2 scale): q stays at most 0.95 */
    float q = fmin(v3_max_component(st->throughput), 0.95f);
    if (!(rng_next(&rr_rng) < q)) {
      st->status = PATH_TERMINATED;
      return shadow;
    }
    st->throughput = v3_scale(st->throughput, 1.0f / q);
  }
  BsdfSample bs = bsdf_sample(&b, wi, u_lobe, u1, u2);
  co_vec3 next_throughput = v3_mul(st->throughput, bs.weight);
  if (bs.flags == 0u || !(bs.wo.z != 0.0f) || v3_max_component(next_throughput) <= 0.0f) {
    st->status = PATH_TERMINATED;
    return shadow;
  }
#ifdef COHORT_FEATURE_NORMAL_MAP
  /* a direction on one side of the shading normal and the other of the surface is absorbed: no
   * ray goes through the surface it was meant to leave from, and no energy is made */
  if (!(v3_dot(frame_to_world(&frame, bs.wo), n_geo) * bs.wo.z > 0.0f)) {
    st->status = PATH_TERMINATED;
    return shadow;
  }
#endif
  st->throughput = next_throughput;
#if defined(COHORT_FEATURE_VOLUME)
  /* a refraction enters or leaves the material's volume; wo.z has the geometric normal's sign
   * (normal maps: checked above) */
  st->medium = medium_beyond(st->medium, m, s->triangle_material[hit.triangle], (bs.flags & BSDF_TRANSMISSION) != 0u, bs.wo.z < 0.0f);
#endif
  st->prev_bsdf_pdf = (bs.flags & BSDF_DELTA) ? 0.0f : bs.pdf; /* 0: the next emitter hit is not MIS-weighted */
  /* offset to the side the new direction leaves from, not the side of the incoming ray; the MIS
   * weight of an emitter this ray hits measures the light pdf from this origin, as NEE does */
  st->org = offset_origin(pos, n_geo, offset, bs.wo.z > 0.0f);
  st->prev_pos = st->org;
  st->dir = frame_to_world(&frame, bs.wo);
  st->segment = segment + 1u;
#if defined(COHORT_FEATURE_ALPHA)
  st->alpha_seed = alpha_ray_seed(path_key, segment + 1u, RNG_ALPHA);
#endif
  return shadow;
}

/* Closes a shadow ray: its light counts only when nothing lies in between. */
CO_INLINE void path_resolve_shadow(PathState* st, const ShadowRay* sr, HitOut occluder) {
  if (occluder.triangle == HIT_NONE) st->radiance = v3_add(st->radiance, sr->contribution);
}

typedef struct PathResult {
  co_vec3 radiance;
  uint32_t rays;
  uint32_t max_steps; /* the most KD-tree nodes one of its rays visited */
} PathResult;

CO_INLINE void path_count_ray(PathResult* result, uint32_t steps) {
  result->rays += 1u;
  result->max_steps = co_umax(result->max_steps, steps);
}

/* A path's ray met `hit` after visiting `steps` nodes: counted, shaded, its shadow ray traced. */
CO_INLINE void path_take_hit(const SceneView* s, const RenderParams* p, PathState* st, HitOut hit, uint32_t steps,
                             uint32_t path_key, PathResult* result) {
  path_count_ray(result, steps);
  ShadowRay sr = path_shade(s, p, st, hit, path_key);
  if (sr.valid) {
    path_resolve_shadow(st, &sr,
                        scene_trace_steps(&s->tree, sr.org, sr.dir, 0.0f, sr.tmax, 1, &steps CO_ALPHA_ARG(sr.alpha_seed)));
    path_count_ray(result, steps);
  }
}

/* A started path to its end, one ray and its shadow ray at a time. */
CO_INLINE void path_continue(const SceneView* s, const RenderParams* p, PathState* st, uint32_t path_key,
                             PathResult* result) {
  while (st->status == PATH_ALIVE) {
    uint32_t steps = 0u;
    HitOut hit = scene_trace_steps(&s->tree, st->org, st->dir, 0.0f, INFINITY, 0, &steps CO_ALPHA_ARG(st->alpha_seed));
    path_take_hit(s, p, st, hit, steps, path_key, result);
  }
  result->radiance = st->radiance;
}

CO_INLINE PathResult path_result_none(void) {
  PathResult result;
  result.radiance = v3_splat(0.0f);
  result.rays = 0u;
  result.max_steps = 0u;
  return result;
}

/* The whole path in one call: what the NAIVE megakernel runs per sample. */
CO_INLINE PathResult trace_path(const SceneView* s, const RenderParams* p, uint32_t pixel, uint32_t sample) {
  PathResult result = path_result_none();
  const uint32_t key = rng_path_key(p->seed, pixel, sample);
  PathState st = path_start(p, pixel, key);
  path_continue(s, p, &st, key, &result);
  return result;
}

#if defined(COHORT_PAIRED_WALKS) && defined(COHORT_ACCEL_BVH8F)
#define COHORT_NAIVE_PAIRS 1
/* One place of trace_paths_paired's pair: while its path (st, the batch's path *j, its result r) has
 * ended and the batch has more, the result goes out and the batch's next path takes the place, its
 * camera hit taken at once; where the paths come shaded (`begun`), its result so far taken instead.
 * Forced inline, so that the pair's states stay in registers. */
CO_FORCE_INLINE void paired_refill(const SceneView* s, const RenderParams* p, uint32_t n, const uint32_t* walked,
                                   const PathState* start, const uint32_t* keys, const HitOut* hits,
                                   const uint32_t* steps, const PathResult* begun, PathResult* results, PathState* st,
                                   uint32_t* j, PathResult* r, uint32_t* next) {
  while (st->status != PATH_ALIVE && *next < n) {
    r->radiance = st->radiance;
    results[walked[*j]] = *r;
    *j = (*next)++;
    *st = start[walked[*j]];
    if (begun) {
      *r = begun[*j];
    } else {
      *r = path_result_none();
      path_take_hit(s, p, st, hits[*j], steps[*j], keys[walked[*j]], r);
    }
  }
}

/* A batch's n >= 2 started paths in pairs, for CPUs: two paths' rays walk the tree in turn
 * (bvh8f_trace_pair), so the core waits on two chains of node loads at once, and their set-up and
 * shading are two independent chains of arithmetic in one stream. Path j (0 <= j < n) is the
 * batch's sample walked[j], started as start[walked[j]] with the stream key keys[walked[j]]
 * (path_start_batch); its camera ray met hits[j] after steps[j] visits (bvh8f_trace_packet); its
 * result goes to results[walked[j]]. When a path ends, the next of the batch takes its place (its
 * camera hit shaded at once), so the walks stay in pairs until one path is left, which goes on alone.
 * Where `begun` is not null, the paths come shaded (trace_paths_diffuse): start[] holds the states
 * after their last hit's shading, begun[j] path j's result so far (every ray it walked counted), and
 * hits and steps are not read; the pair begins with the walks of their next rays. Each path computes
 * exactly what trace_path computes for it: the same calls on the same values, only interleaved with
 * another path's. */
CO_INLINE void trace_paths_paired(const SceneView* s, const RenderParams* p, uint32_t n, const uint32_t* walked,
                                  const PathState* start, const uint32_t* keys, const HitOut* hits,
                                  const uint32_t* steps, const PathResult* begun, PathResult* results) {
  uint32_t ja = 0u, jb = 1u, next = 2u;
  PathState a = start[walked[0]], b = start[walked[1]];
  HitOut hit_a = hit_none(INFINITY), hit_b = hit_none(INFINITY);
  uint32_t steps_a = 0u, steps_b = 0u;
  PathResult ra, rb;
  if (begun) {
    ra = begun[0];
    rb = begun[1];
  } else {
    ra = path_result_none();
    rb = path_result_none();
    hit_a = hits[0];
    hit_b = hits[1];
    steps_a = steps[0];
    steps_b = steps[1];
  }
  for (int taken = begun != 0;; taken = 0) {
    ShadowRay sa, sb;
    sa.valid = sb.valid = 0;
    if (!taken) {
      path_count_ray(&ra, steps_a);
      path_count_ray(&rb, steps_b);
      sa = path_shade(s, p, &a, hit_a, keys[walked[ja]]);
      sb = path_shade(s, p, &b, hit_b, keys[walked[jb]]);
    }
    Bvh8fWalk wa, wb;
    if (sa.valid || sb.valid) {
      if (sa.valid) bvh8f_walk_start(&s->tree, &wa, sa.org, sa.dir, 0.0f, sa.tmax, 1 CO_ALPHA_ARG(sa.alpha_seed));
      if (sb.valid) bvh8f_walk_start(&s->tree, &wb, sb.org, sb.dir, 0.0f, sb.tmax, 1 CO_ALPHA_ARG(sb.alpha_seed));
      if (sa.valid && sb.valid)
        bvh8f_trace_pair(&s->tree, &wa, &wb);
      else
        bvh8f_walk_run(&s->tree, sa.valid ? &wa : &wb);
      if (sa.valid) {
        path_resolve_shadow(&a, &sa, wa.hit);
        path_count_ray(&ra, wa.count);
      }
      if (sb.valid) {
        path_resolve_shadow(&b, &sb, wb.hit);
        path_count_ray(&rb, wb.count);
      }
    }
    paired_refill(s, p, n, walked, start, keys, hits, steps, begun, results, &a, &ja, &ra, &next);
    paired_refill(s, p, n, walked, start, keys, hits, steps, begun, results, &b, &jb, &rb, &next);
    if (a.status != PATH_ALIVE || b.status != PATH_ALIVE) break;
    bvh8f_walk_start(&s->tree, &wa, a.org, a.dir, 0.0f, INFINITY, 0 CO_ALPHA_ARG(a.alpha_seed));
    bvh8f_walk_start(&s->tree, &wb, b.org, b.dir, 0.0f, INFINITY, 0 CO_ALPHA_ARG(b.alpha_seed));
    bvh8f_trace_pair(&s->tree, &wa, &wb);
    hit_a = wa.hit;
    hit_b = wb.hit;
    steps_a = wa.count;
    steps_b = wb.count;
  }
  path_continue(s, p, &a, keys[walked[ja]], &ra);
  path_continue(s, p, &b, keys[walked[jb]], &rb);
  results[walked[ja]] = ra;
  results[walked[jb]] = rb;
}

/* A started path whose camera ray met `hit` after `steps` nodes (bvh8f_trace_packet) to its end. */
CO_INLINE PathResult trace_path_from_hit(const SceneView* s, const RenderParams* p, PathState st, HitOut hit,
                                         uint32_t steps, uint32_t path_key) {
  PathResult result = path_result_none();
  path_take_hit(s, p, &st, hit, steps, path_key, &result);
  path_continue(s, p, &st, path_key, &result);
  return result;
}

/* A started path whose camera ray misses the scene's box (path_start_batch): what trace_path gives
 * it, without the walk, which finds no triangle for it. The ray counts one node visit, the root's
 * (a ray grazing the padding of the root's child boxes would have counted a few more: a statistic,
 * never the image). */
CO_INLINE PathResult trace_path_outside(const SceneView* s, const RenderParams* p, PathState st, uint32_t path_key) {
  PathResult result = path_result_none();
  path_count_ray(&result, 1u);
  path_shade(s, p, &st, hit_none(INFINITY), path_key); /* the sky: the path ends */
  result.radiance = st.radiance;
  return result;
}
#endif

/* A sample added to a film pixel's running sum (rgb; w stays 0), component by component as
 * OpenCL's float4 addition does. */
CO_INLINE co_float4 film_add(co_float4 acc, co_vec3 r) {
  acc.x = acc.x + r.x;
  acc.y = acc.y + r.y;
  acc.z = acc.z + r.z;
  return acc;
}

/* A beauty sample: film_add, and w sums the square of the sample's luminance (Rec. 709), the
 * per-pixel variance that adaptive sampling estimates its error from (runtime/render/run/adaptive.h).
 * One expression per step, FP_CONTRACT off (port.h): the same bits in every kernel and on the host. */
CO_INLINE co_float4 film_add_sample(co_float4 acc, co_vec3 r) {
  float y = 0.2126f * r.x + 0.7152f * r.y + 0.0722f * r.z;
  acc = film_add(acc, r);
  acc.w = acc.w + y * y;
  return acc;
}

#endif
