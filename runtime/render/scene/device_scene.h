// A scene and its KD-tree uploaded to one device.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/accel/wide_bvh.h"
#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/backend/device.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/render/scene/emitters.h"
#include "runtime/render/scene/environment_map.h"
#include "runtime/render/scene/punctual_lights.h"
#include "runtime/scene/scene.h"

namespace cohort {

// The bytes of an array as uploaded.
template <class T, class Allocator>
std::size_t bytes_of(const std::vector<T, Allocator>& v) {
  return v.size() * sizeof(T);
}

// What the shading code of a scene needs compiled: the BSDF families its materials can select
// (bsdf_from_gltf's rules; the Lambertian is always there), texture lookups, and the lights
// beyond emissive triangles and the constant environment. Every rendering program of a render is
// built with the same options, so the methods still agree bit for bit.
struct SceneFeatures {
  bool textures = false;
  bool texcoord1 = false;      // some texture reads a second coordinate set (glTF TEXCOORD_1)
  bool vertex_colors = false;  // glTF COLOR_0 multiplies the base colour
  bool normal_map = false;     // some used material has a tangent-space normal map
  bool conductor = false;
  bool dielectric = false;
  bool plastic = false;
  bool envmap = false;    // an environment map (--env FILE.exr)
  bool punctual = false;  // KHR_lights_punctual point or spot lights
  bool alpha = false;     // some used material is alphaMode MASK or BLEND: every traversal tests alpha
  bool texture_transform = false;  // some uploaded texture slot has a KHR_texture_transform
  bool volume = false;  // some used material can refract into an absorbing interior (KHR_materials_volume)
  bool clearcoat = false;  // some used material has a clearcoat (KHR_materials_clearcoat, factor > 0)
  bool sheen = false;   // some used material has a non-zero sheen colour (KHR_materials_sheen)
  bool specular = false;  // some used material has a KHR_materials_specular of other than default values

  std::vector<std::string> names() const;  // "textures", "conductor", ...; empty for diffuse only
  std::string build_options() const;       // "-DCOHORT_FEATURE_TEXTURES ..."; empty for diffuse only
  bool operator==(const SceneFeatures&) const = default;
};

// The families bsdf_from_gltf can return for a material (any u_select).
SceneFeatures material_features(const Material& m);

// Host-side device data, testable without a device.
struct SceneTables {
  std::vector<Material> materials;
  std::vector<std::uint32_t> triangle_material;  // per kept triangle
  EmitterTable emitters;
  // textures, only when some used material has one and the scene has texture coordinates
  // (otherwise empty, and every material's texture index is -1)
  std::vector<TriangleUv> triangle_uvs;  // per kept triangle
  // the textures used, renumbered in order of first use (one per texture and transform), then each
  // distinct KHR_texture_transform as two entries (TextureTransform, types.h)
  std::vector<TextureDesc> textures;
  std::vector<std::uint32_t> texels;     // RGBA8 words, r in the low byte
  std::vector<TriangleColor> triangle_colors;  // per kept triangle, only with features.vertex_colors
  std::vector<TriangleFrame> triangle_frames;  // per kept triangle, only with features.normal_map
  std::vector<MaterialCoat> material_coats;    // per material, only with features.clearcoat
  std::vector<MaterialSheen> material_sheen;   // per material, only with features.sheen
  std::vector<MaterialSpecular> material_specular;  // per material, only with features.specular
  PunctualTable punctual;                // point and spot lights
  std::optional<EnvironmentMap> environment;
  SceneFeatures features;                // of the materials the kept triangles use, and the lights
};

Material to_device_material(const SceneMaterial& m);
MaterialCoat to_device_coat(const SceneClearcoat& c);
// The sheen of a material as the kernels read it (texture indices as in the scene, before upload).
MaterialSheen to_device_sheen(const SceneMaterial& m);
// KHR_materials_specular of a material as the kernels read it (texture indices as in the scene).
MaterialSpecular to_device_specular(const SceneSpecular& s);
SceneTables make_scene_tables(const Scene& scene, const KdTree& tree);
// Lights the scene with an environment map (it replaces any constant environment).
void set_environment_map(SceneTables& tables, EnvironmentMap map);

// Probabilities with which NEE picks each kind of light: proportional to an estimate of the
// power each sends into the scene (docs/lights.md); all 0 without lights. `radius` bounds the
// scene, for the power of the environment (pi r^2 times its luminance integral).
struct LightPick {
  float triangles = 0, environment = 0, punctual = 0;
};
LightPick light_pick(const SceneTables& tables, float radius);

struct DeviceScene {
  DeviceBuffer nodes, leaf_triangles, triangles, triangle_material, materials, emitters;
  DeviceBuffer triangle_uvs, textures, texels;  // one-element placeholders without textures
  DeviceBuffer triangle_colors;                 // a one-element placeholder without vertex colours
  DeviceBuffer triangle_frames;                 // a one-element placeholder without normal maps
  DeviceBuffer material_coats;                  // unset without clearcoat: the programs take no such argument
  DeviceBuffer material_sheen;                  // unset without sheen: the programs take no such argument
  DeviceBuffer material_specular;               // unset without specular: the programs take no such argument
  DeviceBuffer env_texels, env_tables, punctual_lights;  // placeholders without those lights
  SceneFeatures features;
  std::string build_options;  // features.build_options() (and the BVH's): every rendering program gets them
  bool bvh4 = false;          // nodes and leaf lists are a 4-wide BVH's (programs built with COHORT_ACCEL_BVH4)
  bool bvh8 = false;          // nodes and leaf lists are an 8-wide BVH's (programs built with COHORT_ACCEL_BVH8)
  bool bvh8f = false;         // nodes and leaf lists are the float-plane 8-wide BVH's (COHORT_ACCEL_BVH8F)
  std::uint32_t emitter_count = 0;
  float emitter_power_total = 0;
  std::uint32_t env_width = 0, env_height = 0;  // 0 x 0 without an environment map
  std::uint32_t punctual_count = 0;
  LightPick pick;
  Bounds bounds;
  std::size_t bytes = 0;
  // host-side facts the PTH method sizes itself from
  // first node of each depth, then the node count: the KD-tree's, or the BVH's breadth-first top
  std::vector<std::uint32_t> level_starts;
  std::array<std::vector<float>, 3> centroid_samples;  // sorted triangle centroids per axis (subsampled)

  // The scene's kernel arguments (SCENE_BUFFERS in kernels/common/core/kernel_params.h).
  SceneBuffers kernel_buffers() const;
};

// The arrays behind the kernels' node and leaf-list arguments: the BVH's when there is one, else the
// KD-tree's, and the build option with which a program reads them (kernels/common/accel/scene_accel.h).
struct TraversalArrays {
  const char* name;  // "BVH" or "KD-tree", for buffer names and messages
  const void* nodes;
  std::size_t node_bytes;
  const void* leaf_lists;
  std::size_t leaf_list_bytes;
  const char* build_option;  // "-DCOHORT_ACCEL_BVH4", "-DCOHORT_ACCEL_BVH8", "-DCOHORT_ACCEL_BVH8F" or empty
};
TraversalArrays traversal_arrays(const KdTree& tree, WideBvh bvh);

// With `bvh`, its nodes and leaf lists go where the KD-tree's would, and every rendering program is
// built with COHORT_ACCEL_BVH4, COHORT_ACCEL_BVH8 or COHORT_ACCEL_BVH8F to trace them (traversal_arrays).
DeviceScene upload_scene(const Device& cl, const KdTree& tree, const SceneTables& tables, WideBvh bvh = {});

}  // namespace cohort
