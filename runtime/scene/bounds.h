#pragma once

#include <glm/glm.hpp>
#include <limits>

namespace cohort {

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};

  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Bounds& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  glm::vec3 extent() const { return hi - lo; }
  float diagonal() const { return empty() ? 0.f : glm::length(hi - lo); }
  float surface_area() const {
    if (empty()) return 0.f;
    const glm::vec3 e = hi - lo;
    return 2.f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

}  // namespace cohort
