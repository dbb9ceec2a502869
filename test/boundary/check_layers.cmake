# The include rule between the folders of ROOT/runtime (docs/design.md, "Where the code lives"): a
# folder includes "runtime/<folder>/..." only from the folders below it, so the dependencies run one
# way: util at the bottom; scene, image and backend on it; accel on scene; cl, cuda and sort on
# backend; render on accel, backend, image, scene and sort (never on cl or cuda: the backend
# boundary, check_includes.cmake); mpi and bench on render; cli on everything but cl and cuda; peers
# on bench; main.cpp on cli. runtime/backend/open_device.cpp, the one file that chooses a backend,
# may include cl and cuda. A folder the rule does not place is reported too.
#   cmake -DROOT=<source tree> -P check_layers.cmake   (exit code 1 and one line per leak)
cmake_minimum_required(VERSION 3.20)  # IN_LIST
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -P check_layers.cmake")
endif()
get_filename_component(ROOT "${ROOT}" ABSOLUTE)

# what each folder may include besides itself
set(below_util "")
set(below_scene util)
set(below_image util)
set(below_backend util)
set(below_cl backend util)
set(below_cuda backend util)
set(below_accel scene util)
set(below_sort backend util)
set(below_render accel backend image scene sort util)
set(below_mpi render ${below_render})
set(below_bench render ${below_render})
set(below_cli bench mpi render ${below_render})
set(below_peers bench render ${below_render})
set(below_main cli)
set(chooser runtime/backend/open_device.cpp)
set(below_chooser cl cuda ${below_backend})

# the layer of a file: its folder's, the chooser's, or main's for a file directly in runtime/
function(layer_of f out)
  if(f STREQUAL chooser)
    set(${out} chooser PARENT_SCOPE)
  elseif(f MATCHES "^runtime/([^/]+)/")
    set(${out} ${CMAKE_MATCH_1} PARENT_SCOPE)
  else()
    set(${out} main PARENT_SCOPE)
  endif()
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/includes_of.cmake)
runtime_includes(${ROOT} files includes)
set(leaks "")
set(checked 0)
foreach(f IN LISTS files)
  layer_of(${f} folder)
  if(DEFINED below_${folder})
    math(EXPR checked "${checked} + 1")
  else()
    string(APPEND leaks "  ${f}: runtime/${folder}/ has no place in the layers (add it to check_layers.cmake)\n")
  endif()
endforeach()
foreach(entry IN LISTS includes)
  if(NOT entry MATCHES "^([^:]+):([0-9]+):(runtime/([^/]+)/.*)$")
    continue()
  endif()
  set(f ${CMAKE_MATCH_1})
  set(number ${CMAKE_MATCH_2})
  set(header ${CMAKE_MATCH_3})
  set(target ${CMAKE_MATCH_4})
  layer_of(${f} folder)
  if(DEFINED below_${folder} AND NOT f MATCHES "^runtime/${target}/" AND NOT target IN_LIST below_${folder})
    string(APPEND leaks "  ${f}:${number}: includes <${header}>\n")
  endif()
endforeach()

report_leaks(${checked} "${leaks}" "includes against the layers (docs/design.md, \"Where the code lives\")"
             "layers: ${checked} files under runtime/ include only the folders below their own")
