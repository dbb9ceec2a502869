#include "runtime/render/scene/device_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "runtime/util/error.h"
#include "runtime/render/scene/scene_memory.h"

namespace cohort {
namespace {

co_float4 to_float4(const glm::vec3& v, float w = 0.f) { return co_float4{v.x, v.y, v.z, w}; }

// Nodes are breadth-first, so each depth is a contiguous range; walk the tree once to find them.
std::vector<std::uint32_t> level_starts(const KdTree& tree) {
  std::vector<std::uint32_t> depth(tree.nodes.size(), 0);
  std::vector<std::uint32_t> starts{0};
  for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
    if (depth[i] + 1 > starts.size()) starts.push_back(i);
    const KdNode n = tree.nodes[i];
    if (!kd_is_leaf(n)) depth[kd_left_child(n)] = depth[kd_left_child(n) + 1] = depth[i] + 1;
  }
  starts.push_back(static_cast<std::uint32_t>(tree.nodes.size()));
  return starts;
}

std::array<std::vector<float>, 3> centroid_samples(const KdTree& tree) {
  constexpr std::size_t kMaxSamples = 1 << 16;  // quantiles of a 64K sample are plenty for 1K cells
  const std::size_t step = std::max<std::size_t>(1, tree.triangles.size() / kMaxSamples);
  std::array<std::vector<float>, 3> axes;
  for (std::size_t i = 0; i < tree.triangles.size(); i += step) {
    const Triangle& t = tree.triangles[i];
    axes[0].push_back((t.v0.x + t.v1.x + t.v2.x) / 3.f);
    axes[1].push_back((t.v0.y + t.v1.y + t.v2.y) / 3.f);
    axes[2].push_back((t.v0.z + t.v1.z + t.v2.z) / 3.f);
  }
  for (auto& a : axes) std::sort(a.begin(), a.end());
  return axes;
}

}  // namespace

Material to_device_material(const SceneMaterial& m) {
  Material d{};
  d.base_color = to_float4(m.base_color, m.alpha);
  d.emission = to_float4(m.emission);
  d.metallic = m.metallic;
  d.roughness = m.roughness;
  d.transmission = m.transmission;
  d.ior = m.ior;
  d.base_color_texture = m.base_color_texture;
  d.flags = m.double_sided ? MAT_TWO_SIDED_EMISSION : 0u;
  if (m.base_color_texcoord == 1) d.flags |= MAT_UV1_BASE_COLOR;
  if (m.metallic_roughness_texcoord == 1) d.flags |= MAT_UV1_METALLIC_ROUGHNESS;
  if (m.emission_texcoord == 1) d.flags |= MAT_UV1_EMISSION;
  if (m.normal_texcoord == 1) d.flags |= MAT_UV1_NORMAL;
  d.normal_texture = m.normal_texture;
  d.normal_scale = m.normal_scale;
  d.emission_texture = m.emission_texture;
  d.metallic_roughness_texture = m.metallic_roughness_texture;
  if (m.alpha_mode == AlphaMode::mask) d.flags |= MAT_ALPHA_MASK;
  if (m.alpha_mode == AlphaMode::blend) d.flags |= MAT_ALPHA_BLEND;
  d.alpha_cutoff = m.alpha_cutoff;
  d.absorption = to_float4(m.absorption);
  return d;
}

MaterialCoat to_device_coat(const SceneClearcoat& c) {
  MaterialCoat d{};
  d.factor = c.factor;
  d.roughness = c.roughness;
  d.factor_texture = c.texture;
  d.roughness_texture = c.roughness_texture;
  d.normal_texture = c.normal_texture;
  d.normal_scale = c.normal_scale;
  if (c.texcoord == 1) d.flags |= COAT_UV1_FACTOR;
  if (c.roughness_texcoord == 1) d.flags |= COAT_UV1_ROUGHNESS;
  if (c.normal_texcoord == 1) d.flags |= COAT_UV1_NORMAL;
  return d;
}

