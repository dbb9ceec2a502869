// Error types that main() turns into exit codes: InputError -> 2 (bad usage or input), anything else -> 1.
#pragma once

#include <stdexcept>
#include <string>

namespace cohort {

// Bad input or usage: the message names the file (or option) and what is wrong.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace cohort
