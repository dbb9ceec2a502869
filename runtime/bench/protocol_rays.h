// The rays of docs/bench-protocol.md, generated on the host. One implementation, used by
// `cohort bench` and by the Embree harness (runtime/peers), so both sides trace the same rays.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/common/core/types.h"
#include "runtime/scene/bounds.h"
#include "runtime/scene/scene.h"

namespace cohort {

// The protocol's hash: pcg(v) of 32-bit unsigned arithmetic.
std::uint32_t protocol_pcg(std::uint32_t v);

// A uniform number in [0, 1) from a hash: (h >> 8) / 2^24.
float protocol_unit(std::uint32_t h);

// The pixel each ray of a res x res launch goes through: row by row (pixel k), or in 8x4 tiles
// (tiled_pixel, kernels/common/core/types.h) on devices that launch camera rays that way
// (DeviceSupport::pixel_tiles). The protocol fixes the rays, not the order they are traced in.
std::vector<std::uint32_t> protocol_pixel_order(std::uint32_t res, bool tiles);

// res x res rays through the pixel centres of a pinhole at camera.eye looking at camera.target,
// +Y up, vertical field of view camera.vfov_degrees; pixel index i = y * res + x, y = 0 at the top.
// tnear 0 (origin.w), tfar infinity (dir.w). Ray k goes through pixel order[k] (empty: pixel k).
std::vector<RayIn> protocol_primary_rays(const SceneCamera& camera, std::uint32_t res,
                                         std::span<const std::uint32_t> order = {});

// One closest hit per primary ray: t, and the hit triangle as an index into `positions` / 3
// (HIT_NONE on a miss).
struct ProtocolHit {
  float t = 0;
  std::uint32_t triangle = HIT_NONE;
};

// The diffuse workload: for each primary ray that hit, in the primary rays' order, a ray from the
// hit point offset by 1e-4 * diag along the geometric normal facing the incoming ray, in a
// cosine-weighted direction drawn with h1 = pcg(2i + 1), h2 = pcg(h1), i the pixel index of the
// primary ray (order[k] for primary[k], as protocol_primary_rays; empty: k). positions: 3 per
// triangle (Scene::positions); diag: the diagonal of the bounds of all vertices.
std::vector<RayIn> protocol_diffuse_rays(std::span<const RayIn> primary, std::span<const ProtocolHit> hits,
                                         std::span<const glm::vec3> positions, float diag,
                                         std::span<const std::uint32_t> order = {});

}  // namespace cohort
