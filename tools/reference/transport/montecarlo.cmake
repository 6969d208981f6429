# tools/reference/transport/montecarlo.cmake: the Monte Carlo reference (transport/montecarlo.hpp).
#   cloudmath_montecarlo_lib   static library: phase models, slab and sphere path tracing
#   cloudmath_montecarlo       command-line tool (transport/montecarlo_main.cpp)
#   reference.montecarlo       doctest validation against published and closed-form values
#   reference.montecarlo_cli   command-line checks: bad flags/values exit 2 (trailing junk,
#                              nan, hexadecimal, runs above the 1e10-path cap), a missing
#                              phase table exits 1, a tiny run writes its CSV, a killed run
#                              and --out /dev/full leave the old file as it was
#   reference.montecarlo_failed_write  --out under a failing disk (expect_failed_write.cmake)
# Run as a script (cmake -DTOOL=<exe> -DOUT=<dir> -P transport/montecarlo.cmake) it performs the
# command-line checks; included from CMakeLists.txt it declares the targets.

if(CMAKE_SCRIPT_MODE_FILE)
  function(expect_exit code)
    execute_process(COMMAND "${TOOL}" ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out
      ERROR_VARIABLE err)
    if(NOT rc EQUAL code)
      message(FATAL_ERROR "'${ARGN}' exited ${rc}, expected ${code}\n${out}\n${err}")
    endif()
  endfunction()
  file(MAKE_DIRECTORY "${OUT}")
  expect_exit(2)
  expect_exit(0 --help)
  expect_exit(2 nonsense)
  expect_exit(2 slab --bogus 1)
  expect_exit(2 slab --tau)
  expect_exit(2 slab --tau -1)
  expect_exit(2 slab --mu0 0)
  expect_exit(2 slab --photons 1.5)
  expect_exit(2 slab --phase hg:1.5)
  expect_exit(2 slab --phase wrong)
  expect_exit(2 slab-radiance --views "x:1,0")
  expect_exit(2 sphere --view-angle 200)
  expect_exit(2 sphere --points 3 --grid 3)
  # Numbers are read strictly (strict_number.hpp): no junk, no nan, no spaces, no hex.
  expect_exit(2 slab --tau 1xyz)
  expect_exit(2 slab --tau nan)
  expect_exit(2 slab --tau 0x10)
  expect_exit(2 slab --photons " 5")
  expect_exit(2 slab --photons -5)
  expect_exit(2 slab --phase hg:0.5xyz)
  # The cap: at most 1e10 paths per run (hours of work otherwise).
  expect_exit(2 slab --photons 1e11)
  expect_exit(2 sphere --paths 1e11)
  expect_exit(2 sphere --grid 4096 --paths 1000)
  expect_exit(2 slab-radiance --views "r:1,0;r:0.5,0" --paths 6e9)
  expect_exit(1 slab --phase "table:${OUT}/no_such_table.csv" --photons 10)
  expect_exit(1 slab --photons 10 --out "${OUT}/no_such_dir/out.csv")
  expect_exit(0 slab --tau 1 --photons 2000 --bins 4 --out "${OUT}/slab.csv")
  file(STRINGS "${OUT}/slab.csv" lines)
  list(FIND lines "side,mu_low,mu_high,mu_centre,radiance,std_error" header)
  list(LENGTH lines n)
  math(EXPR expected "${header} + 9")
  if(header LESS 0 OR NOT n EQUAL expected)
    message(FATAL_ERROR "slab.csv: expected the header and 8 histogram rows")
  endif()
  expect_exit(0 sphere --tau 2 --points 3 --paths 100 --out "${OUT}/sphere.csv")
  # --out is written only at the end, atomically: a run killed on the way (here by the
  # timeout) and a failed write (/dev/full: exit 1) leave the old file as it was, and no
  # temporary. Before, the file was truncated when the run started.
  file(WRITE "${OUT}/kept.csv" "old contents\n")
  execute_process(COMMAND "${TOOL}" slab --photons 1e9 --threads 1 --out "${OUT}/kept.csv"
    RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET TIMEOUT 1)
  file(READ "${OUT}/kept.csv" kept)
  file(GLOB left "${OUT}/kept.csv?*")
  if(rc EQUAL 0 OR NOT kept STREQUAL "old contents\n" OR left)
    message(FATAL_ERROR "a killed run (exit '${rc}') changed kept.csv to '${kept}' or left '${left}'")
  endif()
  if(EXISTS /dev/full)
    expect_exit(1 slab --photons 100 --out /dev/full)
  endif()
  expect_exit(0 slab-radiance --views "t:0.5,0" --paths 100 --out "${OUT}/rad.csv")
  return()
endif()

add_library(cloudmath_montecarlo_lib STATIC transport/montecarlo.cpp)
cloudmath_reference_target(cloudmath_montecarlo_lib)
target_include_directories(cloudmath_montecarlo_lib PUBLIC ${cloudmath_reference_include_dirs})
target_link_libraries(cloudmath_montecarlo_lib PUBLIC cloudmath_phase_table)

add_executable(cloudmath_montecarlo transport/montecarlo_main.cpp)
cloudmath_reference_target(cloudmath_montecarlo)
target_link_libraries(cloudmath_montecarlo PRIVATE cloudmath_montecarlo_lib)

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(montecarlo transport/test_montecarlo.cpp)
  target_link_libraries(cloudmath_reference_test_montecarlo PRIVATE cloudmath_montecarlo_lib)
  add_test(NAME reference.montecarlo_cli
    COMMAND "${CMAKE_COMMAND}" "-DTOOL=$<TARGET_FILE:cloudmath_montecarlo>"
      "-DOUT=${CMAKE_CURRENT_BINARY_DIR}/montecarlo_cli"
      -P "${CMAKE_CURRENT_SOURCE_DIR}/transport/montecarlo.cmake")
  add_test(NAME reference.montecarlo_failed_write
    COMMAND "${CMAKE_COMMAND}" "-DCOMMAND=$<TARGET_FILE:cloudmath_montecarlo>"
      "-DARGS=slab;--photons;1000;--out;@WORK@/slab.csv" -DFILES=slab.csv
      "-DWORK=${CMAKE_CURRENT_BINARY_DIR}/montecarlo_failed_write"
      -P "${PROJECT_SOURCE_DIR}/tools/common/expect_failed_write.cmake")
endif()
