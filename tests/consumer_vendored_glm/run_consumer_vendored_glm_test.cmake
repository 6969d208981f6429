# consumer.vendored_glm: a project that defines glm::glm itself and has no GLM package
# (tests/consumer_vendored_glm) uses cloudmath (1) through add_subdirectory() of this source
# tree and (2) through find_package() of the main build installed into a scratch prefix.
# Before cloudmath skipped find_package(glm) for an existing glm::glm, both failed to
# configure. Variables: SOURCE_DIR (this folder), CLOUDMATH_SOURCE_DIR, MAIN_BUILD_DIR,
# CONFIG (may be empty), SCRATCH_DIR, GENERATOR, MAKE_PROGRAM, CXX_COMPILER.
cmake_minimum_required(VERSION 3.20)
include("${CMAKE_CURRENT_LIST_DIR}/../consumer/consumer_steps.cmake")

file(REMOVE_RECURSE "${SCRATCH_DIR}")
consumer_configure_args(configure_args)

function(build_and_run mode build_dir)
  consumer_step("configure vendored-GLM consumer (${mode})"
    "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${build_dir}" ${configure_args} ${ARGN})
  consumer_step("build vendored-GLM consumer (${mode})" "${CMAKE_COMMAND}" --build "${build_dir}")
  file(READ "${build_dir}/glsl_dir.txt" glsl_dir)
  consumer_step("run vendored-GLM consumer (${mode})" "${build_dir}/consumer_vendored_glm" "${glsl_dir}")
endfunction()

# (1) add_subdirectory.
build_and_run(add_subdirectory "${SCRATCH_DIR}/subdir" "-DCLOUDMATH_SOURCE_DIR=${CLOUDMATH_SOURCE_DIR}")

# (2) find_package of an install.
set(prefix "${SCRATCH_DIR}/prefix")
consumer_install("${prefix}")
build_and_run(find_package "${SCRATCH_DIR}/find_package" "-DCLOUDMATH_PREFIX=${prefix}")
