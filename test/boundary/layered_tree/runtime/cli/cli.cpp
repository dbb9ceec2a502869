// The command line may include every folder but the backends'; cl is a leak (line 4).
#include "runtime/bench/figures.h"
#include "runtime/mpi/mpi_team.h"
#include "runtime/cl/context.h"
