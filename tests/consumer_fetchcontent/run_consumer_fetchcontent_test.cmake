# consumer.fetchcontent: the README's FetchContent lines (GIT_SHALLOW TRUE) against this
# checkout's committed HEAD, served from a bare copy in the scratch folder under a branch
# name (a shallow fetch needs a branch or tag, not a commit id). Checks that the fetch is
# shallow (one commit), builds and runs the consumer, and prints the fetched pack's size.
# Variables: SOURCE_DIR (this folder), CLOUDMATH_SOURCE_DIR, SCRATCH_DIR, GENERATOR,
# MAKE_PROGRAM, CXX_COMPILER, GIT.
cmake_minimum_required(VERSION 3.20)
include("${CMAKE_CURRENT_LIST_DIR}/../consumer/consumer_steps.cmake")

file(REMOVE_RECURSE "${SCRATCH_DIR}")
file(MAKE_DIRECTORY "${SCRATCH_DIR}")
consumer_step("find this checkout's commit" "${GIT}" -C "${CLOUDMATH_SOURCE_DIR}" rev-parse HEAD)
string(STRIP "${consumer_step_output}" head)
consumer_step("bare copy" "${GIT}" clone -q --bare --no-tags "${CLOUDMATH_SOURCE_DIR}" "${SCRATCH_DIR}/cloudmath.git")
consumer_step("branch at HEAD" "${GIT}" -C "${SCRATCH_DIR}/cloudmath.git" branch -f fetch-test "${head}")

consumer_configure_args(configure_args)
consumer_step("configure FetchContent consumer"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${SCRATCH_DIR}/build" ${configure_args}
  "-DCLOUDMATH_GIT_URL=file://${SCRATCH_DIR}/cloudmath.git" -DCLOUDMATH_GIT_TAG=fetch-test)
set(fetched "${SCRATCH_DIR}/build/_deps/cloudmath-src")
consumer_step("count the fetched commits" "${GIT}" -C "${fetched}" rev-list --count HEAD)
string(STRIP "${consumer_step_output}" commits)
if(NOT commits STREQUAL "1")
  message(FATAL_ERROR "consumer test: GIT_SHALLOW TRUE fetched ${commits} commits, want 1")
endif()
consumer_step("the fetched commit" "${GIT}" -C "${fetched}" rev-parse HEAD)
string(STRIP "${consumer_step_output}" got)
if(NOT got STREQUAL head)
  message(FATAL_ERROR "consumer test: fetched ${got}, want ${head}")
endif()
consumer_step("build FetchContent consumer" "${CMAKE_COMMAND}" --build "${SCRATCH_DIR}/build")
consumer_step("run FetchContent consumer" "${SCRATCH_DIR}/build/consumer_fetchcontent" "${fetched}/include/cloudmath/glsl")
file(GLOB packs "${fetched}/.git/objects/pack/*.pack")
set(bytes 0)
foreach(p IN LISTS packs)
  file(SIZE "${p}" size)
  math(EXPR bytes "${bytes} + ${size}")
endforeach()
message(STATUS "consumer test: the shallow fetch's pack: ${bytes} bytes")
