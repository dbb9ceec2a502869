#include "runtime/render/run/render_team.h"

#include <unistd.h>

#include <array>
#include <stdexcept>

namespace cohort {
namespace {

std::string this_host() {
  std::array<char, 256> name{};
  return gethostname(name.data(), name.size() - 1) == 0 ? std::string(name.data()) : std::string();
}

class SoloTeam final : public RenderTeam {
 public:
  explicit SoloTeam(std::shared_ptr<const void> keep) : keep_(std::move(keep)) {}

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
  std::shared_ptr<const void> keep_;
  std::string host_ = this_host();
};

}  // namespace

std::unique_ptr<RenderTeam> solo_render_team(std::shared_ptr<const void> keep) {
  return std::make_unique<SoloTeam>(std::move(keep));
}

}  // namespace cohort
