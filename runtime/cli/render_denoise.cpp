// --denoise: Open Image Denoise over the finished beauty, guided by the first-hit albedo and
// normal, written beside it (OUT.denoised.exr/.png); the beauty itself is never replaced.
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <system_error>

#include "runtime/cli/render_steps.h"
#include "runtime/image/denoiser.h"

namespace cohort {
namespace {

// Where the pyoidn wheel may be: $COHORT_VENV (scripts/lib/venv.sh), else the venv beside the binary
// (build/venv, where scripts/setup.sh puts it).
std::vector<std::filesystem::path> wheel_candidates(const std::vector<std::filesystem::path>& venvs = {}) {
  std::vector<std::filesystem::path> out;
  for (const auto& venv : venvs)
    for (auto& p : Denoiser::venv_candidates(venv)) out.push_back(std::move(p));
  if (const char* venv = std::getenv("COHORT_VENV"); venv && *venv) out = Denoiser::venv_candidates(venv);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (auto& p : Denoiser::venv_candidates(exe.parent_path() / "venv")) out.push_back(std::move(p));
  return out;
}

}  // namespace

Image denoise_image(const RenderOutcome& outcome, const std::vector<std::filesystem::path>& venvs,
                    std::string* library) {
  const Denoiser denoiser = Denoiser::load(wheel_candidates(venvs));
  if (library) *library = denoiser.library();
  const AovImages& aovs = *outcome.aovs;
  return denoiser.denoise(outcome.result.image, &aovs.albedo, &aovs.normal);
}

DenoiseOutcome write_denoised(const RenderCommand& command, const RenderOutcome& outcome, const OutputPaths& out) {
  DenoiseOutcome done;
  if (!command.denoise) return done;
  try {
    const auto start = std::chrono::steady_clock::now();
    const Image denoised = denoise_image(outcome, {}, &done.library);
    done.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    done.aov_seconds = outcome.aov_seconds;
    done.denoised = true;
    write_exr(out.denoised_exr, denoised);
    write_png(out.denoised_png, denoised);
    fmt::print("denoised with {} in {:.3f}s (first-hit AOVs {:.3f}s)\nwrote {}\nwrote {}\n", done.library,
               done.seconds, done.aov_seconds, out.denoised_exr.string(), out.denoised_png.string());
  } catch (const DenoiserUnavailable& e) {
    fmt::print(stderr, "cohort: --denoise: {}\nthe undenoised image is written: {}\n", e.what(), out.exr.string());
    done.code = 2;
  }
  return done;
}

}  // namespace cohort
