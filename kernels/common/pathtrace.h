/* The reference estimator: unidirectional path tracing with next-event estimation on emissive
 * triangles and multiple importance sampling (power heuristic), Russian roulette, and a depth
 * counted in path segments as Mitsuba's max_depth (1 = emitters seen directly). Surfaces are
 * two-sided Lambertian with albedo = base colour at this stage. */
#ifndef COHORT_PATHTRACE_H
#define COHORT_PATHTRACE_H

#include "common/camera.h"
#include "common/rng.h"
#include "common/scene_view.h"

typedef struct PathResult {
  co_vec3 radiance;
  uint32_t rays;
} PathResult;

/* Direct light at p from one emitter sample (NEE), MIS-weighted against BSDF sampling. */
CO_INLINE co_vec3 sample_direct_light(const SceneView* s, const RenderParams* p, Rng* rng, co_vec3 pos,
                                      co_vec3 n, co_vec3 albedo, uint32_t* rays) {
  co_vec3 zero = v3_splat(0.0f);
  float u_pick = rng_next(rng), u1 = rng_next(rng), u2 = rng_next(rng);
  uint32_t e = pick_emitter(s, u_pick);
  EmitterEntry entry = s->emitters[e];
  CO_GLOBAL const Triangle* tri = &s->tree.triangles[entry.triangle];
  const CO_GLOBAL Material* m = &s->materials[s->triangle_material[entry.triangle]];
  float b1, b2;
  sample_triangle(u1, u2, &b1, &b2);
  co_vec3 p0 = v3_from4(tri->v0);
  co_vec3 e1 = v3_sub(v3_from4(tri->v1), p0), e2 = v3_sub(v3_from4(tri->v2), p0);
  co_vec3 pl = v3_add(p0, v3_add(v3_scale(e1, b1), v3_scale(e2, b2)));
  co_vec3 nl = v3_normalize(v3_cross(e1, e2));
  co_vec3 to_light = v3_sub(pl, pos);
  float dist2 = v3_dot(to_light, to_light);
  if (!(dist2 > 0.0f)) return zero;
  float dist = sqrt(dist2);
  co_vec3 wi = v3_scale(to_light, 1.0f / dist);
  float cos_s = v3_dot(n, wi);
  if (cos_s <= 0.0f) return zero;
  co_vec3 le = emitted_radiance(m, nl, v3_neg(wi));
  if (v3_max_component(le) <= 0.0f) return zero;

  /* the shadow ray leaves from the offset origin and stops one epsilon short of the light, so
   * neither the receiver's nor the light's own triangle can occlude the sample */
  co_vec3 origin = v3_madd(pos, n, p->ray_epsilon);
  co_vec3 shadow = v3_sub(pl, origin);
  float shadow_len = v3_length(shadow);
  if (!(shadow_len > 2.0f * p->ray_epsilon)) return zero;
  *rays += 1u;
  HitOut occ = kd_trace(&s->tree, origin, v3_scale(shadow, 1.0f / shadow_len), 0.0f, shadow_len - p->ray_epsilon, 1);
  if (occ.triangle != HIT_NONE) return zero;

  float pdf_light = light_pdf_solid_angle(s, m, entry.area, pos, pl, nl);
  float weight = (p->flags & RENDER_FLAG_MIS) ? mis_power(pdf_light, cos_s * CO_INV_PI) : 1.0f;
  /* estimator divides by the probability the table actually used to pick this triangle */
  float pdf_pick = entry.pmf * dist2 / (entry.area * fabs(v3_dot(nl, wi)));
  float scale = cos_s * CO_INV_PI * weight / pdf_pick;
  return v3_scale(v3_mul(albedo, le), scale);
}

