#include "runtime/scene/gltf_materials.h"

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

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

TextureWrap wrap_mode(int gltf_wrap) {
  if (gltf_wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::clamp_to_edge;
  if (gltf_wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::mirrored_repeat;
  return TextureWrap::repeat;
}

// Without mip-maps a texture has one level, so a mip-map filter is its within-level filter
// (NEAREST_MIPMAP_* as NEAREST, LINEAR_MIPMAP_* as LINEAR). There is one filter per texture, not
// one for magnification and one for minification: magFilter decides, minFilter where it is absent.
bool nearest_filter(const tinygltf::Sampler& s) {
  const int filter = s.magFilter >= 0 ? s.magFilter : s.minFilter;
  return filter == TINYGLTF_TEXTURE_FILTER_NEAREST || filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
         filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
}

// Decodes each image once, however many materials and samplers share it, and keeps one scene
// texture per image, sampler and encoding (sRGB colour or linear data).
class TextureTable {
 public:
  TextureTable(const tinygltf::Model& model, const std::string& file, Scene& scene)
      : model_(model), file_(file), scene_(scene) {}

  // The scene texture for glTF texture `gltf_texture`, or -1; `use` says what it drives.
  int index_of(int gltf_texture, bool srgb, const std::string& use) {
    if (gltf_texture < 0) return -1;
    if (static_cast<std::size_t>(gltf_texture) >= model_.textures.size()) {
      warn(fmt::format("texture {} does not exist", gltf_texture));
      return -1;
    }
    const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(gltf_texture)];
    const int image = texture.source;
    if (image < 0 || static_cast<std::size_t>(image) >= model_.images.size()) {
      warn(fmt::format("texture {} has no image this loader can read", gltf_texture));
      return -1;
    }
    const TextureSampler sampler = sampler_of(texture);
    const auto key = std::tuple{image, sampler.nearest, sampler.wrap_s, sampler.wrap_t, srgb};
    const auto [it, inserted] = by_key_.try_emplace(key, -1);
    if (inserted) it->second = add(image, sampler, srgb);
    if (it->second >= 0) scene_.textures[static_cast<std::size_t>(it->second)].uses.push_back(use);
    return it->second;
  }

 private:
  TextureSampler sampler_of(const tinygltf::Texture& texture) {
    if (texture.sampler < 0) return {};  // glTF: repeat, and filtering up to the renderer (bilinear)
    if (static_cast<std::size_t>(texture.sampler) >= model_.samplers.size()) {
      warn(fmt::format("sampler {} does not exist; the default sampler is used", texture.sampler));
      return {};
    }
    const tinygltf::Sampler& s = model_.samplers[static_cast<std::size_t>(texture.sampler)];
    return {.nearest = nearest_filter(s), .wrap_s = wrap_mode(s.wrapS), .wrap_t = wrap_mode(s.wrapT)};
  }

  int add(int image, const TextureSampler& sampler, bool srgb) {
    const auto [decoded, first] = decoded_.try_emplace(image, -1);
    if (first) {
      decoded->second = decode(image);
      if (decoded->second < 0) return -1;
      Texture& t = scene_.textures[static_cast<std::size_t>(decoded->second)];
      t.sampler = sampler;
      t.srgb = srgb;
      return decoded->second;
    }
    if (decoded->second < 0) return -1;
    // the same image under another sampler or encoding: a texture of its own with the same texels
    Texture copy = scene_.textures[static_cast<std::size_t>(decoded->second)];
    copy.sampler = sampler;
    copy.srgb = srgb;
    copy.uses.clear();
    scene_.textures.push_back(std::move(copy));
    return static_cast<int>(scene_.textures.size() - 1);
  }

  int decode(int index) {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
    const std::string name = image_name(model_, index);
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
  std::map<int, int> decoded_;  // image -> the scene texture its texels were decoded into, or -1
  std::map<std::tuple<int, bool, TextureWrap, TextureWrap, bool>, int> by_key_;
};

// glTF's alphaMode and alphaCutoff (read with MASK only, as the specification says); a mode the
// specification does not name, or a negative cutoff (its minimum is 0), is a broken file. A cutoff
// above 1 is valid and cuts out the whole material.
void read_alpha(const tinygltf::Material& m, std::size_t index, const std::string& file, SceneMaterial& out) {
  const std::string which = fmt::format("material {}{}", index, m.name.empty() ? "" : fmt::format(" '{}'", m.name));
  if (m.alphaMode == "OPAQUE") {
    out.alpha_mode = AlphaMode::opaque;
  } else if (m.alphaMode == "MASK") {
    out.alpha_mode = AlphaMode::mask;
  } else if (m.alphaMode == "BLEND") {
    out.alpha_mode = AlphaMode::blend;
  } else {
    throw InputError(fmt::format("{}: {}: alphaMode \"{}\" is not one of glTF 2.0's OPAQUE, MASK and BLEND", file,
                                 which, m.alphaMode));
  }
  if (out.alpha_mode != AlphaMode::mask) return;
  if (!(m.alphaCutoff >= 0.0) || !std::isfinite(m.alphaCutoff))
    throw InputError(fmt::format("{}: {}: alphaCutoff {} is negative; glTF 2.0 requires a cutoff >= 0 (default 0.5)",
                                 file, which, m.alphaCutoff));
  out.alpha_cutoff = static_cast<float>(m.alphaCutoff);
}

// One extension object of a glTF file, read strictly: `fail` throws an InputError naming the place
// and the extension, `number` takes a finite number or fails naming the field.
class ExtensionReader {
 public:
  ExtensionReader(const tinygltf::Value& value, std::string context) : value_(value), context_(std::move(context)) {
    if (!value_.IsObject()) fail("is not an object");
  }
  const tinygltf::Value& value() const { return value_; }
  const std::string& context() const { return context_; }  // "FILE: material N 'name': EXTENSION"
  [[noreturn]] void fail(const std::string& what) const { throw InputError(fmt::format("{} {}", context_, what)); }
  double number(const tinygltf::Value& v, const std::string& name) const {
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) fail(fmt::format("{} is not a finite number", name));
    return v.GetNumberAsDouble();
  }
  // An optional factor in [0, 1] of the extension's object: `value` keeps its default when absent.
  void unit(const std::string& name, float& value) const {
    if (!value_.Has(name)) return;
    const double v = number(value_.Get(name), name);
    if (!(v >= 0.0 && v <= 1.0)) fail(fmt::format("{} {} is outside [0, 1]", name, v));
    value = static_cast<float>(v);
  }

 private:
  const tinygltf::Value& value_;
  std::string context_;
};

// KHR_texture_transform of one texture reference: `offset` and `scale` arrays of two numbers,
// `rotation` a number (radians), each optional, and `texCoord`, which replaces the reference's own
// coordinate set. Anything else there is a broken file.
UvTransform read_transform(const tinygltf::ExtensionMap& extensions, int& tex_coord, const std::string& where) {
  UvTransform x;
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end()) return x;
  const ExtensionReader r(it->second, fmt::format("{}: KHR_texture_transform", where));
  const tinygltf::Value& e = r.value();
  const auto pair = [&](const std::string& name, glm::vec2& out) {
    if (!e.Has(name)) return;
    const tinygltf::Value& v = e.Get(name);
    if (!v.IsArray() || v.ArrayLen() != 2) r.fail(fmt::format("{} is not an array of two numbers", name));
    out = glm::vec2(static_cast<float>(r.number(v.Get(0), name)), static_cast<float>(r.number(v.Get(1), name)));
  };
  pair("offset", x.offset);
  pair("scale", x.scale);
  if (e.Has("rotation")) x.rotation = static_cast<float>(r.number(e.Get("rotation"), "rotation"));
  if (e.Has("texCoord")) {
    const tinygltf::Value& v = e.Get("texCoord");
    if (!v.IsInt() || v.GetNumberAsInt() < 0) r.fail("texCoord is not an integer >= 0");
    tex_coord = v.GetNumberAsInt();
  }
  return x;
}

