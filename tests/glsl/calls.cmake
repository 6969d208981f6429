# Reads tests/glsl/calls.txt (format described at its top). include() it from a cmake -P
# script. Shared by validate_glsl.cmake and check_twins.cmake.
#
# cloudmath_parse_calls(<path> <names_out> <body_out>)
#   names_out: the function name of every call line, in file order (a CMake list).
#   body_out:  GLSL statements `    cm_test_s += (<expression>);  // <file>:<line> <name>`,
#              one per call line, for a main() that declares `float cm_test_s`.
# The file is walked with string(FIND) rather than as a CMake list, so expressions may
# contain ";" or "[" without confusing CMake. Malformed lines stop the script.
include("${CMAKE_CURRENT_LIST_DIR}/../../cmake/TextLines.cmake")

function(cloudmath_parse_calls path names_out body_out)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "calls: no file ${path}")
  endif()
  file(READ "${path}" text)
  get_filename_component(file_name "${path}" NAME)
  set(names "")
  set(body "")
  set(line_number 0)
  while(NOT text STREQUAL "")
    cloudmath_pop_line(text line)
    math(EXPR line_number "${line_number} + 1")
    string(STRIP "${line}" line)
    if(line STREQUAL "" OR line MATCHES "^#")
      continue()
    endif()
    string(FIND "${line}" "|" bar)
    if(bar EQUAL -1)
      message(FATAL_ERROR "calls: ${path}:${line_number}: no '|' in '${line}'")
    endif()
    string(SUBSTRING "${line}" 0 ${bar} name)
    math(EXPR after "${bar} + 1")
    string(SUBSTRING "${line}" ${after} -1 expression)
    string(STRIP "${name}" name)
    string(STRIP "${expression}" expression)
    if(NOT name MATCHES "^cm_[A-Za-z0-9_]+$")
      message(FATAL_ERROR "calls: ${path}:${line_number}: '${name}' is not a cm_ function name")
    endif()
    if(expression STREQUAL "")
      message(FATAL_ERROR "calls: ${path}:${line_number}: empty expression for ${name}")
    endif()
    list(APPEND names "${name}")
    string(APPEND body "    cm_test_s += (${expression});  // ${file_name}:${line_number} ${name}\n")
  endwhile()
  set(${names_out} "${names}" PARENT_SCOPE)
  set(${body_out} "${body}" PARENT_SCOPE)
endfunction()
