#include "runtime/scene/obj_materials.h"

#include <algorithm>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include "runtime/scene/file_lookup.h"
#include "runtime/scene/gzip_file.h"
#include "runtime/scene/obj_text_check.h"
#include "runtime/scene/texture_decode.h"
#include "runtime/util/error.h"

namespace cohort::obj {
namespace {

// Decodes each map_Kd once; textures that are missing are reported together, not one by one.
class TextureFiles {
 public:
  TextureFiles(const std::filesystem::path& obj_path, Scene& scene) : obj_path_(obj_path), scene_(scene) {}

  // `use` says what the texture drives, for `info`.
  int index_of(const std::string& name, const std::string& use) {
    if (name.empty()) return -1;
    const auto [it, inserted] = by_name_.try_emplace(name, -1);
    if (inserted) it->second = load(name);
    if (it->second >= 0) scene_.textures[static_cast<std::size_t>(it->second)].uses.push_back(use);
    return it->second;
  }

  void report_missing() const {
    if (missing_.empty()) return;
    scene_.warnings.push_back(fmt::format("{}: {} base colour texture(s) not found, e.g. '{}'",
                                          obj_path_.string(), missing_.size(), missing_.front()));
  }

 private:
  int load(const std::string& name) {
    const auto file = find_file(obj_path_.parent_path(), name);
    if (!file) {
      missing_.push_back(name);
      return -1;
    }
    const std::string bytes = read_whole_file(*file);
    std::string error;
    auto texture =
        decode_texture(name, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), &error);
    // A texture that is there but broken is an error; a missing one (reported above) is not.
    if (!texture)
      throw InputError(
          fmt::format("{}: texture '{}' cannot be decoded: {}", obj_path_.string(), file->string(), error));
    scene_.textures.push_back(std::move(*texture));
    return static_cast<int>(scene_.textures.size() - 1);
  }

  const std::filesystem::path& obj_path_;
  Scene& scene_;
  std::map<std::string, int> by_name_;
  std::vector<std::string> missing_;
};

// Classic .mtl files describe Phong lobes (Ks, Ns) that have no faithful metallic-roughness
// equivalent, so materials stay diffuse: Kd, Ke and dissolve only.
SceneMaterial convert(const tinyobj::material_t& m, TextureFiles& textures) {
  SceneMaterial out;
  out.name = m.name;
  out.base_color = glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
  out.emission = glm::max(glm::vec3(m.emission[0], m.emission[1], m.emission[2]), glm::vec3(0.f));
  out.alpha = std::clamp(static_cast<float>(m.dissolve), 0.f, 1.f);
  out.base_color_texture = textures.index_of(m.diffuse_texname, fmt::format("base colour of '{}'", m.name));
  return out;
}

}  // namespace

bool MaterialLibraries::operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                                   std::map<std::string, int>* names, std::string* warn, std::string* err) {
  const auto file = find_file(obj_path_.parent_path(), name);
  if (!file) {
    scene_.warnings.push_back(fmt::format("{}: material library '{}' not found; its materials use defaults",
                                          obj_path_.string(), name));
    return false;
  }
  std::istringstream text;
  try {
    text.str(checked_mtl_text(read_whole_file(*file), file->string()));
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: material library {}", obj_path_.string(), e.what()));
  }
  tinyobj::LoadMtl(names, materials, &text, warn, err);
  return true;
}

void convert_materials(const std::vector<tinyobj::material_t>& materials,
                       const std::filesystem::path& obj_path, Scene& scene) {
  TextureFiles textures(obj_path, scene);
  scene.materials.reserve(scene.materials.size() + materials.size());
  for (const tinyobj::material_t& m : materials) scene.materials.push_back(convert(m, textures));
  textures.report_missing();
}

}  // namespace cohort::obj
