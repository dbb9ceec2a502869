// glTF material inputs beyond the factors as the loader reads them: samplers, the metallic-roughness
// texture, TEXCOORD_1 and COLOR_0, KHR_texture_transform and the material extensions (volume,
// clearcoat, sheen, specular); and, one table, the malformed values of each that are input errors
// naming the file, the material and the value.
#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using nlohmann::json;
using test::GltfWriter;
using test::TempDir;

const std::vector<glm::vec3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

// The warnings but the one about a scene without lights, joined.
std::string material_warnings(const Scene& s) {
  std::string out;
  for (const std::string& w : s.warnings)
    if (w.find("no light") == std::string::npos) out += w + "\n";
  return out;
}

// One triangle with `material`; one 1x1 PPM image behind every texture of `textures`.
GltfWriter textured_triangle(const TempDir& dir, const json& material, const json& textures, const json& samplers) {
  test::write_file(dir / "px.ppm", std::string("P6\n1 1\n255\n") + std::string("\x10\x80\xf0", 3));
  GltfWriter g;
  g.doc()["images"] = {{{"uri", "px.ppm"}}};
  g.doc()["textures"] = textures;
  if (!samplers.is_null()) g.doc()["samplers"] = samplers;
  const int pos = g.positions(kTriangle);
  g.roots({g.node({{"mesh", g.mesh(pos, -1, g.material(material))}})});
  const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {0, 1}};
  const int acc = g.accessor(g.view(uv.data(), uv.size() * sizeof(glm::vec2)), 5126, uv.size(), "VEC2");
  g.doc()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = acc;
  return g;
}

// One triangle with `material` (which names itself), two textures of the one image and TEXCOORD_1 the
// same coordinates as TEXCOORD_0; each of the material's extensions and KHR_texture_transform
// declared used and required. Written as <stem>.gltf.
std::filesystem::path one_material_gltf(const TempDir& dir, const std::string& stem, const json& material) {
  GltfWriter g = textured_triangle(dir, material, json::array({{{"source", 0}}, {{"source", 0}}}), nullptr);
  json extensions = json::array({"KHR_texture_transform"});
  if (material.contains("extensions"))
    for (const auto& [name, value] : material["extensions"].items()) extensions.push_back(name);
  g.doc()["extensionsUsed"] = g.doc()["extensionsRequired"] = extensions;
  auto& attributes = g.doc()["meshes"][0]["primitives"][0]["attributes"];
  attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"];
  return g.write_gltf(dir.path(), stem);
}

// A material named `name` with one extension.
json with_extension(const std::string& name, const std::string& extension, const json& value) {
  return {{"name", name}, {"extensions", {{extension, value}}}};
}

TEST(GltfSamplers, FiltersAndWrapModesAreRead) {
  TempDir dir;
  // NEAREST_MIPMAP_LINEAR (9986) is nearest within the one level there is; magFilter decides over minFilter
  const json samplers = {{{"magFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33648}},
                         {{"minFilter", 9986}},
                         {{"magFilter", 9729}, {"minFilter", 9728}},
                         json::object()};
  const json textures = {{{"source", 0}, {"sampler", 0}}, {{"source", 0}, {"sampler", 1}},
                         {{"source", 0}, {"sampler", 2}}, {{"source", 0}, {"sampler", 3}}};
  GltfWriter g = textured_triangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}, textures,
                                   samplers);
  for (int t = 1; t < 4; ++t)  // one material per further texture
    g.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", t}}}}}});
  const Scene s = load_scene(g.write_gltf(dir.path(), "samplers"));
  ASSERT_EQ(s.textures.size(), 3u);  // one image, three distinct samplers: three textures with the same texels
  auto sampler_of = [&](std::size_t material) {
    return s.textures[static_cast<std::size_t>(s.materials[material].base_color_texture)].sampler;
  };
  EXPECT_EQ(sampler_of(0), (TextureSampler{.nearest = true, .wrap_s = TextureWrap::clamp_to_edge,
                                           .wrap_t = TextureWrap::mirrored_repeat}));
  EXPECT_EQ(sampler_of(1), (TextureSampler{.nearest = true}));
  EXPECT_EQ(sampler_of(2), TextureSampler{});
  EXPECT_EQ(s.materials[3].base_color_texture, s.materials[2].base_color_texture);  // LINEAR is the default
  for (const Texture& t : s.textures) EXPECT_EQ(t.rgba, s.textures[0].rgba);
  EXPECT_EQ(material_warnings(s), "");
}

