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
  bool sorts;      // sorts the rays of later bounces before tracing them (hash, pth)
  std::unique_ptr<PassLauncher> (*set_up)(const MethodInputs&);
};

const std::vector<Method>& methods();
std::vector<std::string> method_names();
const Method& find_method(const std::string& name);  // throws InputError for an unknown name

// What `auto` renders where a render is too short to probe: the method measured fastest on that
// kind of device (docs/results.md): the megakernel on a CPU (per CPU second on every bench scene),
// sc+rg on a GPU (within 1 % of the fastest on the H200).
const char* device_default_method(bool is_gpu);

}  // namespace cohort
