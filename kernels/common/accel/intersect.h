/* Ray-triangle and ray-box tests.
 * Triangles use the watertight test of Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection"
 * (JCGT 2013): rays through a shared edge or vertex never slip between adjacent triangles, so closed
 * scenes (the Cornell box, the furnace sphere) leak no light, at a cost close to Moller-Trumbore. */
#ifndef COHORT_INTERSECT_H
#define COHORT_INTERSECT_H

#include "common/core/types.h"
#include "common/core/vec.h"
#include "common/accel/alpha_view.h"

/* Per-ray constants of the watertight test: the shear that maps the ray to +Z, as three rows.
 * Row x is e_kx - sx e_kz, row y is e_ky - sy e_kz, row z is e_kz: each has at most two nonzero
 * entries, so dot(A, row) rounds exactly as Woop's A[kx] - sx * A[kz] (adding the zero term is
 * exact) while the kernel needs no data-dependent component selects per triangle. */
typedef struct WatertightRay {
  co_vec3 org;
  co_vec3 row_x, row_y, row_z;
  float sz;
#if defined(COHORT_FEATURE_ALPHA)
  const AlphaView* alpha; /* the scene's alpha modes, set by the traversal (alpha.h) */
  uint32_t alpha_seed;    /* the ray's seed for BLEND decisions */
#endif
} WatertightRay;

CO_INLINE co_vec3 unit_axis(uint32_t k) { return v3(k == 0u ? 1.0f : 0.0f, k == 1u ? 1.0f : 0.0f, k == 2u ? 1.0f : 0.0f); }

CO_INLINE WatertightRay watertight_ray(co_vec3 org, co_vec3 dir) {
  WatertightRay r;
  co_vec3 a = v3_abs(dir);
  uint32_t kz = (a.x > a.y) ? ((a.x > a.z) ? 0u : 2u) : ((a.y > a.z) ? 1u : 2u);
  uint32_t kx = kz == 2u ? 0u : kz + 1u;
  uint32_t ky = kx == 2u ? 0u : kx + 1u;
  float dz = v3_get(dir, kz);
  if (dz < 0.0f) { uint32_t tmp = kx; kx = ky; ky = tmp; }  /* keep the winding */
  co_vec3 ez = unit_axis(kz);
  r.org = org;
  r.row_x = v3_madd(unit_axis(kx), ez, -(v3_get(dir, kx) / dz));
  r.row_y = v3_madd(unit_axis(ky), ez, -(v3_get(dir, ky) / dz));
  r.row_z = ez;
  r.sz = 1.0f / dz;
  return r;
}

/* Returns 1 and writes t, u, v (weights of v1 and v2) when the ray hits the triangle with
 * tmin < t < tmax. Both faces hit. */
CO_INLINE int intersect_triangle(const WatertightRay* r, co_vec3 p0, co_vec3 p1, co_vec3 p2,
                                 float tmin, float tmax, float* t_out, float* u_out, float* v_out) {
  co_vec3 a = v3_sub(p0, r->org), b = v3_sub(p1, r->org), c = v3_sub(p2, r->org);
  float ax = v3_dot(a, r->row_x), ay = v3_dot(a, r->row_y), az = v3_dot(a, r->row_z);
  float bx = v3_dot(b, r->row_x), by = v3_dot(b, r->row_y), bz = v3_dot(b, r->row_z);
  float cx = v3_dot(c, r->row_x), cy = v3_dot(c, r->row_y), cz = v3_dot(c, r->row_z);
  float eu = cx * by - cy * bx;
  float ev = ax * cy - ay * cx;
  float ew = bx * ay - by * ax;
  if ((eu < 0.0f || ev < 0.0f || ew < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f)) return 0;
  float det = eu + ev + ew;
  if (det == 0.0f) return 0;
  float tscaled = r->sz * (eu * az + ev * bz + ew * cz);
  float inv_det = 1.0f / det;
  float t = tscaled * inv_det;
  if (!(t > tmin && t < tmax)) return 0;
  *t_out = t;
  *u_out = ev * inv_det;
  *v_out = ew * inv_det;
  return 1;
}

/* intersect_triangle on the four triangles of a block (types.h, Triangle4) at once: each lane does
 * intersect_triangle's operations in its order, so each lane's t, u and v are the bits that test
 * gives that triangle alone. A lane whose det is 0 needs no test of its own: its t is NaN or
 * infinite, which tmin < t < tmax rejects. Returns the mask of the lanes hit in (tmin, tmax), lane
 * i in bit i, and writes every lane's t, u and v unless the mask is 0. */
