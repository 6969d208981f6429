# optics/phase_error.cmake: the phase-function error report (included by CMakeLists.txt).
#   cloudmath_phase_error_lib   comparison metrics, log-space fits, SVG plots (optics/phase_error.hpp)
#   cloudmath_phase_error       the CLI writing docs/phase_error.md, .csv and the SVGs:
#     cloudmath_phase_error [--docs DIR] [--images DIR] docs/data/mie_*.csv
add_library(cloudmath_phase_error_lib STATIC optics/phase_error.cpp)
cloudmath_reference_target(cloudmath_phase_error_lib)
target_include_directories(cloudmath_phase_error_lib PUBLIC ${cloudmath_reference_include_dirs})
target_link_libraries(cloudmath_phase_error_lib PUBLIC cloudmath_phase_table)

add_executable(cloudmath_phase_error optics/phase_error_main.cpp)
cloudmath_reference_target(cloudmath_phase_error)
target_link_libraries(cloudmath_phase_error PRIVATE cloudmath_phase_error_lib)

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(phase_error optics/test_phase_error.cpp)
  target_link_libraries(cloudmath_reference_test_phase_error PRIVATE cloudmath_phase_error_lib)
  # The end-to-end test runs the CLI on a small table.
  add_dependencies(cloudmath_reference_test_phase_error cloudmath_phase_error)
  target_compile_definitions(cloudmath_reference_test_phase_error PRIVATE
    "CLOUDMATH_PHASE_ERROR_EXE=\"$<TARGET_FILE:cloudmath_phase_error>\"")

  # Command-line errors: unknown flag and no table -> 2, unreadable table or r_eff_um that is
  # not a number (strtod read it as 0) -> 1, --help -> 0.
  add_test(NAME reference.phase_error_cli
    COMMAND sh -c [=[
      "$1" --no-such-flag 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad flag: exit $s, want 2"; exit 1; }
      "$1" 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "no table: exit $s, want 2"; exit 1; }
      "$1" --docs 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "--docs without value: exit $s, want 2"; exit 1; }
      "$1" --docs "$2" "$2/missing_table.csv" 2>"$2.err"; s=$?
      [ $s -eq 1 ] || { echo "missing table: exit $s, want 1"; exit 1; }
      grep -q missing_table.csv "$2.err" || { echo "message does not name the path"; exit 1; }
      [ ! -e "$2/phase_error.md" ] || { echo "wrote a report despite the error"; exit 1; }
      printf '# r_eff_um: abc\ntheta_deg,mu,phase\n0,1,0.0795774715\n180,-1,0.0795774715\n' >"$2.bad_reff.csv"
      "$1" --docs "$2" "$2.bad_reff.csv" 2>"$2.err"; s=$?
      [ $s -eq 1 ] && grep -q "r_eff_um 'abc' is not a number" "$2.err" || { echo "r_eff_um abc: exit $s, want 1"; exit 1; }
      [ ! -e "$2/phase_error.md" ] || { echo "wrote a report despite the bad r_eff_um"; exit 1; }
      "$1" --help >/dev/null; s=$?; [ $s -eq 0 ] || { echo "--help: exit $s, want 0"; exit 1; }
      ]=] sh $<TARGET_FILE:cloudmath_phase_error> "${CMAKE_CURRENT_BINARY_DIR}/phase_error_cli_test")
endif()
