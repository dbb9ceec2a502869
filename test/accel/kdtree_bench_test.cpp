// Build times and tree statistics on the shared models. Disabled in the normal run (it takes a
// while); scripts/bench-suite kd-build runs it: test_accel --gtest_also_run_disabled_tests
// --gtest_filter='KdTreeBench.*'.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <climits>
#include <utility>

#include "accel/test_meshes.h"
#include "accel/tree_check.h"
#include "kernels/common/accel/kdtree_traverse.h"

namespace cohort::test {
namespace {

void bench(const char* model) {
  const auto positions = load_shared(model);
  if (!positions) {
    fmt::print("[{}] not found, skipped\n", model);
    return;
  }
  KdBuildOptions serial;
  serial.parallel = false;
  KdBuildOptions exact;  // every node by the exact sweep: Wald & Havran's tree, the quality reference
  exact.exact_triangles = INT_MAX;
  for (const auto& [name, options] : {std::pair{"parallel", KdBuildOptions{}}, std::pair{"serial  ", serial},
                                      std::pair{"exact   ", exact}}) {
    const KdTree tree = build_kdtree(*positions, options);
    fmt::print("[{}] {}: {}\n", model, name, summary(tree));
    for (const std::string& e : layout_errors(tree, KD_MAX_DEPTH)) ADD_FAILURE() << e;
  }
}

TEST(KdTreeBench, DISABLED_SharedModels) {
  if (!shared_scenes()) GTEST_SKIP() << "shared scenes not found";
  for (const char* model :
       {"cornell-box-mcguire/CornellBox-Original.obj", "bunny/bun_zipper_res2.ply",
        "bunny/bun_zipper.ply", "dragon-decimated-100k/dragon.ply", "crytek-sponza/sponza.obj.gz",
        "conference/conference.obj.gz", "armadillo/Armadillo.ply.gz"}) {
    bench(model);
  }
}

}  // namespace
}  // namespace cohort::test
