/* OpenCL entry point: device radix sort; SORT_WG, SORT_ITEMS, SCAN_WG and SORT_LOCAL_EXCHANGE come from the host.
 * The kernels live in common/sort/radix_sort_kernels.h. */
#include "common/sort/radix_sort_kernels.h"
