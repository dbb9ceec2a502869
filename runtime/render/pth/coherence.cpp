#include "runtime/render/pth/coherence.h"

#include <algorithm>
#include <charconv>
#include <sstream>

#include <fmt/format.h>

#include "runtime/backend/device_support.h"
#include "runtime/util/error.h"

namespace cohort {

namespace {

struct Part {
  std::string name;
  std::uint32_t width = 0;
};

std::string preset_names() {
  std::string names;
  for (const CodePreset& p : code_presets()) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

// Bits a part takes in the key: 3 per axis of a point, 2 per PTH level, 2 per octahedral coordinate.
unsigned part_bits(const std::string& name, std::uint32_t width) {
  return name == "pth" || name == "dir" ? 2 * width : 3 * width;
}

// The parts of a layout or of the preset it names, most significant first.
std::vector<Part> layout_parts(const std::string& given) {
  std::string layout = given;
  for (const CodePreset& p : code_presets())
    if (given == p.name) layout = p.layout;
  std::vector<Part> parts;
  std::istringstream in(layout);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto colon = item.find(':');
    Part part{item.substr(0, colon)};
    const char* first = item.data() + colon + 1;
    const char* last = item.data() + item.size();
    if (colon == std::string::npos || std::from_chars(first, last, part.width).ptr != last)
      throw InputError(fmt::format("--code {}: expected parts like origin:8,pth:10,dir:8 or a preset ({})", layout,
                                   preset_names()));
    parts.push_back(part);
  }
  return parts;
}

}  // namespace

const std::vector<CodePreset>& code_presets() {
  static const std::vector<CodePreset> presets{{"paper", "origin:8,pth:10,dir:8"},
                                               {"hash", "origin:8,dir:8"},
                                               {"origin-first", "origin-uniform:8,dir:4"},
                                               {"two-point", "origin-uniform:5,end:5"},
                                               {"pth-32", "origin-uniform:7,pth:4,dir:1"}};
  return presets;
}

std::string default_code_layout(bool with_pth) { return with_pth ? "pth-32" : "origin-first"; }

std::uint32_t layout_pth_levels(const std::string& layout) {
  std::uint32_t levels = 0;
  for (const Part& p : layout_parts(layout))
    if (p.name == "pth") levels = p.width;
  return levels;
}

std::uint32_t requested_pth_levels(const std::string& code, std::uint32_t pth_levels) {
  if (code.empty()) return pth_levels ? pth_levels : layout_pth_levels(default_code_layout(true));
  const std::uint32_t coded = code.empty() ? 0 : layout_pth_levels(code);
  if (coded != 0 && pth_levels != 0 && coded != pth_levels)
    throw InputError(fmt::format("--code {} asks for {} PTH levels and --pth-levels for {}: give one", code, coded,
                                 pth_levels));
  return coded != 0 ? coded : pth_levels;
}

CodeParams parse_code_layout(const std::string& layout, std::uint32_t pth_levels, const Bounds& bounds) {
  const std::vector<Part> parts = layout_parts(layout);
  CodeParams c{};
  c.lo = {bounds.lo.x, bounds.lo.y, bounds.lo.z, 0.f};
  c.hi = {bounds.hi.x, bounds.hi.y, bounds.hi.z, 0.f};
  unsigned total = 0;
  for (const auto& p : parts) {
    if (p.name == "origin" || p.name == "origin-uniform") {
      if (p.width > 10) throw InputError(fmt::format("--code {}: origin takes at most 10 bits per axis", layout));
      c.origin_bits = p.width;
      c.origin_adaptive = p.name == "origin";
    } else if (p.name == "end") {
      if (p.width > 10) throw InputError(fmt::format("--code {}: end takes at most 10 bits per axis", layout));
      c.end_bits = p.width;
    } else if (p.name == "pth") {
      c.pth_levels = pth_levels ? pth_levels : p.width;
      if (c.pth_levels > 16) throw InputError(fmt::format("--code {}: pth takes at most 16 levels", layout));
    } else if (p.name == "dir") {
      if (p.width > 16) throw InputError(fmt::format("--code {}: dir takes at most 16 bits", layout));
      c.direction_bits = p.width;
    } else {
      throw InputError(
          fmt::format("--code {}: unknown part '{}' (origin, origin-uniform, end, pth, dir)", layout, p.name));
    }
    total += part_bits(p.name, p.name == "pth" ? c.pth_levels : p.width);
  }
  if (total > 64) throw InputError(fmt::format("--code {}: {} bits do not fit a 64-bit key", layout, total));
  // the first part is the most significant: shift each part above the ones after it
  unsigned shift = total;
  for (const auto& p : parts) {
    shift -= part_bits(p.name, p.name == "pth" ? c.pth_levels : p.width);
    if (p.name == "pth") c.pth_shift = shift;
    else if (p.name == "dir") c.direction_shift = shift;
    else if (p.name == "end") c.end_shift = shift;
    else c.origin_shift = shift;
  }
  c.key_bits = total;
  return c;
}

std::vector<float> origin_boundaries(const DeviceScene& scene, std::uint32_t bits) {
  if (bits == 0) return {0.f};
  const std::size_t cells = std::size_t(1) << bits;
  std::vector<float> out;
  for (const auto& axis : scene.centroid_samples) {
    for (std::size_t k = 1; k < cells; ++k)
      out.push_back(axis.empty() ? 0.f : axis[std::min(axis.size() - 1, k * axis.size() / cells)]);
  }
  return out;
}

SubtreeChoice choose_subtree(const DeviceInfo& device, const DeviceScene& scene, std::uint32_t requested) {
  SubtreeChoice c;
  const auto& starts = scene.level_starts;  // starts[d] = first node of depth d; back() = node count
  const std::size_t node_bytes = scene.bvh4 ? sizeof(Bvh4Node) : sizeof(KdNode);
  const std::uint32_t tree_levels = static_cast<std::uint32_t>(starts.size() - 1);
  c.levels = std::min<std::uint32_t>(requested ? requested : 10, tree_levels);
  // the BVH's levels are 4-wide (a layout's pth:10 names binary levels): it walks as many of the
  // requested levels as the budget holds
  if (requested == 0 || scene.bvh4) {
    const std::size_t budget = device_support(device).local_budget;
    while (c.levels > 0 && starts[c.levels] * node_bytes > budget) --c.levels;
  }
  c.nodes = starts[c.levels];
  c.local_bytes = std::size_t(c.nodes) * node_bytes;
  if (c.local_bytes > device.local_memory)
    throw InputError(fmt::format("--pth-levels {}: the subtree needs {} bytes of local memory; {} has {}", requested,
                                 c.local_bytes, device.name, device.local_memory));
  return c;
}

}  // namespace cohort
