/* The hits of a pixel's batch shaded eight to a vector, for the paired naive megakernel on CPUs, in
 * programs whose materials are all untextured Lambertians: the camera hits, and in interior views the
 * bounce hits too (trace_paths_diffuse).
 *
 * Why: on PoCL each work item is scalar code, so path_shade runs one sample at a time, while Mitsuba
 * 3's llvm variant shades eight samples to an AVX vector; `perf` gives path_shade 13-30 % of the
 * white-sky renders, most of it the camera hits'. PoCL's compiler did not vectorise a loop over
 * path_shade's steps (docs/design.md, "Paired walks"), so the steps are written here in OpenCL's
 * float8 and uint8: each lane runs path_shade's operations in its order (the same roundings: no
 * contraction, correctly rounded division and square root), so a lane's state is the bits path_shade
 * gives it. Only what a diffuse-only program's path_shade does at a hit is here; it runs where no
 * shadow ray and no roulette follow the hits (nee_enabled false, the segment below rr_depth).
 * `Methods.DiffuseCameraHitsShadedSideBySide` renders such scenes against the unpaired kernels. */
#ifndef COHORT_SHADE_BATCH_H
#define COHORT_SHADE_BATCH_H

#include "common/wavefront/pathtrace.h"

#if defined(COHORT_NAIVE_PAIRS) && defined(__OPENCL_VERSION__) && !BSDF_WITH_CONDUCTOR && \
    !BSDF_WITH_DIELECTRIC && !BSDF_WITH_PLASTIC && !BSDF_WITH_COAT && !BSDF_WITH_SHEEN &&          \
    !BSDF_WITH_SPECULAR && !defined(COHORT_FEATURE_ALPHA) && !defined(COHORT_FEATURE_VOLUME) &&    \
    !defined(COHORT_FEATURE_NORMAL_MAP) && !defined(COHORT_FEATURE_TEXTURES) &&                     \
    !defined(COHORT_FEATURE_VERTEX_COLORS) && !defined(COHORT_FEATURE_CLEARCOAT)
#define COHORT_DIFFUSE_BATCH 1
#define SHADE_BATCH 8u /* float8's lanes */
#define SHADE_SCALAR_MOST 2u /* hits shaded one by one where no more than this many are shaded */
#define BY_BOUNCE_LEAST 4u   /* paths that go on bounce by bounce; fewer go on in refilled pairs */
#if PATH_START_BATCH != SHADE_BATCH
#error "a batch of camera rays (PATH_START_BATCH) is shaded as one float8"
#endif

/* Three float8: a co_vec3 per lane. The helpers below are vec.h's, lane by lane. */
typedef struct Vec3x8 {
  float8 x, y, z;
} Vec3x8;

