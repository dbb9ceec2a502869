// Not leaks: a comment naming "runtime/render/renderer.h", and folders below sort.
// #include "runtime/render/renderer.h"
#include "runtime/backend/device.h"
#include "runtime/util/error.h"
#include "render/renderer.h"
