// How one process takes part in a render: alone, or as one rank of an MPI job (runtime/mpi/mpi_team.h).
// Chosen once by the caller; the run (render_run.h) asks the team and never tests for MPI itself.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/render/run/multi_device.h"
#include "runtime/render/run/pass_job.h"

namespace cohort {

class RenderTeam {
 public:
  virtual ~RenderTeam() = default;

  virtual int rank() const = 0;
  virtual int local_rank() const = 0;  // among the ranks on this machine: picks this rank's devices
  virtual std::size_t size() const = 0;
  virtual const std::string& host() const = 0;
  bool leads() const { return rank() == 0; }  // rank 0 owns the image and writes every output

  // Runs one rank's whole render and returns its exit code; in a job of several ranks a failing
  // rank ends every rank with its rank and host, never leaves the others waiting.
  virtual int run(const std::function<int()>& render) const = 0;

  // Rank 0, while its own devices render `job`: hands passes to the other ranks until the job is done.
  virtual void serve(PassJob& job, std::size_t pixels) const = 0;

  // Any other rank: renders the passes rank 0 assigns on the workers `start` starts (one per
  // device of `devices`) until rank 0 says there are no more, and returns their figures.
  using StartWorkers = std::function<std::unique_ptr<DeviceWorkers>(PassSource& passes)>;
  virtual std::vector<DeviceRun> follow(std::size_t devices, const StartWorkers& start, std::size_t pixels) const = 0;

  // Every rank's `figures` in rank order on rank 0; an empty vector elsewhere.
  virtual std::vector<std::string> gather(const std::string& figures) const = 0;
};

// A team of this process alone, whatever launched it; `keep` stays alive as long as the team (the
// MPI session of a job of one rank).
std::unique_ptr<RenderTeam> solo_render_team(std::shared_ptr<const void> keep = nullptr);

}  // namespace cohort
