/* NAIVE: the reference megakernel. One work item per pixel traces this pass's samples of its
 * pixel in sample order and adds each to the film in that order, so the film is the same sum
 * whatever the work-group size or device scheduling. */
#include "common/pathtrace.h"

__kernel void render_naive(SCENE_KERNEL_PARAMS, __global float4* film, __global uint* ray_counter,
                           __global uint* dropped_samples) {
  uint pixel = get_global_id(0);
  RenderParams p = *params;
  if (pixel >= p.width * p.height) return;
  SceneView s = SCENE_VIEW(p);

  float4 acc = film[pixel];
  uint rays = 0u, dropped = 0u;
  for (uint i = 0u; i < p.samples_per_pass; ++i) {
    PathResult r = trace_path(&s, &p, pixel, p.sample_offset + i);
    rays += r.rays;
    /* a NaN or infinite sample never reaches the image; it counts as a zero sample */
    if (v3_is_finite(r.radiance)) acc += (float4)(r.radiance.x, r.radiance.y, r.radiance.z, 0.0f);
    else ++dropped;
  }
  film[pixel] = acc;
  atomic_add(ray_counter, rays);
  if (dropped) atomic_add(dropped_samples, dropped);
}