TEST(GltfMaterialTextures, MetallicRoughnessIsLinearDataAndSharedImagesKeepTheirEncoding) {
  TempDir dir;
  const json material = {{"pbrMetallicRoughness",
                          {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}},
                         {"name", "both"}};
  const Scene s = load_scene(textured_triangle(dir, material, {{{"source", 0}}}, nullptr).write_gltf(dir.path(), "mr"));
  const SceneMaterial& m = s.materials[0];
  ASSERT_GE(m.base_color_texture, 0);
  ASSERT_GE(m.metallic_roughness_texture, 0);
  ASSERT_NE(m.base_color_texture, m.metallic_roughness_texture);  // the same image, sRGB once and linear once
  const Texture& colour = s.textures[static_cast<std::size_t>(m.base_color_texture)];
  const Texture& data = s.textures[static_cast<std::size_t>(m.metallic_roughness_texture)];
  EXPECT_TRUE(colour.srgb);
  EXPECT_FALSE(data.srgb);
  EXPECT_EQ(colour.uses, std::vector<std::string>{"base colour of 'both'"});
  EXPECT_EQ(data.uses, std::vector<std::string>{"metallic (B) and roughness (G) of 'both'"});
  EXPECT_EQ(material_warnings(s), "");
}

TEST(GltfVertexAttributes, SecondCoordinateSetAndVertexColoursAreRead) {
  TempDir dir;
  const json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}};
  GltfWriter g = textured_triangle(dir, material, {{{"source", 0}}}, nullptr);
  const std::vector<glm::vec2> uv1 = {{0.5f, 0.25f}, {0.75f, 0}, {0, 1}};
  const int uv1_acc = g.accessor(g.view(uv1.data(), uv1.size() * sizeof(glm::vec2)), 5126, 3, "VEC2");
  const std::uint8_t rgba[12] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0};  // normalized unsigned bytes
  const int colour_acc = g.accessor(g.view(rgba, sizeof rgba), 5121, 3, "VEC4");
  g.doc()["accessors"][colour_acc]["normalized"] = true;
  auto& attributes = g.doc()["meshes"][0]["primitives"][0]["attributes"];
  attributes["TEXCOORD_1"] = uv1_acc;
  attributes["COLOR_0"] = colour_acc;
  // a second mesh without either: its triangle gets zeros and white
  const int pos = g.positions(kTriangle);
  g.doc()["nodes"].push_back({{"mesh", g.mesh(pos)}});
  g.doc()["scenes"][0]["nodes"].push_back(1);
  const Scene s = load_scene(g.write_gltf(dir.path(), "attributes"));
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.materials[0].base_color_texcoord, 1);
  ASSERT_EQ(s.uvs1.size(), 6u);
  EXPECT_EQ(s.uvs1[0], glm::vec2(0.5f, 0.25f));
  EXPECT_EQ(s.uvs1[5], glm::vec2(0.f));
  ASSERT_EQ(s.colors.size(), 6u);
  EXPECT_EQ(s.colors[0], glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(s.colors[1].w, 128 / 255.f, 1e-7f);
  EXPECT_EQ(s.colors[4], glm::vec4(1.f));
  EXPECT_EQ(material_warnings(s), "");

  // RGB colours (VEC3) get an alpha of 1; a count that differs from POSITION's is an error
  GltfWriter rgb = textured_triangle(dir, json::object(), {{{"source", 0}}}, nullptr);
  const std::vector<glm::vec3> c3 = {{0.1f, 0.2f, 0.3f}, {1, 1, 1}, {0, 0, 0}};
  rgb.doc()["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] =
      rgb.accessor(rgb.view(c3.data(), c3.size() * sizeof(glm::vec3)), 5126, 3, "VEC3");
  EXPECT_EQ(load_scene(rgb.write_gltf(dir.path(), "rgb")).colors[0], glm::vec4(0.1f, 0.2f, 0.3f, 1.f));
  rgb.doc()["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] =
      rgb.accessor(rgb.view(c3.data(), 2 * sizeof(glm::vec3)), 5126, 2, "VEC3");
  test::expect_input_error(rgb.write_gltf(dir.path(), "short"), "COLOR_0 has 2 elements but POSITION has 3");
}

TEST(GltfVertexAttributes, ATextureOnACoordinateSetNoPrimitiveHasIsNamed) {
  TempDir dir;
  const json material = {{"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 0}, {"texCoord", 1}}}}}};
  const Scene s =
      load_scene(textured_triangle(dir, material, {{{"source", 0}}}, nullptr).write_gltf(dir.path(), "noset"));
  EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
    return w.find("textures read with TEXCOORD_1, which no primitive has, are ignored: 1 material") != std::string::npos;
  })) << (s.warnings.empty() ? "no warning" : s.warnings.front());
}

// KHR_texture_transform per texture reference: offset, rotation and scale as written (defaults where
// absent), and texCoord replacing the reference's own set; malformed values are input errors.
TEST(GltfTextureTransform, IsReadPerTextureAndChecked) {
  TempDir dir;
  const auto with = [&](const json& transform) {
    const json material = {
        {"pbrMetallicRoughness",
         {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}},
          {"metallicRoughnessTexture", {{"index", 0}}}}},
        {"emissiveTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}}}}}}},
        {"emissiveFactor", {1, 1, 1}}};
    return textured_triangle(dir, material, json::array({{{"source", 0}}}), nullptr).write_gltf(dir.path(), "tt");
  };
  const Scene s = load_scene(with({{"offset", {0.25, -1}}, {"rotation", 1.5}, {"scale", {2, 0.5}}, {"texCoord", 1}}));
  const SceneMaterial& m = s.materials.at(0);
  EXPECT_EQ(m.base_color_transform, (UvTransform{{0.25f, -1.f}, 1.5f, {2.f, 0.5f}}));
  EXPECT_EQ(m.base_color_texcoord, 1);
  EXPECT_TRUE(m.metallic_roughness_transform.identity());
  EXPECT_EQ(m.metallic_roughness_texcoord, 0);
  EXPECT_EQ(m.emission_transform, (UvTransform{{0.5f, 0.f}, 0.f, {1.f, 1.f}}));
  EXPECT_EQ(load_scene(with({{"rotation", 0.5}})).materials[0].base_color_transform, (UvTransform{{0.f, 0.f}, 0.5f, {1.f, 1.f}}));
  // on a core texture of an unnamed material (the material extensions' textures are in the table below)
  test::expect_input_error(with({{"offset", {1}}}), "material 0: baseColorTexture: KHR_texture_transform offset is not an array of two numbers");
  test::expect_input_error(with({{"scale", {1, "x"}}}), "scale is not a finite number");
  test::expect_input_error(with({{"rotation", "half"}}), "rotation is not a finite number");
  test::expect_input_error(with({{"texCoord", -1}}), "texCoord is not an integer >= 0");
}

