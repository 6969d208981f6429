# consumer.add_subdirectory: configure, build and run tests/consumer_subdir against this
# source tree. Variables: SOURCE_DIR (this folder), CLOUDMATH_SOURCE_DIR, SCRATCH_DIR,
# GENERATOR, MAKE_PROGRAM, CXX_COMPILER.
cmake_minimum_required(VERSION 3.20)
include("${CMAKE_CURRENT_LIST_DIR}/../consumer/consumer_steps.cmake")

file(REMOVE_RECURSE "${SCRATCH_DIR}")
consumer_configure_args(configure_args)
consumer_step("configure add_subdirectory consumer"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${SCRATCH_DIR}" ${configure_args}
  "-DCLOUDMATH_SOURCE_DIR=${CLOUDMATH_SOURCE_DIR}")
consumer_step("build add_subdirectory consumer" "${CMAKE_COMMAND}" --build "${SCRATCH_DIR}")
# The .glsl files of a vendored cloudmath are the source tree's.
consumer_step("run add_subdirectory consumer" "${SCRATCH_DIR}/consumer_subdir"
  "${CLOUDMATH_SOURCE_DIR}/include/cloudmath/glsl")
