/* Pinhole camera; pixel (x, y) with y = 0 at the top, as docs/bench-protocol.md. */
#ifndef COHORT_CAMERA_H
#define COHORT_CAMERA_H

#include "common/core/types.h"
#include "common/core/vec.h"

/* (jx, jy) in [0,1)^2 is the position inside the pixel; 0.5 is its centre. */
CO_INLINE co_vec3 camera_direction(const CameraParams* cam, uint32_t width, uint32_t height, uint32_t x,
                                   uint32_t y, float jx, float jy) {
  float px = ((float)x + jx) / (float)width * 2.0f - 1.0f;
  float py = 1.0f - ((float)y + jy) / (float)height * 2.0f;
  co_vec3 d = v3_add(v3_from4(cam->forward), v3_scale(v3_from4(cam->right), px));
  d = v3_add(d, v3_scale(v3_from4(cam->up), py));
  return v3_normalize(d);
}

#endif