// KHR_materials_volume: sigma_a = -ln(attenuationColor) / attenuationDistance per channel; an absent
// distance is infinite (no absorption); a colour channel of 0 clamps to the largest float; thickness
// is read and left out with a note. Its malformed values are in the GltfBadExtensionValue table.
TEST(GltfVolume, AbsorptionIsRead) {
  TempDir dir;
  const auto with = [&](const json& volume) {
    json material = with_extension("glass", "KHR_materials_volume", volume);
    material["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1}};
    return one_material_gltf(dir, "volume", material);
  };
  const Scene s = load_scene(with({{"attenuationColor", {0.5, 1.0, 0.25}}, {"attenuationDistance", 2.0}}));
  const glm::vec3 a = s.materials.at(0).absorption;
  EXPECT_EQ(a.x, static_cast<float>(std::log(2.0) / 2.0));
  EXPECT_EQ(a.y, 0.f);
  EXPECT_EQ(a.z, static_cast<float>(std::log(4.0) / 2.0));
  EXPECT_EQ(material_warnings(s), "") << "honoured, and accepted as required";
  EXPECT_TRUE(s.notes.empty());
  // no distance: infinite, nothing absorbed whatever the colour; no extension at all: the same
  EXPECT_EQ(load_scene(with({{"attenuationColor", {0.5, 0.5, 0.5}}})).materials[0].absorption, glm::vec3(0.f));
  EXPECT_EQ(load_scene(with(json::object())).materials[0].absorption, glm::vec3(0.f));
  // a channel of 0 absorbs everything: the largest finite sigma, so sigma * 0 stays 0
  EXPECT_EQ(load_scene(with({{"attenuationColor", {0, 1, 1}}, {"attenuationDistance", 1}})).materials[0].absorption.x,
            std::numeric_limits<float>::max());
  // thickness is read, checked and not used, which a note says once
  const Scene thick = load_scene(with({{"thicknessFactor", 0.3}, {"thicknessTexture", {{"index", 0}, {"texCoord", 1}}},
                                       {"attenuationDistance", 1}}));
  EXPECT_EQ(thick.materials[0].absorption, glm::vec3(0.f));  // a white colour absorbs nothing
  ASSERT_EQ(thick.notes.size(), 1u);
  EXPECT_NE(thick.notes[0].find("KHR_materials_volume thicknessFactor and thicknessTexture of 1 material not used"),
            std::string::npos) << thick.notes[0];
}

// KHR_materials_clearcoat: the factors, the three textures (linear) with their texCoord,
// KHR_texture_transform and normal scale, what `info` says they drive, the extension accepted as
// required. Its malformed values are in the GltfBadExtensionValue table.
TEST(GltfClearcoat, FactorsAndTexturesAreRead) {
  TempDir dir;
  const auto with = [&](const json& coat) {
    return one_material_gltf(dir, "coat", with_extension("coated", "KHR_materials_clearcoat", coat));
  };
  // no extension, or an empty one: no coat (glTF's defaults are factor 0 and roughness 0)
  EXPECT_EQ(load_scene(with(json::object())).materials.at(0).clearcoat.factor, 0.f);
  const Scene s = load_scene(with(
      {{"clearcoatFactor", 0.75},
       {"clearcoatRoughnessFactor", 0.25},
       {"clearcoatTexture", {{"index", 0}, {"texCoord", 1}}},
       {"clearcoatRoughnessTexture",
        {{"index", 1}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}}}}}}},
       {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}));
  const SceneClearcoat& c = s.materials.at(0).clearcoat;
  EXPECT_EQ(c.factor, 0.75f);
  EXPECT_EQ(c.roughness, 0.25f);
  ASSERT_GE(c.texture, 0);
  ASSERT_GE(c.roughness_texture, 0);
  ASSERT_GE(c.normal_texture, 0);
  EXPECT_EQ(c.texcoord, 1);
  EXPECT_EQ(c.roughness_texcoord, 0);
  EXPECT_EQ(c.roughness_transform.offset, glm::vec2(0.5f, 0.f));
  EXPECT_TRUE(c.transform.identity());
  EXPECT_EQ(c.normal_scale, 0.5f);
  // linear data, each named by what it drives
  const Texture& factor = s.textures.at(static_cast<std::size_t>(c.texture));
  EXPECT_FALSE(factor.srgb);
  std::string uses;
  for (const Texture& t : s.textures)
    for (const std::string& u : t.uses) uses += u + "\n";
  EXPECT_NE(uses.find("clearcoat factor (R) of 'coated'"), std::string::npos) << uses;
  EXPECT_NE(uses.find("clearcoat roughness (G) of 'coated'"), std::string::npos) << uses;
  EXPECT_NE(uses.find("clearcoat normals (scale 0.5) of 'coated'"), std::string::npos) << uses;
  EXPECT_EQ(material_warnings(s), "") << "honoured, and accepted as required";
}