CO_INLINE Vec3x8 v3x8(float8 x, float8 y, float8 z) { Vec3x8 r; r.x = x; r.y = y; r.z = z; return r; }
CO_INLINE Vec3x8 v3x8_load(const float* x, const float* y, const float* z) {
  return v3x8(vload8(0, x), vload8(0, y), vload8(0, z));
}
CO_INLINE Vec3x8 v3x8_add(Vec3x8 a, Vec3x8 b) { return v3x8(a.x + b.x, a.y + b.y, a.z + b.z); }
CO_INLINE Vec3x8 v3x8_sub(Vec3x8 a, Vec3x8 b) { return v3x8(a.x - b.x, a.y - b.y, a.z - b.z); }
CO_INLINE Vec3x8 v3x8_mul(Vec3x8 a, Vec3x8 b) { return v3x8(a.x * b.x, a.y * b.y, a.z * b.z); }
CO_INLINE Vec3x8 v3x8_scale(Vec3x8 a, float8 s) { return v3x8(a.x * s, a.y * s, a.z * s); }
CO_INLINE Vec3x8 v3x8_neg(Vec3x8 a) { return v3x8(-a.x, -a.y, -a.z); }
CO_INLINE Vec3x8 v3x8_abs(Vec3x8 a) { return v3x8(fabs(a.x), fabs(a.y), fabs(a.z)); }
CO_INLINE float8 v3x8_dot(Vec3x8 a, Vec3x8 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CO_INLINE Vec3x8 v3x8_cross(Vec3x8 a, Vec3x8 b) {
  return v3x8(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
CO_INLINE float8 v3x8_length(Vec3x8 a) { return sqrt(v3x8_dot(a, a)); }
CO_INLINE float8 v3x8_max_component(Vec3x8 a) { return fmax(a.x, fmax(a.y, a.z)); }
/* b where `pick` (a comparison's -1 lanes), else a */
CO_INLINE Vec3x8 v3x8_select(Vec3x8 a, Vec3x8 b, int8 pick) {
  return v3x8(select(a.x, b.x, pick), select(a.y, b.y, pick), select(a.z, b.z, pick));
}

/* pcg_hash and rng_next (rng.h) */
CO_INLINE uint8 pcg_hash8(uint8 v) {
  uint8 s = v * 747796405u + 2891336453u;
  uint8 w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (w >> 22u) ^ w;
}
CO_INLINE float8 rng_next8(uint8* state) {
  *state = pcg_hash8(*state);
  return convert_float8(*state >> 8u) * (1.0f / 16777216.0f);
}

/* co_sincos_2pi (microfacet.h) */
CO_INLINE void sincos_2pi8(float8 u, float8* s, float8* c) {
  float8 q4 = u * 4.0f;
  int8 k = convert_int8(q4); /* toward zero, as (int) */
  float8 r = q4 - convert_float8(k);
  int8 up = r >= 0.5f;
  r = select(r, r - 1.0f, up);
  k = k - up; /* up is -1 where r >= 0.5 */
  float8 x = r * (0.5f * CO_PI);
  float8 x2 = x * x;
  float8 sx = CO_SIN_POLY(x, x2), cx = CO_COS_POLY(x2);
  int8 odd = (k & 1) != 0;
  float8 sin_r = select(sx, cx, odd), cos_r = select(cx, sx, odd);
  *s = select(sin_r, -sin_r, (k & 2) != 0);
  *c = select(cos_r, -cos_r, ((k + 1) & 2) != 0);
}

/* path_shade at the camera hits of lanes l < n whose hit is a triangle: path walked[l], its state
 * st[walked[l]] and stream key keys[walked[l]]. Lanes from n on, and lanes that missed, compute on
 * triangle `some` (a hit of the batch) and are not written; the caller shades the misses. */
CO_INLINE void path_shade_diffuse8(const SceneView* s, const RenderParams* p, uint32_t n, const uint32_t* walked,
                                   const uint32_t* keys, const HitOut* hits, uint32_t some, PathState* st) {
  float v[9][SHADE_BATCH], hu[SHADE_BATCH], hv[SHADE_BATCH], d[3][SHADE_BATCH], tp[3][SHADE_BATCH];
  float rad[3][SHADE_BATCH], base[3][SHADE_BATCH], emit[3][SHADE_BATCH];
  uint32_t seg[SHADE_BATCH], two_sided[SHADE_BATCH], key[SHADE_BATCH];
  for (uint32_t l = 0u; l < SHADE_BATCH; ++l) {
    const uint32_t q = l < n ? l : 0u;
    const uint32_t t = hits[q].triangle != HIT_NONE ? hits[q].triangle : some;
    CO_GLOBAL const Triangle* tri = &s->triangles[t];
    const CO_GLOBAL Material* m = &s->materials[s->triangle_material[t]];
    const PathState* ps = &st[walked[q]];
    v[0][l] = tri->v0.x; v[1][l] = tri->v0.y; v[2][l] = tri->v0.z;
    v[3][l] = tri->v1.x; v[4][l] = tri->v1.y; v[5][l] = tri->v1.z;
    v[6][l] = tri->v2.x; v[7][l] = tri->v2.y; v[8][l] = tri->v2.z;
    hu[l] = hits[q].u; hv[l] = hits[q].v;
    d[0][l] = ps->dir.x; d[1][l] = ps->dir.y; d[2][l] = ps->dir.z;
    tp[0][l] = ps->throughput.x; tp[1][l] = ps->throughput.y; tp[2][l] = ps->throughput.z;
    rad[0][l] = ps->radiance.x; rad[1][l] = ps->radiance.y; rad[2][l] = ps->radiance.z;
    seg[l] = ps->segment;
    key[l] = keys[walked[q]];
    /* surface_params without textures or vertex colours: the factor times 1 */
    const co_vec3 bc = v3_mul(v3_from4(m->base_color), slot_texture(s, -1, 0, t, 0.0f, 0.0f));
    base[0][l] = bc.x; base[1][l] = bc.y; base[2][l] = bc.z;
    emit[0][l] = m->emission.x; emit[1][l] = m->emission.y; emit[2][l] = m->emission.z;
    two_sided[l] = (uint32_t)material_two_sided_emission(m);
  }
  const Vec3x8 p0 = v3x8_load(v[0], v[1], v[2]), p1 = v3x8_load(v[3], v[4], v[5]), p2 = v3x8_load(v[6], v[7], v[8]);
  const Vec3x8 dir = v3x8_load(d[0], d[1], d[2]), throughput = v3x8_load(tp[0], tp[1], tp[2]);
  const float8 b1 = vload8(0, hu), b2 = vload8(0, hv);
  const uint8 segment = vload8(0, seg);
  /* triangle_cross, v3_normalize */
  const Vec3x8 cross_n = v3x8_cross(v3x8_sub(p1, p0), v3x8_sub(p2, p0));
  const Vec3x8 n_geo = v3x8_scale(cross_n, 1.0f / v3x8_length(cross_n));
  /* triangle_point */
  const Vec3x8 pa = v3x8_scale(p0, 1.0f - b1 - b2), pb = v3x8_scale(p1, b1), pc = v3x8_scale(p2, b2);
  const float8 magnitude = v3x8_max_component(v3x8_add(v3x8_add(v3x8_abs(pa), v3x8_abs(pb)), v3x8_abs(pc)));
  const Vec3x8 pos = v3x8_add(v3x8_add(pa, pb), pc);
  /* triangle_edge_error, surface_offset */
  const Vec3x8 e0 = v3x8_sub(p1, p0), e1 = v3x8_sub(p2, p0), e2 = v3x8_sub(p2, p1);
  const float8 l = sqrt(fmax(v3x8_dot(e0, e0), fmax(v3x8_dot(e1, e1), v3x8_dot(e2, e2))));
  const float8 edge_error = l * fmin(l * l / v3x8_length(cross_n), RAY_OFFSET_MAX_ASPECT);
  const float8 offset = fmax(RAY_OFFSET_SCALE * (magnitude + edge_error), 0x1p-126f);
  /* emitted_radiance_at: one-sided emission only towards the front; added with weight 1 (no NEE) */
  Vec3x8 le = v3x8_load(emit[0], emit[1], emit[2]);
  const int8 back = (convert_int8(vload8(0, two_sided)) == 0) & (v3x8_dot(n_geo, v3x8_neg(dir)) <= 0.0f);
  le = v3x8_select(le, v3x8(0.0f, 0.0f, 0.0f), back);
  Vec3x8 radiance = v3x8_load(rad[0], rad[1], rad[2]);
  radiance = v3x8_select(radiance, v3x8_add(radiance, v3x8_scale(v3x8_mul(throughput, le), 1.0f)),
                         v3x8_max_component(le) > 0.0f);
  /* the BSDF stream: rng_at, then u_select, u_lobe, u1, u2 (the diffuse lobe reads u1 and u2) */
  uint8 state = pcg_hash8(vload8(0, key) ^ (segment * 16u + RNG_BSDF));
  (void)rng_next8(&state);
  (void)rng_next8(&state);
  const float8 u1 = rng_next8(&state), u2 = rng_next8(&state);
  /* frame_from_normal (onb_from_normal), frame_to_local */
  const float8 sign = select((float8)(-1.0f), (float8)(1.0f), n_geo.z >= 0.0f);
  const float8 a = -1.0f / (sign + n_geo.z);
  const float8 c = n_geo.x * n_geo.y * a;
  const Vec3x8 ft = v3x8(1.0f + sign * n_geo.x * n_geo.x * a, sign * c, -sign * n_geo.x);
  const Vec3x8 fb = v3x8(c, sign + n_geo.y * n_geo.y * a, -n_geo.y);
  const Vec3x8 to_viewer = v3x8_neg(dir);
  const float8 wi_z = v3x8_dot(to_viewer, n_geo);
  /* bsdf_sample of the Lambertian: mirrored below the surface (bsdf_side), a cosine direction
   * (sample_cosine_local) with pdf wo.z / pi, none where wi.z is not above 0 or the pdf is 0 */
  const float8 side = select((float8)(1.0f), (float8)(-1.0f), wi_z < 0.0f);
  float8 sin_phi, cos_phi;
  sincos_2pi8(u2, &sin_phi, &cos_phi);
  const float8 r = sqrt(u1);
  Vec3x8 wo = v3x8(r * cos_phi, r * sin_phi, sqrt(fmax(1.0f - u1, 0.0f)));
  const float8 pdf = wo.z * CO_INV_PI;
  const int8 sampled = (wi_z * side > 0.0f) & (pdf > 0.0f);
  Vec3x8 weight = v3x8_select(v3x8(0.0f, 0.0f, 0.0f), v3x8_load(base[0], base[1], base[2]), sampled);
  wo.z = select(1.0f, wo.z, sampled) * side; /* bsdf_no_sample's wo is (0, 0, 1) */
  const Vec3x8 next_throughput = v3x8_mul(throughput, weight);
  const int8 max_depth_reached = (int8)(p->max_depth != 0u ? -1 : 0) & convert_int8(segment >= p->max_depth);
  const int8 ends = max_depth_reached | ~sampled | (wo.z == 0.0f) | (v3x8_max_component(next_throughput) <= 0.0f);
  /* offset_origin, frame_to_world */
  const float8 off = select(-offset, offset, wo.z > 0.0f);
  const Vec3x8 org = v3x8(pos.x + n_geo.x * off, pos.y + n_geo.y * off, pos.z + n_geo.z * off);
  const Vec3x8 next_dir = v3x8_add(v3x8_add(v3x8_scale(ft, wo.x), v3x8_scale(fb, wo.y)), v3x8_scale(n_geo, wo.z));
  float o_rad[3][SHADE_BATCH], o_tp[3][SHADE_BATCH], o_org[3][SHADE_BATCH], o_dir[3][SHADE_BATCH];
  float o_pdf[SHADE_BATCH];
  int o_ends[SHADE_BATCH];
  vstore8(radiance.x, 0, o_rad[0]); vstore8(radiance.y, 0, o_rad[1]); vstore8(radiance.z, 0, o_rad[2]);
  vstore8(next_throughput.x, 0, o_tp[0]); vstore8(next_throughput.y, 0, o_tp[1]); vstore8(next_throughput.z, 0, o_tp[2]);
  vstore8(org.x, 0, o_org[0]); vstore8(org.y, 0, o_org[1]); vstore8(org.z, 0, o_org[2]);
  vstore8(next_dir.x, 0, o_dir[0]); vstore8(next_dir.y, 0, o_dir[1]); vstore8(next_dir.z, 0, o_dir[2]);
  vstore8(pdf, 0, o_pdf);
  vstore8(ends, 0, o_ends);
  for (uint32_t j = 0u; j < n; ++j) {
    if (hits[j].triangle == HIT_NONE) continue;
    PathState* ps = &st[walked[j]];
    ps->radiance = v3(o_rad[0][j], o_rad[1][j], o_rad[2][j]);
    if (o_ends[j]) {
      ps->status = PATH_TERMINATED;
      continue;
    }
    ps->throughput = v3(o_tp[0][j], o_tp[1][j], o_tp[2][j]);
    ps->prev_bsdf_pdf = o_pdf[j];
    ps->org = v3(o_org[0][j], o_org[1][j], o_org[2][j]);
    ps->prev_pos = ps->org;
    ps->dir = v3(o_dir[0][j], o_dir[1][j], o_dir[2][j]);
    ps->segment = ps->segment + 1u;
  }
}

/* Whether the paths' hits at `segment` are shaded as path_shade_diffuse8 shades them: no shadow ray
 * and no roulette follows them. */
CO_INLINE int diffuse8_shades(const SceneView* s, const RenderParams* p, uint32_t segment) {
  return !nee_enabled(s, p) && !((p->flags & RENDER_FLAG_RUSSIAN_ROULETTE) && segment >= p->rr_depth);
}

/* Whether the camera's eye lies in the scene's box: an interior view, whose paths mostly live to
 * their last segment. */
CO_INLINE int camera_inside_scene(const RenderParams* p) {
  const co_float4 e = p->camera.eye;
  return e.x >= p->scene_min.x && e.x <= p->scene_max.x && e.y >= p->scene_min.y && e.y <= p->scene_max.y &&
         e.z >= p->scene_min.z && e.z <= p->scene_max.z;
}

/* The hits[k] of paths slot[k] (k < m) shaded: eight to a vector where no shadow ray and no
 * roulette follows them (diffuse8_shades at the paths' segment), some path hit something and more
 * than SHADE_SCALAR_MOST paths are shaded (fewer cost more as a vector than one by one); else, and a
 * lane that missed, by path_shade. */
CO_INLINE void shade_paths8(const SceneView* s, const RenderParams* p, uint32_t m, const uint32_t* slot,
                            const uint32_t* keys, const HitOut* hits, PathState* st) {
  uint32_t some = HIT_NONE, segment = 0u;
  for (uint32_t k = 0u; k < m; ++k) {
    some = hits[k].triangle != HIT_NONE ? hits[k].triangle : some;
    segment = co_umax(segment, st[slot[k]].segment);
  }
  const int vector = some != HIT_NONE && m > SHADE_SCALAR_MOST && diffuse8_shades(s, p, segment);
  if (vector) path_shade_diffuse8(s, p, m, slot, keys, hits, some, st);
  for (uint32_t k = 0u; k < m; ++k)
    if (!vector || hits[k].triangle == HIT_NONE) (void)path_shade(s, p, &st[slot[k]], hits[k], keys[slot[k]]);
}

/* A batch's n >= 2 paths to their ends where no shadow ray and no roulette follows their camera
 * hits: the camera hits shaded eight to a vector; then, in an interior view (camera_inside_scene),
 * bounce by bounce while at least BY_BOUNCE_LEAST paths live (their rays walked in pairs, their hits
 * shaded eight to a vector where no roulette follows them); the paths left (all of them, in an
 * exterior view) in refilled pairs (trace_paths_paired). Path j is the batch's sample walked[j]
 * with state st[walked[j]] and stream key keys[walked[j]]; its camera ray met camera_hits[j] after
 * camera_steps[j] visits; its result goes to results[walked[j]]. Returns 0, having done nothing,
 * where a shadow ray or roulette follows the camera hits (then the paths are trace_paths_paired's).
 * Why the view decides: in an interior most paths live to their last segment, so a round shades
 * eight; on an exterior most paths end at their first or second bounce. Bounce by bounce on every
 * view gave the Sponza interior 1.12x but the exteriors 0.87-1.01x, where the refilled pairs keep
 * their walks going (docs/design.md, "Interior views go on bounce by bounce"). Each path computes
 * what trace_path computes for it. */
CO_INLINE int trace_paths_diffuse(const SceneView* s, const RenderParams* p, uint32_t n, const uint32_t* walked,
                                  const uint32_t* keys, const HitOut* camera_hits, const uint32_t* camera_steps,
                                  PathState* st, PathResult* results) {
  if (!diffuse8_shades(s, p, 1u)) return 0; /* the camera hits' segment */
  shade_paths8(s, p, n, walked, keys, camera_hits, st);
  PathResult r[SHADE_BATCH];
  for (uint32_t j = 0u; j < n; ++j) {
    r[j] = path_result_none();
    path_count_ray(&r[j], camera_steps[j]);
  }
  uint32_t handed = 0u; /* the paths whose results trace_paths_paired or path_continue wrote, path j in bit j */
  const uint32_t least = camera_inside_scene(p) ? BY_BOUNCE_LEAST : SHADE_BATCH + 1u;
  for (;;) {
    uint32_t live[SHADE_BATCH], slot[SHADE_BATCH], m = 0u;
    for (uint32_t j = 0u; j < n; ++j)
      if (st[walked[j]].status == PATH_ALIVE) {
        live[m] = j;
        slot[m++] = walked[j];
      }
    if (m < least) {
      /* the few paths left: in refilled pairs, or alone */
      PathResult begun[SHADE_BATCH];
      for (uint32_t k = 0u; k < m; ++k) begun[k] = r[live[k]];
      if (m >= 2u) {
        trace_paths_paired(s, p, m, slot, st, keys, 0, 0, begun, results);
      } else if (m == 1u) {
        path_continue(s, p, &st[slot[0]], keys[slot[0]], &begun[0]);
        results[slot[0]] = begun[0];
      }
      for (uint32_t k = 0u; k < m; ++k) handed |= 1u << live[k];
      break;
    }
    HitOut hits[SHADE_BATCH];
    for (uint32_t k = 0u; k < m; k += 2u) {
      const PathState* a = &st[slot[k]];
      Bvh8fWalk wa, wb;
      bvh8f_walk_start(&s->tree, &wa, a->org, a->dir, 0.0f, INFINITY, 0);
      if (k + 1u < m) {
        const PathState* b = &st[slot[k + 1u]];
        bvh8f_walk_start(&s->tree, &wb, b->org, b->dir, 0.0f, INFINITY, 0);
        bvh8f_trace_pair(&s->tree, &wa, &wb);
        hits[k + 1u] = wb.hit;
        path_count_ray(&r[live[k + 1u]], wb.count);
      } else {
        bvh8f_walk_run(&s->tree, &wa);
      }
      hits[k] = wa.hit;
      path_count_ray(&r[live[k]], wa.count);
    }
    shade_paths8(s, p, m, slot, keys, hits, st);
  }
  for (uint32_t j = 0u; j < n; ++j)
    if (!((handed >> j) & 1u)) {
      r[j].radiance = st[walked[j]].radiance;
      results[walked[j]] = r[j];
    }
  return 1;
}
#elif defined(COHORT_NAIVE_PAIRS)
/* a program with other materials or features: the paths are trace_paths_paired's */
CO_INLINE int trace_paths_diffuse(const SceneView* s, const RenderParams* p, uint32_t n, const uint32_t* walked,
                                  const uint32_t* keys, const HitOut* camera_hits, const uint32_t* camera_steps,
                                  PathState* st, PathResult* results) {
  (void)s; (void)p; (void)n; (void)walked; (void)keys; (void)camera_hits; (void)camera_steps; (void)st; (void)results;
  return 0;
}
#endif

#endif
