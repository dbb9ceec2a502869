// Strict reading of the numbers in an OBJ file, done before tinyobjloader parses it: its number
// parser reads the longest prefix that looks like a number ("1.5abc" as 1.5, "nan" as 0) and its
// index parser wraps on overflow, so a malformed file would load as some other scene. Checking the
// text first keeps the library unforked.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace cohort::obj {

// A coordinate the strict parse reads as NaN or infinite (tinyobjloader reads those as 0).
struct NonFiniteValue {
  std::size_t index;  // into tinyobjloader's flat attribute array (3 per `v`, 2 per `vt`)
  float value;
};

struct TextCheck {
  std::size_t vertex_lines = 0;    // `v` statements
  std::size_t texcoord_lines = 0;  // `vt` statements
  std::vector<NonFiniteValue> non_finite_vertices;
  std::vector<NonFiniteValue> non_finite_texcoords;
};

// Throws InputError naming `file` and the line when a `v`, `vt` or `vn` statement holds a token that is
// not wholly a number (or too few numbers), or an `f` statement holds an index that is not an integer,
// is 0 or does not fit in an int.
TextCheck check_obj_text(std::string_view text, const std::string& file);

// The same for a material library: Kd, Ke, Ka and Ks take 1 or 3 finite numbers, d, Tr, Ns and Ni one.
// Returns the text for tinyobjloader, with a one-number colour ("Kd 0.5", grey) spelled out as three,
// since it would read the missing two as 0.
std::string checked_mtl_text(std::string_view text, const std::string& file);

}  // namespace cohort::obj