// KHR_materials_sheen: the colour and roughness factors, the colour texture (sRGB, RGB) and the
// roughness texture (linear, A) with their texCoord and KHR_texture_transform, what `info` says they
// drive, the extension accepted as required. Its malformed values are in the GltfBadExtensionValue
// table.
TEST(GltfSheen, FactorsAndTexturesAreRead) {
  TempDir dir;
  const auto with = [&](const json& sheen) {
    return one_material_gltf(dir, "sheen", with_extension("velvet", "KHR_materials_sheen", sheen));
  };
  const Scene s = load_scene(with({{"sheenColorFactor", {0.9, 0.5, 0.25}},
                                   {"sheenRoughnessFactor", 0.3},
                                   {"sheenColorTexture", {{"index", 0}, {"texCoord", 1}}},
                                   {"sheenRoughnessTexture",
                                    {{"index", 1},
                                     {"extensions", {{"KHR_texture_transform", {{"rotation", 0.5}, {"texCoord", 1}}}}}}}}));
  const SceneSheen& sh = s.materials.at(0).sheen;
  EXPECT_EQ(sh.color, glm::vec3(0.9f, 0.5f, 0.25f));
  EXPECT_EQ(sh.roughness, 0.3f);
  EXPECT_TRUE(sh.present());
  ASSERT_GE(sh.color_texture, 0);
  ASSERT_GE(sh.roughness_texture, 0);
  EXPECT_EQ(sh.color_texcoord, 1);
  EXPECT_TRUE(sh.color_transform.identity());
  EXPECT_EQ(sh.roughness_texcoord, 1);  // the transform's texCoord replaces the reference's own
  EXPECT_EQ(sh.roughness_transform, (UvTransform{{0.f, 0.f}, 0.5f, {1.f, 1.f}}));
  const Texture& colour = s.textures.at(std::size_t(sh.color_texture));
  const Texture& rough = s.textures.at(std::size_t(sh.roughness_texture));
  EXPECT_TRUE(colour.srgb);
  EXPECT_FALSE(rough.srgb);
  EXPECT_EQ(colour.uses, (std::vector<std::string>{"sheen colour (RGB) of 'velvet'"}));
  EXPECT_EQ(rough.uses, (std::vector<std::string>{"sheen roughness (A) of 'velvet'"}));
  EXPECT_EQ(material_warnings(s), "") << "honoured, and accepted as required";
  // defaults: colour 0 (no sheen) and roughness 0; no extension at all: the same
  const SceneSheen none = load_scene(with(json::object())).materials[0].sheen;
  EXPECT_EQ(none.color, glm::vec3(0.f));
  EXPECT_EQ(none.roughness, 0.f);
  EXPECT_FALSE(none.present());
  EXPECT_EQ(none.color_texture, -1);
}

