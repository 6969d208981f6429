# consumer.find_package: install the main build tree into a scratch prefix, then use it
# (1) through find_package(cloudmath CONFIG) and (2) through pkg-config.
# Variables: SOURCE_DIR (this folder), MAIN_BUILD_DIR, CONFIG (may be empty), SCRATCH_DIR,
# PROJECT_VERSION, GENERATOR, MAKE_PROGRAM, CXX_COMPILER.
cmake_minimum_required(VERSION 3.20)
include("${CMAKE_CURRENT_LIST_DIR}/consumer_steps.cmake")

set(prefix "${SCRATCH_DIR}/prefix")
file(REMOVE_RECURSE "${SCRATCH_DIR}")

consumer_install("${prefix}")

foreach(file
    include/cloudmath/cloudmath.hpp
    include/cloudmath/version.hpp
    include/cloudmath/glsl.hpp
    include/cloudmath/glsl_embedded.hpp
    include/cloudmath/glsl/cloudmath.glsl
    include/cloudmath/hlsl/cloudmath.hlsl
    include/cloudmath/hlsl/CloudMath.ush
    include/cloudmath/wgsl/cloudmath.wgsl
    include/cloudmath/wgsl/cone_sampling_hooks.wgsl
    share/cmake/cloudmath/cloudmathConfig.cmake
    share/cmake/cloudmath/cloudmathConfigVersion.cmake
    share/cmake/cloudmath/cloudmathTargets.cmake
    share/pkgconfig/cloudmath.pc)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "consumer test: install did not create ${prefix}/${file}")
  endif()
endforeach()

# (1) CMake package.
consumer_configure_args(configure_args)
consumer_step("configure consumer project"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${SCRATCH_DIR}/build" ${configure_args}
  "-DCMAKE_PREFIX_PATH=${prefix}")
string(FIND "${consumer_step_output}" "cloudmath_DIR=${prefix}/" found)
if(found EQUAL -1)
  message(FATAL_ERROR "consumer test: find_package did not pick the scratch install:\n"
    "${consumer_step_output}")
endif()
consumer_step("build consumer project" "${CMAKE_COMMAND}" --build "${SCRATCH_DIR}/build")
# The consumer compares the embedded GLSL with the installed .glsl files.
set(glsl_dir "${prefix}/include/cloudmath/glsl")
consumer_step("run consumer (find_package)" "${SCRATCH_DIR}/build/consumer" "${glsl_dir}")

# (2) pkg-config, with our .pc first on the search path (glm.pc still comes from the system).
find_program(PKG_CONFIG_EXECUTABLE NAMES pkg-config pkgconf REQUIRED)
set(ENV{PKG_CONFIG_PATH} "${prefix}/share/pkgconfig")
consumer_step("pkg-config --modversion" "${PKG_CONFIG_EXECUTABLE}" --modversion cloudmath)
string(STRIP "${consumer_step_output}" version)
if(NOT version STREQUAL PROJECT_VERSION)
  message(FATAL_ERROR "consumer test: pkg-config reports version '${version}', expected ${PROJECT_VERSION}")
endif()
consumer_step("pkg-config --cflags" "${PKG_CONFIG_EXECUTABLE}" --cflags cloudmath)
string(STRIP "${consumer_step_output}" cflags)
string(FIND "${cflags}" "-I${prefix}/" found)
if(found EQUAL -1)
  message(FATAL_ERROR "consumer test: pkg-config cflags '${cflags}' do not point into ${prefix}")
endif()
separate_arguments(cflags UNIX_COMMAND "${cflags}")
consumer_step("compile consumer with pkg-config flags"
  "${CXX_COMPILER}" -std=c++17 -Wall -Wextra -Wpedantic -Werror ${cflags}
  "${SOURCE_DIR}/main.cpp" -o "${SCRATCH_DIR}/consumer_pkgconfig")
consumer_step("run consumer (pkg-config)" "${SCRATCH_DIR}/consumer_pkgconfig" "${glsl_dir}")
