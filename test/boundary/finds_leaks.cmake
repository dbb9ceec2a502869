# An include check (CHECK: check_includes.cmake or check_layers.cmake) on a tree made to leak
# (TREE: leaky_tree/, layered_tree/): it must fail, name each leak the tree's expected.cmake lists
# (`leaks`, under runtime/) with its file and line, and nothing it lists as `allowed`.
#   cmake -DCHECK=<check script> -DTREE=<tree> -P finds_leaks.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${TREE} -P ${CHECK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "the check passed a tree with leaks:\n${out}")
endif()
include(${TREE}/expected.cmake)
foreach(leak IN LISTS leaks)
  string(FIND "${out}" "runtime/${leak}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the check missed runtime/${leak}:\n${out}")
  endif()
endforeach()
foreach(pass IN LISTS allowed)
  string(FIND "${out}" "${pass}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the check reported ${pass}, which is allowed:\n${out}")
  endif()
endforeach()
