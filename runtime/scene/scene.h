// The in-memory scene every loader produces: a world-space triangle soup with a material per
// triangle, a material table, textures and an optional camera.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/scene/bounds.h"

namespace cohort {

// glTF alphaMode: OPAQUE ignores alpha; MASK cuts out where alpha < alpha_cutoff; BLEND is
// stochastic transparency (kernels/common/accel/alpha.h). OBJ and PLY materials stay opaque.
enum class AlphaMode : std::uint8_t { opaque, mask, blend };

// glTF KHR_texture_transform of one texture slot: uv' = T(offset) R(rotation) S(scale) uv, with
// glTF's rotation matrix (counter-clockwise in the image, whose v runs down).
struct UvTransform {
  glm::vec2 offset{0.f};
  float rotation = 0.f;  // radians
  glm::vec2 scale{1.f};
  bool identity() const { return offset == glm::vec2(0.f) && rotation == 0.f && scale == glm::vec2(1.f); }
  bool operator==(const UvTransform&) const = default;
};

// glTF KHR_materials_clearcoat: a dielectric layer (IOR 1.5) over the material (docs/bsdf.md,
// "Clearcoat"); factor 0 is no coat. Textures index Scene::textures (linear data).
struct SceneClearcoat {
  float factor = 0.f;     // clearcoatFactor
  float roughness = 0.f;  // clearcoatRoughnessFactor
  int texture = -1;            // clearcoatTexture: R multiplies the factor
  int roughness_texture = -1;  // clearcoatRoughnessTexture: G multiplies the roughness
  int normal_texture = -1;     // clearcoatNormalTexture: the coat's tangent-space normal map
  float normal_scale = 1.f;    // its scale
  int texcoord = 0, roughness_texcoord = 0, normal_texcoord = 0;  // the coordinate set each reads
  UvTransform transform, roughness_transform, normal_transform;   // each texture's KHR_texture_transform
};

// glTF KHR_materials_sheen of a material (docs/bsdf.md, "Sheen"): a colour of 0 is no sheen.
struct SceneSheen {
  glm::vec3 color{0.f};   // sheenColorFactor, linear
  float roughness = 0.f;  // sheenRoughnessFactor
  int color_texture = -1;      // index into Scene::textures (sRGB colour); its RGB multiplies the colour
  int roughness_texture = -1;  // index into Scene::textures (linear data); its A multiplies the roughness
  int color_texcoord = 0;      // the coordinate set each texture reads
  int roughness_texcoord = 0;
  UvTransform color_transform;  // each texture's KHR_texture_transform
  UvTransform roughness_transform;
  bool present() const { return color.x > 0.f || color.y > 0.f || color.z > 0.f; }
};

// glTF KHR_materials_specular of a material (docs/bsdf.md, "Specular"): the strength and colour of the
// dielectric's specular reflection. Default values and no texture are the material without it.
struct SceneSpecular {
  float factor = 1.f;          // specularFactor, in [0, 1]
  glm::vec3 color{1.f};        // specularColorFactor, linear, >= 0
  int texture = -1;            // specularTexture (linear data): its A multiplies the factor
  int color_texture = -1;      // specularColorTexture (sRGB colour): its RGB multiplies the colour
  int texcoord = 0, color_texcoord = 0;     // the coordinate set each texture reads
  UvTransform transform, color_transform;  // each texture's KHR_texture_transform
  bool present() const { return factor != 1.f || color != glm::vec3(1.f) || texture >= 0 || color_texture >= 0; }
};

struct SceneMaterial {
  std::string name;
  glm::vec3 base_color{0.8f};
  float alpha = 1.f;
  glm::vec3 emission{0.f};  // radiance: emissive factor x KHR_materials_emissive_strength
  float metallic = 0.f;
  float roughness = 1.f;
  float transmission = 0.f;  // KHR_materials_transmission
  float ior = 1.5f;          // KHR_materials_ior
  // KHR_materials_volume: sigma_a per unit length of the interior, -ln(attenuationColor) /
  // attenuationDistance per channel (0: no absorption), used where the material transmits
  glm::vec3 absorption{0.f};
  int base_color_texture = -1;  // index into Scene::textures
  int emission_texture = -1;    // index into Scene::textures (sRGB-encoded); multiplies emission
  int metallic_roughness_texture = -1;  // linear data: B multiplies metallic, G roughness
  int normal_texture = -1;              // linear data: a tangent-space normal map
  float normal_scale = 1.f;             // scales the map's x and y (glTF normalTexture.scale)
  // the coordinate set (0: Scene::uvs, 1: Scene::uvs1) each texture reads
  int base_color_texcoord = 0;
  int emission_texcoord = 0;
  int metallic_roughness_texcoord = 0;
  int normal_texcoord = 0;
  // each texture's KHR_texture_transform (identity where the file has none)
  UvTransform base_color_transform;
  UvTransform emission_transform;
  UvTransform metallic_roughness_transform;
  UvTransform normal_transform;
  SceneClearcoat clearcoat;     // KHR_materials_clearcoat
  bool double_sided = false;    // glTF doubleSided; emission leaves both faces when set
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;    // glTF alphaCutoff, read with MASK only
  SceneSheen sheen;             // KHR_materials_sheen
  SceneSpecular specular;       // KHR_materials_specular
  bool is_emissive() const { return emission.x > 0.f || emission.y > 0.f || emission.z > 0.f; }
};

enum class TextureWrap : std::uint8_t { repeat, clamp_to_edge, mirrored_repeat };

// glTF's sampler; mip-map filters count as their nearest non-mip equivalent (docs/input.md).
struct TextureSampler {
  bool nearest = false;  // nearest texel; else bilinear
  TextureWrap wrap_s = TextureWrap::repeat;
  TextureWrap wrap_t = TextureWrap::repeat;
  bool operator==(const TextureSampler&) const = default;
};

// 8-bit RGBA texels as stored in the file, sampled as the file says: sRGB-encoded colour (base
// colour, emission) or linear data (metallic-roughness).
struct Texture {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
  TextureSampler sampler;
  bool srgb = true;
  std::vector<std::string> uses;  // what it drives, for `info` ("base colour of 'Body'")
};

struct SceneCamera {
  glm::vec3 eye{0.f};
  glm::vec3 target{0.f, 0.f, -1.f};
  glm::vec3 up{0.f, 1.f, 0.f};
  float vfov_degrees = 45.f;
};

// A glTF KHR_lights_punctual point or spot light placed in the world (docs/lights.md).
struct SceneLight {
  enum class Type { point, spot };
  Type type = Type::point;
  std::string name;
  glm::vec3 position{0.f};
  glm::vec3 direction{0.f, 0.f, -1.f};  // spot: unit, the direction it shines in (its node's -Z)
  glm::vec3 intensity{1.f};             // colour x intensity, candela
  float inner_cone = 0.f;               // radians, spot only
  float outer_cone = 0.7853981634f;     // radians, spot only
};

struct Scene {
  std::filesystem::path source;
  std::vector<glm::vec3> positions;        // 3 per triangle, world space, counter-clockwise front
  std::vector<glm::vec2> uvs;              // empty, or 3 per triangle; (0,0) is the top-left texel
  std::vector<glm::vec2> uvs1;             // a second set (glTF TEXCOORD_1): empty, or 3 per triangle
  std::vector<glm::vec4> colors;           // vertex colours (glTF COLOR_0): empty, or 3 per triangle
  std::vector<glm::vec3> normals;          // unit vertex normals, world space: empty, or 3 per triangle (0: none)
  std::vector<glm::vec4> tangents;         // unit tangents, w = +-1 (glTF TANGENT): empty, or 3 per triangle
  std::vector<std::uint32_t> material_ids; // 1 per triangle, index into materials
  std::vector<SceneMaterial> materials;    // never empty once loaded
  std::vector<Texture> textures;
  std::optional<SceneCamera> camera;       // from the file, when it has one
  std::vector<SceneLight> lights;          // punctual lights (glTF KHR_lights_punctual)
  std::vector<std::string> warnings;       // legal but odd input (no light, skipped primitives)
  std::vector<std::string> notes;          // input left out by design, said once by `info`
  // Images the file binds to a slot the renderer does not read by design, each with what it would
  // drive and why it is not read ("Default_AO.jpg: occlusion of 'Helmet', not used: ..."), which
  // `info` lists after the textures it reads.
  std::vector<std::string> unread_textures;

  std::size_t triangle_count() const { return positions.size() / 3; }
  Bounds bounds() const;
  std::size_t emissive_triangle_count() const;
  // Bytes the device buffers of this scene need before the acceleration structure.
  std::size_t geometry_bytes() const;
};

// Loads .gltf, .glb, .obj (with .mtl), .ply, each optionally gzip-compressed (NAME.EXT.gz).
// Throws InputError naming the file and the problem.
Scene load_scene(const std::filesystem::path& path);

// The framing camera of docs/bench-protocol.md: eye = c + (0, 0, diag), looking at c, +Y up, 45 degrees.
SceneCamera framing_camera(const Bounds& bounds);

}  // namespace cohort
