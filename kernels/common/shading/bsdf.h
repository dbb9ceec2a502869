/* BSDFs in the local shading frame, plain C for OpenCL C 1.2 and host C++. docs/bsdf.md has the
 * formulas, the conventions and the tests.
 *
 * Conventions (those of Mitsuba 3, so its formulas and results carry over):
 *   - Local frame: z = shading normal, oriented as the mesh says (front = exterior). Reflection-only
 *     BSDFs (diffuse, conductor, plastic) are two-sided: a wi below the surface is mirrored through
 *     it (wo with it), so a caller may also face-forward the frame for them. Dielectrics need the
 *     true orientation: z > 0 is the exterior, IOR 1.
 *   - wi points towards the previous path vertex (the camera side), wo is the sampled / light
 *     direction; both unit, pointing away from the surface.
 *   - bsdf_eval(b, wi, wo) = f(wi, wo) |cos theta_o|   (the throughput contribution)
 *   - bsdf_pdf(b, wi, wo)  = solid-angle density of bsdf_sample choosing wo (non-delta lobes only)
 *   - bsdf_sample(b, wi, u_lobe, u1, u2): wo, weight = eval / pdf, pdf, eta, flags. Delta lobes
 *     (smooth surfaces) have eval = pdf = 0 in bsdf_eval/bsdf_pdf; their sample carries
 *     BSDF_DELTA, the weight, and as pdf the discrete probability of choosing that lobe.
 *   - Refraction scales radiance by (eta_i / eta_t)^2 (Veach 1997, sec. 5.2): the weight of a
 *     refracted sample (and bsdf_eval of rough transmission) includes it; sample.eta = eta_t / eta_i
 *     lets a caller that transports importance or energy undo it (multiply by eta^2).
 *   - Random numbers come in as arguments: no RNG inside, so results are a pure function of input. */
#ifndef COHORT_BSDF_H
#define COHORT_BSDF_H

#include "common/shading/microfacet.h"
#include "common/core/types.h"

/* ---- Families compiled --------------------------------------------------------------------------
 * A rendering program is specialised to its scene: pathtrace.h defines COHORT_BSDF_SPECIALISED and
 * the host passes -DCOHORT_FEATURE_CONDUCTOR / _DIELECTRIC / _PLASTIC for the families the scene's
 * materials can select (runtime/render/scene/device_scene.cpp, with the rules of bsdf_from_gltf); the
 * Lambertian is always compiled. Everything else (host code, bsdf_test.cl) compiles every family. */
#if defined(COHORT_BSDF_SPECIALISED) && !defined(COHORT_FEATURE_CONDUCTOR)
#define BSDF_WITH_CONDUCTOR 0
#else
#define BSDF_WITH_CONDUCTOR 1
#endif
#if defined(COHORT_BSDF_SPECIALISED) && !defined(COHORT_FEATURE_DIELECTRIC)
#define BSDF_WITH_DIELECTRIC 0
#else
#define BSDF_WITH_DIELECTRIC 1
#endif
#if defined(COHORT_BSDF_SPECIALISED) && !defined(COHORT_FEATURE_PLASTIC)
#define BSDF_WITH_PLASTIC 0
#else
#define BSDF_WITH_PLASTIC 1
#endif
/* the sheen layer (KHR_materials_sheen, sheen.h): -DCOHORT_FEATURE_SHEEN */
#if defined(COHORT_BSDF_SPECIALISED) && !defined(COHORT_FEATURE_SHEEN)
#define BSDF_WITH_SHEEN 0
#else
#define BSDF_WITH_SHEEN 1
#endif

/* glTF's clearcoat layer (BSDF_COAT) only with COHORT_FEATURE_CLEARCOAT (shading/clearcoat.h) */
#if defined(COHORT_BSDF_SPECIALISED) && !defined(COHORT_FEATURE_CLEARCOAT)
#define BSDF_WITH_COAT 0
#else
#define BSDF_WITH_COAT 1
#endif
/* glTF's specular layer (BSDF_SPECULAR, KHR_materials_specular) only with COHORT_FEATURE_SPECULAR
 * (shading/specular.h) */
#if defined(COHORT_BSDF_SPECIALISED) && !defined(COHORT_FEATURE_SPECULAR)
#define BSDF_WITH_SPECULAR 0
#else
#define BSDF_WITH_SPECULAR 1
#endif

/* ---- Shading frame --------------------------------------------------------------------------- */

/* n is the shading normal. With normal maps (COHORT_FEATURE_NORMAL_MAP) ng is the geometric one,
 * which decides the side a direction leaves from (ray offsets, docs/bsdf.md "Normal maps");
 * without them the two are the same, and a program keeps one (frame_geometric_normal). */
typedef struct ShadingFrame {
  co_vec3 t, b, n;
#ifdef COHORT_FEATURE_NORMAL_MAP
  co_vec3 ng;
#endif
} ShadingFrame;
#ifdef COHORT_FEATURE_NORMAL_MAP
#define frame_geometric_normal(f) ((f)->ng)
#else
#define frame_geometric_normal(f) ((f)->n)
#endif