// KHR_materials_volume: the interior of a transmissive material absorbs sigma_a = -ln(attenuationColor) /
// attenuationDistance per unit length and channel (glTF: an absent distance is infinite, no
// absorption). A channel of 0 absorbs everything: its sigma_a is clamped to the largest float, which
// keeps sigma_a d a number (0 at d = 0, not NaN) and zeroes any other distance. thicknessFactor and
// thicknessTexture, a rasterizer's stand-in for the distance travelled inside, are checked but not
// used: the path tracer measures that distance on the geometry (report_unhonoured notes it). Wrong
// types and values outside the schema's ranges are a broken file.
glm::vec3 read_volume(const tinygltf::Material& m, std::size_t texture_count, const std::string& where) {
  const auto it = m.extensions.find("KHR_materials_volume");
  if (it == m.extensions.end()) return glm::vec3(0.f);
  const ExtensionReader r(it->second, fmt::format("{}: KHR_materials_volume", where));
  const tinygltf::Value& e = r.value();
  if (e.Has("thicknessFactor") && !(r.number(e.Get("thicknessFactor"), "thicknessFactor") >= 0.0))
    r.fail("thicknessFactor is negative");
  if (e.Has("thicknessTexture")) {
    const tinygltf::Value& t = e.Get("thicknessTexture");
    if (!t.IsObject() || !t.Has("index") || !t.Get("index").IsInt() || t.Get("index").GetNumberAsInt() < 0 ||
        static_cast<std::size_t>(t.Get("index").GetNumberAsInt()) >= texture_count)
      r.fail("thicknessTexture does not name an existing texture");
    if (t.Has("texCoord") && (!t.Get("texCoord").IsInt() || t.Get("texCoord").GetNumberAsInt() < 0))
      r.fail("thicknessTexture.texCoord is not an integer >= 0");
  }
  double distance = INFINITY;
  if (e.Has("attenuationDistance")) {
    distance = r.number(e.Get("attenuationDistance"), "attenuationDistance");
    if (!(distance > 0.0)) r.fail(fmt::format("attenuationDistance {} is not positive", distance));
  }
  glm::dvec3 colour(1.0);
  if (e.Has("attenuationColor")) {
    const tinygltf::Value& c = e.Get("attenuationColor");
    if (!c.IsArray() || c.ArrayLen() != 3) r.fail("attenuationColor is not an array of three numbers");
    for (int i = 0; i < 3; ++i) {
      colour[i] = r.number(c.Get(i), "attenuationColor");
      if (!(colour[i] >= 0.0 && colour[i] <= 1.0))
        r.fail(fmt::format("attenuationColor ({}, {}, {}) is outside [0, 1]", c.Get(0).GetNumberAsDouble(),
                           c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble()));
    }
  }
  glm::vec3 sigma(0.f);
  if (std::isinf(distance)) return sigma;
  for (int i = 0; i < 3; ++i) {
    const double s = colour[i] > 0.0 ? -std::log(colour[i]) / distance : INFINITY;
    sigma[i] = static_cast<float>(std::fmin(s, double(std::numeric_limits<float>::max())));
  }
  return sigma;
}

