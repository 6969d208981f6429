# tools/reference/truths/atmosphere_truth.cmake: the sky's ground truth (issue 26; included by
# CMakeLists.txt).
#   cloudmath_atmosphere_lib     transport/atmosphere_tracer.cpp: path tracer of a planet's air;
#                                truths/atmosphere_truth.cpp: the truth set, its file, the model's
#                                errors against it; truths/atmosphere_variants.cpp: the
#                                multiple-scattering variants measured while choosing it
#   cloudmath_atmosphere_truth   the CLI: `render` traces docs/data/atmosphere_truth.csv (or
#                                the held-out set), `report` writes docs/atmosphere_truth.md
#                                and its images, `variants` the variants' errors, `ground`
#                                the ground below the horizon against the tracer
#   reference.atmosphere_tracer  the tracer against closed forms and the library's quadrature;
#                                the model against the stored truth (issue 26's targets)
#   reference.atmosphere_truth_cli  command-line errors, a tiny render, and the committed
#                                report reproduced from the stored truth
add_library(cloudmath_atmosphere_lib STATIC transport/atmosphere_tracer.cpp truths/atmosphere_truth.cpp truths/atmosphere_variants.cpp)
cloudmath_reference_target(cloudmath_atmosphere_lib)
target_include_directories(cloudmath_atmosphere_lib PUBLIC ${cloudmath_reference_include_dirs})
target_link_libraries(cloudmath_atmosphere_lib PUBLIC cloudmath_montecarlo_lib)

