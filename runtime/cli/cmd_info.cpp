#include <fmt/format.h>

#include "runtime/backend/device_support.h"
#include "runtime/backend/open_device.h"
#include "runtime/cli/commands.h"
#include "runtime/render/scene/prepared_scene.h"
#include "runtime/render/scene/scene_memory.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

const char* wrap_name(TextureWrap w) {
  return w == TextureWrap::clamp_to_edge ? "clamp" : (w == TextureWrap::mirrored_repeat ? "mirror" : "repeat");
}

// "NAME WxH, sRGB, bilinear, wrap repeat/repeat: base colour of 'M'; emission of 'N'"
std::string describe(const Texture& t) {
  std::string uses;
  for (const std::string& u : t.uses) uses += (uses.empty() ? "" : "; ") + u;
  return fmt::format("{} {}x{}, {}, {}, wrap {}/{}: {}", t.name, t.width, t.height, t.srgb ? "sRGB" : "linear",
                     t.sampler.nearest ? "nearest" : "bilinear", wrap_name(t.sampler.wrap_s),
                     wrap_name(t.sampler.wrap_t), uses.empty() ? "unused" : uses);
}

// The tree `p` holds and its device memory, then, for --tree all, the 8-wide BVHs (compressed, and
// with float planes) and the KD-trees built from the same kept triangles: what each layout costs a scene in bytes per triangle.
void print_layouts(const PreparedScene& p, bool all) {
  const std::size_t triangles = p.tree.triangles.size();
  fmt::print("{}\n", describe_tree(p));
  fmt::print("device memory: {}\n", describe(scene_memory(p.tree, p.tables, p.bvh()), triangles));
  if (!all) return;
  try {  // a scene beyond the compressed BVH's bound still gets the other layouts
    const Bvh8 bvh8 = build_bvh8(p.tree.triangles);
    fmt::print("{}\n", describe_bvh("compressed 8-wide BVH", bvh8.stats, triangles, p.tree.stats.build_seconds));
    fmt::print("device memory: {}\n", describe(scene_memory(p.tree, p.tables, &bvh8), triangles));
  } catch (const InputError& e) {
    fmt::print("compressed 8-wide BVH: not built: {}\n", e.what());
  }
  const Bvh8f bvh8f = build_bvh8f(p.tree.triangles);
  fmt::print("{}\n", describe_bvh("8-wide BVH (float planes)", bvh8f.stats, triangles, p.tree.stats.build_seconds));
  fmt::print("device memory: {}\n", describe(scene_memory(p.tree, p.tables, &bvh8f), triangles));
  for (const bool compact : {false, true}) {
    KdBuildOptions options;
    options.compact = compact;
    const KdTree kd = build_kdtree(p.scene.positions, options);
    fmt::print("{}\n", describe_kdtree(kd.stats));
    fmt::print("device memory: {}\n", describe(scene_memory(kd, p.tables), triangles));
  }
}

}  // namespace

int run_info(const std::filesystem::path& path, const std::string& tree) {
  const bool all = tree == "all";
  const PreparedScene p = prepare_scene(path, tree_options(all ? "bvh4" : tree));
  const Bounds b = p.scene.bounds();
  const auto& ts = p.tree.stats;
  fmt::print("scene: {}\n", path.string());
  fmt::print("triangles: {} ({} kept, {} dropped as degenerate or non-finite)\n", p.scene.triangle_count(),
             p.tree.triangles.size(), ts.dropped_triangles);
  fmt::print("materials: {}\n", p.scene.materials.size());
  for (std::size_t i = 0; i < p.scene.materials.size(); ++i) {
    const auto& m = p.scene.materials[i];
    const std::string alpha = m.alpha_mode == AlphaMode::mask    ? fmt::format(", alphaMode MASK (cutoff {:.3g})", m.alpha_cutoff)
                              : m.alpha_mode == AlphaMode::blend ? fmt::format(", alphaMode BLEND (alpha {:.3g})", m.alpha)
                                                                 : std::string();
    const std::string volume =
        m.absorption == glm::vec3(0.f)
            ? std::string()
            : fmt::format(", volume absorbing ({:.3g}, {:.3g}, {:.3g}) per unit length{}", m.absorption.x, m.absorption.y,
                          m.absorption.z, m.transmission > 0.f ? "" : " (not reached: no transmission)");
    const std::string coat = m.clearcoat.factor > 0.f ? fmt::format(", clearcoat {:.3g} (roughness {:.3g})",
                                                                     m.clearcoat.factor, m.clearcoat.roughness)
                                                         : std::string();
    const std::string sheen =
        m.sheen.present() ? fmt::format(", sheen ({:.3g}, {:.3g}, {:.3g}) roughness {:.3g}{}", m.sheen.color.x,
                                        m.sheen.color.y, m.sheen.color.z, m.sheen.roughness,
                                        m.sheen.color_texture >= 0 || m.sheen.roughness_texture >= 0 ? ", textured" : "")
                          : std::string();
    const std::string specular =
        m.specular.present()
            ? fmt::format(", specular {:.3g} colour ({:.3g}, {:.3g}, {:.3g}){}", m.specular.factor, m.specular.color.x,
                          m.specular.color.y, m.specular.color.z,
                          m.specular.texture >= 0 || m.specular.color_texture >= 0 ? ", textured" : "")
            : std::string();
    fmt::print("  [{}] {}: base colour ({:.3g}, {:.3g}, {:.3g}), metallic {:.3g}, roughness {:.3g}, emission ({:.3g}, "
               "{:.3g}, {:.3g}){}{}{}{}{}{}\n",
               i, m.name.empty() ? "(unnamed)" : m.name, m.base_color.x, m.base_color.y, m.base_color.z, m.metallic,
               m.roughness, m.emission.x, m.emission.y, m.emission.z, m.base_color_texture >= 0 ? ", textured" : "",
               alpha, volume, coat, sheen, specular);
  }
  const std::size_t unread = p.scene.unread_textures.size();
  fmt::print("textures: {}{}\n", p.scene.textures.size(),
             unread == 0 ? std::string() : fmt::format(" read, {} not read", unread));
  for (std::size_t i = 0; i < p.scene.textures.size(); ++i) fmt::print("  [{}] {}\n", i, describe(p.scene.textures[i]));
  for (const std::string& t : p.scene.unread_textures) fmt::print("  [not read] {}\n", t);
  std::size_t spots = 0;
  for (const auto& l : p.scene.lights) spots += l.type == SceneLight::Type::spot;
  fmt::print("lights: {} emissive triangles, total power {:.4g}; {} point, {} spot (KHR_lights_punctual)\n",
             p.tables.emitters.entries.size(), p.tables.emitters.total_power, p.scene.lights.size() - spots, spots);
  fmt::print("bounds: ({:.4g}, {:.4g}, {:.4g}) - ({:.4g}, {:.4g}, {:.4g}), diagonal {:.4g}\n", b.lo.x, b.lo.y, b.lo.z,
             b.hi.x, b.hi.y, b.hi.z, b.diagonal());
  fmt::print("camera: {}, eye ({:.4g}, {:.4g}, {:.4g}), target ({:.4g}, {:.4g}, {:.4g}), vfov {:.4g} deg\n",
             p.scene.camera ? "from the file" : "framing (bench protocol)", p.camera.eye.x, p.camera.eye.y,
             p.camera.eye.z, p.camera.target.x, p.camera.target.y, p.camera.target.z, p.camera.vfov_degrees);
  print_layouts(p, all);
  fmt::print("scene geometry: {:.2f} MiB on the host\n", p.scene.geometry_bytes() / 1048576.0);
  for (const auto& n : p.scene.notes) fmt::print("note: {}\n", n);
  for (const auto& w : p.scene.warnings) fmt::print("warning: {}\n", w);
  return 0;
}