CO_INLINE ShadingFrame frame_from_normal(co_vec3 n) {
  ShadingFrame f;
  f.n = n;
#ifdef COHORT_FEATURE_NORMAL_MAP
  f.ng = n;
#endif
  onb_from_normal(n, &f.t, &f.b);
  return f;
}
CO_INLINE co_vec3 frame_to_local(const ShadingFrame* f, co_vec3 v) {
  return v3(v3_dot(v, f->t), v3_dot(v, f->b), v3_dot(v, f->n));
}
CO_INLINE co_vec3 frame_to_world(const ShadingFrame* f, co_vec3 v) {
  return v3_add(v3_add(v3_scale(f->t, v.x), v3_scale(f->b, v.y)), v3_scale(f->n, v.z));
}

/* ---- BSDF description ------------------------------------------------------------------------ */

#define BSDF_DIFFUSE 0u    /* Lambertian, albedo = color */
#define BSDF_CONDUCTOR 1u  /* GGX conductor, Schlick Fresnel with F0 = color; smooth when alpha = 0 */
#define BSDF_DIELECTRIC 2u /* smooth or GGX (Walter 2007) dielectric; color tints transmission */
#define BSDF_PLASTIC 3u    /* diffuse color under a dielectric coat (Mitsuba's plastic, nonlinear=false) */
#define BSDF_COAT 4u       /* the plastic's coat alone, times spec_weight: glTF's clearcoat layer */
#if BSDF_WITH_SHEEN
#define BSDF_SHEEN 5u      /* the sheen lobe alone, color = sheenColor over its selection probability (sheen.h) */
#endif
#define BSDF_SPECULAR 6u   /* glTF's tinted specular reflection alone (KHR_materials_specular), times spec_weight */

/* GGX alpha below which a surface is smooth (delta lobes): the GGX lobe would be narrower than
 * float sampling resolves well, and its peak D = 1/(pi alpha^2) would pass 3e5. */
#define BSDF_SMOOTH_ALPHA 1e-3f

/* Lobe flags of a sample; 0 = no sample (the path ends). */
#define BSDF_REFLECTION 1u
#define BSDF_TRANSMISSION 2u
#define BSDF_DELTA 4u
#define BSDF_GLOSSY 8u
#define BSDF_DIFFUSE_LOBE 16u

typedef struct Bsdf {
  uint32_t type;
  float alpha;       /* GGX alpha = roughness^2; 0 = smooth */
  float eta;         /* dielectric and plastic: interior IOR / exterior IOR */
  float spec_weight; /* plastic: Mitsuba's specular_sampling_weight = 1 / (1 + mean(color));
                      * coat: the scale of the layer (clearcoat factor over its selection probability);
                      * specular: the scale of the lobe (1 over its selection probability) */
  co_vec3 color;     /* see the types above; specular: f0' = min(f0(eta) specularColor, 1) specular */
  float fdr_int;     /* plastic: F_dr(1/eta), diffuse reflectance of the coat seen from inside;
                      * specular: f90' = specular */
} Bsdf;
CO_STATIC_ASSERT(sizeof(Bsdf) == 32, "Bsdf is shared with bsdf_test.cl");

typedef struct BsdfSample {
  co_vec3 wo;
  co_vec3 weight; /* eval / pdf; for delta lobes the lobe's value over its probability */
  float pdf;      /* solid angle density, or the lobe's discrete probability with BSDF_DELTA */
  float eta;      /* eta_t / eta_i for transmission, 1 for reflection */
  uint32_t flags;
} BsdfSample;
CO_STATIC_ASSERT(sizeof(BsdfSample) == 36, "BsdfSample is shared with bsdf_test.cl");

CO_INLINE float bsdf_snap_alpha(float alpha) { return alpha < BSDF_SMOOTH_ALPHA ? 0.0f : fmin(alpha, 1.0f); }

CO_INLINE Bsdf bsdf_make(uint32_t type, co_vec3 color, float alpha, float eta) {
  Bsdf b;
  b.type = type;
  b.alpha = bsdf_snap_alpha(alpha);
  b.eta = eta;
  b.color = color;
  b.spec_weight = 1.0f / (1.0f + (color.x + color.y + color.z) * (1.0f / 3.0f));
  b.fdr_int = fresnel_diffuse_reflectance(1.0f / eta);
  return b;
}
CO_INLINE Bsdf bsdf_diffuse(co_vec3 albedo) { return bsdf_make(BSDF_DIFFUSE, albedo, 1.0f, 1.0f); }
CO_INLINE Bsdf bsdf_conductor(co_vec3 f0, float alpha) { return bsdf_make(BSDF_CONDUCTOR, f0, alpha, 1.0f); }
CO_INLINE Bsdf bsdf_dielectric(float eta, float alpha, co_vec3 tint) {
  return bsdf_make(BSDF_DIELECTRIC, tint, alpha, eta);
}
CO_INLINE Bsdf bsdf_plastic(co_vec3 diffuse, float eta, float alpha) {
  return bsdf_make(BSDF_PLASTIC, diffuse, alpha, eta);
}

CO_INLINE int bsdf_has_transmission(const Bsdf* b) { return b->type == BSDF_DIELECTRIC; }
/* True when every lobe is a delta: NEE cannot help, and MIS must not weigh the hit. */
CO_INLINE int bsdf_is_delta(const Bsdf* b) {
  return (b->type == BSDF_CONDUCTOR || b->type == BSDF_DIELECTRIC
#if BSDF_WITH_COAT
          || b->type == BSDF_COAT
#endif
#if BSDF_WITH_SPECULAR
          || b->type == BSDF_SPECULAR
#endif
          ) && b->alpha < BSDF_SMOOTH_ALPHA;
}

