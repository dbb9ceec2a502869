// The layer check's own test: lines 3 to 5 include folders above render; the rest are allowed.
#include "runtime/render/run/render_run.h"
#include "runtime/cli/commands.h"
#include "runtime/bench/figures.h"
#  include "runtime/mpi/mpi_team.h"
#include "runtime/util/error.h"
#include <runtime/scene/scene.h>
