# What check_layers.cmake must report on this tree (finds_leaks.cmake), and what it must pass over:
# a folder's own and lower folders, the chooser, comments and look-alikes.
set(leaks "render/leak.cpp:3: includes <runtime/cli/commands.h>" "render/leak.cpp:4: includes <runtime/bench/figures.h>"
          "render/leak.cpp:5: includes <runtime/mpi/mpi_team.h>" "cli/cli.cpp:4: includes <runtime/cl/context.h>"
          "newfolder/thing.cpp: runtime/newfolder/ has no place")
set(allowed "leak.cpp:2:" "leak.cpp:6:" "leak.cpp:7:" "quiet.cpp" "open_device.cpp" "cli.cpp:2:" "cli.cpp:3:")