CO_INLINE BsdfSample bsdf_no_sample(void) {
  BsdfSample s;
  s.wo = v3(0.0f, 0.0f, 1.0f);
  s.weight = v3_splat(0.0f);
  s.pdf = 0.0f;
  s.eta = 1.0f;
  s.flags = 0u;
  return s;
}

/* ---- Lambertian -------------------------------------------------------------------------------- */

CO_INLINE co_vec3 diffuse_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return v3_splat(0.0f);
  return v3_scale(b->color, wo.z * CO_INV_PI);
}
CO_INLINE float diffuse_pdf(co_vec3 wi, co_vec3 wo) {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
  return wo.z * CO_INV_PI;
}
/* Cosine-weighted direction in the local frame (Malley's method); z >= 2^-12 for u1 < 1. */
CO_INLINE co_vec3 sample_cosine_local(float u1, float u2) {
  float r = sqrt(u1);
  float sin_phi, cos_phi;
  co_sincos_2pi(u2, &sin_phi, &cos_phi);
  return v3(r * cos_phi, r * sin_phi, co_safe_sqrt(1.0f - u1));
}
CO_INLINE BsdfSample diffuse_sample(const Bsdf* b, co_vec3 wi, float u1, float u2) {
  BsdfSample s = bsdf_no_sample();
  if (!(wi.z > 0.0f)) return s;
  s.wo = sample_cosine_local(u1, u2);
  s.pdf = s.wo.z * CO_INV_PI;
  if (!(s.pdf > 0.0f)) return bsdf_no_sample();
  s.weight = b->color; /* (color/pi) cos / (cos/pi) */
  s.flags = BSDF_REFLECTION | BSDF_DIFFUSE_LOBE;
  return s;
}

/* ---- Conductor ----------------------------------------------------------------------------------
 * Rough: f = F(wi.m) D(m) G2(wi, wo) / (4 cos_i cos_o) with m = normalize(wi + wo); sampled through
 * the visible normals, so pdf = D_wi(m) / (4 wi.m) = G1(wi) D(m) / (4 cos_i) and the weight
 * reduces to F G2 / G1(wi). Smooth: delta reflection with weight F(cos_i). */

CO_INLINE co_vec3 conductor_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (b->alpha < BSDF_SMOOTH_ALPHA || !(wi.z > 0.0f) || !(wo.z > 0.0f)) return v3_splat(0.0f);
  co_vec3 m = v3_normalize(v3_add(wi, wo));
  float d = ggx_d(m, b->alpha);
  float g = ggx_g2(wi, wo, m, b->alpha);
  co_vec3 f = fresnel_schlick(b->color, v3_dot(wi, m));
  return v3_scale(f, d * g / (4.0f * wi.z));
}
/* Density of a reflection about the visible normal m: D_wi(m) times the Jacobian 1 / (4 wo.m). */
CO_INLINE float microfacet_reflection_pdf(co_vec3 wi, co_vec3 wo, float alpha) {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
  co_vec3 m = v3_normalize(v3_add(wi, wo));
  float dwo = v3_dot(wo, m);
  if (!(dwo > 0.0f)) return 0.0f;
  return ggx_vndf_pdf(wi, m, alpha) / (4.0f * dwo);
}
/* A reflection about a visible normal m sampled from wi (Heitz 2018), with what a rough reflector's
 * weight needs besides its Fresnel term: wo, its pdf D_wi(m) / (4 wi.m), wi.m and G2 / G1(wi).
 * 0 when wo falls below the surface (the single-scattering energy loss) or the pdf vanishes. */
typedef struct MicrofacetReflection {
  co_vec3 wo;
  float pdf, dwi, shadowing;
} MicrofacetReflection;
CO_INLINE int microfacet_reflection_sample(co_vec3 wi, float alpha, float u1, float u2, MicrofacetReflection* r) {
  co_vec3 m = ggx_sample_vndf(wi, alpha, u1, u2);
  co_vec3 wo = v3_reflect(wi, m);
  if (!(wo.z > 0.0f)) return 0;
  float dwi = v3_dot(wi, m);
  float pdf = ggx_vndf_pdf(wi, m, alpha) / (4.0f * dwi);
  float g1 = ggx_g1(wi, m, alpha);
  if (!(pdf > 0.0f) || !(g1 > 0.0f)) return 0;
  r->wo = wo;
  r->pdf = pdf;
  r->dwi = dwi;
  r->shadowing = ggx_g2(wi, wo, m, alpha) / g1;
  return 1;
}
/* The pdf of a reflector that is a delta mirror when smooth and else samples GGX's visible normals:
 * the conductor, the coat and the specular layer alike. */
