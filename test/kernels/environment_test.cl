/* The environment map's sample/pdf/eval on the device for test/bsdf/environment_sampling_test.cpp,
 * which runs the same functions on the host with the same inputs and compares. */
#include "common/shading/environment.h"

__kernel void environment_test(__global const float4* texels, __global const float* tables, uint width, uint height,
                               __global const float2* u, __global const float4* query, __global float4* out,
                               uint count) {
  uint i = get_global_id(0);
  if (i >= count) return;
  EnvironmentView e;
  e.texels = texels;
  e.tables = tables;
  e.width = width;
  e.height = height;
  float pdf;
  co_vec3 d = env_sample(&e, u[i].x, u[i].y, &pdf);
  co_vec3 le = env_eval(&e, d);
  co_vec3 q = v3_from4(query[i]);
  co_vec3 lq = env_eval(&e, q);
  out[4 * i + 0] = (float4)(d.x, d.y, d.z, pdf);
  out[4 * i + 1] = (float4)(le.x, le.y, le.z, env_pdf(&e, d));
  out[4 * i + 2] = (float4)(lq.x, lq.y, lq.z, env_pdf(&e, q));
  out[4 * i + 3] = (float4)(0.0f);
}
