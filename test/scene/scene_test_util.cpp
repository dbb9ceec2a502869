#include "scene_test_util.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>

#include <fmt/format.h>
#include <zlib.h>

#include "runtime/util/error.h"

namespace cohort::test {

std::filesystem::path source_dir() { return COHORT_SOURCE_DIR; }
std::filesystem::path shared_scenes() { return COHORT_SHARED_SCENES; }

TempDir::TempDir() {
  std::random_device rd;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info ? fmt::format("{}-{}", info->test_suite_name(), info->name()) : "scene";
  std::replace(test.begin(), test.end(), '/', '-');  // a parameterised test's name: one folder, not nested ones
  path_ = std::filesystem::temp_directory_path() / fmt::format("cohort-{}-{:08x}", test, rd());
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

void write_gzip(const std::filesystem::path& path, const std::string& bytes) {
  gzFile f = gzopen(path.c_str(), "wb9");
  ASSERT_NE(f, nullptr) << path;
  ASSERT_EQ(gzwrite(f, bytes.data(), static_cast<unsigned>(bytes.size())), static_cast<int>(bytes.size()));
  ASSERT_EQ(gzclose(f), Z_OK);
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_input_error(const std::filesystem::path& path, const std::string& what) {
  try {
    const Scene scene = load_scene(path);
    ADD_FAILURE() << path << " loaded (" << scene.triangle_count() << " triangles) but should not";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << "expected '" << what << "' in: " << message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << " threw a non-InputError: " << e.what();
  }
}

glm::vec3 triangle_normal(const Scene& scene, std::size_t t) {
  const glm::vec3* p = &scene.positions[3 * t];
  return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
}

GltfWriter::GltfWriter() {
  doc_ = {{"asset", {{"version", "2.0"}}},
          {"accessors", nlohmann::json::array()},
          {"bufferViews", nlohmann::json::array()},
          {"meshes", nlohmann::json::array()},
          {"nodes", nlohmann::json::array()}};
}

int GltfWriter::append(nlohmann::json& array, const nlohmann::json& item) {
  array.push_back(item);
  return static_cast<int>(array.size() - 1);
}

int GltfWriter::view(const void* data, std::size_t bytes, std::size_t stride) {
  while (bin_.size() % 4) bin_.push_back(0);
  nlohmann::json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
  if (stride) v["byteStride"] = stride;
  const auto* p = static_cast<const unsigned char*>(data);
  bin_.insert(bin_.end(), p, p + bytes);
  return append(doc_["bufferViews"], v);
}

int GltfWriter::accessor(int view, int component_type, std::size_t count, const std::string& type,
                         std::size_t byte_offset) {
  nlohmann::json a = {
      {"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
  if (byte_offset) a["byteOffset"] = byte_offset;
  return append(doc_["accessors"], a);
}

int GltfWriter::positions(const std::vector<glm::vec3>& points) {
  return accessor(view(points.data(), points.size() * sizeof(glm::vec3)), 5126, points.size(), "VEC3");
}

template <typename T>
int GltfWriter::typed_indices(const std::vector<T>& values, int component_type) {
  return accessor(view(values.data(), values.size() * sizeof(T)), component_type, values.size(), "SCALAR");
}

int GltfWriter::indices(const std::vector<std::uint8_t>& v) { return typed_indices(v, 5121); }
int GltfWriter::indices(const std::vector<std::uint16_t>& v) { return typed_indices(v, 5123); }
int GltfWriter::indices(const std::vector<std::uint32_t>& v) { return typed_indices(v, 5125); }

int GltfWriter::mesh(int position_accessor, int index_accessor, int material, int mode,
                     const std::string& name) {
  nlohmann::json p = {{"attributes", {{"POSITION", position_accessor}}}, {"mode", mode}};
  if (index_accessor >= 0) p["indices"] = index_accessor;
  if (material >= 0) p["material"] = material;
  return append(doc_["meshes"], {{"name", name}, {"primitives", {p}}});
}

int GltfWriter::node(const nlohmann::json& node) { return append(doc_["nodes"], node); }

int GltfWriter::material(const nlohmann::json& material) {
  if (!doc_.contains("materials")) doc_["materials"] = nlohmann::json::array();
  return append(doc_["materials"], material);
}

void GltfWriter::roots(const std::vector<int>& nodes) {
  doc_["scenes"] = {{{"nodes", nodes}}};
  doc_["scene"] = 0;
}

std::filesystem::path GltfWriter::write_gltf(const std::filesystem::path& dir, const std::string& stem) {
  nlohmann::json doc = doc_;
  doc["buffers"] = {{{"byteLength", bin_.size()}, {"uri", stem + ".bin"}}};
  write_file(dir / (stem + ".bin"), std::string(bin_.begin(), bin_.end()));
  write_file(dir / (stem + ".gltf"), doc.dump(1));
  return dir / (stem + ".gltf");
}

std::string GltfWriter::glb_bytes() {
  nlohmann::json doc = doc_;
  doc["buffers"] = {{{"byteLength", bin_.size()}}};
  std::string json = doc.dump();
  while (json.size() % 4) json += ' ';
  std::string bin(bin_.begin(), bin_.end());
  while (bin.size() % 4) bin += '\0';
  auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const auto total = static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size());
  return "glTF" + u32(2) + u32(total) + u32(static_cast<std::uint32_t>(json.size())) + u32(0x4E4F534A) +
         json + u32(static_cast<std::uint32_t>(bin.size())) + u32(0x004E4942) + bin;
}

std::filesystem::path GltfWriter::write_glb(const std::filesystem::path& dir, const std::string& stem) {
  write_file(dir / (stem + ".glb"), glb_bytes());
  return dir / (stem + ".glb");
}

}  // namespace cohort::test
