#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "runtime/scene/gltf_materials.h"
#include "runtime/scene/gltf_nodes.h"
#include "runtime/scene/gltf_unhonoured.h"
#include "runtime/scene/library_message.h"
#include "runtime/scene/loaders.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"

// Keeps external images encoded so that only those materials use get decoded, later. tinygltf passes
// buffer-view images without checking the view's range, so those bytes are not touched here.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

std::uint32_t u32_at(const std::string& bytes, std::size_t offset) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

// tinygltf trusts the BIN chunk header by 8 bytes too many; checking every chunk here first
// keeps a truncated or lying .glb from being read past its end.
void check_glb_chunks(const std::string& bytes, const std::string& file) {
  if (bytes.size() < 20 || u32_at(bytes, 0) != kGlbMagic)
    throw InputError(fmt::format("{}: not a binary glTF (bad header)", file));
  if (u32_at(bytes, 4) != 2)
    throw InputError(fmt::format("{}: binary glTF version {} (only 2 is supported)", file, u32_at(bytes, 4)));
  const std::uint64_t length = u32_at(bytes, 8);
  if (length > bytes.size())
    throw InputError(fmt::format("{}: truncated binary glTF: header says {} bytes, file has {}", file, length,
                                 bytes.size()));
  for (std::uint64_t at = 12; at < length;) {
    if (length - at < 8) throw InputError(fmt::format("{}: truncated chunk header at byte {}", file, at));
    const std::uint64_t chunk = u32_at(bytes, static_cast<std::size_t>(at));
    if (chunk > length - at - 8)
      throw InputError(fmt::format("{}: chunk at byte {} ({} bytes) runs past the end", file, at, chunk));
    at += 8 + chunk;
  }
}

// tinygltf turns extras and extensions into its own Value type recursively, so a deeply nested JSON
// document overflows the stack; no glTF needs more than a few dozen levels.
constexpr int kMaxJsonDepth = 512;

void check_json_depth(std::string_view json, const std::string& file) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(fmt::format("{}: JSON nested deeper than {} levels", file, kMaxJsonDepth));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void add_warnings(const std::string& text, const std::string& file, Scene& scene) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) scene.warnings.push_back(fmt::format("{}: {}", file, library_message(line)));
}

// "MAJOR.MINOR" as asset.version and asset.minVersion spell it, or nullopt for anything else.
std::optional<std::pair<int, int>> version_numbers(const std::string& text) {
  const std::size_t dot = text.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == text.size()) return std::nullopt;
  int major = 0, minor = 0;
  const char* end = text.data() + text.size();
  const auto a = std::from_chars(text.data(), text.data() + dot, major);
  const auto b = std::from_chars(text.data() + dot + 1, end, minor);
  const bool whole = a.ec == std::errc{} && a.ptr == text.data() + dot && b.ec == std::errc{} && b.ptr == end;
  if (!whole || major < 0 || minor < 0) return std::nullopt;
  return std::pair{major, minor};
}

// glTF 2.x readers must load any 2.x file (minor versions stay compatible) unless minVersion asks
// for more than they implement (2.0 here); a 1.0 file has another schema altogether.
void check_version(const tinygltf::Asset& asset, const std::string& file) {
  const auto version = version_numbers(asset.version);
  if (!version || version->first != 2)
    throw InputError(fmt::format("{}: glTF asset.version '{}' is not supported (only 2.x)", file, asset.version));
  if (asset.minVersion.empty()) return;
  const auto min = version_numbers(asset.minVersion);
  if (!min || *min > std::pair{2, 0})
    throw InputError(
        fmt::format("{}: glTF asset.minVersion '{}' is newer than this loader (2.0)", file, asset.minVersion));
}

// A required extension changes what the file means, so loading without it would render some other
// scene: an error. Optional ones the file still renders without, as the specification allows; what
// they and the rest of the file ask for beyond the loader is named by report_unhonoured.
void check_required_extensions(const tinygltf::Model& model, const std::string& file) {
  for (const std::string& name : model.extensionsRequired)
    if (!gltf::extension_implemented(name))
      throw InputError(fmt::format("{}: requires glTF extension {}, which this loader does not implement", file,
                                   library_message(name)));
}

tinygltf::Model parse(const std::filesystem::path& path, const std::string& bytes, bool binary,
                      Scene& scene) {
  const std::string file = path.string();
  if (bytes.size() > std::numeric_limits<unsigned int>::max())
    throw InputError(fmt::format("{}: glTF larger than 4 GiB", file));
  if (binary) {
    check_glb_chunks(bytes, file);
    check_json_depth(std::string_view(bytes).substr(20, u32_at(bytes, 12)), file);
  } else {
    check_json_depth(bytes, file);
  }
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base_dir = path.parent_path().string();
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(
                   &model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()), size, base_dir)
             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), size, base_dir);
  if (!ok) throw InputError(fmt::format("{}: invalid glTF: {}", file, library_message(err)));
  add_warnings(warn, file, scene);
  check_version(model.asset, file);
  check_required_extensions(model, file);
  return model;
}

}  // namespace

Scene load_gltf(const std::filesystem::path& path, const std::string& bytes, bool binary) {
  Scene scene;
  // Content wins over the name: a .gltf that holds binary glTF still loads.
  const bool glb = binary || bytes.compare(0, 4, "glTF") == 0;
  const tinygltf::Model model = parse(path, bytes, glb, scene);
  gltf::convert_materials(model, path.string(), scene);
  gltf::report_unhonoured(model, path.string(), scene);
  gltf::emit_default_scene(model, path.string(), scene);
  gltf::report_missing_coordinates(path.string(), scene);
  return scene;
}

}  // namespace cohort