namespace {
// What Cohort does on the device (runtime/backend/device_support.h).
void print_support(const DeviceSupport& s) {
  if (!s.runs) {
    fmt::print("    Cohort: cannot run here: {}\n", s.refusal);
    return;
  }
  fmt::print("    Cohort: runs; work-groups of up to {} items (each kernel's own limit applies), PTH subtree {} levels "
             "in {} KiB of local memory, BVH prefetch {}, paired walks {}, fused box slabs {}, branch-free BVH "
             "descend {}, GPU min/max in box tests {}, camera rays in 8x4 pixel tiles {}\n",
             s.work_group, s.pth_levels, s.local_budget / 1024, s.prefetch ? "on" : "off",
             s.paired_walks ? "on" : "off", s.fused_slabs ? "on" : "off", s.branch_free_descend ? "on" : "off",
             s.gpu_minmax ? "on" : "off", s.pixel_tiles ? "on" : "off");
  if (!s.sorts) fmt::print("    Cohort: no sorting methods (hash, pth): {}\n", s.sort_refusal);
}
}  // namespace

int run_devices() {
  std::vector<DeviceInfo> devices;
  try {
    devices = list_backend_devices(Backend::opencl);
  } catch (const InputError&) {
    fmt::print("no OpenCL devices found (Debian: install pocl-opencl-icd for the CPU)\n");
    return 1;
  }
  for (const auto& d : devices) {
    fmt::print("[{}] {} | {} | {}\n", d.device_index, d.name, d.platform_name, d.is_gpu ? "GPU" : (d.is_cpu ? "CPU" : "other"));
    fmt::print("    {} compute units, local memory {} KiB{}, global memory {} MiB (max allocation {} MiB)\n",
               d.compute_units, d.local_memory / 1024, d.local_memory_is_global ? " (global)" : "",
               d.global_memory >> 20, d.max_allocation >> 20);
    fmt::print("    {}, driver {}\n", d.version, d.driver_version);
    // what the kernels adapt to: sub-group votes (speculative traversal) and IEEE division
    fmt::print("    {}, max work-group {}, sub-groups (cl_khr_subgroups): {}, correctly rounded divide/sqrt: {}, "
               "float denormals: {}, images: {}\n",
               d.opencl_c_version, d.max_work_group, d.subgroups ? "yes" : "no",
               d.correctly_rounded_divide_sqrt ? "yes" : "no", d.denormals ? "yes" : "no", d.image_support ? "yes" : "no");
    print_support(device_support(d));
  }
  if (cuda_backend_built()) {
    try {
      for (const auto& d : list_backend_devices(Backend::cuda))
        fmt::print("[cuda {}] {} | {}, {} SMs, {} KiB shared memory per block, {} MiB | {}\n", d.device_index, d.name,
                   d.version, d.compute_units, d.local_memory / 1024, d.global_memory >> 20, d.driver_version);
    } catch (const InputError& e) {
      fmt::print("CUDA backend: {}\n", e.what());
    }
  }
  return 0;
}

}  // namespace cohort
