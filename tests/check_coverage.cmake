# Public-function coverage check. Run as:
#   cmake -DHEADER_DIR=<dir with *.hpp> -DTEST_DIR=<dir with test_*.cpp> [-DMIN_PUBLIC=<n>] -P check_coverage.cmake
#
# Rule, kept deliberately simple so it needs no C++ parser:
# - A public function is any function declared with [[nodiscard]] in HEADER_DIR/*.hpp, as
#   listed by cloudmath_public_functions() in public_functions.cmake (shared with the GLSL
#   twin check; the exact parse rule is documented there).
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

include("${CMAKE_CURRENT_LIST_DIR}/public_functions.cmake")

# --- public functions --------------------------------------------------------------------
cloudmath_public_functions("${HEADER_DIR}" public_functions)
list(LENGTH public_functions count)
message(STATUS "check_coverage: ${count} public functions in ${HEADER_DIR}")
if(count LESS MIN_PUBLIC)
  message(FATAL_ERROR
    "check_coverage: found only ${count} public functions (expected at least ${MIN_PUBLIC}); "
    "the [[nodiscard]] parse is probably broken")
endif()

# --- uses in tests ---------------------------------------------------------------------------
# TEST_GLOB (default test_*.cpp): which files count; coverage.fuzz_public_functions passes
# test_fuzz.cpp, so a public function without a fuzz entry fails the suite.
if(NOT DEFINED TEST_GLOB)
  set(TEST_GLOB "test_*.cpp")
endif()
file(GLOB tests "${TEST_DIR}/${TEST_GLOB}")
if(NOT tests)
  message(FATAL_ERROR "check_coverage: no ${TEST_DIR}/${TEST_GLOB}")
endif()
set(all_tests "")
foreach(test IN LISTS tests)
  cloudmath_read_source("${test}" text)
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
    "${TEST_DIR}/${TEST_GLOB}:\n  ${listing}")
endif()
message(STATUS "check_coverage: all ${count} public functions are used in tests")
