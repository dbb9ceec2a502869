// A folder the layers do not place.
#include "runtime/util/error.h"
