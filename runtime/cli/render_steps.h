// `cohort render` in three steps: parse the options into a render's input, run it (prepare the scene
// and devices, render the passes: runtime/render/run/), write the outputs. The command
// (cmd_render.cpp) composes them for each rank of its team; the Python module (scene_commands.h)
// the same way for each render of a loaded scene.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "runtime/cli/commands.h"
#include "runtime/cli/interrupt.h"
#include "runtime/cli/output_paths.h"
#include "runtime/render/run/render_run.h"

namespace cohort {

// The command's options, checked and parsed into what the run takes; nothing loaded or opened yet.
// Throws InputError for options that contradict each other.
RenderInput parse_render(const RenderCommand& command);

// Prints the scene's load warnings (rank 0, once per scene).
void report_scene_warnings(const PreparedScene& scene, const std::filesystem::path& path);

// Writes the image, the --stats file and the summary lines; returns the exit code (128 + signal
// when interrupted).
int write_render(const RenderCommand& command, const PreparedRender& render, const RenderOutcome& outcome,
                 const OutputPaths& out, const InterruptGuard& interrupt);

// The beauty denoised by Open Image Denoise, guided by the AOVs (outcome.aovs); the library is
// looked for in the system, $COHORT_OIDN_LIBRARY, $COHORT_VENV, the venv beside the binary and
// `venvs`. Throws DenoiserUnavailable; names the library it used in `library`.
Image denoise_image(const RenderOutcome& outcome, const std::vector<std::filesystem::path>& venvs = {},
                    std::string* library = nullptr);

// What --denoise did: `code` 0, or 2 when Open Image Denoise could not be loaded or run (with a
// message; the beauty is written by then); on success the library and what it cost, which --stats
// records beside the render's seconds.
struct DenoiseOutcome {
  int code = 0;
  bool denoised = false;
  std::string library;
  double seconds = 0;      // the denoiser itself
  double aov_seconds = 0;  // the first-hit albedo and normal it is guided by
};

// --denoise: writes out.denoised_exr and .png.
DenoiseOutcome write_denoised(const RenderCommand& command, const RenderOutcome& outcome, const OutputPaths& out);

// The JSON figures of the --stats file; `out` names the image files (none: not written), `denoise`
// what --denoise did (none: not asked).
nlohmann::json stats_json(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths* out,
                          const DenoiseOutcome* denoise = nullptr);

}  // namespace cohort