CO_INLINE float glossy_reflection_pdf(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (b->alpha < BSDF_SMOOTH_ALPHA) return 0.0f;
  return microfacet_reflection_pdf(wi, wo, b->alpha);
}
CO_INLINE BsdfSample conductor_sample(const Bsdf* b, co_vec3 wi, float u1, float u2) {
  BsdfSample s = bsdf_no_sample();
  if (!(wi.z > 0.0f)) return s;
  if (b->alpha < BSDF_SMOOTH_ALPHA) {
    s.wo = v3(-wi.x, -wi.y, wi.z);
    s.weight = fresnel_schlick(b->color, wi.z);
    s.pdf = 1.0f;
    s.flags = BSDF_REFLECTION | BSDF_DELTA;
    return s;
  }
  MicrofacetReflection r;
  if (!microfacet_reflection_sample(wi, b->alpha, u1, u2, &r)) return s;
  s.wo = r.wo;
  s.pdf = r.pdf;
  s.weight = v3_scale(fresnel_schlick(b->color, r.dwi), r.shadowing);
  s.flags = BSDF_REFLECTION | BSDF_GLOSSY;
  return s;
}

/* ---- Dielectric ---------------------------------------------------------------------------------
 * Smooth: reflection with probability F (weight 1) and refraction with probability 1 - F (weight
 * tint (eta_i/eta_t)^2), F exact (fresnel_dielectric), total internal reflection included.
 * Rough: Walter et al. 2007 with GGX, as Mitsuba's roughdielectric: the visible normal m is sampled
 * from the side of wi, then reflection with probability F(wi.m) or refraction. With the generalised
 * half vector m = normalize(wi + eta_r wo) (eta_r = eta_t / eta_i, wo's side over wi's side):
 *   reflection  eval = F D G2 / (4 |cos_i|),          pdf = F D_wi(m) / (4 |wo.m|)
 *   refraction  eval = (1-F) D G2 eta_r^2 |wi.m wo.m| / (|cos_i| (wi.m + eta_r wo.m)^2) / eta_r^2
 *               pdf  = (1-F) D_wi(m) eta_r^2 |wo.m| / (wi.m + eta_r wo.m)^2   (Walter eq. 17)
 * so the weight is G2 / G1(wi) (times tint / eta_r^2 for refraction). */

CO_INLINE BsdfSample dielectric_sample(const Bsdf* b, co_vec3 wi, float u_lobe, float u1, float u2) {
  BsdfSample s = bsdf_no_sample();
  float cos_i = wi.z;
  if (cos_i == 0.0f || !(b->eta > 0.0f)) return s;
  float cos_t, eta_ti;
  if (b->alpha < BSDF_SMOOTH_ALPHA) {
    float f = fresnel_dielectric(cos_i, b->eta, &cos_t, &eta_ti);
    if (u_lobe < f) {
      s.wo = v3(-wi.x, -wi.y, wi.z);
      s.weight = v3_splat(1.0f);
      s.pdf = f;
      s.flags = BSDF_REFLECTION | BSDF_DELTA;
    } else {
      s.wo = v3(-eta_ti * wi.x, -eta_ti * wi.y, cos_t);
      s.weight = v3_scale(b->color, eta_ti * eta_ti);
      s.pdf = 1.0f - f;
      s.eta = 1.0f / eta_ti;
      s.flags = BSDF_TRANSMISSION | BSDF_DELTA;
    }
    return s;
  }
  float sign = cos_i > 0.0f ? 1.0f : -1.0f;
  co_vec3 wi_up = v3_scale(wi, sign);
  co_vec3 m = ggx_sample_vndf(wi_up, b->alpha, u1, u2);
  float dwi = v3_dot(wi, m);
  float f = fresnel_dielectric(dwi, b->eta, &cos_t, &eta_ti);
  float g1 = ggx_g1(wi_up, m, b->alpha);
  float vis = ggx_vndf_pdf(wi_up, m, b->alpha);
  if (!(g1 > 0.0f) || !(vis > 0.0f)) return s;
  if (u_lobe < f) {
    co_vec3 wo = v3_reflect(wi, m);
    if (!(wo.z * cos_i > 0.0f)) return s;
    s.wo = wo;
    s.pdf = f * vis / (4.0f * fabs(v3_dot(wo, m)));
    s.weight = v3_splat(ggx_g2(wi, wo, m, b->alpha) / g1);
    s.flags = BSDF_REFLECTION | BSDF_GLOSSY;
  } else {
    /* refraction about m: wo = m (wi.m eta_ti + cos_t) - wi eta_ti (cos_t signed, Snell) */
    co_vec3 wo = v3_sub(v3_scale(m, dwi * eta_ti + cos_t), v3_scale(wi, eta_ti));
    if (!(wo.z * cos_i < 0.0f)) return s;
    float eta_r = 1.0f / eta_ti;
    float dwo = v3_dot(wo, m);
    float denom = dwi + eta_r * dwo;
    s.wo = wo;
    s.pdf = (1.0f - f) * vis * eta_r * eta_r * fabs(dwo) / (denom * denom);
    s.weight = v3_scale(b->color, ggx_g2(wi, wo, m, b->alpha) / g1 * (eta_ti * eta_ti));
    s.eta = eta_r;
    s.flags = BSDF_TRANSMISSION | BSDF_GLOSSY;
  }
  if (!(s.pdf > 0.0f)) return bsdf_no_sample();
  return s;
}

/* The generalised half vector of (wi, wo) turned to the upper side, with the checks shared by
 * eval and pdf: 0 when wi or wo lies in the plane or the microfacet faces away from either. */
