// The ranks of an MPI job as a RenderTeam (runtime/render/run/render_team.h): rank 0 hands out the
// passes (pass_exchange.h), a failing rank ends every rank with its rank and host.
#pragma once

#include <memory>

#include "runtime/render/run/render_team.h"

namespace cohort {

// The MPI job when an MPI launcher started this process with more than one rank; a team of this
// process alone otherwise (holding the MPI session of a job of one rank).
std::unique_ptr<RenderTeam> join_mpi_team();

}  // namespace cohort
