// Every method on every tree renders a scene as naive does on the deep KD-tree, bit for bit: the
// check the glTF feature tests (alpha, volumes, textures) run on their own scenes.
#pragma once

#include <array>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/backend/device_support.h"
#include "runtime/backend/program_cache.h"
#include "runtime/cl/context.h"
#include "runtime/render/methods/methods.h"
#include "runtime/render/renderer.h"
#include "runtime/render/scene/prepared_scene.h"

namespace cohort::test {

// The trees a render can trace, by their --tree names: the deep and compact KD-trees, the 4-wide BVH,
// the compressed 8-wide BVH and the 8-wide BVH with float planes.
struct NamedTree {
  const char* name;
  TreeChoice choice;
  // hash and pth run on it (they walk the KD-trees and the 4-wide BVH; the host refuses them on the
  // 8-wide ones)
  bool sorts = true;
};
inline const std::array<NamedTree, 5>& every_tree() {
  static const std::array<NamedTree, 5> trees{
      {{"deep", TreeChoice{KdBuildOptions{}, false}},
       {"compact", TreeChoice{KdBuildOptions{.compact = true}, false}},
       {"bvh4", TreeChoice{KdBuildOptions{}, true}},
       {"bvh8", TreeChoice{.kd = KdBuildOptions{}, .bvh8 = true}, false},
       {"bvh8f", TreeChoice{.kd = KdBuildOptions{}, .bvh8f = true}, false}}};
  return trees;
}

// What most scenes' checks ask of expect_every_method_and_tree_agree: each tree's prepared scene has
// exactly the feature options `expected`, and the reference image is not black.
inline std::function<void(const PreparedScene&, const char*)> expect_features(SceneFeatures expected) {
  return [expected](const PreparedScene& p, const char* tree) { EXPECT_EQ(p.tables.features, expected) << tree; };
}
inline bool any_light(const Image& image) {
  double sum = 0;
  for (float v : image.rgb) sum += v;
  return sum > 0.0;
}

// The glTF feature rooms' view and render (a unit room seen from its front wall): 24x20 at 3 spp,
// Russian roulette from depth 3, so every method and tree runs in seconds.
inline SceneCamera feature_room_camera() { return {{0.5f, 0.5f, 0.02f}, {0.5f, 0.3f, 1.f}, {0, 1, 0}, 70}; }
inline RenderSettings feature_room_settings() {
  RenderSettings s;
  s.width = 24;
  s.height = 20;
  s.spp = 3;
  s.rr_depth = 3;
  s.seed = 5;
  return s;
}

// Renders `scene` from `camera` with `settings` (its method, pool, payload and speculation are set
// here) on every tree (every_tree), with every method the device and the tree run; the
// sorting methods also in a pool of 129 paths that refills (the speculative resume on the KD-trees)
// and with the gathered payload. Every image and ray count must equal the first (naive on the deep
// tree), which `lit` must accept (a black image proves nothing). `check` sees each tree's prepared
// scene (for its feature options). Returns how many renders were compared with the first.
inline int expect_every_method_and_tree_agree(const std::string& name, const Scene& scene, const SceneCamera& camera,
                                              RenderSettings settings,
                                              const std::function<void(const PreparedScene&, const char*)>& check,
                                              const std::function<bool(const Image&)>& lit) {
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const bool sorts = device_support(cl.info()).sorts;
  std::vector<float> reference;
  std::uint64_t reference_rays = 0;
  int compared = 0;
  const auto compare = [&](const RenderResult& r, const std::string& what) {
    if (reference.empty()) {
      reference = r.image.rgb;
      reference_rays = r.rays;
      EXPECT_TRUE(lit(r.image)) << name << ": a black image proves nothing";
      return;
    }
    ++compared;
    EXPECT_EQ(0, std::memcmp(reference.data(), r.image.rgb.data(), reference.size() * sizeof(float)))
        << name << ": " << what << " differs from naive on deep";
    EXPECT_EQ(reference_rays, r.rays) << name << ": " << what;
  };
  for (const NamedTree& t : every_tree()) {
    PreparedScene p = prepare_loaded_scene(name, scene, t.choice);
    p.camera = camera;
    check(p, t.name);
    const DeviceScene uploaded = upload_scene(cl, p.tree, p.tables, p.bvh());
    for (const auto& m : methods()) {
      if (m.sorts && !(sorts && t.sorts)) continue;
      RenderSettings s = settings;
      s.method = m.name;
      s.wavefront_size = 0;
      s.speculative = false;
      s.sort.sort_payload = "indirect";
      compare(render(cl, cache, uploaded, p.camera, s), std::string(m.name) + " on " + t.name);
      if (!m.sorts) continue;
      s.wavefront_size = 129;
      s.speculative = !p.bvh();  // the speculative resume walks the KD-tree only
      compare(render(cl, cache, uploaded, p.camera, s),
              std::string(m.name) + (s.speculative ? " speculative" : " pool 129") + " on " + t.name);
      s.speculative = false;
      s.sort.sort_payload = "gather";
      compare(render(cl, cache, uploaded, p.camera, s), std::string(m.name) + " gathered on " + t.name);
    }
  }
  // every method on every tree: hash and pth (three ways each) walk and resume on the 4-wide BVH too
  std::size_t sorting = 0, expected = 0;
  for (const auto& m : methods()) sorting += m.sorts ? 1u : 0u;
  for (const NamedTree& t : every_tree())
    expected += sorts && t.sorts ? methods().size() + 2 * sorting : methods().size() - sorting;
  EXPECT_EQ(std::size_t(compared), expected - 1) << name;  // the first is the reference
  return compared;
}

}  // namespace cohort::test
