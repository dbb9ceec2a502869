# What the include checks (check_includes.cmake, check_layers.cmake) read of a source tree, and how
# they report.

# runtime_includes(ROOT FILES INCLUDES): every source file under ROOT/runtime (relative to ROOT,
# sorted) into FILES, and every include they hold into INCLUDES as "FILE:LINE:HEADER" entries
# (commented-out lines are not includes).
function(runtime_includes root files_out includes_out)
  file(GLOB_RECURSE files RELATIVE ${root} ${root}/runtime/*.h ${root}/runtime/*.hpp ${root}/runtime/*.cpp
       ${root}/runtime/*.in)
  list(SORT files)
  set(found "")
  foreach(f IN LISTS files)
    # one list element per line: brackets and semicolons would join or split elements
    file(READ ${root}/${f} text)
    string(REGEX REPLACE "[][;]" "_" text "${text}")
    string(REPLACE "\n" ";" lines "${text}")
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"]")
        list(APPEND found "${f}:${number}:${CMAKE_MATCH_1}")
      endif()
    endforeach()
  endforeach()
  set(${files_out} "${files}" PARENT_SCOPE)
  set(${includes_out} "${found}" PARENT_SCOPE)
endfunction()

# report_leaks(CHECKED LEAKS HEADING STATUS): fails with HEADING and the leaks when there are any,
# else prints STATUS; a scan that checked no file fails too.
function(report_leaks checked leaks heading status)
  if(checked EQUAL 0)
    message(FATAL_ERROR "no source files under ${ROOT}/runtime")
  endif()
  if(NOT leaks STREQUAL "")
    message(FATAL_ERROR "${heading}:\n${leaks}")
  endif()
  message(STATUS "${status}")
endfunction()