add_executable(cloudmath_atmosphere_truth truths/atmosphere_truth_main.cpp)
cloudmath_reference_target(cloudmath_atmosphere_truth)
target_include_directories(cloudmath_atmosphere_truth SYSTEM PRIVATE "${CLOUDMATH_STB_INCLUDE_DIR}")
target_link_libraries(cloudmath_atmosphere_truth PRIVATE cloudmath_atmosphere_lib cloudmath_stb_image_write)

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(atmosphere_tracer transport/test_atmosphere_tracer.cpp)
  target_link_libraries(cloudmath_reference_test_atmosphere_tracer PRIVATE cloudmath_atmosphere_lib)

  add_test(NAME reference.atmosphere_truth_cli
    COMMAND sh -c [=[
      set -u
      tool=$1 out=$2 src=$3
      "$tool" 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "no command: exit $s, want 2"; exit 1; }
      "$tool" --help >/dev/null || { echo "--help failed"; exit 1; }
      "$tool" nowhere 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad command: exit $s, want 2"; exit 1; }
      for bad in "--bogus 1" "--out" "--table-paths 10" "--out x.csv --table-paths 0" "--out x.csv --table-paths 1.5" \
                 "--out x.csv --panorama-paths nan" "--out x.csv --seed -1" "--out x.csv --threads 2xyz"; do
        "$tool" render $bad 2>/dev/null; s=$?
        [ $s -eq 2 ] || { echo "render $bad: exit $s, want 2"; exit 1; }
      done
      rm -rf "$out"; mkdir -p "$out/docs/images"
      "$tool" render --out "$out/no_such_dir/t.csv" --quiet 2>"$out.err"; s=$?
      [ $s -eq 1 ] && grep -q "no_such_dir/t.csv" "$out.err" || { echo "render into a missing directory: exit $s"; exit 1; }
      "$tool" report --data "$out/none.csv" --docs "$out/docs" 2>"$out.err"; s=$?
      [ $s -eq 1 ] && grep -q "none.csv" "$out.err" || { echo "missing truth: exit $s"; exit 1; }
      "$tool" render --out "$out/t.csv" --table-paths 64 --panorama-paths 4 --threads 2 --quiet || { echo "render failed"; exit 1; }
      [ "$(grep -c '^table,' "$out/t.csv")" -eq 35 ] && [ "$(grep -c '^panorama,' "$out/t.csv")" -eq 4320 ] ||
        { echo "want 35 table and 4320 panorama rows"; exit 1; }
      "$tool" report --data "$out/t.csv" --docs "$out/docs" >/dev/null || { echo "report failed"; exit 1; }
      for f in atmosphere_truth.md images/atmosphere_sun_90.png images/atmosphere_sun_m2.png; do
        [ -s "$out/docs/$f" ] || { echo "missing $f"; exit 1; }
      done
      # A malformed row and a truncated file: exit 1 naming the file.
      sed '5s/,0\./,x./' "$out/t.csv" >"$out/bad.csv"
      "$tool" report --data "$out/bad.csv" --docs "$out/docs" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "bad.csv:5: malformed row" "$out.err" || { echo "malformed: exit $s"; cat "$out.err"; exit 1; }
      head -n 20 "$out/t.csv" >"$out/short.csv"
      "$tool" report --data "$out/short.csv" --docs "$out/docs" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "short.csv: 16 rows" "$out.err" || { echo "truncated: exit $s"; cat "$out.err"; exit 1; }
      # The committed report is what the stored truth gives.
      mkdir -p "$out/committed/images"
      "$tool" report --data "$src/docs/data/atmosphere_truth.csv" --docs "$out/committed" >/dev/null || { echo "report of the stored truth failed"; exit 1; }
      sed "s|$src/||" "$out/committed/atmosphere_truth.md" | cmp -s - "$src/docs/atmosphere_truth.md" ||
        { echo "docs/atmosphere_truth.md differs from the report of the stored truth"; exit 1; }
      "$tool" report --set holdout --data "$src/docs/data/atmosphere_holdout.csv" --docs "$out/committed" >/dev/null ||
        { echo "report of the stored held-out truth failed"; exit 1; }
      sed "s|$src/||" "$out/committed/atmosphere_holdout.md" | cmp -s - "$src/docs/atmosphere_holdout.md" ||
        { echo "docs/atmosphere_holdout.md differs from the report of the stored held-out truth"; exit 1; }
      for f in "$out"/committed/images/*.png; do
        cmp -s "$f" "$src/docs/images/$(basename "$f")" || { echo "docs/images/$(basename "$f") differs"; exit 1; }
      done
      "$tool" report --set elsewhere 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad set: exit $s, want 2"; exit 1; }
      "$tool" variants --set holdout --data "$out/t.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "t.csv: row 1 is not the set's" "$out.err" || { echo "variants of the wrong set: exit $s"; cat "$out.err"; exit 1; }
      # ground: a bad count -> 2; a tiny run prints the 20 rows (5 suns x 4 views) and its paths.
      "$tool" ground --paths 0 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "ground --paths 0: exit $s, want 2"; exit 1; }
      "$tool" ground --paths 50 --threads 2 >"$out/ground.md" || { echo "ground failed"; exit 1; }
      [ "$(grep -c '^| -\{0,1\}[0-9]* | [0-9]* m |' "$out/ground.md")" -eq 20 ] || { echo "ground: want 20 rows"; cat "$out/ground.md"; exit 1; }
      grep -q '^50 paths per channel and view' "$out/ground.md" || { echo "ground: no paths line"; exit 1; }
      # horizon: a tiny trace writes the 16 views; the table of the stored truth is the one in
      # docs/atmosphere.md, line for line; a file of another set is refused.
      "$tool" horizon --out "$out/h.csv" --paths 0 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "horizon --paths 0: exit $s, want 2"; exit 1; }
      "$tool" horizon --out "$out/h.csv" --paths 40 --threads 2 --quiet || { echo "horizon trace failed"; exit 1; }
      [ "$(grep -c '^horizon,up' "$out/h.csv")" -eq 16 ] || { echo "horizon: want 16 rows"; exit 1; }
      "$tool" horizon --data "$out/h.csv" | grep -q '^| 60 | 10 up | away |' || { echo "horizon: no table of a tiny trace"; exit 1; }
      "$tool" horizon --data "$out/t.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "t.csv: 4355 rows, the set has 16" "$out.err" || { echo "horizon of the wrong file: exit $s"; cat "$out.err"; exit 1; }
      "$tool" horizon --data "$src/docs/data/atmosphere_horizon.csv" >"$out/horizon.md" || { echo "horizon of the stored truth failed"; exit 1; }
      [ "$(grep -c '^|' "$out/horizon.md")" -eq 18 ] || { echo "horizon: want a table of 16 rows"; exit 1; }
      while IFS= read -r line; do
        [ -z "$line" ] || grep -qxF -- "$line" "$src/docs/atmosphere.md" ||
          { echo "docs/atmosphere.md lacks the horizon table's line: $line"; exit 1; }
      done <"$out/horizon.md"
      exit 0
      ]=] sh $<TARGET_FILE:cloudmath_atmosphere_truth> "${CMAKE_CURRENT_BINARY_DIR}/atmosphere_truth_cli_test"
        "${PROJECT_SOURCE_DIR}")
endif()