CO_INLINE uint32_t intersect_triangle4(const WatertightRay* r, const CO_GLOBAL Triangle4* q, float tmin, float tmax,
                                       float* t_out, float* u_out, float* v_out) {
  const co_float4 ox = co_f4_splat(r->org.x), oy = co_f4_splat(r->org.y), oz = co_f4_splat(r->org.z);
  /* v3_dot's order: (x * row.x + y * row.y) + z * row.z */
#define CO_ROW_DOT4(X, Y, Z, row) \
  co_f4_add(co_f4_add(co_f4_scale((X), (row).x), co_f4_scale((Y), (row).y)), co_f4_scale((Z), (row).z))
  const co_float4 pax = co_f4_sub(q->v[0][0], ox), pay = co_f4_sub(q->v[0][1], oy), paz = co_f4_sub(q->v[0][2], oz);
  const co_float4 pbx = co_f4_sub(q->v[1][0], ox), pby = co_f4_sub(q->v[1][1], oy), pbz = co_f4_sub(q->v[1][2], oz);
  const co_float4 pcx = co_f4_sub(q->v[2][0], ox), pcy = co_f4_sub(q->v[2][1], oy), pcz = co_f4_sub(q->v[2][2], oz);
  const co_float4 ax = CO_ROW_DOT4(pax, pay, paz, r->row_x), ay = CO_ROW_DOT4(pax, pay, paz, r->row_y);
  const co_float4 bx = CO_ROW_DOT4(pbx, pby, pbz, r->row_x), by = CO_ROW_DOT4(pbx, pby, pbz, r->row_y);
  const co_float4 cx = CO_ROW_DOT4(pcx, pcy, pcz, r->row_x), cy = CO_ROW_DOT4(pcx, pcy, pcz, r->row_y);
  const co_float4 az = CO_ROW_DOT4(pax, pay, paz, r->row_z), bz = CO_ROW_DOT4(pbx, pby, pbz, r->row_z);
  const co_float4 cz = CO_ROW_DOT4(pcx, pcy, pcz, r->row_z);
#undef CO_ROW_DOT4
  const co_float4 eu = co_f4_sub(co_f4_mul(cx, by), co_f4_mul(cy, bx));
  const co_float4 ev = co_f4_sub(co_f4_mul(ax, cy), co_f4_mul(ay, cx));
  const co_float4 ew = co_f4_sub(co_f4_mul(bx, ay), co_f4_mul(by, ax));
  const co_float4 zero = co_f4_splat(0.0f);
  const uint32_t negative = co_f4_less(eu, zero) | co_f4_less(ev, zero) | co_f4_less(ew, zero);
  const uint32_t positive = co_f4_less(zero, eu) | co_f4_less(zero, ev) | co_f4_less(zero, ew);
  const uint32_t inside = ~(negative & positive) & 15u;
  /* most leaves a ray enters hold no triangle it meets: then no lane needs its t, u and v (the
   * division and the seven multiplies below), and none is written */
  if (inside == 0u) return 0u;
  const co_float4 det = co_f4_add(co_f4_add(eu, ev), ew);
  const co_float4 tscaled =
      co_f4_scale(co_f4_add(co_f4_add(co_f4_mul(eu, az), co_f4_mul(ev, bz)), co_f4_mul(ew, cz)), r->sz);
  const co_float4 inv_det = co_f4_div(co_f4_splat(1.0f), det);
  const co_float4 t = co_f4_mul(tscaled, inv_det);
  co_f4_store(t, t_out);
  co_f4_store(co_f4_mul(ev, inv_det), u_out);
  co_f4_store(co_f4_mul(ew, inv_det), v_out);
  return inside & co_f4_less(co_f4_splat(tmin), t) & co_f4_less(t, co_f4_splat(tmax));
}

/* Slab test; returns 1 and the clipped interval when the ray meets the box within [*t0, *t1]. */
CO_INLINE int intersect_box(co_vec3 org, co_vec3 inv_dir, co_vec3 lo, co_vec3 hi, float* t0, float* t1) {
  float tx0 = (lo.x - org.x) * inv_dir.x, tx1 = (hi.x - org.x) * inv_dir.x;
  float ty0 = (lo.y - org.y) * inv_dir.y, ty1 = (hi.y - org.y) * inv_dir.y;
  float tz0 = (lo.z - org.z) * inv_dir.z, tz1 = (hi.z - org.z) * inv_dir.z;
  /* An origin on a face of the box with a zero direction component across it (0 * inf, NaN) runs
   * in that face: the whole slab, as for an origin inside it, so the box stays closed. fmin/fmax
   * would drop the NaN and keep the other bound's infinity, which for the upper face is -inf. */
  if (tx0 != tx0 || tx1 != tx1) { tx0 = -INFINITY; tx1 = INFINITY; }
  if (ty0 != ty0 || ty1 != ty1) { ty0 = -INFINITY; ty1 = INFINITY; }
  if (tz0 != tz0 || tz1 != tz1) { tz0 = -INFINITY; tz1 = INFINITY; }
  float tnear = fmax(fmax(fmin(tx0, tx1), fmin(ty0, ty1)), fmax(fmin(tz0, tz1), *t0));
  float tfar = fmin(fmin(fmax(tx0, tx1), fmax(ty0, ty1)), fmin(fmax(tz0, tz1), *t1));
  /* widen by a few ulps so rays grazing the box face are not lost to rounding */
  tfar *= 1.0000004f;
  if (tnear > tfar) return 0;
  *t0 = tnear;
  *t1 = tfar;
  return 1;
}

#endif
