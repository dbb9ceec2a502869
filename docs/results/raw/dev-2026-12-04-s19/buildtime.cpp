#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <chrono>
#include <tbb/global_control.h>
#include "runtime/accel/kdtree.h"
#include "runtime/scene/scene.h"
int main(int argc, char** argv) {
  int threads = std::atoi(argv[1]), reps = std::atoi(argv[2]);
  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
  for (int i = 3; i < argc; ++i) {
    cohort::Scene s = cohort::load_scene(argv[i]);
    std::vector<double> t;
    for (int r = 0; r < reps; ++r) {
      cohort::KdBuildOptions o; o.compact = true;
      auto tree = cohort::build_kdtree(s.positions, o);
      t.push_back(tree.stats.build_seconds);
    }
    std::vector<double> sorted = t; std::sort(sorted.begin(), sorted.end());
    std::printf("%s median %.3f min %.3f :", argv[i], sorted[sorted.size()/2], sorted[0]);
    for (double x : t) std::printf(" %.3f", x);
    std::printf("\n");
  }
}
