/* Pinhole camera; pixel (x, y) with y = 0 at the top, as docs/bench-protocol.md. */
#ifndef COHORT_CAMERA_H
#define COHORT_CAMERA_H

#include "common/core/types.h"
#include "common/core/vec.h"

/* The unnormalised direction through the image-plane point (px, py) in [-1, 1]^2 (y up). */
CO_INLINE co_vec3 camera_plane_point(const CameraParams* cam, float px, float py) {
  return v3_add(v3_add(v3_from4(cam->forward), v3_scale(v3_from4(cam->right), px)), v3_scale(v3_from4(cam->up), py));
}

/* (jx, jy) in [0,1)^2 is the position inside the pixel; 0.5 is its centre. */
CO_INLINE co_vec3 camera_direction(const CameraParams* cam, uint32_t width, uint32_t height, uint32_t x,
                                   uint32_t y, float jx, float jy) {
  float px = ((float)x + jx) / (float)width * 2.0f - 1.0f;
  float py = 1.0f - ((float)y + jy) / (float)height * 2.0f;
  return v3_normalize(camera_plane_point(cam, px, py));
}

/* 1 when no ray through pixel (x, y), for any (jx, jy), can meet the box [lo, hi]: the box lies
 * wholly outside one of the four planes through the eye that bound the pixel's directions (the
 * corners' directions, unnormalised, taken two by two), by a margin of 1e-4 of the box's extent
 * from the eye times the plane normal's size, far above the rounding of camera_direction, of the
 * normals and of the products here. Conservative: 0 says nothing (a box around the eye, or one
 * that only an edge of the pixel's pyramid passes). */
CO_INLINE int camera_pixel_misses_box(const CameraParams* cam, uint32_t width, uint32_t height, uint32_t x,
                                      uint32_t y, co_vec3 lo, co_vec3 hi) {
  /* the corners' directions, unnormalised: camera_direction's image-plane points at jx, jy = 0 and
   * 1, each coordinate within a few ulps of its own (the margin covers them) */
  const float sx = 2.0f / (float)width, sy = 2.0f / (float)height;
  const float px0 = (float)x * sx - 1.0f, px1 = (float)(x + 1u) * sx - 1.0f;
  const float py0 = 1.0f - (float)y * sy, py1 = 1.0f - (float)(y + 1u) * sy;
  co_vec3 corner[4];
  corner[0] = camera_plane_point(cam, px0, py0);
  corner[1] = camera_plane_point(cam, px1, py0);
  corner[2] = camera_plane_point(cam, px1, py1);
  corner[3] = camera_plane_point(cam, px0, py1);
  co_vec3 centre = v3_add(v3_add(corner[0], corner[1]), v3_add(corner[2], corner[3]));
  co_vec3 eye = v3_from4(cam->eye);
  co_vec3 to_lo = v3_sub(lo, eye), to_hi = v3_sub(hi, eye);
  float extent = fmax(fabs(to_lo.x), fabs(to_hi.x)) + fmax(fabs(to_lo.y), fabs(to_hi.y)) +
                 fmax(fabs(to_lo.z), fabs(to_hi.z));
  if (!(extent < INFINITY)) return 0; /* not a finite box (an empty scene's): no claim */
  for (int side = 0; side < 4; ++side) {
    co_vec3 n = v3_cross(corner[side], corner[(side + 1) & 3]);
    if (v3_dot(n, centre) < 0.0f) n = v3_neg(n); /* the pixel's directions on the positive side */
    /* the farthest any box corner reaches onto the positive side */
    float reach = fmax(n.x * to_lo.x, n.x * to_hi.x) + fmax(n.y * to_lo.y, n.y * to_hi.y) +
                  fmax(n.z * to_lo.z, n.z * to_hi.z);
    float margin = 1e-4f * (fabs(n.x) + fabs(n.y) + fabs(n.z)) * extent;
    if (reach < -margin) return 1;
  }
  return 0;
}

#endif
