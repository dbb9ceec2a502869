# The backend boundary (runtime/backend/device.h): under ROOT/runtime, OpenCL headers are included
# only in runtime/cl and CUDA headers only in runtime/cuda; everything else sees Device and
# DeviceInfo. The one file that chooses a backend, runtime/backend/open_device.cpp, may include both.
#   cmake -DROOT=<source tree> -P check_includes.cmake   (exit code 1 and one line per leak)
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -P check_includes.cmake")
endif()
get_filename_component(ROOT "${ROOT}" ABSOLUTE)

# include paths that belong to each backend: its API's headers and the backend's own files
set(opencl_headers "^(CL|OpenCL)/" "(^|/)(cl|cl2|opencl)\\.(h|hpp)$" "^runtime/cl/")
set(cuda_headers "^(cuda|cuda_runtime|cuda_runtime_api|cudaTypedefs|nvrtc)\\.h$" "^runtime/cuda/")
set(chooser runtime/backend/open_device.cpp)

include(${CMAKE_CURRENT_LIST_DIR}/includes_of.cmake)
runtime_includes(${ROOT} files includes)
list(REMOVE_ITEM files ${chooser})
list(LENGTH files checked)
set(leaks "")
foreach(entry IN LISTS includes)
  string(REGEX MATCH "^([^:]+):([0-9]+):(.*)$" _ "${entry}")
  set(f ${CMAKE_MATCH_1})
  set(number ${CMAKE_MATCH_2})
  set(header ${CMAKE_MATCH_3})
  set(forbidden "")
  if(f STREQUAL chooser)
    continue()
  endif()
  if(NOT f MATCHES "^runtime/cl/")
    list(APPEND forbidden ${opencl_headers})
  endif()
  if(NOT f MATCHES "^runtime/cuda/")
    list(APPEND forbidden ${cuda_headers})
  endif()
  foreach(pattern IN LISTS forbidden)
    if(header MATCHES "${pattern}")
      string(APPEND leaks "  ${f}:${number}: includes <${header}>\n")
      break()
    endif()
  endforeach()
endforeach()

report_leaks(${checked} "${leaks}"
             "backend headers outside their backend (OpenCL: runtime/cl, CUDA: runtime/cuda; elsewhere use runtime/backend/device.h)"
             "backend boundary: ${checked} files under runtime/ include no other backend's headers")
