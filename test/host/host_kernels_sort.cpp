// The radix sort kernels compiled as host C++ with the CPU tiling RadixSort picks for a device of
// one work item per work-group (runtime/sort/radix_sort.cpp, choose_tiling).
#define SORT_WG 1
#define SORT_ITEMS 4096
#define SCAN_WG 1
#define SORT_LOCAL_EXCHANGE 0
#include "kernels/common/radix_sort_kernels.h"

#include "host/host_device.h"

namespace cohort::test {

const HostProgram& host_sort_program() {
  static const HostProgram program{"-DSORT_WG=1 -DSORT_ITEMS=4096 -DSCAN_WG=1 -DSORT_LOCAL_EXCHANGE=0",
                                   {{"sort_histogram", host_kernel(&sort_histogram)},
                                    {"sort_scan_segments", host_kernel(&sort_scan_segments)},
                                    {"sort_scan_add", host_kernel(&sort_scan_add)},
                                    {"sort_scatter", host_kernel(&sort_scatter)}}};
  return program;
}

}  // namespace cohort::test
