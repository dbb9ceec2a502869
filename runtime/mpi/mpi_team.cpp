#include "runtime/mpi/mpi_team.h"

#include <stdexcept>

#include "runtime/mpi/pass_exchange.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

class MpiTeam final : public RenderTeam {
 public:
  explicit MpiTeam(std::unique_ptr<MpiSession> session) : mpi_(std::move(session)) {}

  int rank() const override { return mpi_->rank(); }
  int local_rank() const override { return mpi_->local_rank(); }
  std::size_t size() const override { return static_cast<std::size_t>(mpi_->size()); }
  const std::string& host() const override { return mpi_->host(); }

  int run(const std::function<int()>& render) const override {
    try {
      return render();
    } catch (const InputError& e) {
      mpi_->abort(e.what(), 2);
    } catch (const std::exception& e) {
      mpi_->abort(e.what(), 1);
    }
  }

  void serve(PassJob& job, std::size_t pixels) const override {
    try {
      serve_passes(*mpi_, job, pixels);
    } catch (...) {
      job.abort();
      throw;
    }
  }

  std::vector<DeviceRun> follow(std::size_t devices, const StartWorkers& start, std::size_t pixels) const override {
    AssignedPasses passes(devices);
    const auto workers = start(passes);
    try {
      run_assigned_passes(passes, pixels);
    } catch (...) {
      passes.abort();
      throw;
    }
    return workers->join();
  }

  std::vector<std::string> gather(const std::string& figures) const override { return mpi_->gather(figures); }

 private:
  std::unique_ptr<MpiSession> mpi_;
};

}  // namespace

std::unique_ptr<RenderTeam> join_mpi_team() {
  if (!MpiSession::launched_by_mpi()) return solo_render_team();
  auto session = std::make_unique<MpiSession>();
  if (session->size() > 1) return std::make_unique<MpiTeam>(std::move(session));
  return solo_render_team(std::shared_ptr<const MpiSession>(std::move(session)));
}

}  // namespace cohort