CO_INLINE int dielectric_half_vector(const Bsdf* b, co_vec3 wi, co_vec3 wo, co_vec3* m, float* eta_r) {
  float cos_i = wi.z, cos_o = wo.z;
  if (cos_i == 0.0f || cos_o == 0.0f || b->alpha < BSDF_SMOOTH_ALPHA) return 0;
  int reflect = cos_i * cos_o > 0.0f;
  *eta_r = reflect ? 1.0f : (cos_i > 0.0f ? b->eta : 1.0f / b->eta);
  co_vec3 h = v3_madd(wi, wo, *eta_r);
  float len = v3_length(h);
  if (!(len > 0.0f)) return 0;
  h = v3_scale(h, (h.z < 0.0f ? -1.0f : 1.0f) / len);
  *m = h;
  return v3_dot(wi, h) * cos_i > 0.0f && v3_dot(wo, h) * cos_o > 0.0f;
}

CO_INLINE co_vec3 dielectric_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  co_vec3 m;
  float eta_r;
  if (!dielectric_half_vector(b, wi, wo, &m, &eta_r)) return v3_splat(0.0f);
  float d = ggx_d(m, b->alpha);
  float g = ggx_g2(wi, wo, m, b->alpha);
  float dwi = v3_dot(wi, m);
  float f = fresnel_dielectric_r(dwi, b->eta);
  if (wi.z * wo.z > 0.0f) return v3_splat(f * d * g / (4.0f * fabs(wi.z)));
  float dwo = v3_dot(wo, m);
  float denom = dwi + eta_r * dwo;
  /* Walter's BTDF times |cos_o|; the eta_r^2 of the Jacobian and the radiance scale 1/eta_r^2
   * cancel, both are kept visible */
  float value = (1.0f - f) * fabs(d * g * eta_r * eta_r * dwi * dwo / (wi.z * denom * denom));
  return v3_scale(b->color, value / (eta_r * eta_r));
}

CO_INLINE float dielectric_pdf(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  co_vec3 m;
  float eta_r;
  if (!dielectric_half_vector(b, wi, wo, &m, &eta_r)) return 0.0f;
  float sign = wi.z > 0.0f ? 1.0f : -1.0f;
  float vis = ggx_vndf_pdf(v3_scale(wi, sign), m, b->alpha);
  float dwi = v3_dot(wi, m), dwo = v3_dot(wo, m);
  float f = fresnel_dielectric_r(dwi, b->eta);
  if (wi.z * wo.z > 0.0f) return f * vis / (4.0f * fabs(dwo));
  float denom = dwi + eta_r * dwo;
  return (1.0f - f) * vis * eta_r * eta_r * fabs(dwo) / (denom * denom);
}

/* ---- Plastic ------------------------------------------------------------------------------------
 * Mitsuba's `plastic` (nonlinear = false): a smooth dielectric coat (eta) over a Lambertian base.
 *   specular: delta reflection, value F_i = F(cos_i)
 *   diffuse:  f = color / (1 - F_dr(1/eta)) * (1 - F_i) (1 - F_o) / (eta^2 pi)
 * The coat is chosen with probability p_s = F_i w / (F_i w + (1 - F_i)(1 - w)), w = 1 / (1 +
 * mean(color)), else the base (cosine-weighted). For a white base the albedo is exactly 1 up to
 * the F_dr fit, because (1 - F_dr(eta)) / eta^2 = 1 - F_dr(1/eta).
 * Rough (alpha > 0; our extension, documented in docs/bsdf.md): the coat's delta lobe becomes a GGX
 * reflection F(wi.m) D G2 / (4 cos_i cos_o) sampled by visible normals; the diffuse term keeps the
 * smooth-interface transmittances (1 - F_i)(1 - F_o); sample picks the coat with p_s and returns
 * the mixture's eval / pdf (one-sample MIS), so the weight and pdf always agree with bsdf_eval and
 * bsdf_pdf. */

