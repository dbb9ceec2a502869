# The backend boundary (runtime/backend/device.h): under ROOT/runtime, only runtime/cl includes OpenCL
# headers and only runtime/cuda includes CUDA's; everything else sees Device and DeviceInfo. The one
# file that chooses a backend, runtime/backend/open_device.cpp, may include both backends' headers.
#   cmake -DROOT=<source tree> -P check_includes.cmake   (exit code 1 and one line per leak)
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source tree> -P check_includes.cmake")
endif()

# include paths that belong to a backend: the OpenCL and CUDA headers, and the backends' own files
set(backend_headers
    "^(CL|OpenCL)/"
    "(^|/)(cl|cl2|opencl)\\.(h|hpp)$"
    "^(cuda|cuda_runtime|cuda_runtime_api|cudaTypedefs|nvrtc)\\.h$"
    "^runtime/(cl|cuda)/")
set(chooser runtime/backend/open_device.cpp)
get_filename_component(ROOT "${ROOT}" ABSOLUTE)

file(GLOB_RECURSE files RELATIVE ${ROOT} ${ROOT}/runtime/*.h ${ROOT}/runtime/*.hpp ${ROOT}/runtime/*.cpp
     ${ROOT}/runtime/*.in)
list(SORT files)
set(leaks "")
set(checked 0)
foreach(f IN LISTS files)
  if(f MATCHES "^runtime/(cl|cuda)/" OR f STREQUAL chooser)
    continue()
  endif()
  math(EXPR checked "${checked} + 1")
  # one list element per line: brackets and semicolons would join or split elements
  file(READ ${ROOT}/${f} text)
  string(REGEX REPLACE "[][;]" "_" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"]")
      set(header ${CMAKE_MATCH_1})
      foreach(pattern IN LISTS backend_headers)
        if(header MATCHES "${pattern}")
          string(APPEND leaks "  ${f}:${number}: includes <${header}>\n")
          break()
        endif()
      endforeach()
    endif()
  endforeach()
endforeach()

if(checked EQUAL 0)
  message(FATAL_ERROR "no source files under ${ROOT}/runtime")
endif()
if(NOT leaks STREQUAL "")
  message(FATAL_ERROR "backend headers outside runtime/cl and runtime/cuda (use runtime/backend/device.h):\n${leaks}")
endif()
message(STATUS "backend boundary: ${checked} files under runtime/ include no OpenCL or CUDA header")