// TEXCOORD_0 and _1 are read; a higher set is named by report_unhonoured, and set 0 stands in.
int texcoord_set(int tex_coord) { return tex_coord == 1 ? 1 : 0; }

// A textureInfo inside a material extension (clearcoat's and sheen's slots), read as the core slots
// are: an existing texture, its texCoord and KHR_texture_transform, and for a normal texture its
// scale (`scale` not null). `info` lists it as `use` (with the scale) and `of` (the material). Wrong
// types are a broken file.
void read_extension_texture(const ExtensionReader& r, const char* slot, std::size_t texture_count,
                            TextureTable& textures, bool srgb, const std::string& use, const std::string& of,
                            int& index, int& set, UvTransform& transform, float* scale = nullptr) {
  const tinygltf::Value& e = r.value();
  if (!e.Has(slot)) return;
  const tinygltf::Value& t = e.Get(slot);
  if (!t.IsObject() || !t.Has("index") || !t.Get("index").IsInt() || t.Get("index").GetNumberAsInt() < 0 ||
      static_cast<std::size_t>(t.Get("index").GetNumberAsInt()) >= texture_count)
    r.fail(fmt::format("{} does not name an existing texture", slot));
  int tex_coord = 0;
  if (t.Has("texCoord")) {
    if (!t.Get("texCoord").IsInt() || t.Get("texCoord").GetNumberAsInt() < 0)
      r.fail(fmt::format("{}.texCoord is not an integer >= 0", slot));
    tex_coord = t.Get("texCoord").GetNumberAsInt();
  }
  std::string described = use + of;
  if (scale) {
    if (t.Has("scale")) *scale = static_cast<float>(r.number(t.Get("scale"), fmt::format("{}.scale", slot)));
    described = fmt::format("{} (scale {:.3g}){}", use, *scale, of);
  }
  tinygltf::ExtensionMap extensions;
  if (t.Has("extensions")) {
    const tinygltf::Value& x = t.Get("extensions");
    if (!x.IsObject()) r.fail(fmt::format("{}.extensions is not an object", slot));
    for (const std::string& key : x.Keys()) extensions[key] = x.Get(key);
  }
  transform = read_transform(extensions, tex_coord, fmt::format("{}.{}", r.context(), slot));
  set = texcoord_set(tex_coord);
  index = textures.index_of(t.Get("index").GetNumberAsInt(), srgb, described);
}

