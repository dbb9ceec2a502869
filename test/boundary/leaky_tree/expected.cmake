# What check_includes.cmake must report on this tree (finds_leaks.cmake), and what it must pass over:
# each backend's own headers, the chooser and look-alikes.
set(leaks "render/leak.cpp:3: includes <CL/opencl.hpp>" "render/leak.cpp:4: includes <runtime/cl/context.h>"
          "render/leak.cpp:5: includes <cuda.h>" "render/leak.cpp:6: includes <runtime/cuda/cuda_api.h>"
          "cuda/device.cpp:4: includes <CL/cl.h>" "cuda/device.cpp:5: includes <runtime/cl/devices.h>"
          "cl/context.cpp:4: includes <nvrtc.h>")
set(allowed "leak.cpp:2:" "quiet.cpp" "device.cpp:2:" "device.cpp:3:" "context.cpp:2:" "context.cpp:3:"
            "open_device.cpp")
