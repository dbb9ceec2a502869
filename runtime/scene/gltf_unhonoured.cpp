#include "runtime/scene/gltf_unhonoured.h"

#include <algorithm>
#include <array>
#include <utility>
#include <functional>
#include <map>
#include <set>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "runtime/scene/gltf_materials.h"
#include "runtime/scene/library_message.h"

namespace cohort::gltf {
namespace {

constexpr std::array kImplemented = {
    std::string_view("KHR_materials_emissive_strength"), std::string_view("KHR_materials_transmission"),
    std::string_view("KHR_materials_ior"), std::string_view("KHR_mesh_quantization"),
    std::string_view("KHR_lights_punctual"), std::string_view("KHR_texture_transform"),
    std::string_view("KHR_materials_volume"), std::string_view("KHR_materials_clearcoat"),
    std::string_view("KHR_materials_sheen"), std::string_view("KHR_materials_specular")};

// A texture reference of a material (glTF's textureInfo and its normal and occlusion variants), with
// the coordinate set it reads (KHR_texture_transform's texCoord replaces the reference's own).
struct TextureRef {
  int index;
  int tex_coord;
};

TextureRef texture_ref(int index, int tex_coord, const tinygltf::ExtensionMap& extensions) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it != extensions.end() && it->second.IsObject() && it->second.Has("texCoord") &&
      it->second.Get("texCoord").IsInt())
    tex_coord = it->second.Get("texCoord").GetNumberAsInt();
  return {index, tex_coord};
}

// The texture references of a material that the loader reads (their samplers and coordinate sets
// matter); references inside unimplemented extensions are covered by the extension's own warning.
std::vector<TextureRef> honoured_textures(const tinygltf::Material& m) {
  std::vector<TextureRef> out;
  for (const tinygltf::TextureInfo* t : {&m.pbrMetallicRoughness.baseColorTexture,
                                         &m.pbrMetallicRoughness.metallicRoughnessTexture, &m.emissiveTexture})
    if (t->index >= 0) out.push_back(texture_ref(t->index, t->texCoord, t->extensions));
  if (m.normalTexture.index >= 0)
    out.push_back(texture_ref(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions));
  // the textureInfos of the material extensions the loader reads (it has checked their types)
  constexpr std::array<std::pair<const char*, std::array<const char*, 3>>, 3> kExtensionSlots = {{
      {"KHR_materials_clearcoat", {"clearcoatTexture", "clearcoatRoughnessTexture", "clearcoatNormalTexture"}},
      {"KHR_materials_sheen", {"sheenColorTexture", "sheenRoughnessTexture", nullptr}},
      {"KHR_materials_specular", {"specularTexture", "specularColorTexture", nullptr}},
  }};
  for (const auto& [extension, slots] : kExtensionSlots) {
    const auto it = m.extensions.find(extension);
    if (it == m.extensions.end() || !it->second.IsObject()) continue;
    for (const char* slot : slots) {
      if (!slot || !it->second.Has(slot)) continue;
      const tinygltf::Value& t = it->second.Get(slot);
      if (!t.IsObject() || !t.Get("index").IsInt()) continue;
      tinygltf::ExtensionMap extensions;
      if (t.Get("extensions").IsObject())
        for (const std::string& key : t.Get("extensions").Keys()) extensions[key] = t.Get("extensions").Get(key);
      const int tex_coord = t.Get("texCoord").IsInt() ? t.Get("texCoord").GetNumberAsInt() : 0;
      out.push_back(texture_ref(t.Get("index").GetNumberAsInt(), tex_coord, extensions));
    }
  }
  return out;
}

bool any_texture(const tinygltf::Material& m, const std::function<bool(const TextureRef&)>& test) {
  const auto refs = honoured_textures(m);
  return std::any_of(refs.begin(), refs.end(), test);
}

// A feature the loader leaves out, and how to tell whether a material asks for it.
struct Unhonoured {
  std::string what;  // the feature and what is rendered instead
  std::function<bool(const tinygltf::Model&, const tinygltf::Material&)> used_by;
  std::string extension = {};  // the extension this feature is, if one
};

// A KHR_materials_specular of other than default values (or with a texture) on a material that also
// transmits (KHR_materials_transmission): the specular layering is the opaque dielectric's only
// (docs/bsdf.md, "Specular"), so its transmissive part keeps the exact Fresnel of its IOR.
bool specular_on_transmission(const tinygltf::Material& m) {
  const auto s = m.extensions.find("KHR_materials_specular");
  const auto t = m.extensions.find("KHR_materials_transmission");
  if (s == m.extensions.end() || t == m.extensions.end() || !s->second.IsObject() || !t->second.IsObject())
    return false;
  const tinygltf::Value& f = t->second.Get("transmissionFactor");
  if (!(f.IsNumber() && f.GetNumberAsDouble() > 0.0) && !t->second.Has("transmissionTexture")) return false;
  const tinygltf::Value& e = s->second;
  const auto is_one = [](const tinygltf::Value& v) { return v.IsNumber() && v.GetNumberAsDouble() == 1.0; };
  bool default_colour = true;
  if (e.Has("specularColorFactor")) {
    const tinygltf::Value& c = e.Get("specularColorFactor");
    default_colour = c.IsArray() && c.ArrayLen() == 3 && is_one(c.Get(0)) && is_one(c.Get(1)) && is_one(c.Get(2));
  }
  return (e.Has("specularFactor") && !is_one(e.Get("specularFactor"))) || !default_colour ||
         e.Has("specularTexture") || e.Has("specularColorTexture");
}

