#include "runtime/cli/render_team.h"

#include <unistd.h>

#include <array>
#include <stdexcept>

#include "runtime/util/error.h"
#ifdef COHORT_HAVE_MPI
#include "runtime/mpi/pass_exchange.h"
#endif

namespace cohort {
namespace {

std::string this_host() {
  std::array<char, 256> name{};
  return gethostname(name.data(), name.size() - 1) == 0 ? std::string(name.data()) : std::string();
}

class SoloTeam final : public RenderTeam {
 public:
  // `session`: kept alive for the render when an MPI launcher started this one process
  explicit SoloTeam(std::shared_ptr<const void> session = nullptr) : session_(std::move(session)) {}

  int rank() const override { return 0; }
  int local_rank() const override { return 0; }
  std::size_t size() const override { return 1; }
  const std::string& host() const override { return host_; }
  int run(const std::function<int()>& render) const override { return render(); }
  void serve(PassJob&, std::size_t) const override {}
  std::vector<DeviceRun> follow(std::size_t, const StartWorkers&, std::size_t) const override {
    throw std::logic_error("a render of one process has no rank 0 to follow");
  }
  std::vector<std::string> gather(const std::string& figures) const override { return {figures}; }

 private:
  std::shared_ptr<const void> session_;
  std::string host_ = this_host();
};

#ifdef COHORT_HAVE_MPI
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
#endif

}  // namespace

std::unique_ptr<RenderTeam> join_render_team() {
#ifdef COHORT_HAVE_MPI
  if (MpiSession::launched_by_mpi()) {
    auto session = std::make_unique<MpiSession>();
    if (session->size() > 1) return std::make_unique<MpiTeam>(std::move(session));
    return std::make_unique<SoloTeam>(std::shared_ptr<const MpiSession>(std::move(session)));
  }
#endif
  return std::make_unique<SoloTeam>();
}

std::unique_ptr<RenderTeam> solo_render_team() { return std::make_unique<SoloTeam>(); }

}  // namespace cohort
