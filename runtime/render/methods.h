// The rendering methods by name (`--method`): each is one file under runtime/render/methods.
#pragma once

#include <string>
#include <vector>

#include "runtime/render/methods/method.h"

namespace cohort {

struct Method {
  const char* name;
  const char* description;
  bool wavefront;  // traces from a pool of path slots, one launch per stage (false: the megakernel)
  std::unique_ptr<PassLauncher> (*set_up)(const MethodInputs&);
};

const std::vector<Method>& methods();
std::vector<std::string> method_names();
const Method& find_method(const std::string& name);  // throws InputError for an unknown name

}  // namespace cohort