std::vector<Unhonoured> unhonoured_features() {
  return {
      {"textures read with TEXCOORD_2 or above (TEXCOORD_0 used)",
       [](const auto&, const auto& m) { return any_texture(m, [](const TextureRef& t) { return t.tex_coord > 1; }); }},
      {"KHR_materials_specular on the transmission (KHR_materials_transmission) of a material (its refraction and "
       "reflection keep the exact Fresnel of its IOR; the specular layering is its opaque part's only)",
       [](const auto&, const auto& m) { return specular_on_transmission(m); }},
  };
}

std::string materials(std::size_t n) { return fmt::format("{} material{}", n, n == 1 ? "" : "s"); }

// Each image bound as an occlusionTexture, once, with the materials it would darken: a path tracer
// traces the occlusion such a map approximates, so the slot is not read (one line per image in
// `info`'s texture list, no warning).
void list_occlusion_textures(const tinygltf::Model& model, Scene& scene) {
  std::map<int, std::string> uses;  // image -> "occlusion of 'A'; occlusion of 'B'"
  for (std::size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& m = model.materials[i];
    const int texture = m.occlusionTexture.index;
    if (texture < 0 || static_cast<std::size_t>(texture) >= model.textures.size()) continue;
    const int image = model.textures[static_cast<std::size_t>(texture)].source;
    if (image < 0 || static_cast<std::size_t>(image) >= model.images.size()) continue;
    std::string& use = uses[image];
    use += fmt::format("{}occlusion of '{}'", use.empty() ? "" : "; ", m.name.empty() ? fmt::format("material {}", i) : m.name);
  }
  for (const auto& [image, use] : uses)
    scene.unread_textures.push_back(fmt::format("{}: {}, not used: a path tracer traces the occlusion it approximates",
                                                image_name(model, image), use));
}

}  // namespace

bool extension_implemented(const std::string& name) {
  return std::find(kImplemented.begin(), kImplemented.end(), name) != kImplemented.end();
}

void report_unhonoured(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  auto warn = [&](const std::string& what, std::size_t count) {
    scene.warnings.push_back(
        fmt::format("{}: glTF feature not honoured: {}: {}", file, library_message(what), materials(count)));
  };
  std::set<std::string> named;  // extensions a warning above names already
  for (const Unhonoured& feature : unhonoured_features()) {
    const auto n = std::count_if(model.materials.begin(), model.materials.end(),
                                 [&](const tinygltf::Material& m) { return feature.used_by(model, m); });
    if (n == 0) continue;
    warn(feature.what, static_cast<std::size_t>(n));
    if (!feature.extension.empty()) named.insert(feature.extension);
  }

  // Material extensions by name, each with its material count.
  std::map<std::string, std::size_t> extensions;
  for (const tinygltf::Material& m : model.materials)
    for (const auto& [name, value] : m.extensions)
      if (!extension_implemented(name)) ++extensions[name];
  for (const auto& [name, count] : extensions) {
    warn(fmt::format("extension {}", name), count);
    named.insert(name);
  }
  std::string others;
  for (const std::string& name : model.extensionsUsed)
    if (!extension_implemented(name) && !named.count(name)) others += (others.empty() ? "" : ", ") + name;
  if (!others.empty())
    scene.warnings.push_back(fmt::format("{}: glTF extensions ignored (optional, not implemented): {}", file,
                                         library_message(others)));

  list_occlusion_textures(model, scene);

  const auto thick = std::count_if(model.materials.begin(), model.materials.end(), [](const tinygltf::Material& m) {
    const auto it = m.extensions.find("KHR_materials_volume");
    return it != m.extensions.end() && it->second.IsObject() &&
           (it->second.Has("thicknessFactor") || it->second.Has("thicknessTexture"));
  });
  if (thick > 0)
    scene.notes.push_back(fmt::format("{}: KHR_materials_volume thicknessFactor and thicknessTexture of {} not "
                                      "used: a path tracer measures the distance inside on the geometry",
                                      file, materials(static_cast<std::size_t>(thick))));
}

void report_missing_coordinates(const std::string& file, Scene& scene) {
  const auto count = [&](const std::vector<glm::vec2>& uvs, int set) {
    if (uvs.size() == 3 * scene.triangle_count()) return std::size_t{0};
    return static_cast<std::size_t>(std::count_if(scene.materials.begin(), scene.materials.end(), [&](const SceneMaterial& m) {
      return (m.base_color_texture >= 0 && m.base_color_texcoord == set) ||
             (m.emission_texture >= 0 && m.emission_texcoord == set) ||
             (m.metallic_roughness_texture >= 0 && m.metallic_roughness_texcoord == set) ||
             (m.normal_texture >= 0 && m.normal_texcoord == set) ||
             (m.clearcoat.texture >= 0 && m.clearcoat.texcoord == set) ||
             (m.clearcoat.roughness_texture >= 0 && m.clearcoat.roughness_texcoord == set) ||
             (m.clearcoat.normal_texture >= 0 && m.clearcoat.normal_texcoord == set) ||
             (m.sheen.color_texture >= 0 && m.sheen.color_texcoord == set) ||
             (m.sheen.roughness_texture >= 0 && m.sheen.roughness_texcoord == set) ||
             (m.specular.texture >= 0 && m.specular.texcoord == set) ||
             (m.specular.color_texture >= 0 && m.specular.color_texcoord == set);
    }));
  };
  for (int set : {0, 1})
    if (const std::size_t n = count(set == 0 ? scene.uvs : scene.uvs1, set))
      scene.warnings.push_back(fmt::format("{}: textures read with TEXCOORD_{}, which no primitive has, are "
                                           "ignored: {}",
                                           file, set, materials(n)));
}

}  // namespace cohort::gltf
