#include "runtime/cli/output_paths.h"

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort {

OutputPaths output_paths(const std::string& output, const std::filesystem::path& scene) {
  namespace fs = std::filesystem;
  fs::path base;
  if (output.empty()) {
    base = scene.filename();
    while (base.has_extension()) base = base.stem();  // cornell-box.gltf, model.obj.gz -> the bare name
  } else {
    base = output;
    const auto ext = base.extension().string();
    if (ext == ".exr" || ext == ".png") base.replace_extension();
    else if (!ext.empty() && ext != base.string())
      throw InputError(fmt::format("-o {}: the output must end in .exr, .png or have no extension", output));
  }
  const fs::path dir = base.has_parent_path() ? base.parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    throw InputError(fmt::format("-o {}: directory {} does not exist", output, dir.string()));
  OutputPaths paths;
  paths.exr = fs::path(base).concat(".exr");
  paths.png = fs::path(base).concat(".png");
  paths.checkpoint = fs::path(base).concat(".checkpoint");
  paths.denoised_exr = fs::path(base).concat(".denoised.exr");
  paths.denoised_png = fs::path(base).concat(".denoised.png");
  return paths;
}

}  // namespace cohort
