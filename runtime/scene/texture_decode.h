// Decodes an encoded image (PNG, JPEG, TGA, BMP...) into an 8-bit RGBA Texture.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "runtime/scene/scene.h"

namespace cohort {

// std::nullopt with *error set when the bytes are not a decodable image.
std::optional<Texture> decode_texture(std::string name, const unsigned char* bytes, std::size_t size,
                                      std::string* error);

}  // namespace cohort
