// One glTF mesh instance to world-space triangles: topology, indices, TEXCOORD_0/1, COLOR_0, winding.
#pragma once

#include <map>
#include <string>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"
#include "runtime/scene/scene_builder.h"

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace cohort::gltf {

class PrimitiveEmitter {
 public:
  PrimitiveEmitter(const tinygltf::Model& model, const std::string& file, Scene& scene, SceneBuilder& builder)
      : model_(model), file_(file), scene_(scene), builder_(builder) {}

  void emit_mesh(int mesh, const glm::dmat4& world);
  // Adds one warning per kind of skipped primitive.
  void finish();

 private:
  // Counts primitives that are not triangles or have no positions, for finish().
  bool skipped(const tinygltf::Primitive& p, int mode);
  void emit_primitive(const tinygltf::Primitive& p, const std::string& where, const glm::dmat4& world);
  std::uint32_t material_id(int material, const std::string& where);

  const tinygltf::Model& model_;
  const std::string& file_;
  Scene& scene_;
  SceneBuilder& builder_;
  std::map<std::string, std::size_t> skipped_;  // reason -> primitive count
};

}  // namespace cohort::gltf
