// Every method on scenes built to defeat it: each must give the NAIVE image bit for bit, without a
// crash or a hang.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>

#include "accel/straggler_check.h"
#include "render_fixture.h"
#include "scene_building.h"
#include "runtime/render/methods/methods.h"

using namespace cohort;
using namespace cohort::test;

namespace {

Scene base_scene() {
  Scene s;
  SceneMaterial white;
  white.base_color = glm::vec3(0.7f);
  SceneMaterial light;
  light.base_color = glm::vec3(0.5f);
  light.emission = glm::vec3(4.f);
  light.double_sided = true;
  s.materials = {white, light};
  return s;
}

// An axis-aligned closed box of `size` at the origin, faces pointing inwards, and a light inside.
Scene closed_box(float size) {
  Scene s = base_scene();
  const glm::vec3 x(size, 0, 0), y(0, size, 0), z(0, 0, size), o(0.f);
  add_quad(s, o, z, x, 0);          // floor
  add_quad(s, o + y, x, z, 0);      // ceiling
  add_quad(s, o, y, z, 0);          // x = 0 wall
  add_quad(s, o + x, z, y, 0);      // x = size wall
  add_quad(s, o, x, y, 0);          // z = 0 wall
  add_quad(s, o + z, y, x, 0);      // z = size wall
  add_quad(s, glm::vec3(0.4f, 0.99f, 0.4f) * size, glm::vec3(0.2f * size, 0, 0), glm::vec3(0, 0, 0.2f * size), 1);
  return s;
}

struct Adversary {
  const char* name;
  std::function<Scene()> scene;
  SceneCamera camera;
  bool environment = false;
};

std::vector<Adversary> adversaries() {
  std::vector<Adversary> out;
  {
    Scene s = base_scene();
    add_triangle(s, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 1);
    out.push_back({"one_triangle", [s] { return s; }, {{0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 50}});
  }
  out.push_back({"all_rays_miss", [] { return closed_box(1.f); }, {{0.5f, 0.5f, -2}, {0.5f, 0.5f, -5}, {0, 1, 0}, 40},
                 true});
  {
    Scene s = base_scene();
    add_quad(s, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0);
    add_quad(s, {-0.2f, 1, -0.2f}, {0.4f, 0, 0}, {0, 0, 0.4f}, 1);
    out.push_back({"tree_shallower_than_subtree", [s] { return s; }, {{0, 2, 3}, {0, 0, 0}, {0, 1, 0}, 50}, true});
  }
  {
    Scene s = base_scene();
    add_quad(s, {-100, 0, -100}, {0, 0, 200}, {200, 0, 0}, 0);
    add_quad(s, {-1, 1, -1}, {2, 0, 0}, {0, 0, 2}, 1);
    // nearly parallel primary rays, all hitting the plane at the same angle
    out.push_back({"coherent_rays", [s] { return s; }, {{0, 500, 0.01f}, {0, 0, 0}, {0, 0, 1}, 0.05f}});
  }
  out.push_back({"million_triangles_in_one_leaf_region",
                 [] {
                   Scene s = closed_box(1.f);
                   std::mt19937 rng(5);
                   std::uniform_real_distribution<float> u(0.49f, 0.51f);
                   for (int i = 0; i < 1000000; ++i)
                     add_triangle(s, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, 0);
                   return s;
                 },
                 {{0.5f, 0.5f, 0.05f}, {0.5f, 0.5f, 0.5f}, {0, 1, 0}, 30}});
  out.push_back({"origins_in_split_planes",
                 [] { return closed_box(2.f); },
                 // the eye lies in the wall plane x = 0 and looks along it: every primary ray starts in
                 // a split plane, and half of them run inside it
                 {{0, 1, 0.5f}, {0, 1, 1.5f}, {0, 1, 0}, 60}});
  out.push_back({"camera_inside_geometry",
                 [] {
                   Scene s = closed_box(1.f);
                   // a closed box around the camera whose faces point outwards
                   const glm::vec3 o(0.4f), x(0.2f, 0, 0), y(0, 0.2f, 0), z(0, 0, 0.2f);
                   add_quad(s, o, x, z, 0);
                   add_quad(s, o + y, z, x, 0);
                   add_quad(s, o, z, y, 0);
                   add_quad(s, o + x, y, z, 0);
                   add_quad(s, o, y, x, 0);
                   add_quad(s, o + z, x, y, 0);
                   return s;
                 },
                 {{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 1}, {0, 1, 0}, 90}});
  return out;
}

class Adversarial : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Adversarial, EveryMethodGivesTheReferenceImage) {
  const Adversary adv = adversaries()[GetParam()];
  PreparedScene p;
  p.scene = adv.scene();
  p.tree = build_kdtree(p.scene.positions);
  p.tables = make_scene_tables(p.scene, p.tree);
  p.camera = adv.camera;
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, p.tree, p.tables);
  RenderSettings s;
  s.width = 20;
  s.height = 16;
  s.spp = 2;
  s.rr_depth = 2;
  if (adv.environment) s.environment = glm::vec3(0.5f, 0.6f, 0.7f);
  const RenderResult reference = render(cl, cache, scene, p.camera, s);
  EXPECT_EQ(reference.dropped_samples, 0u);
  for (const auto& m : methods()) {
    if (!m.wavefront) continue;
    s.method = m.name;
    const RenderResult r = render(cl, cache, scene, p.camera, s);
    EXPECT_EQ(0, std::memcmp(reference.image.rgb.data(), r.image.rgb.data(), r.image.rgb.size() * sizeof(float)))
        << adv.name << ": " << m.name << " differs from naive";
    EXPECT_EQ(reference.rays, r.rays) << adv.name << ": " << m.name;
    // the same rays through the same traversal: the straggler figure agrees too (pth counts only
    // the resumed part of its extension rays, after the walk in local memory)
    if (m.name != std::string("pth")) {
      EXPECT_EQ(reference.max_nodes_per_ray, r.max_nodes_per_ray) << adv.name << ": " << m.name;
    }
  }
  if (adv.name != std::string("all_rays_miss")) {
    EXPECT_GT(reference.max_nodes_per_ray, 0u) << adv.name;
  }
}

// Rays built to straggle (zero direction components, origins on split planes, box faces, edges
// and surfaces) never visit a node whose cell they do not touch on these scenes either.
TEST_P(Adversarial, NoRayVisitsCellsItNeverTouches) {
  const Adversary adv = adversaries()[GetParam()];
  const KdTree tree = build_kdtree(adv.scene().positions);
  // a million triangles in a few leaves make each ray through them slow on the host: fewer rays
  const auto rays = straggler_rays(tree, std::min<std::size_t>(12'000, 300'000'000 / tree.triangles.size()), 31);
  const StragglerCheck check = check_stragglers(tree, rays, host_visits(tree, rays));
  for (const std::string& w : check.worst) std::printf("  %s\n", w.c_str());
  EXPECT_EQ(check.over_bound, 0u) << adv.name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, Adversarial, ::testing::Range<std::size_t>(0, adversaries().size()),
                         [](const auto& info) { return std::string(adversaries()[info.param].name); });

}  // namespace
