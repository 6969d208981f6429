# compilers.clang: cloudmath's plain unit tests and header checks built with clang++ and run.
# The build tree BUILD_DIR is kept between runs, so a rerun rebuilds only what changed.
# In that build (tests/CMakeLists.txt, CMAKE_CXX_COMPILER_ID Clang) the unit tests and
# cloudmath_header_check_weverything compile the public headers under -Weverything
# (documented exceptions there), warnings as errors.
# Variables: CLANGXX, SOURCE_DIR (the repository), BUILD_DIR, GENERATOR, MAKE_PROGRAM.
cmake_minimum_required(VERSION 3.20)
include("${CMAKE_CURRENT_LIST_DIR}/consumer/consumer_steps.cmake")

set(generator_args -G "${GENERATOR}")
if(MAKE_PROGRAM)
  list(APPEND generator_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
# A tree configured with another compiler (or generator) cannot be reused.
if(EXISTS "${BUILD_DIR}/CMakeCache.txt")
  file(STRINGS "${BUILD_DIR}/CMakeCache.txt" cached REGEX "^CMAKE_CXX_COMPILER:")
  if(NOT cached STREQUAL "CMAKE_CXX_COMPILER:FILEPATH=${CLANGXX}")
    file(REMOVE_RECURSE "${BUILD_DIR}")
  endif()
endif()
# Only the library, its tests (plain variant) and what configuring the tests needs.
consumer_step("configure with ${CLANGXX}"
  "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${BUILD_DIR}" ${generator_args}
  "-DCMAKE_CXX_COMPILER=${CLANGXX}" -DCMAKE_BUILD_TYPE=Release
  -DCLOUDMATH_BUILD_TESTS=ON -DCLOUDMATH_BUILD_EXAMPLES=OFF -DCLOUDMATH_BUILD_BENCH=OFF
  -DCLOUDMATH_BUILD_PEER_BENCH=OFF -DCLOUDMATH_TEST_VARIANTS=plain)
consumer_step("build the unit tests and header checks with clang"
  "${CMAKE_COMMAND}" --build "${BUILD_DIR}" -j 2
  --target cloudmath_unit_tests cloudmath_header_check cloudmath_header_check_weverything)
consumer_step("run the clang-built unit tests"
  "${CMAKE_CTEST_COMMAND}" --test-dir "${BUILD_DIR}" -L unit --output-on-failure -j 2)
message(STATUS "${consumer_step_output}")