// KHR_materials_clearcoat (docs/bsdf.md, "Clearcoat"): clearcoatFactor and clearcoatRoughnessFactor
// in [0, 1]; clearcoatTexture (R), clearcoatRoughnessTexture (G) and clearcoatNormalTexture (with its
// scale), each a textureInfo naming an existing texture, with texCoord and KHR_texture_transform as
// the core textures. Wrong types and values outside the schema's ranges are a broken file.
SceneClearcoat read_clearcoat(const tinygltf::Material& m, TextureTable& textures, std::size_t texture_count,
                              const std::string& where) {
  SceneClearcoat out;
  const auto it = m.extensions.find("KHR_materials_clearcoat");
  if (it == m.extensions.end()) return out;
  const ExtensionReader r(it->second, fmt::format("{}: KHR_materials_clearcoat", where));
  r.unit("clearcoatFactor", out.factor);
  r.unit("clearcoatRoughnessFactor", out.roughness);
  const std::string of = m.name.empty() ? "" : fmt::format(" of '{}'", m.name);
  read_extension_texture(r, "clearcoatTexture", texture_count, textures, false, "clearcoat factor (R)", of,
                         out.texture, out.texcoord, out.transform);
  read_extension_texture(r, "clearcoatRoughnessTexture", texture_count, textures, false,
                         "clearcoat roughness (G)", of, out.roughness_texture, out.roughness_texcoord,
                         out.roughness_transform);
  read_extension_texture(r, "clearcoatNormalTexture", texture_count, textures, false, "clearcoat normals", of,
                         out.normal_texture, out.normal_texcoord, out.normal_transform, &out.normal_scale);
  return out;
}

// KHR_materials_sheen: sheenColorFactor (three numbers in [0, 1], linear), sheenRoughnessFactor (a
// number in [0, 1]), sheenColorTexture (RGB, sRGB colour) and sheenRoughnessTexture (A, linear data),
// each texture with its texCoord and KHR_texture_transform as the core slots have. Wrong types, values
// outside the schema's ranges and textures that do not exist are a broken file.
SceneSheen read_sheen(const tinygltf::Material& m, TextureTable& textures, std::size_t texture_count,
                      const std::string& where) {
  SceneSheen out;
  const auto it = m.extensions.find("KHR_materials_sheen");
  if (it == m.extensions.end()) return out;
  const ExtensionReader r(it->second, fmt::format("{}: KHR_materials_sheen", where));
  const tinygltf::Value& e = r.value();
  if (e.Has("sheenColorFactor")) {
    const tinygltf::Value& c = e.Get("sheenColorFactor");
    if (!c.IsArray() || c.ArrayLen() != 3) r.fail("sheenColorFactor is not an array of three numbers");
    for (int i = 0; i < 3; ++i) {
      const double v = r.number(c.Get(i), "sheenColorFactor");
      if (!(v >= 0.0 && v <= 1.0))
        r.fail(fmt::format("sheenColorFactor ({}, {}, {}) is outside [0, 1]", c.Get(0).GetNumberAsDouble(),
                           c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble()));
      out.color[i] = static_cast<float>(v);
    }
  }
  r.unit("sheenRoughnessFactor", out.roughness);
  const std::string of = m.name.empty() ? "" : fmt::format(" of '{}'", m.name);
  read_extension_texture(r, "sheenColorTexture", texture_count, textures, true, "sheen colour (RGB)", of,
                         out.color_texture, out.color_texcoord, out.color_transform);
  read_extension_texture(r, "sheenRoughnessTexture", texture_count, textures, false, "sheen roughness (A)", of,
                         out.roughness_texture, out.roughness_texcoord, out.roughness_transform);
  return out;
}

