// Wavefront .mtl handling for the OBJ loader: reading the libraries an OBJ names and converting
// their materials (Kd, Ke, d, map_Kd) to SceneMaterial.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "runtime/scene/scene.h"

namespace cohort::obj {

// Reads each `mtllib` from the OBJ's folder (ignoring letter case, plain or .gz). A missing library
// is a warning, not an error: its materials fall back to the default.
class MaterialLibraries : public tinyobj::MaterialReader {
 public:
  MaterialLibraries(const std::filesystem::path& obj_path, Scene& scene)
      : obj_path_(obj_path), scene_(scene) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warn, std::string* err) override;

 private:
  const std::filesystem::path& obj_path_;
  Scene& scene_;
};

// Appends the materials in order (OBJ material i is scene material i) and decodes their map_Kd.
void convert_materials(const std::vector<tinyobj::material_t>& materials,
                       const std::filesystem::path& obj_path, Scene& scene);

}  // namespace cohort::obj