// KHR_materials_specular: the factor and colour factor, the specular texture (linear, A) and the colour
// texture (sRGB, RGB) with their texCoord and KHR_texture_transform, what `info` says they drive, the
// extension accepted as required; default values are the material without it; a specular on a
// transmissive material is reported as not honoured there. Its malformed values are in the
// GltfBadExtensionValue table.
TEST(GltfSpecular, FactorsAndTexturesAreRead) {
  TempDir dir;
  const auto with = [&](const json& specular, double transmission = 0.0) {
    json material = with_extension("lacquer", "KHR_materials_specular", specular);
    if (transmission > 0.0)
      material["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", transmission}};
    return one_material_gltf(dir, "specular", material);
  };
  const Scene s = load_scene(with({{"specularFactor", 0.3},
                                   {"specularColorFactor", {2.0, 0.5, 0.25}},
                                   {"specularTexture", {{"index", 1}, {"texCoord", 1}}},
                                   {"specularColorTexture",
                                    {{"index", 0},
                                     {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"texCoord", 1}}}}}}}}));
  const SceneSpecular& sp = s.materials.at(0).specular;
  EXPECT_EQ(sp.factor, 0.3f);
  EXPECT_EQ(sp.color, glm::vec3(2.0f, 0.5f, 0.25f));  // glTF allows a colour above 1
  EXPECT_TRUE(sp.present());
  ASSERT_GE(sp.texture, 0);
  ASSERT_GE(sp.color_texture, 0);
  EXPECT_EQ(sp.texcoord, 1);
  EXPECT_TRUE(sp.transform.identity());
  EXPECT_EQ(sp.color_texcoord, 1);  // the transform's texCoord replaces the reference's own
  EXPECT_EQ(sp.color_transform, (UvTransform{{0.5f, 0.25f}, 0.f, {1.f, 1.f}}));
  const Texture& factor = s.textures.at(std::size_t(sp.texture));
  const Texture& colour = s.textures.at(std::size_t(sp.color_texture));
  EXPECT_FALSE(factor.srgb);
  EXPECT_TRUE(colour.srgb);
  EXPECT_EQ(factor.uses, (std::vector<std::string>{"specular factor (A) of 'lacquer'"}));
  EXPECT_EQ(colour.uses, (std::vector<std::string>{"specular colour (RGB) of 'lacquer'"}));
  EXPECT_EQ(material_warnings(s), "") << "honoured, and accepted as required";
  // defaults: factor 1 and colour 1, the material without the extension
  for (const json& defaults : {json::object(), json{{"specularFactor", 1.0}, {"specularColorFactor", {1, 1, 1}}}}) {
    const SceneSpecular d = load_scene(with(defaults)).materials[0].specular;
    EXPECT_EQ(d.factor, 1.f);
    EXPECT_EQ(d.color, glm::vec3(1.f));
    EXPECT_FALSE(d.present());
    EXPECT_EQ(d.texture, -1);
    EXPECT_EQ(d.color_texture, -1);
  }
  EXPECT_TRUE(load_scene(with({{"specularFactor", 0.0}})).materials[0].specular.present());
  EXPECT_TRUE(load_scene(with({{"specularTexture", {{"index", 0}}}})).materials[0].specular.present());
  // the transmissive part does not take it: one line, with the material count
  const std::string glass = material_warnings(load_scene(with({{"specularFactor", 0.5}}, 0.8)));
  EXPECT_NE(glass.find("glTF feature not honoured: KHR_materials_specular on the transmission"), std::string::npos) << glass;
  EXPECT_NE(glass.find(": 1 material"), std::string::npos) << glass;
  EXPECT_EQ(material_warnings(load_scene(with(json::object(), 0.8))), "") << "default values change nothing";
}

