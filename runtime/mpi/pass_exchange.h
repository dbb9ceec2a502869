// Sample passes across MPI ranks. Rank 0 owns the PassJob: it hands passes to its own devices and,
// on request, to the other ranks, and adds every partial film in pass order, so the image equals
// the single-process image bit for bit on identical devices. Other ranks render what rank 0 assigns
// and send each partial film back. All MPI calls stay on each rank's main thread; devices work in
// their own threads (DeviceWorkers) meanwhile.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>

#include "runtime/mpi/mpi_session.h"
#include "runtime/render/run/pass_job.h"

namespace cohort {

// Rank 0: serves the other ranks until `job` is finished and every rank was told to stop, or until
// a local device aborted the job.
void serve_passes(const MpiSession& mpi, PassJob& job, std::size_t pixels);

// The passes rank 0 assigned to this rank, as a PassSource for this rank's devices.
class AssignedPasses final : public PassSource {
 public:
  explicit AssignedPasses(std::size_t devices) : devices_(devices) {}
  std::optional<SamplePass> next() override;
  void deliver(PassFilm film) override;
  void abort() override;

 private:
  friend void run_assigned_passes(AssignedPasses& passes, std::size_t pixels);
  const std::size_t devices_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<SamplePass> assigned_;
  std::deque<PassFilm> finished_;
  std::size_t rendering_ = 0;
  bool ended_ = false;
  bool aborted_ = false;
};

// Any other rank: asks rank 0 for passes while its devices could use more, sends their films
// back, and returns once rank 0 said there is no more and every film is sent.
void run_assigned_passes(AssignedPasses& passes, std::size_t pixels);

}  // namespace cohort
