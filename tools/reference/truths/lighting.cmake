# Lighting models against the Monte Carlo reference (included by CMakeLists.txt).
#   cloudmath_lighting_lib    truths/lighting_models.cpp: the real-time models along test-medium rays;
#                             truths/lighting_error.cpp: the reference data set, errors and fits;
#                             truths/lighting_diffusion.cpp: the chord-diffusion research model's fit
#                             truths/lighting_report.cpp: docs/lighting_error.md, .csv and SVGs
#   cloudmath_lighting_error  the CLI: `reference` path-traces docs/data/lighting_reference.csv,
#                             `report` writes the report (truths/lighting_error_main.cpp)
add_library(cloudmath_lighting_lib STATIC truths/lighting_models.cpp truths/lighting_error.cpp truths/lighting_diffusion.cpp
  truths/lighting_report.cpp)
cloudmath_reference_target(cloudmath_lighting_lib)
target_include_directories(cloudmath_lighting_lib PUBLIC ${cloudmath_reference_include_dirs})
target_link_libraries(cloudmath_lighting_lib PUBLIC cloudmath_montecarlo_lib cloudmath_phase_error_lib)

add_executable(cloudmath_lighting_error truths/lighting_error_main.cpp)
cloudmath_reference_target(cloudmath_lighting_error)
target_link_libraries(cloudmath_lighting_error PRIVATE cloudmath_lighting_lib)

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(lighting_models truths/test_lighting_models.cpp)
  target_link_libraries(cloudmath_reference_test_lighting_models PRIVATE cloudmath_lighting_lib)
