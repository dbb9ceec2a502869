# check_includes.cmake on leaky_tree/: it must fail, name each leaking include of
# runtime/render/leak.cpp with its line, and pass over the backends, the chooser and look-alikes.
#   cmake -DCHECK=<check_includes.cmake> -DTREE=<leaky_tree> -P finds_leaks.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${TREE} -P ${CHECK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "the check passed a tree with leaks:\n${out}")
endif()
foreach(leak "leak.cpp:3: includes <CL/opencl.hpp>" "leak.cpp:4: includes <runtime/cl/context.h>"
             "leak.cpp:5: includes <cuda.h>" "leak.cpp:6: includes <runtime/cuda/cuda_api.h>")
  string(FIND "${out}" "runtime/render/${leak}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the check missed runtime/render/${leak}:\n${out}")
  endif()
endforeach()
foreach(allowed "leak.cpp:2:" "quiet.cpp" "runtime/cl/context.cpp" "open_device.cpp")
  string(FIND "${out}" "${allowed}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the check reported ${allowed}, which is allowed:\n${out}")
  endif()
endforeach()
