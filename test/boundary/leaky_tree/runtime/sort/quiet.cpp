// Not leaks: a comment naming <CL/cl.h>, and headers whose names only look alike.
// #include <CL/cl.h>
#include "runtime/backend/program_cache.h"
#include "runtime/render/cl_free.h"
#include <cudaish.h>