MaterialSheen to_device_sheen(const SceneMaterial& m) {
  MaterialSheen d{};
  d.color_roughness = to_float4(m.sheen.color, m.sheen.roughness);
  d.color_texture = m.sheen.color_texture;
  d.roughness_texture = m.sheen.roughness_texture;
  if (m.sheen.color_texcoord == 1) d.flags |= MAT_SHEEN_UV1_COLOR;
  if (m.sheen.roughness_texcoord == 1) d.flags |= MAT_SHEEN_UV1_ROUGHNESS;
  return d;
}

MaterialSpecular to_device_specular(const SceneSpecular& s) {
  MaterialSpecular d{};
  d.color_factor = to_float4(s.color, s.factor);
  d.factor_texture = s.texture;
  d.color_texture = s.color_texture;
  if (s.texcoord == 1) d.flags |= MAT_SPECULAR_UV1_FACTOR;
  if (s.color_texcoord == 1) d.flags |= MAT_SPECULAR_UV1_COLOR;
  if (s.present()) d.flags |= MAT_SPECULAR_LAYER;
  return d;
}

std::vector<std::string> SceneFeatures::names() const {
  std::vector<std::string> out;
  if (textures) out.push_back("textures");
  if (texcoord1) out.push_back("texcoord1");
  if (vertex_colors) out.push_back("vertex_colors");
  if (normal_map) out.push_back("normal_map");
  if (conductor) out.push_back("conductor");
  if (dielectric) out.push_back("dielectric");
  if (plastic) out.push_back("plastic");
  if (envmap) out.push_back("envmap");
  if (punctual) out.push_back("punctual");
  if (alpha) out.push_back("alpha");
  if (texture_transform) out.push_back("texture_transform");
  if (volume) out.push_back("volume");
  if (clearcoat) out.push_back("clearcoat");
  if (sheen) out.push_back("sheen");
  if (specular) out.push_back("specular");
  return out;
}