// A malformed value of a material extension: the test's name, the extension, its JSON object and
// what the error says of it after "material 0 'checked': ".
struct BadExtensionValue {
  const char* name;
  const char* extension;
  const char* value;
  const char* message;
};

void PrintTo(const BadExtensionValue& bad, std::ostream* os) { *os << bad.extension << ' ' << bad.value; }

const BadExtensionValue kBadExtensionValues[] = {
    // KHR_materials_volume (on a transmissive material, where glTF gives it a meaning)
    {"VolumeNegativeDistance", "KHR_materials_volume", R"({"attenuationDistance": -1})",
     "KHR_materials_volume attenuationDistance -1 is not positive"},
    {"VolumeZeroDistance", "KHR_materials_volume", R"({"attenuationDistance": 0})",
     "KHR_materials_volume attenuationDistance 0 is not positive"},
    {"VolumeDistanceNotANumber", "KHR_materials_volume", R"({"attenuationDistance": "far"})",
     "KHR_materials_volume attenuationDistance is not a finite number"},
    {"VolumeColourAboveOne", "KHR_materials_volume", R"({"attenuationColor": [0.5, 1.5, 0.5]})",
     "KHR_materials_volume attenuationColor (0.5, 1.5, 0.5) is outside [0, 1]"},
    {"VolumeColourBelowZero", "KHR_materials_volume", R"({"attenuationColor": [0.5, -0.1, 0.5]})",
     "KHR_materials_volume attenuationColor (0.5, -0.1, 0.5) is outside [0, 1]"},
    {"VolumeColourOfTwoNumbers", "KHR_materials_volume", R"({"attenuationColor": [0.5, 0.5]})",
     "KHR_materials_volume attenuationColor is not an array of three numbers"},
    {"VolumeNegativeThickness", "KHR_materials_volume", R"({"thicknessFactor": -0.5})",
     "KHR_materials_volume thicknessFactor is negative"},
    {"VolumeThicknessTextureMissing", "KHR_materials_volume", R"({"thicknessTexture": {"index": 3}})",
     "KHR_materials_volume thicknessTexture does not name an existing texture"},
    // KHR_materials_clearcoat
    {"ClearcoatFactorBelowZero", "KHR_materials_clearcoat", R"({"clearcoatFactor": -0.5})",
     "KHR_materials_clearcoat clearcoatFactor -0.5 is outside [0, 1]"},
    {"ClearcoatRoughnessAboveOne", "KHR_materials_clearcoat", R"({"clearcoatRoughnessFactor": 1.5})",
     "KHR_materials_clearcoat clearcoatRoughnessFactor 1.5 is outside [0, 1]"},
    {"ClearcoatFactorNotANumber", "KHR_materials_clearcoat", R"({"clearcoatFactor": "thick"})",
     "KHR_materials_clearcoat clearcoatFactor is not a finite number"},
    {"ClearcoatTextureMissing", "KHR_materials_clearcoat", R"({"clearcoatTexture": {"index": 5}})",
     "KHR_materials_clearcoat clearcoatTexture does not name an existing texture"},
    {"ClearcoatRoughnessTexCoordNegative", "KHR_materials_clearcoat",
     R"({"clearcoatRoughnessTexture": {"index": 0, "texCoord": -1}})",
     "KHR_materials_clearcoat clearcoatRoughnessTexture.texCoord is not an integer >= 0"},
    {"ClearcoatNormalScaleNotANumber", "KHR_materials_clearcoat",
     R"({"clearcoatNormalTexture": {"index": 0, "scale": "big"}})",
     "KHR_materials_clearcoat clearcoatNormalTexture.scale is not a finite number"},
    // KHR_materials_sheen
    {"SheenColourAboveOne", "KHR_materials_sheen", R"({"sheenColorFactor": [0.5, 1.5, 0.5]})",
     "KHR_materials_sheen sheenColorFactor (0.5, 1.5, 0.5) is outside [0, 1]"},
    {"SheenColourOfTwoNumbers", "KHR_materials_sheen", R"({"sheenColorFactor": [0.5, 0.5]})",
     "KHR_materials_sheen sheenColorFactor is not an array of three numbers"},
    {"SheenColourNotANumber", "KHR_materials_sheen", R"({"sheenColorFactor": [0.5, "red", 0.5]})",
     "KHR_materials_sheen sheenColorFactor is not a finite number"},
    {"SheenRoughnessBelowZero", "KHR_materials_sheen", R"({"sheenRoughnessFactor": -0.1})",
     "KHR_materials_sheen sheenRoughnessFactor -0.1 is outside [0, 1]"},
    {"SheenRoughnessAboveOne", "KHR_materials_sheen", R"({"sheenRoughnessFactor": 2})",
     "KHR_materials_sheen sheenRoughnessFactor 2 is outside [0, 1]"},
    {"SheenRoughnessNotANumber", "KHR_materials_sheen", R"({"sheenRoughnessFactor": "soft"})",
     "KHR_materials_sheen sheenRoughnessFactor is not a finite number"},
    {"SheenColourTextureMissing", "KHR_materials_sheen", R"({"sheenColorTexture": {"index": 7}})",
     "KHR_materials_sheen sheenColorTexture does not name an existing texture"},
    {"SheenRoughnessTextureNotAnObject", "KHR_materials_sheen", R"({"sheenRoughnessTexture": 3})",
     "KHR_materials_sheen sheenRoughnessTexture does not name an existing texture"},
    {"SheenColourTexCoordNegative", "KHR_materials_sheen", R"({"sheenColorTexture": {"index": 0, "texCoord": -2}})",
     "KHR_materials_sheen sheenColorTexture.texCoord is not an integer >= 0"},
    {"SheenColourTransformScaleNotAPair", "KHR_materials_sheen",
     R"({"sheenColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": 2}}}})",
     "KHR_materials_sheen.sheenColorTexture: KHR_texture_transform scale is not an array of two numbers"},
    // KHR_materials_specular
    {"SpecularFactorAboveOne", "KHR_materials_specular", R"({"specularFactor": 1.5})",
     "KHR_materials_specular specularFactor 1.5 is outside [0, 1]"},
    {"SpecularFactorBelowZero", "KHR_materials_specular", R"({"specularFactor": -0.1})",
     "KHR_materials_specular specularFactor -0.1 is outside [0, 1]"},
    {"SpecularFactorNotANumber", "KHR_materials_specular", R"({"specularFactor": "shiny"})",
     "KHR_materials_specular specularFactor is not a finite number"},
    {"SpecularColourNegative", "KHR_materials_specular", R"({"specularColorFactor": [0.5, -1.0, 0.5]})",
     "KHR_materials_specular specularColorFactor (0.5, -1, 0.5) has a negative or too large component"},
    {"SpecularColourOfTwoNumbers", "KHR_materials_specular", R"({"specularColorFactor": [0.5, 0.5]})",
     "KHR_materials_specular specularColorFactor is not an array of three numbers"},
    {"SpecularColourNotANumber", "KHR_materials_specular", R"({"specularColorFactor": [0.5, "red", 0.5]})",
     "KHR_materials_specular specularColorFactor is not a finite number"},
    {"SpecularTextureMissing", "KHR_materials_specular", R"({"specularTexture": {"index": 7}})",
     "KHR_materials_specular specularTexture does not name an existing texture"},
    {"SpecularColourTextureNotAnObject", "KHR_materials_specular", R"({"specularColorTexture": 3})",
     "KHR_materials_specular specularColorTexture does not name an existing texture"},
    {"SpecularTexCoordNegative", "KHR_materials_specular", R"({"specularTexture": {"index": 0, "texCoord": -2}})",
     "KHR_materials_specular specularTexture.texCoord is not an integer >= 0"},
    {"SpecularColourTransformScaleNotAPair", "KHR_materials_specular",
     R"({"specularColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": 2}}}})",
     "KHR_materials_specular.specularColorTexture: KHR_texture_transform scale is not an array of two numbers"},
};

class GltfBadExtensionValue : public ::testing::TestWithParam<BadExtensionValue> {};

// The material, named 'checked', has the one extension with the bad value (a volume with a
// transmission); loading it is an input error that names the file, the material and the value.
TEST_P(GltfBadExtensionValue, IsAnInputError) {
  const BadExtensionValue& bad = GetParam();
  TempDir dir;
  json material = with_extension("checked", bad.extension, json::parse(bad.value));
  if (std::string(bad.extension) == "KHR_materials_volume")
    material["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1}};
  test::expect_input_error(one_material_gltf(dir, bad.name, material), std::string("material 0 'checked': ") + bad.message);
}

INSTANTIATE_TEST_SUITE_P(MaterialExtensions, GltfBadExtensionValue, ::testing::ValuesIn(kBadExtensionValues),
                         [](const ::testing::TestParamInfo<BadExtensionValue>& info) { return info.param.name; });

}  // namespace
}  // namespace cohort