CO_INLINE float plastic_spec_prob(const Bsdf* b, float f_i) {
  float ps = f_i * b->spec_weight;
  float pd = (1.0f - f_i) * (1.0f - b->spec_weight);
  return ps + pd > 0.0f ? ps / (ps + pd) : 0.5f;
}
CO_INLINE co_vec3 plastic_diffuse_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  float t_i = 1.0f - fresnel_dielectric_r(wi.z, b->eta);
  float t_o = 1.0f - fresnel_dielectric_r(wo.z, b->eta);
  float scale = t_i * t_o / (b->eta * b->eta * (1.0f - b->fdr_int)) * wo.z * CO_INV_PI;
  return v3_scale(b->color, scale);
}
CO_INLINE float plastic_coat_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  co_vec3 m = v3_normalize(v3_add(wi, wo));
  float f = fresnel_dielectric_r(v3_dot(wi, m), b->eta);
  return f * ggx_d(m, b->alpha) * ggx_g2(wi, wo, m, b->alpha) / (4.0f * wi.z);
}
CO_INLINE co_vec3 plastic_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return v3_splat(0.0f);
  co_vec3 r = plastic_diffuse_eval(b, wi, wo);
  if (b->alpha >= BSDF_SMOOTH_ALPHA) r = v3_add(r, v3_splat(plastic_coat_eval(b, wi, wo)));
  return r;
}
CO_INLINE float plastic_pdf(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
  float ps = plastic_spec_prob(b, fresnel_dielectric_r(wi.z, b->eta));
  float p = (1.0f - ps) * wo.z * CO_INV_PI;
  if (b->alpha >= BSDF_SMOOTH_ALPHA) p += ps * microfacet_reflection_pdf(wi, wo, b->alpha);
  return p;
}
CO_INLINE BsdfSample plastic_sample(const Bsdf* b, co_vec3 wi, float u_lobe, float u1, float u2) {
  BsdfSample s = bsdf_no_sample();
  if (!(wi.z > 0.0f)) return s;
  float f_i = fresnel_dielectric_r(wi.z, b->eta);
  float ps = plastic_spec_prob(b, f_i);
  int coat = u_lobe < ps;
  if (b->alpha < BSDF_SMOOTH_ALPHA) {
    if (coat) {
      s.wo = v3(-wi.x, -wi.y, wi.z);
      s.weight = v3_splat(f_i / ps);
      s.pdf = ps;
      s.flags = BSDF_REFLECTION | BSDF_DELTA;
    } else {
      s.wo = sample_cosine_local(u1, u2);
      s.pdf = (1.0f - ps) * s.wo.z * CO_INV_PI;
      if (!(s.pdf > 0.0f)) return bsdf_no_sample();
      s.weight = v3_scale(plastic_diffuse_eval(b, wi, s.wo), 1.0f / s.pdf);
      s.flags = BSDF_REFLECTION | BSDF_DIFFUSE_LOBE;
    }
    return s;
  }
  co_vec3 wo = coat ? v3_reflect(wi, ggx_sample_vndf(wi, b->alpha, u1, u2)) : sample_cosine_local(u1, u2);
  if (!(wo.z > 0.0f)) return s;
  float pdf = plastic_pdf(b, wi, wo);
  if (!(pdf > 0.0f)) return s;
  s.wo = wo;
  s.pdf = pdf;
  s.weight = v3_scale(plastic_eval(b, wi, wo), 1.0f / pdf);
  s.flags = BSDF_REFLECTION | (coat ? BSDF_GLOSSY : BSDF_DIFFUSE_LOBE);
  return s;
}

/* ---- Coat ---------------------------------------------------------------------------------------
 * glTF's clearcoat layer on its own (docs/bsdf.md, "Clearcoat"): the plastic's coat, a GGX reflection
 * F(wi.m) D G2 / (4 cos_i cos_o) of a dielectric of IOR eta with the exact Fresnel, or its delta
 * mirror of value F(cos_i) when smooth, times `scale` (spec_weight). The caller picks the layer with
 * probability q = c F(cos_i) and scales it by c / q, so the estimate is c times the layer; a smooth
 * coat's sample then weighs exactly c F / q = 1. */
#if BSDF_WITH_COAT
CO_INLINE Bsdf bsdf_coat(float eta, float alpha, float scale) {
  Bsdf b = bsdf_make(BSDF_COAT, v3_splat(0.0f), alpha, eta);
  b.spec_weight = scale;
  return b;
}
CO_INLINE co_vec3 coat_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (b->alpha < BSDF_SMOOTH_ALPHA || !(wi.z > 0.0f) || !(wo.z > 0.0f)) return v3_splat(0.0f);
  return v3_splat(b->spec_weight * plastic_coat_eval(b, wi, wo));
}
CO_INLINE BsdfSample coat_sample(const Bsdf* b, co_vec3 wi, float u1, float u2) {
  BsdfSample s = bsdf_no_sample();
  if (!(wi.z > 0.0f)) return s;
  if (b->alpha < BSDF_SMOOTH_ALPHA) {
    s.wo = v3(-wi.x, -wi.y, wi.z);
    s.weight = v3_splat(b->spec_weight * fresnel_dielectric_r(wi.z, b->eta));
    s.pdf = 1.0f;
    s.flags = BSDF_REFLECTION | BSDF_DELTA;
    return s;
  }
  MicrofacetReflection r;
  if (!microfacet_reflection_sample(wi, b->alpha, u1, u2, &r)) return s;
  s.wo = r.wo;
  s.pdf = r.pdf;
  s.weight = v3_splat(b->spec_weight * fresnel_dielectric_r(r.dwi, b->eta) * r.shadowing);
  s.flags = BSDF_REFLECTION | BSDF_GLOSSY;
  return s;
}
#endif
#if BSDF_WITH_SPECULAR
/* ---- Specular (KHR_materials_specular) ------------------------------------------------------------
 * glTF's specular reflection of the dielectric with its Fresnel term re-shaped (docs/bsdf.md,
 * "Specular"): F(cos) = f0' + (f90' - f0') s(cos), f0' = min(f0 specularColor, 1) specular (color),
 * f90' = specular (fdr_int), and s the exact dielectric Fresnel's shape between f0 = ((eta-1)/(eta+1))^2
 * and 1, s = (F_exact(cos) - f0) / (1 - f0) clamped to [0, 1], so F = F_exact where specular and its
 * colour are 1. The lobe: F(wi.m) D G2 / (4 cos_i cos_o) sampled by visible normals, or its delta
 * mirror of value F(cos_i) when smooth, times `scale` (spec_weight). The caller (specular.h) takes it
 * with probability q = max3 F(cos_i) and scale 1 / q. */
