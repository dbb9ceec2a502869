// What to render and how: everything the CLI can set, in one value.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"

namespace cohort {

// How hash and pth sort their rays (--code, --pth-levels, --sort-from-bounce, --sort-payload):
// `cohort render` and `cohort bench` set them alike, and the render reports them as it resolved
// them (CoherenceFigures). Declared once, copied whole, written by one printer (sort_json).
struct SortSettings {
  std::string code;                    // coherence code layout; empty: the method's default
  std::uint32_t pth_levels = 0;        // subtree levels of pth; 0: chosen from the device and the tree
  std::uint32_t sort_from_bounce = 3;  // sort bounces from this one on (1: camera rays too);
                                       // H200: bounces 1 and 2 never pay for their sort
  std::string sort_payload = "indirect";  // "indirect" traces through the permutation; "gather"
                                          // first copies each sorted ray to its sorted position
                                          // (H200: 3 % faster trace, but the copy costs more)
};

struct RenderSettings {
  std::uint32_t width = 512;
  std::uint32_t height = 512;
  std::uint32_t spp = 64;
  std::uint32_t max_depth = 0;  // path segments, as Mitsuba's max_depth; 0 = until Russian roulette
  std::uint32_t rr_depth = 5;   // first segment at which Russian roulette may end a path
  std::uint32_t seed = 0;
  std::uint32_t pass_samples = 0;  // samples per pixel in one pass (pass_schedule.h); 0: the default
  double time_limit = 0;        // seconds; 0 = none. Stops after the pass that crosses it.
  double target_error = 0;      // adaptive sampling (adaptive.h): tiles stop below this estimated
                                // relative error and spp is each pixel's most; 0: uniform sampling
  bool nee = true;
  bool mis = true;
  bool russian_roulette = true;
  std::optional<glm::vec3> environment;  // constant environment radiance
  std::string method = "naive";
  std::uint32_t wavefront_size = 0;  // path slots of the wavefront methods; 0: chosen from the device
  bool speculative = false;          // hash/pth: resumed traversal postpones leaf tests (Aila & Laine)
  SortSettings sort;                 // hash/pth: how they sort their rays
  std::uint32_t straggler_rays = 0;  // wavefront methods: keep this many of the extension rays that
                                     // visited the most nodes, and per-pass percentiles (a diagnostic)
};

}  // namespace cohort