std::string SceneFeatures::build_options() const {
  std::string out;
  for (const std::string& name : names()) {
    if (!out.empty()) out += ' ';
    out += "-DCOHORT_FEATURE_";
    for (char c : name) out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

// Mirrors bsdf_from_gltf (kernels/common/shading/bsdf.h) with the same clamps, so that no family the
// kernel can select is left out. With u_select in [0, 1): a conductor whenever metallic > 0; the
// remapped u lies in [0, 1], reaching 1 only through rounding when 0 < metallic < 1, so a
// dielectric is possible whenever transmission > 0 and the opaque base unless transmission > 1,
// or transmission = 1 with metallic = 0 (NaN transmission: always the base). A metallic-roughness
// texture scales both factors by [0, 1]: any metallic and roughness from 0 to the factors.
SceneFeatures material_features(const Material& m) {
  SceneFeatures f;
  const bool mr_texture = m.metallic_roughness_texture >= 0;
  const float met = std::fmin(std::fmax(m.metallic, 0.f), 1.f);
  const float r = std::fmin(std::fmax(m.roughness, 0.f), 1.f);
  f.conductor = met > 0.f;
  if (met < 1.f || mr_texture) {
    f.dielectric = m.transmission > 0.f;
    const bool opaque = !(m.transmission >= 1.f) || (m.transmission == 1.f && met > 0.f);
    f.plastic = opaque && (r < 1.f || mr_texture);
  }
  // a path enters a volume only by refracting through the dielectric
  f.volume = f.dielectric && (m.absorption.x > 0.f || m.absorption.y > 0.f || m.absorption.z > 0.f);
  return f;
}

namespace {

bool texture_usable(const Scene& scene, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= scene.textures.size()) return false;
  const Texture& t = scene.textures[static_cast<std::size_t>(index)];
  return t.width > 0 && t.height > 0 &&
         t.rgba.size() == std::size_t(t.width) * std::size_t(t.height) * 4 &&
         std::size_t(t.width) * std::size_t(t.height) < std::numeric_limits<std::uint32_t>::max();
}

std::uint32_t wrap_bits(TextureWrap w) {
  return w == TextureWrap::clamp_to_edge ? TEX_WRAP_CLAMP : (w == TextureWrap::mirrored_repeat ? TEX_WRAP_MIRROR : TEX_WRAP_REPEAT);
}

std::uint32_t sampler_bits(const Texture& t) {
  return tex_sampler((t.sampler.nearest ? TEX_NEAREST : 0u) | (t.srgb ? 0u : TEX_DATA), wrap_bits(t.sampler.wrap_s),
                     wrap_bits(t.sampler.wrap_t));
}

bool has_set(const Scene& scene, int set) {
  return (set == 1 ? scene.uvs1 : scene.uvs).size() == 3 * scene.triangle_count();
}

// glTF's T * R * S of KHR_texture_transform as the rows of an affine map of (u, v).
TextureTransform affine(const UvTransform& x) {
  const float c = std::cos(x.rotation), s = std::sin(x.rotation);
  return TextureTransform{c * x.scale.x, s * x.scale.y, x.offset.x, -s * x.scale.x, c * x.scale.y, x.offset.y, 0.f, 0.f};
}

// Uploads only the textures that used materials refer to, renumbered; the others stay on the host.
// A texture whose coordinate set the scene lacks is left out (the loader has warned). A texture read
// through a KHR_texture_transform gets a descriptor of its own per transform (the texels are shared)
// whose sampler points at the transform, stored after the descriptors.
void add_textures(const Scene& scene, const KdTree& tree, const std::vector<bool>& used, SceneTables& t) {
  std::vector<std::uint32_t> texel_offset(scene.textures.size(), std::numeric_limits<std::uint32_t>::max());
  std::map<std::pair<int, std::array<float, 5>>, int> new_index;  // (scene texture, transform) -> descriptor
  std::vector<UvTransform> transforms;
  auto remap = [&](std::int32_t& index, const UvTransform& transform) {
    if (!texture_usable(scene, index)) {
      index = -1;
      return;
    }
    const Texture& tex = scene.textures[static_cast<std::size_t>(index)];
    std::uint32_t& offset = texel_offset[static_cast<std::size_t>(index)];
    if (offset == std::numeric_limits<std::uint32_t>::max()) {
      const std::size_t texels = std::size_t(tex.width) * std::size_t(tex.height);
      if (t.texels.size() + texels > std::numeric_limits<std::uint32_t>::max()) {
        index = -1;  // the descriptor's 32-bit offset cannot reach it
        return;
      }
      offset = static_cast<std::uint32_t>(t.texels.size());
      t.texels.resize(t.texels.size() + texels);
      std::memcpy(t.texels.data() + offset, tex.rgba.data(), texels * 4);  // little-endian: r in the low byte
    }
    const std::array<float, 5> key = {transform.offset.x, transform.offset.y, transform.rotation, transform.scale.x,
                                      transform.scale.y};
    auto [it, added] = new_index.try_emplace({index, key}, static_cast<int>(t.textures.size()));
    if (added) {
      std::uint32_t sampler = sampler_bits(tex);
      if (!transform.identity()) {
        // the transform's number for now; its entry once the descriptors are all known
        sampler |= TEX_TRANSFORM | (static_cast<std::uint32_t>(transforms.size()) << 8);
        transforms.push_back(transform);
      }
      t.textures.push_back(TextureDesc{offset, std::uint32_t(tex.width), std::uint32_t(tex.height), sampler});
    }
    index = it->second;
  };
  bool set1 = false;  // some uploaded texture reads TEXCOORD_1
  auto slot = [&](std::int32_t& index, bool used_material, int set, const UvTransform& transform) {
    if (!used_material || !has_set(scene, set)) {
      index = -1;
      return;
    }
    remap(index, transform);
    set1 |= index >= 0 && set == 1;
  };
  for (std::size_t i = 0; i < t.materials.size(); ++i) {
    Material& m = t.materials[i];
    const SceneMaterial& sm = scene.materials[i];
    slot(m.base_color_texture, used[i], sm.base_color_texcoord, sm.base_color_transform);
    slot(m.emission_texture, used[i], sm.emission_texcoord, sm.emission_transform);
    slot(m.metallic_roughness_texture, used[i], sm.metallic_roughness_texcoord, sm.metallic_roughness_transform);
    slot(m.normal_texture, used[i], sm.normal_texcoord, sm.normal_transform);
    if (t.features.sheen) {
      // the sheen's textures, uploaded only where the material has a sheen
      MaterialSheen& sheen = t.material_sheen[i];
      const bool sheen_used = used[i] && sm.sheen.present();
      slot(sheen.color_texture, sheen_used, sm.sheen.color_texcoord, sm.sheen.color_transform);
      slot(sheen.roughness_texture, sheen_used, sm.sheen.roughness_texcoord, sm.sheen.roughness_transform);
    }
    if (t.features.specular) {
      // the specular textures, uploaded only where the material has the extension's layering
      MaterialSpecular& spec = t.material_specular[i];
      const bool spec_used = used[i] && sm.specular.present();
      slot(spec.factor_texture, spec_used, sm.specular.texcoord, sm.specular.transform);
      slot(spec.color_texture, spec_used, sm.specular.color_texcoord, sm.specular.color_transform);
    }
    t.features.normal_map |= m.normal_texture >= 0;
    if (!t.features.clearcoat) continue;
    // a coat's textures only where the coat is there (factor > 0): a scene without one uploads none
    MaterialCoat& c = t.material_coats[i];
    const SceneClearcoat& sc = sm.clearcoat;
    const bool coat = used[i] && c.factor > 0.f;
    slot(c.factor_texture, coat, sc.texcoord, sc.transform);
    slot(c.roughness_texture, coat, sc.roughness_texcoord, sc.roughness_transform);
    slot(c.normal_texture, coat, sc.normal_texcoord, sc.normal_transform);
    t.features.normal_map |= c.normal_texture >= 0;
  }
  if (t.textures.empty()) return;
  t.features.textures = true;
  if (!transforms.empty()) {
    const auto descriptors = static_cast<std::uint32_t>(t.textures.size());
    if (descriptors + 2 * transforms.size() > (1u << 24))
      throw InputError(fmt::format("{} textures with {} texture transforms are more than the kernels address",
                                   descriptors, transforms.size()));
    for (TextureDesc& d : t.textures)
      if (d.sampler & TEX_TRANSFORM)
        d.sampler = (d.sampler & 0xffu) | ((descriptors + 2 * tex_transform_entry(d.sampler)) << 8);
    for (const UvTransform& x : transforms) {
      const TextureTransform rows = affine(x);
      TextureDesc entries[2];
      std::memcpy(entries, &rows, sizeof rows);
      t.textures.insert(t.textures.end(), entries, entries + 2);
    }
    t.features.texture_transform = true;
  }
  t.features.texcoord1 = set1;
  auto push = [&](const std::vector<glm::vec2>& uvs, std::uint32_t src) {
    if (uvs.empty()) {
      t.triangle_uvs.push_back(TriangleUv{});
      return;
    }
    const glm::vec2* uv = &uvs[3 * std::size_t(src)];
    t.triangle_uvs.push_back(TriangleUv{uv[0].x, uv[0].y, uv[1].x, uv[1].y, uv[2].x, uv[2].y});
  };
  // one set per triangle, or both interleaved (COHORT_FEATURE_TEXCOORD1: set s of triangle i at 2i + s)
  t.triangle_uvs.reserve(tree.source_index.size() * (set1 ? 2 : 1));
  for (std::uint32_t src : tree.source_index) {
    push(scene.uvs, src);
    if (set1) push(scene.uvs1, src);
  }
}

// Vertex normals and tangents per kept triangle, when a used material has a normal map; zeros where
// the scene has none (the kernel then shades with the geometric normal, or without the map).
void add_frames(const Scene& scene, const KdTree& tree, SceneTables& t) {
  if (!t.features.normal_map) return;
  const bool normals = scene.normals.size() == 3 * scene.triangle_count();
  const bool tangents = scene.tangents.size() == 3 * scene.triangle_count();
  t.triangle_frames.reserve(tree.source_index.size());
  for (std::uint32_t src : tree.source_index) {
    TriangleFrame f{};
    co_float4* n[3] = {&f.n0, &f.n1, &f.n2};
    co_float4* tg[3] = {&f.t0, &f.t1, &f.t2};
    for (std::size_t k = 0; k < 3; ++k) {
      if (normals) {
        const glm::vec3& v = scene.normals[3 * std::size_t(src) + k];
        *n[k] = co_float4{v.x, v.y, v.z, 0.f};
      }
      if (tangents) {
        const glm::vec4& v = scene.tangents[3 * std::size_t(src) + k];
        *tg[k] = co_float4{v.x, v.y, v.z, v.w};
      }
    }
    t.triangle_frames.push_back(f);
  }
}

// COLOR_0 per kept triangle, when the scene has vertex colours.
void add_vertex_colors(const Scene& scene, const KdTree& tree, SceneTables& t) {
  if (scene.colors.size() != 3 * scene.triangle_count()) return;
  t.features.vertex_colors = true;
  auto c4 = [](const glm::vec4& c) { return co_float4{c.x, c.y, c.z, c.w}; };
  t.triangle_colors.reserve(tree.source_index.size());
  for (std::uint32_t src : tree.source_index) {
    const glm::vec4* c = &scene.colors[3 * std::size_t(src)];
    t.triangle_colors.push_back(TriangleColor{c4(c[0]), c4(c[1]), c4(c[2])});
  }
}

}  // namespace

SceneTables make_scene_tables(const Scene& scene, const KdTree& tree) {
  SceneTables t;
  for (const auto& m : scene.materials) t.materials.push_back(to_device_material(m));
  t.triangle_material.reserve(tree.source_index.size());
  for (std::uint32_t src : tree.source_index) t.triangle_material.push_back(scene.material_ids.at(src));
  std::vector<bool> used(t.materials.size(), false);
  for (std::uint32_t id : t.triangle_material) used.at(id) = true;
  for (std::size_t i = 0; i < t.materials.size(); ++i)
    t.features.clearcoat |= used[i] && scene.materials[i].clearcoat.factor > 0.f;
  if (t.features.clearcoat)
    for (const auto& m : scene.materials) t.material_coats.push_back(to_device_coat(m.clearcoat));
  // the sheen's table likewise, only where a used material has one (the programs take it only then)
  for (std::size_t i = 0; i < t.materials.size(); ++i) t.features.sheen |= used[i] && scene.materials[i].sheen.present();
  if (t.features.sheen)
    for (const auto& m : scene.materials) t.material_sheen.push_back(to_device_sheen(m));
  // KHR_materials_specular's likewise, where a used material has one of other than default values
  for (std::size_t i = 0; i < t.materials.size(); ++i)
    t.features.specular |= used[i] && scene.materials[i].specular.present();
  if (t.features.specular)
    for (const auto& m : scene.materials) t.material_specular.push_back(to_device_specular(m.specular));
  add_textures(scene, tree, used, t);  // first: a texture left out selects no more families
  add_vertex_colors(scene, tree, t);
  add_frames(scene, tree, t);
  for (std::size_t i = 0; i < t.materials.size(); ++i) {
    if (!used[i]) continue;
    const SceneFeatures f = material_features(t.materials[i]);
    t.features.conductor |= f.conductor;
    t.features.dielectric |= f.dielectric;
    t.features.plastic |= f.plastic;
    t.features.volume |= f.volume;
    t.features.alpha |= (t.materials[i].flags & (MAT_ALPHA_MASK | MAT_ALPHA_BLEND)) != 0u;
  }
  // the path slot keeps the medium, 1 + a material index, as a float (wavefront_path.h): exact below 2^24
  if (t.features.volume && t.materials.size() >= (std::size_t{1} << 24) - 1)
    throw InputError(fmt::format("{} materials: volumes (KHR_materials_volume) need fewer than 2^24 - 1",
                                 t.materials.size()));
  t.emitters = build_emitter_table(tree, t.materials, t.triangle_material);
  t.punctual = make_punctual_table(scene.lights);
  t.features.punctual = !t.punctual.lights.empty();
  return t;
}

void set_environment_map(SceneTables& tables, EnvironmentMap map) {
  tables.environment = std::move(map);
  tables.features.envmap = true;
}

LightPick light_pick(const SceneTables& t, float radius) {
  // fluxes: pi L A per emitting side, 4 pi I per point light, pi r^2 E for the environment
  const double triangles = M_PI * t.emitters.total_power;
  const double environment =
      t.environment ? M_PI * double(radius) * radius * t.environment->luminance_integral : 0.0;
  const double punctual = t.punctual.power;
  const double total = triangles + environment + punctual;
  LightPick pick;
  if (!(total > 0)) return pick;
  // only triangles: exactly 1, so the estimator is the one without the other lights bit for bit
  if (environment == 0 && punctual == 0) {
    pick.triangles = 1.f;
    return pick;
  }
  pick.environment = static_cast<float>(environment / total);
  pick.punctual = static_cast<float>(punctual / total);
  pick.triangles = triangles > 0 ? 1.f - pick.environment - pick.punctual : 0.f;
  if (triangles == 0 && punctual == 0) pick.environment = 1.f;
  if (triangles == 0 && environment == 0) pick.punctual = 1.f;
  return pick;
}

SceneBuffers DeviceScene::kernel_buffers() const {
  SceneBuffers b;
  b.nodes = nodes;
  b.leaf_triangles = leaf_triangles;
  b.triangles = triangles;
  b.triangle_material = triangle_material;
  b.materials = materials;
  b.emitters = emitters;
  b.triangle_uvs = triangle_uvs;
  b.textures = textures;
  b.texels = texels;
  b.triangle_colors = triangle_colors;
  b.triangle_frames = triangle_frames;
  b.env_texels = env_texels;
  b.env_tables = env_tables;
  b.punctual_lights = punctual_lights;
  b.material_coats = material_coats;
  b.material_sheen = material_sheen;
  b.material_specular = material_specular;
  return b;
}

TraversalArrays traversal_arrays(const KdTree& tree, WideBvh bvh) {
  if (const Bvh4* b = bvh.bvh4)
    return {"BVH", b->nodes.data(), bytes_of(b->nodes), b->leaf_vertices.data(), bytes_of(b->leaf_vertices),
            "-DCOHORT_ACCEL_BVH4"};
  if (const Bvh8* b = bvh.bvh8)
    return {"BVH", b->nodes.data(), bytes_of(b->nodes), b->leaf_vertices.data(), bytes_of(b->leaf_vertices),
            "-DCOHORT_ACCEL_BVH8"};
  if (const Bvh8f* b = bvh.bvh8f)
    return {"BVH", b->nodes.data(), bytes_of(b->nodes), b->leaf_blocks.data(), bytes_of(b->leaf_blocks),
            "-DCOHORT_ACCEL_BVH8F"};
  return {"KD-tree", tree.nodes.data(), bytes_of(tree.nodes), tree.leaf_triangles.data(), bytes_of(tree.leaf_triangles),
          ""};
}

DeviceScene upload_scene(const Device& cl, const KdTree& tree, const SceneTables& tables, WideBvh bvh) {
  DeviceScene d;
  const SceneMemory memory = scene_memory(tree, tables, bvh);
  d.bytes = memory.total();
  if (d.bytes > cl.info().global_memory)
    throw DeviceError(fmt::format("the scene needs {} bytes of device memory ({}); {} has {} bytes", d.bytes,
                                  describe(memory, tree.triangles.size()), cl.info().name,
                                  cl.info().global_memory));
  const auto ro = Access::read_only;
  const TraversalArrays arrays = traversal_arrays(tree, bvh);
  d.nodes = cl.allocate(fmt::format("{} nodes", arrays.name), arrays.node_bytes, arrays.nodes, ro);
  d.leaf_triangles =
      cl.allocate(fmt::format("{} leaf lists", arrays.name), arrays.leaf_list_bytes, arrays.leaf_lists, ro);
  d.triangles = cl.allocate("triangles", bytes_of(tree.triangles), tree.triangles.data(), ro);
  d.triangle_material =
      cl.allocate("triangle materials", bytes_of(tables.triangle_material), tables.triangle_material.data(), ro);
  d.materials = cl.allocate("materials", bytes_of(tables.materials), tables.materials.data(), ro);
  d.emitters = cl.allocate("emitters", bytes_of(tables.emitters.entries), tables.emitters.entries.data(), ro);
  // without textures the kernels never read these; they take one-element placeholders
  auto upload = [&](const char* what, const auto& v) {
    return cl.allocate(what, bytes_of(v), v.empty() ? nullptr : v.data(), ro);
  };
  d.triangle_uvs = upload("texture coordinates", tables.triangle_uvs);
  d.textures = upload("texture descriptors", tables.textures);
  d.texels = upload("texels", tables.texels);
  d.triangle_colors = upload("vertex colours", tables.triangle_colors);
  d.triangle_frames = upload("tangent frames", tables.triangle_frames);
  d.punctual_lights = upload("punctual lights", tables.punctual.lights);
  if (tables.features.clearcoat) d.material_coats = upload("clearcoat", tables.material_coats);
  if (tables.features.sheen) d.material_sheen = upload("material sheen", tables.material_sheen);
  if (tables.features.specular) d.material_specular = upload("material specular", tables.material_specular);
  d.punctual_count = static_cast<std::uint32_t>(tables.punctual.lights.size());
  if (tables.environment) {
    d.env_texels = upload("environment map", tables.environment->texels);
    d.env_tables = upload("environment sampling tables", tables.environment->tables);
    d.env_width = tables.environment->width;
    d.env_height = tables.environment->height;
  } else {
    d.env_texels = upload("environment map", std::vector<co_float4>{});
    d.env_tables = upload("environment sampling tables", std::vector<float>{});
  }
  d.pick = light_pick(tables, 0.5f * tree.bounds.diagonal());
  d.features = tables.features;
  d.build_options = tables.features.build_options();
  d.bvh4 = bvh.bvh4 != nullptr;
  d.bvh8 = bvh.bvh8 != nullptr;
  d.bvh8f = bvh.bvh8f != nullptr;
  if (*arrays.build_option) {
    if (!d.build_options.empty()) d.build_options += ' ';
    d.build_options += arrays.build_option;
  }
  d.emitter_count = static_cast<std::uint32_t>(tables.emitters.entries.size());
  d.emitter_power_total = tables.emitters.total_power;
  d.bounds = tree.bounds;
  // the 8-wide BVHs have no breadth-first top (the PTH walk does not run on them)
  d.level_starts = bvh.bvh4                  ? bvh.bvh4->top_level_starts
                   : bvh.bvh8 || bvh.bvh8f ? std::vector<std::uint32_t>{}
                                             : level_starts(tree);
  d.centroid_samples = centroid_samples(tree);
  return d;
}

}  // namespace cohort
