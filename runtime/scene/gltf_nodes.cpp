#include "runtime/scene/gltf_nodes.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <tiny_gltf.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "runtime/scene/gltf_primitive.h"
#include "runtime/scene/scene_builder.h"
#include "runtime/util/error.h"

namespace cohort::gltf {
namespace {

// Far beyond any authored hierarchy; a deeper one is corrupt or hostile and would overflow the stack.
constexpr int kMaxDepth = 256;
// A node graph that shares subtrees (a DAG) is walked once per path; this bounds the expansion.
constexpr std::size_t kMaxNodeVisits = std::size_t{1} << 22;

bool all_finite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// A transform the specification does not allow is an error: ignoring it (or part of it) would place
// the node's meshes somewhere the file does not say.
void check_transform(const tinygltf::Node& n, int index, const std::string& file) {
  const auto check = [&](const std::vector<double>& values, std::size_t size, const char* name) {
    if (!values.empty() && values.size() != size)
      throw InputError(fmt::format("{}: node {} {} has {} numbers, not {}", file, index, name, values.size(), size));
    if (!all_finite(values))
      throw InputError(fmt::format("{}: node {} {} is not finite", file, index, name));
  };
  check(n.matrix, 16, "matrix");
  check(n.translation, 3, "translation");
  check(n.rotation, 4, "rotation");
  check(n.scale, 3, "scale");
  // A matrix whose last row is not (0, 0, 0, 1) is a projection, not a node transform.
  const auto& m = n.matrix;
  if (m.size() == 16 && (m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0))
    throw InputError(fmt::format("{}: node {} matrix is not affine (last row not 0, 0, 0, 1)", file, index));
  if (n.rotation.size() == 4) {
    const double length = glm::length(glm::dvec4(n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]));
    // Unit within what exporters round to; far from 1 (0, or a lost normalization) is not a rotation.
    if (!(std::abs(length - 1.0) < 1e-2))
      throw InputError(
          fmt::format("{}: node {} rotation is not a unit quaternion (length {})", file, index, length));
  }
}

glm::dmat4 local_transform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3)
    m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

bool is_finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

bool usable_direction(const glm::dvec3& v) {
  const double length = glm::length(v);
  return std::isfinite(length) && length > 1e-12;
}

class NodeWalker {
 public:
  NodeWalker(const tinygltf::Model& model, const std::string& file, Scene& scene)
      : model_(model),
        file_(file),
        scene_(scene),
        builder_(scene),
        emitter_(model, file, scene, builder_),
        on_path_(model.nodes.size(), false),
        instances_below_(model.nodes.size(), 0) {}

  void walk() {
    if (model_.nodes.empty()) {
      // Meshes with no nodes at all are still geometry; place them untransformed.
      for (std::size_t m = 0; m < model_.meshes.size(); ++m)
        emitter_.emit_mesh(static_cast<int>(m), glm::dmat4(1.0));
      return;
    }
    const std::vector<int> roots = root_nodes();
    // Counted on the graph first (each node once), so a DAG that expands past the limit is refused in
    // microseconds instead of after emitting millions of mesh instances.
    std::size_t instances = 0;
    for (int root : roots) instances = saturating_add(instances, count_instances(root, 0));
    if (instances > kMaxNodeVisits)
      throw InputError(
          fmt::format("{}: node graph expands to more than {} node instances", file_, kMaxNodeVisits));
    for (int root : roots) visit(root, glm::dmat4(1.0), 0);
  }

  void finish() { emitter_.finish(); }

 private:
  std::vector<int> root_nodes() const {
    if (!model_.scenes.empty()) {
      // Scene 0 stands in only when the file names none; a named scene that does not exist is an error,
      // not a reason to render another one.
      if (static_cast<std::size_t>(std::max(model_.defaultScene, 0)) >= model_.scenes.size())
        throw InputError(fmt::format("{}: scene {} does not exist ({} scenes)", file_, model_.defaultScene,
                                     model_.scenes.size()));
      return model_.scenes[static_cast<std::size_t>(std::max(model_.defaultScene, 0))].nodes;
    }
    std::vector<bool> is_child(model_.nodes.size(), false);
    for (const auto& n : model_.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<std::size_t>(c) < is_child.size())
          is_child[static_cast<std::size_t>(c)] = true;
    std::vector<int> roots;
    for (std::size_t i = 0; i < is_child.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
    return roots;
  }

  void visit(int index, const glm::dmat4& parent, int depth) {
    check_node(index, depth);
    const auto i = static_cast<std::size_t>(index);
    const tinygltf::Node& node = model_.nodes[i];
    check_transform(node, index, file_);
    const glm::dmat4 world = parent * local_transform(node);
    if (!is_finite(world))
      throw InputError(fmt::format("{}: node {} world transform overflows (not finite)", file_, index));
    if (node.mesh >= 0) {
      // Legal (a scale of 0 hides a node) but the mesh then renders as nothing; worth a line.
      if (glm::determinant(glm::dmat3(world)) == 0.0)
        scene_.warnings.push_back(
            fmt::format("{}: node {} has a singular transform; its mesh collapses to nothing", file_, index));
      emitter_.emit_mesh(node.mesh, world);
    }
    if (node.camera >= 0 && !scene_.camera) take_camera(node.camera, world);
    take_light(node, world);
    on_path_[i] = true;
    for (int child : node.children) visit(child, world, depth + 1);
    on_path_[i] = false;
  }

  static std::size_t saturating_add(std::size_t a, std::size_t b) {
    return std::min(a + b, kMaxNodeVisits + 1);  // both operands are at most kMaxNodeVisits + 1
  }

  // Instances of the subtree at index when expanded as visit() walks it (saturated past the limit),
  // memoised per node; checks the node, cycles and depth on the way, as visit() does. walk() visits
  // only a graph whose count is within the limit, so visit() needs no count of its own.
  std::size_t count_instances(int index, int depth) {
    check_node(index, depth);
    const auto i = static_cast<std::size_t>(index);
    if (instances_below_[i] != 0) return instances_below_[i];
    std::size_t count = 1;
    on_path_[i] = true;
    for (int child : model_.nodes[i].children) count = saturating_add(count, count_instances(child, depth + 1));
    on_path_[i] = false;
    instances_below_[i] = count;
    return count;
  }

  void check_node(int index, int depth) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
      throw InputError(
          fmt::format("{}: node {} does not exist ({} nodes)", file_, index, model_.nodes.size()));
    if (on_path_[static_cast<std::size_t>(index)])
      throw InputError(fmt::format("{}: node {} is its own ancestor (cyclic node graph)", file_, index));
    if (depth > kMaxDepth)
      throw InputError(fmt::format("{}: node hierarchy deeper than {} levels", file_, kMaxDepth));
  }

