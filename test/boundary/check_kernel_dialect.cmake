# Fails when a device source under ROOT/kernels uses what NVIDIA's OpenCL C 1.2 compiler rejects
# although PoCL accepts it: variadic macros (`...` / __VA_ARGS__ in a #define). Run with
# cmake -DROOT=<source dir> -P check_kernel_dialect.cmake.
file(GLOB_RECURSE sources ${ROOT}/kernels/*.h ${ROOT}/kernels/*.cl)
set(bad "")
foreach(f IN LISTS sources)
  file(STRINGS ${f} lines REGEX "#[ \t]*define.*(\\.\\.\\.|__VA_ARGS__)")
  foreach(line IN LISTS lines)
    string(APPEND bad "\n  ${f}: ${line}")
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "variadic macros in device code (NVIDIA's OpenCL compiler rejects them):${bad}")
endif()
