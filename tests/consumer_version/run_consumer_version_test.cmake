# consumer.version: the installed package's version compatibility is SameMinorVersion.
# With cloudmath X.Y.Z installed, find_package(cloudmath X.Y) and (X.Y.Z) succeed, while
# (X.Y+1) and (X.Y-1) fail; and an install that claims X.Y+1.0 (a copy of this one with its
# version file rewritten) is rejected by find_package(cloudmath X.Y). The X.Y-1 case (0.0
# against 0.1.0) passed with the former SameMajorVersion.
# Variables: SOURCE_DIR (this folder), MAIN_BUILD_DIR, CONFIG (may be empty), SCRATCH_DIR,
# PROJECT_VERSION (cloudmath's project(VERSION)), GENERATOR, MAKE_PROGRAM.
cmake_minimum_required(VERSION 3.20)
include("${CMAKE_CURRENT_LIST_DIR}/../consumer/consumer_steps.cmake")

file(REMOVE_RECURSE "${SCRATCH_DIR}")
if(NOT PROJECT_VERSION MATCHES "^([0-9]+)\\.([0-9]+)\\.([0-9]+)$")
  message(FATAL_ERROR "consumer test: PROJECT_VERSION '${PROJECT_VERSION}' is not X.Y.Z")
endif()
set(major "${CMAKE_MATCH_1}")
set(minor "${CMAKE_MATCH_2}")
math(EXPR next_minor "${minor} + 1")
math(EXPR previous_minor "${minor} - 1")

set(prefix "${SCRATCH_DIR}/prefix")
consumer_install("${prefix}")

set(generator_args -G "${GENERATOR}")
if(MAKE_PROGRAM)
  list(APPEND generator_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
set(run 0)
# expect_version(<ACCEPT|REJECT> <requested version> <prefix>)
function(expect_version expectation want from)
  math(EXPR run "${run} + 1")
  set(run "${run}" PARENT_SCOPE)
  set(build "${SCRATCH_DIR}/configure_${run}")
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${build}" ${generator_args}
      "-DWANT=${want}" "-DCLOUDMATH_PREFIX=${from}"
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  set(what "find_package(cloudmath ${want}) against ${from}")
  if(expectation STREQUAL "ACCEPT")
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "consumer test: ${what} failed, expected it to succeed:\n${output}")
    endif()
  else()
    if(result EQUAL 0)
      message(FATAL_ERROR "consumer test: ${what} succeeded, expected a version mismatch:\n${output}")
    endif()
    # It must fail because of the version, not for any other reason.
    string(FIND "${output}" "compatible with requested version \"${want}\"" found)
    if(found EQUAL -1)
      message(FATAL_ERROR "consumer test: ${what} failed, but not for its version:\n${output}")
    endif()
  endif()
  message(STATUS "consumer test: ${what}: ${expectation}ed as expected")
endfunction()

expect_version(ACCEPT "${major}.${minor}" "${prefix}")
expect_version(ACCEPT "${PROJECT_VERSION}" "${prefix}")
expect_version(REJECT "${major}.${next_minor}" "${prefix}")
if(minor GREATER 0)
  expect_version(REJECT "${major}.${previous_minor}" "${prefix}")
endif()

# A newer minor release: the same install, its version file rewritten to X.Y+1.0.
set(next_prefix "${SCRATCH_DIR}/next_prefix")
file(COPY "${prefix}/" DESTINATION "${next_prefix}")
set(version_file "${next_prefix}/share/cmake/cloudmath/cloudmathConfigVersion.cmake")
file(READ "${version_file}" text)
string(REPLACE "\"${PROJECT_VERSION}\"" "\"${major}.${next_minor}.0\"" rewritten "${text}")
if(rewritten STREQUAL text)
  message(FATAL_ERROR "consumer test: ${version_file} does not contain \"${PROJECT_VERSION}\"")
endif()
file(WRITE "${version_file}" "${rewritten}")
expect_version(ACCEPT "${major}.${next_minor}" "${next_prefix}")  # the copy itself is usable
expect_version(REJECT "${major}.${minor}" "${next_prefix}")
