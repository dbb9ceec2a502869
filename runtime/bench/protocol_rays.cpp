#include "runtime/bench/protocol_rays.h"

#include <cmath>
#include <limits>

#include <stdexcept>

namespace cohort {

namespace {

// The protocol's pixel index of launch index k: order[k], or k where the order is rows (empty).
std::uint32_t pixel_of(std::span<const std::uint32_t> order, std::size_t k) {
  return order.empty() ? std::uint32_t(k) : order[k];
}

}  // namespace

std::uint32_t protocol_pcg(std::uint32_t v) {
  const std::uint32_t s = v * 747796405u + 2891336453u;
  const std::uint32_t w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (w >> 22u) ^ w;
}

float protocol_unit(std::uint32_t h) { return float(h >> 8u) * (1.0f / 16777216.0f); }

std::vector<std::uint32_t> protocol_pixel_order(std::uint32_t res, bool tiles) {
  std::vector<std::uint32_t> order(std::size_t(res) * res);
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = tiles ? tiled_pixel(k, res, res) : k;
  return order;
}

std::vector<RayIn> protocol_primary_rays(const SceneCamera& camera, std::uint32_t res,
                                         std::span<const std::uint32_t> order) {
  if (!order.empty() && order.size() != std::size_t(res) * res)
    throw std::invalid_argument("protocol_primary_rays: one pixel per ray");
  const glm::vec3 fwd = glm::normalize(camera.target - camera.eye);
  const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0.f, 1.f, 0.f)));
  const glm::vec3 up = glm::cross(right, fwd);
  const float tan_half = std::tan(glm::radians(camera.vfov_degrees) * 0.5f);
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<RayIn> rays(std::size_t(res) * res);
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const std::uint32_t pixel = pixel_of(order, k);
    if (pixel >= rays.size()) throw std::invalid_argument("protocol_primary_rays: a pixel outside the image");
    const std::uint32_t x = pixel % res, y = pixel / res;
    const float px = (float(x) + 0.5f) / float(res) * 2.f - 1.f;
    const float py = 1.f - (float(y) + 0.5f) / float(res) * 2.f;
    const glm::vec3 d = glm::normalize(fwd + right * (px * tan_half) + up * (py * tan_half));
    rays[k] = RayIn{{camera.eye.x, camera.eye.y, camera.eye.z, 0.f}, {d.x, d.y, d.z, inf}};
  }
  return rays;
}

std::vector<RayIn> protocol_diffuse_rays(std::span<const RayIn> primary, std::span<const ProtocolHit> hits,
                                         std::span<const glm::vec3> positions, float diag,
                                         std::span<const std::uint32_t> order) {
  if (hits.size() != primary.size()) throw std::invalid_argument("protocol_diffuse_rays: one hit per primary ray");
  if (!order.empty() && order.size() != primary.size())
    throw std::invalid_argument("protocol_diffuse_rays: one pixel per primary ray");
  const float inf = std::numeric_limits<float>::infinity();
  const float offset = 1e-4f * diag;
  std::vector<RayIn> rays;
  for (std::size_t i = 0; i < primary.size(); ++i) {
    const ProtocolHit& h = hits[i];
    if (h.triangle == HIT_NONE) continue;
    const glm::vec3 org(primary[i].origin.x, primary[i].origin.y, primary[i].origin.z);
    const glm::vec3 dir(primary[i].dir.x, primary[i].dir.y, primary[i].dir.z);
    const glm::vec3* v = &positions[std::size_t(h.triangle) * 3];
    glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
    if (glm::dot(n, dir) > 0.f) n = -n;
    const glm::vec3 p = org + h.t * dir + offset * n;
    const std::uint32_t h1 = protocol_pcg(2u * pixel_of(order, i) + 1u);
    const std::uint32_t h2 = protocol_pcg(h1);
    const float u1 = protocol_unit(h1), u2 = protocol_unit(h2);
    const float r = std::sqrt(u1), phi = 2.f * 3.14159265358979f * u2;
    // orthonormal frame around n (Duff et al. 2017); the protocol leaves the tangent free
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z), b = n.x * n.y * a;
    const glm::vec3 t1(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const glm::vec3 t2(b, sign + n.y * n.y * a, -n.y);
    const glm::vec3 d = glm::normalize(t1 * (r * std::cos(phi)) + t2 * (r * std::sin(phi)) + n * std::sqrt(1.f - u1));
    rays.push_back(RayIn{{p.x, p.y, p.z, 0.f}, {d.x, d.y, d.z, inf}});
  }
  return rays;
}

}  // namespace cohort
