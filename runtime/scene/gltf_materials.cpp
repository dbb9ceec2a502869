#include "runtime/scene/gltf_materials.h"

#include <map>
#include <optional>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "runtime/scene/gltf_accessor.h"
#include "runtime/scene/texture_decode.h"
#include "runtime/util/error.h"

namespace cohort::gltf {
namespace {

// A number from a material extension, or `fallback` when the extension or value is absent.
float extension_number(const tinygltf::Material& m, const std::string& extension, const std::string& key,
                       float fallback) {
  const auto it = m.extensions.find(extension);
  if (it == m.extensions.end() || !it->second.IsObject()) return fallback;
  const tinygltf::Value& v = it->second.Get(key);
  return v.IsNumber() ? static_cast<float>(v.GetNumberAsDouble()) : fallback;
}

glm::vec3 vec3_or(const std::vector<double>& v, glm::vec3 fallback) {
  return v.size() >= 3 ? glm::vec3(v[0], v[1], v[2]) : fallback;
}

// Decodes the images of base-colour and emissive textures once each, however many materials share them.
class TextureTable {
 public:
  TextureTable(const tinygltf::Model& model, const std::string& file, Scene& scene)
      : model_(model), file_(file), scene_(scene) {}

  int index_of(int gltf_texture) {
    if (gltf_texture < 0) return -1;
    if (static_cast<std::size_t>(gltf_texture) >= model_.textures.size()) {
      warn(fmt::format("texture {} does not exist", gltf_texture));
      return -1;
    }
    const int image = model_.textures[static_cast<std::size_t>(gltf_texture)].source;
    if (image < 0 || static_cast<std::size_t>(image) >= model_.images.size()) {
      warn(fmt::format("texture {} has no image this loader can read", gltf_texture));
      return -1;
    }
    const auto [it, inserted] = by_image_.try_emplace(image, -1);
    if (inserted) it->second = decode(image);
    return it->second;
  }

 private:
  int decode(int index) {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
    // A data URI would quote the whole image in messages.
    const std::string name = image.uri.empty() || image.uri.starts_with("data:") ? fmt::format("image {}", index)
                                                                                   : image.uri;
    // Images in buffer views are read here, bounds-checked; tinygltf only kept the external ones.
    const std::string_view bytes =
        image.bufferView >= 0
            ? buffer_view_bytes(model_, image.bufferView, fmt::format("{}: image {}", file_, index))
            : std::string_view(reinterpret_cast<const char*>(image.image.data()), image.image.size());
    if (bytes.empty()) {
      warn(fmt::format("{} could not be read; texture ignored", name));
      return -1;
    }
    std::string error;
    auto texture =
        decode_texture(name, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), &error);
    // Image bytes that are there but broken are a broken file, unlike a missing one (often a
    // texture left out of a copy): rendering without them would pass a wrong image off as right.
    if (!texture) throw InputError(fmt::format("{}: {} cannot be decoded: {}", file_, name, error));
    scene_.textures.push_back(std::move(*texture));
    return static_cast<int>(scene_.textures.size() - 1);
  }

  void warn(const std::string& what) { scene_.warnings.push_back(fmt::format("{}: {}", file_, what)); }

  const tinygltf::Model& model_;
  const std::string& file_;
  Scene& scene_;
  std::map<int, int> by_image_;
};

SceneMaterial convert(const tinygltf::Material& m, TextureTable& textures) {
  const auto& pbr = m.pbrMetallicRoughness;
  SceneMaterial out;
  out.name = m.name;
  const auto& factor = pbr.baseColorFactor;
  out.base_color = vec3_or(factor, glm::vec3(1.f));
  out.alpha = factor.size() >= 4 ? static_cast<float>(factor[3]) : 1.f;
  out.metallic = static_cast<float>(pbr.metallicFactor);
  out.roughness = static_cast<float>(pbr.roughnessFactor);
  out.emission = vec3_or(m.emissiveFactor, glm::vec3(0.f)) *
                 extension_number(m, "KHR_materials_emissive_strength", "emissiveStrength", 1.f);
  out.transmission = extension_number(m, "KHR_materials_transmission", "transmissionFactor", 0.f);
  out.ior = extension_number(m, "KHR_materials_ior", "ior", 1.5f);
  out.double_sided = m.doubleSided;
  out.base_color_texture = textures.index_of(pbr.baseColorTexture.index);
  out.emission_texture = textures.index_of(m.emissiveTexture.index);
  return out;
}

}  // namespace

void convert_materials(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  TextureTable textures(model, file, scene);
  scene.materials.reserve(scene.materials.size() + model.materials.size());
  for (const tinygltf::Material& m : model.materials) scene.materials.push_back(convert(m, textures));
}

}  // namespace cohort::gltf
