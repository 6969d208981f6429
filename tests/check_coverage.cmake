# Public-function coverage check. Run as:
#   cmake -DHEADER_DIR=<dir with *.hpp> -DTEST_DIR=<dir with test_*.cpp> [-DMIN_PUBLIC=<n>] -P check_coverage.cmake
#
# Rule, kept deliberately simple so it needs no C++ parser:
# - A public function is any function declared with [[nodiscard]] in HEADER_DIR/*.hpp
#   (not recursive: glsl/ and other subfolders are not C++ API). Its name is the identifier
#   immediately before the first "(" after the attribute; the declaration may span lines.
#   Operators are skipped, overloads count once. Helpers in `namespace detail` carry no
#   [[nodiscard]] by convention, so they are not public and need no namespace parsing.
# - It counts as tested when its name, preceded by a non-identifier character and followed
#   by "(" or "<" (optionally after spaces), appears in some TEST_DIR/test_*.cpp.
# - Comments are removed from headers and tests first, so a commented-out call or a
#   "[[nodiscard]]" in prose changes nothing.
# The check fails listing every untested name, and also when fewer than MIN_PUBLIC
# (default 5) public functions were found, which would mean the parse broke.
cmake_minimum_required(VERSION 3.20)

foreach(var HEADER_DIR TEST_DIR)
  if(NOT IS_DIRECTORY "${${var}}")
    message(FATAL_ERROR "check_coverage: ${var}='${${var}}' is not a directory")
  endif()
endforeach()
if(NOT DEFINED MIN_PUBLIC)
  set(MIN_PUBLIC 5)
endif()

# Reads a source file with comments removed. Semicolons become "}" because CMake treats ";"
# as a list separator (and "}" still ends a declaration for the regexes below); the other
# square brackets become spaces so that "x[i]" cannot read as a call to x.
function(read_source path out)
  file(READ "${path}" text)
  # Block comments: cut from each "/*" to the next "*/" (CMake regexes are greedy).
  while(TRUE)
    string(FIND "${text}" "/*" begin)
    if(begin EQUAL -1)
      break()
    endif()
    string(SUBSTRING "${text}" ${begin} -1 rest)
    string(FIND "${rest}" "*/" length)
    if(length EQUAL -1)
      string(SUBSTRING "${text}" 0 ${begin} text)
      break()
    endif()
    math(EXPR after "${begin} + ${length} + 2")
    string(SUBSTRING "${text}" 0 ${begin} head)
    string(SUBSTRING "${text}" ${after} -1 tail)
    set(text "${head} ${tail}")
  endwhile()
  string(REGEX REPLACE "//[^\n]*" "" text "${text}")
  string(REPLACE ";" "}" text "${text}")
  string(REPLACE "[[nodiscard]]" " CLOUDMATH_NODISCARD " text "${text}")
  string(REPLACE "[" " " text "${text}")
  string(REPLACE "]" " " text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# --- public functions --------------------------------------------------------------------
file(GLOB headers "${HEADER_DIR}/*.hpp")
set(public_functions "")
foreach(header IN LISTS headers)
  read_source("${header}" text)
  # Attribute, then anything up to the first "(" that does not cross a "}" or "{".
  string(REGEX MATCHALL " CLOUDMATH_NODISCARD [^(){}]*\\(" declarations "${text}")
  foreach(declaration IN LISTS declarations)
    if(declaration MATCHES "(^|[^A-Za-z0-9_])operator([^A-Za-z0-9_]|$)")
      continue()
    endif()
    if(declaration MATCHES "([A-Za-z_][A-Za-z0-9_]*)[ \t\r\n]*\\($")
      list(APPEND public_functions "${CMAKE_MATCH_1}")
    else()
      message(FATAL_ERROR "check_coverage: cannot find the name in '${declaration}' (${header})")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES public_functions)
list(SORT public_functions)
list(LENGTH public_functions count)
message(STATUS "check_coverage: ${count} public functions in ${HEADER_DIR}")
if(count LESS MIN_PUBLIC)
  message(FATAL_ERROR
    "check_coverage: found only ${count} public functions (expected at least ${MIN_PUBLIC}); "
    "the [[nodiscard]] parse is probably broken")
endif()

# --- uses in tests ---------------------------------------------------------------------------
file(GLOB tests "${TEST_DIR}/test_*.cpp")
set(all_tests "")
foreach(test IN LISTS tests)
  read_source("${test}" text)
  string(APPEND all_tests "\n${text}")
endforeach()

set(untested "")
foreach(name IN LISTS public_functions)
  if(NOT all_tests MATCHES "(^|[^A-Za-z0-9_])${name}[ \t]*[(<]")
    list(APPEND untested "${name}")
  endif()
endforeach()
if(untested)
  list(LENGTH untested missing)
  list(JOIN untested "\n  " listing)
  message(FATAL_ERROR
    "check_coverage: ${missing} of ${count} public functions are not called in any "
    "${TEST_DIR}/test_*.cpp:\n  ${listing}")
endif()
message(STATUS "check_coverage: all ${count} public functions are used in tests")