CO_INLINE Bsdf bsdf_specular(float eta, float alpha, co_vec3 f0, float f90, float scale) {
  Bsdf b = bsdf_make(BSDF_SPECULAR, f0, alpha, eta);
  b.spec_weight = scale;
  b.fdr_int = f90;
  return b;
}
/* s(cos) for a dielectric of relative IOR eta: 0 at normal incidence, 1 at grazing. */
CO_INLINE float specular_fresnel_shape(float cos_theta, float eta) {
  float r = (eta - 1.0f) / (eta + 1.0f);
  float f0 = r * r;
  if (!(f0 < 1.0f)) return 1.0f;
  float s = (fresnel_dielectric_r(cos_theta, eta) - f0) / (1.0f - f0);
  return fmin(fmax(s, 0.0f), 1.0f);
}
CO_INLINE co_vec3 specular_fresnel(co_vec3 f0, float f90, float cos_theta, float eta) {
  float s = specular_fresnel_shape(cos_theta, eta);
  return v3(f0.x + (f90 - f0.x) * s, f0.y + (f90 - f0.y) * s, f0.z + (f90 - f0.z) * s);
}
CO_INLINE co_vec3 specular_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  if (b->alpha < BSDF_SMOOTH_ALPHA || !(wi.z > 0.0f) || !(wo.z > 0.0f)) return v3_splat(0.0f);
  co_vec3 m = v3_normalize(v3_add(wi, wo));
  co_vec3 f = specular_fresnel(b->color, b->fdr_int, v3_dot(wi, m), b->eta);
  return v3_scale(f, b->spec_weight * ggx_d(m, b->alpha) * ggx_g2(wi, wo, m, b->alpha) / (4.0f * wi.z));
}
CO_INLINE BsdfSample specular_sample(const Bsdf* b, co_vec3 wi, float u1, float u2) {
  BsdfSample s = bsdf_no_sample();
  if (!(wi.z > 0.0f)) return s;
  if (b->alpha < BSDF_SMOOTH_ALPHA) {
    s.wo = v3(-wi.x, -wi.y, wi.z);
    s.weight = v3_scale(specular_fresnel(b->color, b->fdr_int, wi.z, b->eta), b->spec_weight);
    s.pdf = 1.0f;
    s.flags = BSDF_REFLECTION | BSDF_DELTA;
    return s;
  }
  MicrofacetReflection r;
  if (!microfacet_reflection_sample(wi, b->alpha, u1, u2, &r)) return s;
  s.wo = r.wo;
  s.pdf = r.pdf;
  s.weight = v3_scale(specular_fresnel(b->color, b->fdr_int, r.dwi, b->eta), b->spec_weight * r.shadowing);
  s.flags = BSDF_REFLECTION | BSDF_GLOSSY;
  return s;
}
#endif
#if BSDF_WITH_SHEEN
/* The sheen lobe (BSDF_SHEEN) is defined in sheen.h, which a program includes after this file (the
 * kernel sources expand each header once, at its first #include, so sheen.h and the medium.h it needs
 * are included where the rendering programs' order of headers allows: pathtrace.h). */
CO_INLINE co_vec3 sheen_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo);
CO_INLINE BsdfSample sheen_sample(const Bsdf* b, co_vec3 wi, float u1, float u2);
#endif

/* ---- Dispatch ---------------------------------------------------------------------------------- */

/* Two-sidedness of the reflection-only BSDFs: mirror both directions through the surface when wi
 * is below it (Mitsuba's twosided adapter). Returns the sign applied to z. */
CO_INLINE float bsdf_side(const Bsdf* b, co_vec3 wi) {
  return (!bsdf_has_transmission(b) && wi.z < 0.0f) ? -1.0f : 1.0f;
}

/* The dispatchers below mirror wi and wo into local copies, never into their by-value parameters:
 * Mesa's rusticl (llvmpipe, LLVM 15) let such a write reach the caller's variable, so a later call
 * with the same arguments saw them mirrored (its BSDF device test failed on a two-sided BSDF seen
 * from below, 2026-12-05). */
CO_INLINE co_vec3 bsdf_mirrored(co_vec3 w, float side) { return v3(w.x, w.y, w.z * side); }

CO_INLINE co_vec3 bsdf_eval(const Bsdf* b, co_vec3 wi_in, co_vec3 wo_in) {
  float side = bsdf_side(b, wi_in);
  co_vec3 wi = bsdf_mirrored(wi_in, side), wo = bsdf_mirrored(wo_in, side);
  if (b->type == BSDF_DIFFUSE) return diffuse_eval(b, wi, wo);
#if BSDF_WITH_CONDUCTOR
  if (b->type == BSDF_CONDUCTOR) return conductor_eval(b, wi, wo);
#endif
#if BSDF_WITH_DIELECTRIC
  if (b->type == BSDF_DIELECTRIC) return dielectric_eval(b, wi, wo);
#endif
#if BSDF_WITH_PLASTIC
  if (b->type == BSDF_PLASTIC) return plastic_eval(b, wi, wo);
#endif
#if BSDF_WITH_COAT
  if (b->type == BSDF_COAT) return coat_eval(b, wi, wo);
#endif
#if BSDF_WITH_SHEEN
  if (b->type == BSDF_SHEEN) return sheen_eval(b, wi, wo);
#endif
#if BSDF_WITH_SPECULAR
  if (b->type == BSDF_SPECULAR) return specular_eval(b, wi, wo);
#endif
  return v3_splat(0.0f);
}

