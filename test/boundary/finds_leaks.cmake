# check_includes.cmake on leaky_tree/: it must fail, name each leaking include with its file and
# line, and pass over each backend's own headers, the chooser and look-alikes.
#   cmake -DCHECK=<check_includes.cmake> -DTREE=<leaky_tree> -P finds_leaks.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${TREE} -P ${CHECK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "the check passed a tree with leaks:\n${out}")
endif()
foreach(leak "render/leak.cpp:3: includes <CL/opencl.hpp>" "render/leak.cpp:4: includes <runtime/cl/context.h>"
             "render/leak.cpp:5: includes <cuda.h>" "render/leak.cpp:6: includes <runtime/cuda/cuda_api.h>"
             "cuda/device.cpp:4: includes <CL/cl.h>" "cuda/device.cpp:5: includes <runtime/cl/devices.h>"
             "cl/context.cpp:4: includes <nvrtc.h>")
  string(FIND "${out}" "runtime/${leak}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the check missed runtime/${leak}:\n${out}")
  endif()
endforeach()
foreach(allowed "leak.cpp:2:" "quiet.cpp" "device.cpp:2:" "device.cpp:3:" "context.cpp:2:" "context.cpp:3:"
                "open_device.cpp")
  string(FIND "${out}" "${allowed}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the check reported ${allowed}, which is allowed:\n${out}")
  endif()
endforeach()
