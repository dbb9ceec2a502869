// --tree auto's choice (tree_options): the 8-wide BVH with float planes where every device is a CPU
// and the method walks it, the 4-wide BVH on GPUs, for hash and pth, and without devices, a KD-tree
// when one is asked for; the named trees as named.
#include <gtest/gtest.h>

#include <vector>

#include "runtime/render/scene/prepared_scene.h"
#include "runtime/util/error.h"

namespace cohort::test {
namespace {

DeviceInfo device(bool gpu) {
  DeviceInfo d;
  d.is_gpu = gpu;
  d.is_cpu = !gpu;
  return d;
}

const char* kind(const TreeChoice& t) {
  return t.bvh4 ? "bvh4" : t.bvh8 ? "bvh8" : t.bvh8f ? "bvh8f" : t.kd.compact ? "compact" : "deep";
}

TEST(TreeChoice, AutoTracesTheFloatPlaneEightWideBvhOnCpus) {
  const DeviceInfo cpu = device(false), gpu = device(true);
  const std::vector<DeviceInfo> cpus{cpu, cpu}, mixed{cpu, gpu};
  EXPECT_STREQ(kind(tree_options("auto", cpu)), "bvh8f");
  EXPECT_STREQ(kind(tree_options("auto", cpus)), "bvh8f");
  EXPECT_STREQ(kind(tree_options("auto", gpu)), "bvh4");
  EXPECT_STREQ(kind(tree_options("auto", mixed)), "bvh4") << "a GPU among the devices keeps the 4-wide BVH";
  EXPECT_STREQ(kind(tree_options("auto")), "bvh4") << "no devices (info): the 4-wide BVH";
  EXPECT_STREQ(kind(tree_options("auto", cpu, false, true)), "bvh4") << "hash and pth walk the 4-wide BVH's top";
  EXPECT_STREQ(kind(tree_options("auto", cpu, true)), "compact") << "a KD-tree asked for, on a CPU";
  EXPECT_STREQ(kind(tree_options("auto", gpu, true)), "deep") << "a KD-tree asked for, on a GPU";
}

TEST(TreeChoice, NamedTreesAreBuiltAsNamed) {
  const DeviceInfo cpu = device(false), gpu = device(true);
  for (const DeviceInfo& d : {cpu, gpu}) {
    for (const char* name : {"bvh4", "bvh8", "bvh8f", "deep", "compact"}) EXPECT_STREQ(kind(tree_options(name, d)), name);
    for (const char* name : {"bvh4", "bvh8", "bvh8f"}) EXPECT_THROW(tree_options(name, d, true), InputError) << name;
  }
  EXPECT_THROW(tree_options("bvh16", cpu), InputError);
}

}  // namespace
}  // namespace cohort::test