CO_INLINE float bsdf_pdf(const Bsdf* b, co_vec3 wi_in, co_vec3 wo_in) {
  float side = bsdf_side(b, wi_in);
  co_vec3 wi = bsdf_mirrored(wi_in, side), wo = bsdf_mirrored(wo_in, side);
  if (b->type == BSDF_DIFFUSE) return diffuse_pdf(wi, wo);
#if BSDF_WITH_CONDUCTOR
  if (b->type == BSDF_CONDUCTOR) return glossy_reflection_pdf(b, wi, wo);
#endif
#if BSDF_WITH_DIELECTRIC
  if (b->type == BSDF_DIELECTRIC) return dielectric_pdf(b, wi, wo);
#endif
#if BSDF_WITH_PLASTIC
  if (b->type == BSDF_PLASTIC) return plastic_pdf(b, wi, wo);
#endif
#if BSDF_WITH_COAT
  if (b->type == BSDF_COAT) return glossy_reflection_pdf(b, wi, wo);
#endif
#if BSDF_WITH_SHEEN
  if (b->type == BSDF_SHEEN) return diffuse_pdf(wi, wo);
#endif
#if BSDF_WITH_SPECULAR
  if (b->type == BSDF_SPECULAR) return glossy_reflection_pdf(b, wi, wo);
#endif
  return 0.0f;
}

/* u_lobe picks the lobe (Fresnel or coat choice), (u1, u2) the direction; all in [0, 1). */
CO_INLINE BsdfSample bsdf_sample(const Bsdf* b, co_vec3 wi_in, float u_lobe, float u1, float u2) {
  float side = bsdf_side(b, wi_in);
  co_vec3 wi = bsdf_mirrored(wi_in, side);
  BsdfSample s;
  if (b->type == BSDF_DIFFUSE) s = diffuse_sample(b, wi, u1, u2);
#if BSDF_WITH_CONDUCTOR
  else if (b->type == BSDF_CONDUCTOR) s = conductor_sample(b, wi, u1, u2);
#endif
#if BSDF_WITH_DIELECTRIC
  else if (b->type == BSDF_DIELECTRIC) s = dielectric_sample(b, wi, u_lobe, u1, u2);
#endif
#if BSDF_WITH_PLASTIC
  else if (b->type == BSDF_PLASTIC) s = plastic_sample(b, wi, u_lobe, u1, u2);
#endif
#if BSDF_WITH_COAT
  else if (b->type == BSDF_COAT) s = coat_sample(b, wi, u1, u2);
#endif
#if BSDF_WITH_SHEEN
  else if (b->type == BSDF_SHEEN) s = sheen_sample(b, wi, u1, u2);
#endif
#if BSDF_WITH_SPECULAR
  else if (b->type == BSDF_SPECULAR) s = specular_sample(b, wi, u1, u2);
#endif
  else s = bsdf_no_sample();
  s.wo.z *= side;
  return s;
}

/* ---- glTF metallic-roughness ----------------------------------------------------------------------
 * One BSDF per shading point, chosen stochastically: a conductor with probability `metallic`, else
 * a dielectric with probability `transmission`, else the opaque dielectric base. Because the
 * choice is made with the mixture weights and the chosen BSDF is then used whole (for NEE and for
 * sampling alike), the expected contribution is the glTF mix. u_select in [0, 1) decides, so the
 * result is deterministic; the caller gives it its own random number.
 *   metal:        BSDF_CONDUCTOR, F0 = base colour, alpha = roughness^2
 *   transmissive: BSDF_DIELECTRIC, eta = ior, alpha = roughness^2, transmission tinted by base colour
 *   opaque:       roughness >= 1: BSDF_DIFFUSE (albedo = base colour; a Lambertian exactly as
 *                 Mitsuba's `diffuse`, the Cornell box case); otherwise BSDF_PLASTIC with eta = ior
 *                 and alpha = roughness^2 (the glTF dielectric: specular coat over diffuse).
 * ior outside [1, 10] (absent, 0 or nonsense) falls back to glTF's default 1.5. */
CO_INLINE Bsdf bsdf_from_gltf(co_vec3 base_color, float metallic, float roughness, float transmission, float ior,
                              float u_select) {
  float r = fmin(fmax(roughness, 0.0f), 1.0f);
  float alpha = r * r;
  float eta = (ior >= 1.0f && ior <= 10.0f) ? ior : 1.5f;
  float met = fmin(fmax(metallic, 0.0f), 1.0f);
  /* a program specialised to its scene leaves out the branches its materials cannot take */
#if BSDF_WITH_CONDUCTOR
  if (u_select < met) return bsdf_conductor(base_color, alpha);
#endif
  float u = (u_select - met) / (1.0f - met); /* remapped to [0, 1) given "not metal" */
#if BSDF_WITH_DIELECTRIC
  if (u < transmission) return bsdf_dielectric(eta, alpha, base_color);
#endif
#if BSDF_WITH_PLASTIC
  if (r < 1.0f) return bsdf_plastic(base_color, eta, alpha);
#endif
  return bsdf_diffuse(base_color);
}

/* The same for a scene material; base_color is the material's colour times its texture, which
 * the caller looks up. */
CO_INLINE Bsdf bsdf_from_material(const CO_GLOBAL Material* m, co_vec3 base_color, float u_select) {
  return bsdf_from_gltf(base_color, m->metallic, m->roughness, m->transmission, m->ior, u_select);
}

#endif
