// Helpers shared by the scene tests: locations, temporary folders, file writers, a small glTF
// writer and an InputError expectation.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "runtime/scene/scene.h"

namespace cohort::test {

std::filesystem::path source_dir();
std::filesystem::path shared_scenes();

// A fresh folder under the system temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

void write_file(const std::filesystem::path& path, const std::string& bytes);
void write_gzip(const std::filesystem::path& path, const std::string& bytes);
std::string read_file(const std::filesystem::path& path);

// Expects load_scene(path) to throw InputError whose message names the file and contains `what`.
void expect_input_error(const std::filesystem::path& path, const std::string& what = "");

glm::vec3 triangle_normal(const Scene& scene, std::size_t triangle);  // normalised, CCW front

// Builds glTF files with one binary buffer, written as .gltf + .bin or as .glb.
class GltfWriter {
 public:
  GltfWriter();

  // Appends bytes (4-byte aligned) as a buffer view; returns the view index.
  int view(const void* data, std::size_t bytes, std::size_t stride = 0);
  int accessor(int view, int component_type, std::size_t count, const std::string& type,
               std::size_t byte_offset = 0);
  int positions(const std::vector<glm::vec3>& points);
  int indices(const std::vector<std::uint8_t>& values);
  int indices(const std::vector<std::uint16_t>& values);
  int indices(const std::vector<std::uint32_t>& values);
  // A mesh of one primitive; index_accessor < 0 means non-indexed.
  int mesh(int position_accessor, int index_accessor = -1, int material = -1, int mode = 4,
           const std::string& name = "mesh");
  int node(const nlohmann::json& node);
  int material(const nlohmann::json& material);
  void roots(const std::vector<int>& nodes);

  nlohmann::json& doc() { return doc_; }
  std::filesystem::path write_gltf(const std::filesystem::path& dir, const std::string& stem);
  std::filesystem::path write_glb(const std::filesystem::path& dir, const std::string& stem);
  std::string glb_bytes();

 private:
  template <typename T>
  int typed_indices(const std::vector<T>& values, int component_type);
  int append(nlohmann::json& array, const nlohmann::json& item);

  nlohmann::json doc_;
  std::vector<unsigned char> bin_;
};

}  // namespace cohort::test

// Skips the calling test when the external models (scenes/external.json) are not there.
#define COHORT_REQUIRE_SHARED()                                                         \
  do {                                                                                  \
    if (!std::filesystem::is_directory(::cohort::test::shared_scenes()))                \
      GTEST_SKIP() << "shared scenes not found at " << ::cohort::test::shared_scenes(); \
  } while (0)