CO_INLINE PathResult trace_path(const SceneView* s, const RenderParams* p, uint32_t pixel, uint32_t sample) {
  PathResult result;
  result.radiance = v3_splat(0.0f);
  result.rays = 0u;
  uint32_t x = pixel % p->width, y = pixel / p->width;
  Rng cam_rng = rng_make(p->seed, pixel, sample, 0u, RNG_CAMERA);
  float jx = rng_next(&cam_rng), jy = rng_next(&cam_rng);
  co_vec3 org = v3_from4(p->camera.eye);
  co_vec3 dir = camera_direction(&p->camera, p->width, p->height, x, y, jx, jy);
  co_vec3 throughput = v3_splat(1.0f);
  int nee = (p->flags & RENDER_FLAG_NEE) && s->emitter_count > 0u;
  float prev_bsdf_pdf = 0.0f; /* 0: the previous vertex was the camera */
  co_vec3 prev_pos = org;

  for (uint32_t segment = 1u;; ++segment) {
    result.rays += 1u;
    HitOut hit = kd_trace(&s->tree, org, dir, 0.0f, INFINITY, 0);
    if (hit.triangle == HIT_NONE) {
      if (p->flags & RENDER_FLAG_ENVIRONMENT)
        result.radiance = v3_add(result.radiance, v3_mul(throughput, v3_from4(p->environment)));
      break;
    }
    CO_GLOBAL const Triangle* tri = &s->tree.triangles[hit.triangle];
    const CO_GLOBAL Material* m = &s->materials[s->triangle_material[hit.triangle]];
    co_vec3 cross_n = triangle_cross(tri);
    co_vec3 n_geo = v3_normalize(cross_n);
    co_vec3 pos = v3_madd(org, dir, hit.t);

    co_vec3 le = emitted_radiance(m, n_geo, v3_neg(dir));
    if (v3_max_component(le) > 0.0f) {
      float w = 1.0f;
      if (prev_bsdf_pdf > 0.0f && nee) {
        if (p->flags & RENDER_FLAG_MIS) {
          float area = 0.5f * v3_length(cross_n);
          w = mis_power(prev_bsdf_pdf, light_pdf_solid_angle(s, m, area, prev_pos, pos, n_geo));
        } else {
          w = 0.0f; /* NEE alone accounts for emitters after the first segment */
        }
      }
      result.radiance = v3_add(result.radiance, v3_scale(v3_mul(throughput, le), w));
    }
    if (p->max_depth != 0u && segment >= p->max_depth) break;

    co_vec3 n = v3_dot(n_geo, dir) < 0.0f ? n_geo : v3_neg(n_geo); /* two-sided: face the ray */
    co_vec3 albedo = v3_from4(m->base_color);
    if (nee) {
      Rng light_rng = rng_make(p->seed, pixel, sample, segment, RNG_LIGHT);
      co_vec3 direct = sample_direct_light(s, p, &light_rng, pos, n, albedo, &result.rays);
      result.radiance = v3_add(result.radiance, v3_mul(throughput, direct));
    }
    if ((p->flags & RENDER_FLAG_RUSSIAN_ROULETTE) && segment >= p->rr_depth) {
      Rng rr_rng = rng_make(p->seed, pixel, sample, segment, RNG_ROULETTE);
      float q = fmin(v3_max_component(throughput), 0.95f);
      if (!(rng_next(&rr_rng) < q)) break;
      throughput = v3_scale(throughput, 1.0f / q);
    }
    Rng bsdf_rng = rng_make(p->seed, pixel, sample, segment, RNG_BSDF);
    float u1 = rng_next(&bsdf_rng), u2 = rng_next(&bsdf_rng);
    co_vec3 wi = sample_cosine_hemisphere(n, u1, u2);
    float cos_i = v3_dot(wi, n);
    if (!(cos_i > 0.0f)) break;
    throughput = v3_mul(throughput, albedo); /* f cos / pdf = albedo for Lambertian */
    if (v3_max_component(throughput) <= 0.0f) break;
    prev_bsdf_pdf = cos_i * CO_INV_PI;
    prev_pos = pos;
    org = v3_madd(pos, n, p->ray_epsilon);
    dir = wi;
  }
  return result;
}

#endif