  void take_camera(int index, const glm::dmat4& world) {
    if (static_cast<std::size_t>(index) >= model_.cameras.size())
      throw InputError(
          fmt::format("{}: camera {} does not exist ({} cameras)", file_, index, model_.cameras.size()));
    const tinygltf::Camera& c = model_.cameras[static_cast<std::size_t>(index)];
    if (c.type != "perspective") {
      scene_.warnings.push_back(fmt::format("{}: {} camera {} ignored", file_, c.type, index));
      return;
    }
    // glTF cameras look down their local -Z with +Y up.
    const glm::dvec3 eye(world * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 forward(world * glm::dvec4(0, 0, -1, 0));
    const glm::dvec3 up(world * glm::dvec4(0, 1, 0, 0));
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0.0 && yfov < glm::pi<double>()) || !usable_direction(forward) || !usable_direction(up)) {
      scene_.warnings.push_back(
          fmt::format("{}: camera {} ignored: degenerate transform or yfov {}", file_, index, yfov));
      return;
    }
    scene_.camera = SceneCamera{.eye = glm::vec3(eye),
                                .target = glm::vec3(eye + glm::normalize(forward)),
                                .up = glm::vec3(glm::normalize(up)),
                                .vfov_degrees = static_cast<float>(glm::degrees(yfov))};
  }

  // KHR_lights_punctual: {"extensions": {"KHR_lights_punctual": {"light": index}}} on the node;
  // the light sits at the node's origin and a spot shines down its local -Z.
  void take_light(const tinygltf::Node& node, const glm::dmat4& world) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end() || !ext->second.Has("light")) return;
    const tinygltf::Value& index_value = ext->second.Get("light");
    const int index = index_value.IsInt() ? index_value.GetNumberAsInt() : -1;
    if (index < 0 || static_cast<std::size_t>(index) >= model_.lights.size())
      throw InputError(fmt::format("{}: KHR_lights_punctual light {} does not exist ({} lights)", file_, index,
                                   model_.lights.size()));
    const tinygltf::Light& l = model_.lights[static_cast<std::size_t>(index)];
    SceneLight light;
    light.name = l.name;
    if (l.type == "spot") {
      light.type = SceneLight::Type::spot;
    } else if (l.type != "point") {
      scene_.warnings.push_back(fmt::format("{}: {} light {} ignored (only point and spot)", file_, l.type, index));
      return;
    }
    glm::dvec3 color(1.0);
    if (l.color.size() == 3) color = glm::dvec3(l.color[0], l.color[1], l.color[2]);
    const glm::dvec3 intensity = color * l.intensity;
    const glm::dvec3 position(world * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 direction(world * glm::dvec4(0, 0, -1, 0));
    const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
    const bool cone_ok = !(light.type == SceneLight::Type::spot) ||
                         (inner >= 0.0 && inner < outer && outer <= glm::half_pi<double>());
    if (!std::isfinite(position.x + position.y + position.z) || !usable_direction(direction) ||
        !(intensity.x >= 0.0 && intensity.y >= 0.0 && intensity.z >= 0.0) ||
        !std::isfinite(intensity.x + intensity.y + intensity.z) || !cone_ok)
      throw InputError(fmt::format("{}: KHR_lights_punctual light {} has a non-finite or negative intensity, a "
                                   "degenerate transform or cone angles outside 0 <= inner < outer <= pi/2",
                                   file_, index));
    if (l.range > 0.0)
      scene_.warnings.push_back(fmt::format("{}: light {}: range {} ignored (inverse-square falloff everywhere)",
                                            file_, index, l.range));
    light.position = glm::vec3(position);
    light.direction = glm::vec3(glm::normalize(direction));
    light.intensity = glm::vec3(intensity);
    light.inner_cone = static_cast<float>(inner);
    light.outer_cone = static_cast<float>(outer);
    scene_.lights.push_back(light);
  }

  const tinygltf::Model& model_;
  const std::string& file_;
  Scene& scene_;
  SceneBuilder builder_;
  PrimitiveEmitter emitter_;
  std::vector<bool> on_path_;
  std::vector<std::size_t> instances_below_;  // 0 until counted
};

}  // namespace

void emit_default_scene(const tinygltf::Model& model, const std::string& file, Scene& scene) {
  NodeWalker walker(model, file, scene);
  walker.walk();
  walker.finish();
}

}  // namespace cohort::gltf