// KHR_materials_specular: specularFactor (a number in [0, 1], default 1), specularColorFactor (three
// numbers >= 0, linear, default 1; glTF allows them above 1, the f0 they tint is clamped to 1),
// specularTexture (A, linear data) and specularColorTexture (RGB, sRGB colour), each texture with its
// texCoord and KHR_texture_transform as the core slots have. Wrong types, values outside the schema's
// ranges and textures that do not exist are a broken file.
SceneSpecular read_specular(const tinygltf::Material& m, TextureTable& textures, std::size_t texture_count,
                            const std::string& where) {
  SceneSpecular out;
  const auto it = m.extensions.find("KHR_materials_specular");
  if (it == m.extensions.end()) return out;
  const ExtensionReader r(it->second, fmt::format("{}: KHR_materials_specular", where));
  const tinygltf::Value& e = r.value();
  r.unit("specularFactor", out.factor);
  if (e.Has("specularColorFactor")) {
    const tinygltf::Value& c = e.Get("specularColorFactor");
    if (!c.IsArray() || c.ArrayLen() != 3) r.fail("specularColorFactor is not an array of three numbers");
    for (int i = 0; i < 3; ++i) {
      const double v = r.number(c.Get(i), "specularColorFactor");
      if (!(v >= 0.0) || v > double(std::numeric_limits<float>::max()))
        r.fail(fmt::format("specularColorFactor ({}, {}, {}) has a negative or too large component",
                           c.Get(0).GetNumberAsDouble(), c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble()));
      out.color[i] = static_cast<float>(v);
    }
  }
  const std::string of = m.name.empty() ? "" : fmt::format(" of '{}'", m.name);
  read_extension_texture(r, "specularTexture", texture_count, textures, false, "specular factor (A)", of,
                         out.texture, out.texcoord, out.transform);
  read_extension_texture(r, "specularColorTexture", texture_count, textures, true, "specular colour (RGB)", of,
                         out.color_texture, out.color_texcoord, out.color_transform);
  return out;
}

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
  const std::string of = fmt::format(" of '{}'", m.name);
  out.base_color_texture = textures.index_of(pbr.baseColorTexture.index, true, "base colour" + of);
  out.base_color_texcoord = texcoord_set(pbr.baseColorTexture.texCoord);
  out.emission_texture = textures.index_of(m.emissiveTexture.index, true, "emission" + of);
  out.emission_texcoord = texcoord_set(m.emissiveTexture.texCoord);
  out.metallic_roughness_texture = textures.index_of(pbr.metallicRoughnessTexture.index, false,
                                                     "metallic (B) and roughness (G)" + of);
  out.metallic_roughness_texcoord = texcoord_set(pbr.metallicRoughnessTexture.texCoord);
  out.normal_scale = static_cast<float>(m.normalTexture.scale);
  out.normal_texture =
      textures.index_of(m.normalTexture.index, false, fmt::format("normals (scale {:.3g}){}", out.normal_scale, of));
  out.normal_texcoord = texcoord_set(m.normalTexture.texCoord);
  return out;
}

}  // namespace

std::string image_name(const tinygltf::Model& model, int index) {
  const tinygltf::Image& image = model.images[static_cast<std::size_t>(index)];
  return image.uri.empty() || image.uri.starts_with("data:") ? fmt::format("image {}", index) : image.uri;
}

void convert_materials(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  TextureTable textures(model, file, scene);
  scene.materials.reserve(scene.materials.size() + model.materials.size());
  for (std::size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& m = model.materials[i];
    scene.materials.push_back(convert(m, textures));
    SceneMaterial& out = scene.materials.back();
    read_alpha(m, i, file, out);
    const std::string where =
        fmt::format("{}: material {}{}", file, i, m.name.empty() ? "" : fmt::format(" '{}'", m.name));
    out.absorption = read_volume(m, model.textures.size(), where);
    out.clearcoat = read_clearcoat(m, textures, model.textures.size(), where);
    out.sheen = read_sheen(m, textures, model.textures.size(), where);
    out.specular = read_specular(m, textures, model.textures.size(), where);
    const auto transform = [&](const tinygltf::ExtensionMap& extensions, int tex_coord, const char* slot,
                               UvTransform& x, int& set) {
      x = read_transform(extensions, tex_coord, fmt::format("{}: {}", where, slot));
      set = texcoord_set(tex_coord);
    };
    const auto& pbr = m.pbrMetallicRoughness;
    transform(pbr.baseColorTexture.extensions, pbr.baseColorTexture.texCoord, "baseColorTexture",
              out.base_color_transform, out.base_color_texcoord);
    transform(pbr.metallicRoughnessTexture.extensions, pbr.metallicRoughnessTexture.texCoord,
              "metallicRoughnessTexture", out.metallic_roughness_transform, out.metallic_roughness_texcoord);
    transform(m.emissiveTexture.extensions, m.emissiveTexture.texCoord, "emissiveTexture", out.emission_transform,
              out.emission_texcoord);
    transform(m.normalTexture.extensions, m.normalTexture.texCoord, "normalTexture", out.normal_transform,
              out.normal_texcoord);
  }
}

}  // namespace cohort::gltf