endif()

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(lighting_error truths/test_lighting_error.cpp)
  target_link_libraries(cloudmath_reference_test_lighting_error PRIVATE cloudmath_lighting_lib)
  target_compile_definitions(cloudmath_reference_test_lighting_error PRIVATE
    "CLOUDMATH_BINARY_DIR=\"${CMAKE_CURRENT_BINARY_DIR}\"")
  cloudmath_reference_test(lighting_diffusion truths/test_lighting_diffusion.cpp)
  target_link_libraries(cloudmath_reference_test_lighting_diffusion PRIVATE cloudmath_lighting_lib)
  cloudmath_reference_test(lighting_presets truths/test_lighting_presets.cpp)
  target_link_libraries(cloudmath_reference_test_lighting_presets PRIVATE cloudmath_lighting_lib)

  # The CLI: bad command lines -> 2, a missing reference -> 1 naming it, and a --quick
  # reference turned into a report (every output file written).
  add_test(NAME reference.lighting_error_cli
    COMMAND sh -c [=[
      set -u
      "$1" 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "no command: exit $s, want 2"; exit 1; }
      "$1" report --no-such-flag 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad flag: exit $s, want 2"; exit 1; }
      "$1" reference --paths x 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad --paths: exit $s, want 2"; exit 1; }
      rm -rf "$2"; mkdir -p "$2/images"
      "$1" report --reference "$2/missing.csv" --docs "$2" 2>"$2.err"; s=$?
      [ $s -eq 1 ] || { echo "missing reference: exit $s, want 1"; exit 1; }
      grep -q missing.csv "$2.err" || { echo "message does not name the path"; exit 1; }
      "$1" reference --quick --threads 2 --out "$2/ref.csv" 2>/dev/null || { echo "reference --quick failed"; exit 1; }
      [ "$(grep -c '^sphere,' "$2/ref.csv")" -eq 30 ] || { echo "quick reference: want 30 sphere rows"; exit 1; }
      # A valid reference of one row: a data failure of that file (exit 1 naming it), not a bad
      # command line; a negative radiance: exit 1 naming the file and the value.
      mkdir -p "$2/one/images"; grep -v '^sphere,\|^slab' "$2/ref.csv" >"$2/one.csv"; grep -m1 '^sphere,' "$2/ref.csv" >>"$2/one.csv"
      "$1" report --reference "$2/one.csv" --docs "$2/one" 2>"$2.err"; s=$?
      [ $s -eq 1 ] && grep -q "one.csv: no row with radiance > 0 in the fit range" "$2.err" || { echo "1-row reference: exit $s"; cat "$2.err"; exit 1; }
      grep -v '^sphere,\|^slab' "$2/ref.csv" >"$2/negative.csv"; grep -m1 '^sphere,' "$2/ref.csv" | awk -F, -v OFS=, '{$16 = "-1"} 1' >>"$2/negative.csv"
      "$1" report --reference "$2/negative.csv" --docs "$2/one" 2>"$2.err"; s=$?
      [ $s -eq 1 ] && grep -q "negative.csv.*radiance -1 is negative" "$2.err" || { echo "radiance -1: exit $s"; cat "$2.err"; exit 1; }
      "$1" report --reference "$2/ref.csv" --docs "$2" 2>/dev/null || { echo "report failed"; exit 1; }
      for f in lighting_error.md lighting_error.csv images/lighting_error_vs_tau.svg images/lighting_error_sphere_profile.svg; do
        [ -s "$2/$f" ] || { echo "missing $f"; exit 1; }
      done
      grep -q "ms_preset::thin" "$2/lighting_error.md" || { echo "report lacks the presets"; exit 1; }
      "$1" fit-diffusion --train "$2/ref.csv" --holdout "$2/ref.csv" >"$2/fit.txt" 2>/dev/null || { echo "fit-diffusion failed"; exit 1; }
      grep -q "^held out" "$2/fit.txt" || { echo "fit-diffusion measured no held-out set"; exit 1; }
      "$1" reference --quick --holdout 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "--quick --holdout: exit $s, want 2"; exit 1; }
      "$1" reference --quick --albedo 1.5 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "--albedo 1.5: exit $s, want 2"; exit 1; }
      "$1" choice --reference "$2/ref.csv" --out "$2/choice.hpp" >/dev/null || { echo "choice failed"; exit 1; }
      grep -q "diffusion_models::fitted" "$2/choice.hpp" || { echo "choice data lacks the diffusion model"; exit 1; }
      "$1" --help >/dev/null || { echo "--help failed"; exit 1; }
      ]=] sh $<TARGET_FILE:cloudmath_lighting_error> "${CMAKE_CURRENT_BINARY_DIR}/lighting_error_cli_test")

  # Numbers on the command line are read strictly and path counts are capped (exit 2 at
  # once: " -5" paths wrapped round to 2^64 - 5, "0.01xyz" read as 0.01, nan accepted), and
  # --out is checked before any tracing (exit 1 at once, the old file untouched).
  add_test(NAME reference.lighting_error_cli_numbers
    COMMAND sh -c [=[
      set -u
      rm -rf "$2"; mkdir -p "$2"
      for bad in "--paths=-5" "--paths= -5" "--paths= 5" "--paths=5x" "--paths=1e12" "--max-paths=2e8" "--threads=-1" \
                 "--seed=1.5" "--target-error=0.01xyz" "--target-error=nan" "--albedo=nan" "--albedo=0x1"; do
        flag=${bad%%=*} value=${bad#*=}
        "$1" reference --quick "$flag" "$value" --out "$2/ref.csv" 2>"$2.err"; s=$?
        [ $s -eq 2 ] || { echo "reference $flag '$value': exit $s, want 2"; exit 1; }
        grep -q "^cloudmath_lighting_error: $flag" "$2.err" || { echo "reference $bad: no message naming the flag"; cat "$2.err"; exit 1; }
      done
      [ ! -e "$2/ref.csv" ] || { echo "a rejected command line wrote ref.csv"; exit 1; }
      "$1" reference --quick --out "$2/no_such_dir/ref.csv" 2>"$2.err"; s=$?
      [ $s -eq 1 ] || { echo "missing directory: exit $s, want 1"; exit 1; }
      grep -q "no_such_dir/ref.csv" "$2.err" || { echo "the message does not name the path"; exit 1; }
      grep -q "sphere" "$2.err" && { echo "traced before checking --out"; exit 1; }
      exit 0
      ]=] sh $<TARGET_FILE:cloudmath_lighting_error> "${CMAKE_CURRENT_BINARY_DIR}/lighting_error_cli_numbers")
endif()
