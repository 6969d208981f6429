# consumer.add_subdirectory: configure, build and run tests/consumer_subdir against this
# source tree, then install it: by default the install tree holds the consumer's executable
# and nothing of cloudmath's; reconfigured with -DCLOUDMATH_INSTALL=ON it holds our headers
# and package files as well.
# Variables: SOURCE_DIR (this folder), CLOUDMATH_SOURCE_DIR, SCRATCH_DIR, GENERATOR,
# MAKE_PROGRAM, CXX_COMPILER.
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

# Install with CLOUDMATH_INSTALL at its subproject default: only the parent's own file.
set(prefix "${SCRATCH_DIR}/prefix_default")
consumer_step("install add_subdirectory consumer (CLOUDMATH_INSTALL default)"
  "${CMAKE_COMMAND}" --install "${SCRATCH_DIR}" --prefix "${prefix}")
file(GLOB_RECURSE installed LIST_DIRECTORIES false RELATIVE "${prefix}" "${prefix}/*")
if(NOT installed STREQUAL "bin/consumer_subdir")
  message(FATAL_ERROR "consumer test: a parent's install of a cloudmath subproject must hold "
    "only the parent's files (bin/consumer_subdir), it holds: ${installed}")
endif()

# Asked for, the subproject installs like a top-level build.
consumer_step("reconfigure add_subdirectory consumer with -DCLOUDMATH_INSTALL=ON"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${SCRATCH_DIR}" -DCLOUDMATH_INSTALL=ON)
set(prefix "${SCRATCH_DIR}/prefix_install_on")
consumer_step("install add_subdirectory consumer (CLOUDMATH_INSTALL=ON)"
  "${CMAKE_COMMAND}" --install "${SCRATCH_DIR}" --prefix "${prefix}")
foreach(file
    bin/consumer_subdir
    include/cloudmath/cloudmath.hpp
    include/cloudmath/version.hpp
    include/cloudmath/glsl_embedded.hpp
    include/cloudmath/glsl/cloudmath.glsl
    share/cmake/cloudmath/cloudmathConfig.cmake
    share/cmake/cloudmath/cloudmathConfigVersion.cmake
    share/cmake/cloudmath/cloudmathTargets.cmake
    share/pkgconfig/cloudmath.pc)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "consumer test: with CLOUDMATH_INSTALL=ON the install lacks ${file}")
  endif()
endforeach()
