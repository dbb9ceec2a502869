// The radix sort kernels for 32-bit keys compiled as host C++ (see host_kernels_sort.cpp). The kernel
// names are those of the 64-bit build, so they live in a namespace of their own.
#define SORT_WG 1
#define SORT_ITEMS 4096
#define SORT_LOCAL_EXCHANGE 0
#define SORT_KEY64 0
#include "kernels/common/core/port.h"
namespace sort32 {
#include "kernels/common/sort/radix_sort_kernels.h"
}  // namespace sort32

#include "host/host_device.h"

namespace cohort::test {

const HostProgram& host_sort32_program() {
  static const HostProgram program{"-DSORT_WG=1 -DSORT_ITEMS=4096 -DSORT_LOCAL_EXCHANGE=0 -DSORT_KEY64=0",
                                   {{"sort_histogram", host_kernel(&sort32::sort_histogram)},
                                    {"sort_pass", host_kernel(&sort32::sort_pass)}}};
  return program;
}

}  // namespace cohort::test
