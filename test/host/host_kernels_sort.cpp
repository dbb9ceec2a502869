// The radix sort kernels compiled as host C++ with the CPU tiling RadixSort picks for a device of
// one work item per work-group (runtime/sort/radix_sort.cpp, choose_tiling), for 64-bit keys (this
// file) and 32-bit keys (host_kernels_sort32.cpp).
#define SORT_WG 1
#define SORT_ITEMS 4096
#define SORT_LOCAL_EXCHANGE 0
#define SORT_KEY64 1
#include "kernels/common/sort/radix_sort_kernels.h"

#include "host/host_device.h"

namespace cohort::test {

const HostProgram& host_sort64_program() {
  static const HostProgram program{"-DSORT_WG=1 -DSORT_ITEMS=4096 -DSORT_LOCAL_EXCHANGE=0 -DSORT_KEY64=1",
                                   {{"sort_histogram", host_kernel(&sort_histogram)},
                                    {"sort_pass", host_kernel(&sort_pass)}}};
  return program;
}

}  // namespace cohort::test
