# tools/reference/volume_truth.cmake: ground truth for whole cloud images (included by
# CMakeLists.txt; needs the example renderer's core, so it is built with the examples).
#   cloudmath_volume_tracer_lib  volume_tracer.cpp: delta/ratio-tracking path tracer for
#                                heterogeneous media; cloud_medium.cpp: the renderer's clouds,
#                                sky and camera as its medium and light
#   cloudmath_volume_truth       the CLI: `render` path-traces a preset into docs/data,
#                                `report` compares the renderer's variants with it
#                                (docs/lighting_truth.md; volume_truth_main.cpp)
#   reference.volume_tracer      validation against montecarlo.hpp, determinism, majorants
#   reference.volume_truth_cli   command-line errors and a tiny render + report
add_library(cloudmath_volume_tracer_lib STATIC volume_tracer.cpp cloud_medium.cpp)
cloudmath_reference_target(cloudmath_volume_tracer_lib)
target_include_directories(cloudmath_volume_tracer_lib PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}")
target_link_libraries(cloudmath_volume_tracer_lib PUBLIC cloudmath_montecarlo_lib cloud_renderer_core)

add_executable(cloudmath_volume_truth volume_truth_main.cpp)
cloudmath_reference_target(cloudmath_volume_truth)
target_link_libraries(cloudmath_volume_truth PRIVATE cloudmath_volume_tracer_lib)

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(volume_tracer test_volume_tracer.cpp)
  target_link_libraries(cloudmath_reference_test_volume_tracer PRIVATE cloudmath_volume_tracer_lib)
  target_compile_definitions(cloudmath_reference_test_volume_tracer PRIVATE
    "CLOUDMATH_TRUTH_TEST_CACHE=\"${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache\"")
endif()
