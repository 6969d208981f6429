# tools/reference/truths/volume_truth.cmake: ground truth for whole cloud images (included by
# CMakeLists.txt; needs the example renderer's core, so it is built with the examples).
#   cloudmath_volume_tracer_lib  transport/volume_tracer.cpp: delta/ratio-tracking path tracer for
#                                heterogeneous media; transport/cloud_medium.cpp: the renderer's clouds,
#                                sky and camera as its medium and light; transport/truth_checkpoint.cpp:
#                                a render that stops and resumes across sessions
#   cloudmath_volume_truth       the CLI: `render` path-traces a preset into docs/data,
#                                `report` compares the renderer's variants with it
#                                (docs/lighting_truth.md; truths/volume_truth_main.cpp)
#   reference.volume_tracer      validation against transport/montecarlo.hpp, determinism, majorants
#   reference.truth_checkpoint   a render stopped and resumed is the uninterrupted one to the
#                                bit; malformed and mismatched checkpoints refused
#   reference.volume_truth_cli   command-line errors and a tiny render + report
#   reference.volume_truth_report the documented errors reproduced from the stored truth
add_library(cloudmath_volume_tracer_lib STATIC transport/volume_tracer.cpp transport/cloud_medium.cpp transport/truth_checkpoint.cpp)
cloudmath_reference_target(cloudmath_volume_tracer_lib)
target_include_directories(cloudmath_volume_tracer_lib PUBLIC ${cloudmath_reference_include_dirs})
target_link_libraries(cloudmath_volume_tracer_lib PUBLIC cloudmath_montecarlo_lib cloud_renderer_core)

add_executable(cloudmath_volume_truth truths/volume_truth_main.cpp)
cloudmath_reference_target(cloudmath_volume_truth)
target_link_libraries(cloudmath_volume_truth PRIVATE cloudmath_volume_tracer_lib cloudmath_lighting_lib  # read_clouds_model
  cloudmath_tools_gzip)  # the truths stored as .csv.gz

if(CLOUDMATH_BUILD_TESTS)
  cloudmath_reference_test(truth_checkpoint transport/test_truth_checkpoint.cpp)
  target_link_libraries(cloudmath_reference_test_truth_checkpoint PRIVATE cloudmath_volume_tracer_lib)
  cloudmath_reference_test(volume_tracer transport/test_volume_tracer.cpp)
  target_link_libraries(cloudmath_reference_test_volume_tracer PRIVATE cloudmath_volume_tracer_lib)
  target_compile_definitions(cloudmath_reference_test_volume_tracer PRIVATE
    "CLOUDMATH_TRUTH_TEST_CACHE=\"${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache\"")
endif()

if(CLOUDMATH_BUILD_TESTS)
  # The CLI: bad command lines -> 2, a missing truth file -> 1 naming it, and a tiny render
  # turned into a report (every output file written).
  add_test(NAME reference.volume_truth_cli
    COMMAND sh -c [=[
      set -u
      tool=$1 out=$2 cache=$3
      "$tool" 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "no command: exit $s, want 2"; exit 1; }
      "$tool" --help >/dev/null || { echo "--help failed"; exit 1; }
      "$tool" render --bogus 1 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad flag: exit $s, want 2"; exit 1; }
      "$tool" render --preset nowhere --out x.csv 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad preset: exit $s, want 2"; exit 1; }
      "$tool" render --preset ground --phase hg:2 --out x.csv 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad phase: exit $s, want 2"; exit 1; }
      "$tool" render --preset ground --spp 0 --out x.csv 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad spp: exit $s, want 2"; exit 1; }
      "$tool" report --variant "x=phase=nope" 2>/dev/null; s=$?; [ $s -eq 2 ] || { echo "bad variant: exit $s, want 2"; exit 1; }
      for bad in "--noise-target 0.03 --spp 8" "--noise-target 0" "--noise-target 1" "--noise-target nan" \
                 "--pilot-spp 8" "--noise-target 0.1 --pilot-spp 1" "--noise-target 0.1 --min-spp 9 --max-spp 8"; do
        "$tool" render --preset ground --out x.csv $bad 2>/dev/null; s=$?
        [ $s -eq 2 ] || { echo "render $bad: exit $s, want 2"; exit 1; }
      done
      rm -rf "$out"; mkdir -p "$out/docs/images"
      "$tool" report --data "$out/none" --docs "$out/docs" --cache "$cache" 2>"$out.err"; s=$?
      [ $s -eq 1 ] || { echo "missing truth: exit $s, want 1"; exit 1; }
      grep -q "truth_ground.csv" "$out.err" || { echo "message does not name the path"; exit 1; }
      "$tool" render --preset ground --sky artistic --width 8 --height 4 --spp 2 --threads 2 --cache "$cache" --quiet \
        --out "$out/truth_ground.csv" >/dev/null || { echo "render failed"; exit 1; }
      [ "$(grep -c '^[0-9]' "$out/truth_ground.csv")" -eq 32 ] || { echo "want 32 pixel rows"; exit 1; }
      grep -q '^r,g,b,se_r,se_g,se_b$' "$out/truth_ground.csv" || { echo "no header"; exit 1; }
      grep -q '^# allocation: uniform$' "$out/truth_ground.csv" || { echo "no uniform allocation line"; exit 1; }
      grep -q '^# sky: artistic$' "$out/truth_ground.csv" || { echo "no artistic sky line"; exit 1; }
      # --sky: the file says which sky it was traced under; the report renders the model under
      # it and refuses truths traced under two skies.
      "$tool" render --preset ground --sky blue --out x.csv 2>/dev/null; s=$?
      [ $s -eq 2 ] || { echo "bad sky: exit $s, want 2"; exit 1; }
      # The report makes DOCS/images itself (here: physical/ has none).
      mkdir -p "$out/physical" "$out/mixed/images"
      # No --sky: the presets' own sky, the physical one.
      "$tool" render --preset ground --width 8 --height 4 --spp 2 --threads 2 --cache "$cache" --quiet \
        --out "$out/physical/truth_ground.csv" >/dev/null || { echo "physical render failed"; exit 1; }
      grep -q '^# sky: physical$' "$out/physical/truth_ground.csv" || { echo "no physical sky line"; exit 1; }
      grep '^[0-9]' "$out/truth_ground.csv" >"$out/artistic.rows"; grep '^[0-9]' "$out/physical/truth_ground.csv" >"$out/physical.rows"
      cmp -s "$out/artistic.rows" "$out/physical.rows" && { echo "the physical sky changed no pixel"; exit 1; }
      "$tool" report --presets ground --variant "default=" --data "$out/physical" --docs "$out/physical" --cache "$cache" \
        --quiet >/dev/null || { echo "physical report failed"; exit 1; }
      grep -qF '`--sky physical`' "$out/physical/lighting_truth.md" || { echo "physical report does not name its sky"; exit 1; }
      [ -f "$out/physical/images/truth_ground.png" ] || { echo "the report did not make its images folder"; exit 1; }
      # A --docs folder that cannot be made fails before any rendering, with the path.
      : > "$out/a_file"
      "$tool" report --presets ground --variant "default=" --data "$out/physical" --docs "$out/a_file/docs" --cache "$cache" \
        --quiet >/dev/null 2>"$out.err"; s=$?
      [ $s -eq 1 ] && grep -qF "cannot make $out/a_file/docs/images" "$out.err" || { echo "unmakeable --docs: exit $s"; cat "$out.err"; exit 1; }
      # A truth over a scene that has changed since (its fingerprint differs): the report marks it
      # stale, in its section and in the summary; the truth of the scene as it is, not.
      grep -q "scene that has changed since" "$out/physical/lighting_truth.md" && { echo "a current truth marked stale"; exit 1; }
      mkdir -p "$out/stale/images"
      grep -q '^# scene: [0-9a-f]\{16\}$' "$out/physical/truth_ground.csv" || { echo "no scene line"; exit 1; }
      sed 's/^# scene: .*/# scene: 0123456789abcdef/' "$out/physical/truth_ground.csv" >"$out/stale/truth_ground.csv"
      "$tool" report --presets ground --variant "default=" --data "$out/stale" --docs "$out/stale" --cache "$cache" \
        --quiet >/dev/null || { echo "report of a stale truth failed"; exit 1; }
      [ "$(grep -c "scene that has changed since" "$out/stale/lighting_truth.md")" -eq 2 ] &&
        grep -q "traces them again): ground\.$" "$out/stale/lighting_truth.md" ||
        { echo "a stale truth not marked"; exit 1; }
      cp "$out/physical/truth_ground.csv" "$out/mixed/"
      sed 's/^# preset: ground$/# preset: inside/; s/^# sky: physical$/# sky: artistic/' "$out/physical/truth_ground.csv" \
        >"$out/mixed/truth_inside.csv"
      "$tool" report --presets ground,inside --data "$out/mixed" --docs "$out/mixed" --cache "$cache" --quiet \
        2>"$out.err" >/dev/null; s=$?
      [ $s -eq 2 ] && grep -q "one report, one sky" "$out.err" || { echo "two skies in one report: exit $s"; cat "$out.err"; exit 1; }
      # --light: the truth split by source (the physical sky only); with the same seed and paths the
      # sun's and the sky's files add up to the whole's, row by row; the report renders the model
      # with the same light and refuses two lights in one report.
      "$tool" render --preset ground --sky artistic --light sun --out x.csv 2>"$out.err"; s=$?
      [ $s -eq 2 ] && grep -q "needs the physical sky" "$out.err" || { echo "--light sun, artistic sky: exit $s"; exit 1; }
      "$tool" render --preset ground --sky physical --light moon --out x.csv 2>/dev/null; s=$?
      [ $s -eq 2 ] || { echo "--light moon: exit $s, want 2"; exit 1; }
      mkdir -p "$out/light/images"
      for l in all sun sky; do
        "$tool" render --preset sunrise --light $l --width 8 --height 4 --spp 16 --threads 2 --cache "$cache" --quiet \
          --out "$out/light/$l.csv" >/dev/null || { echo "render --light $l failed"; exit 1; }
      done
      grep -q '^# light: sun$' "$out/light/sun.csv" || { echo "no light line"; exit 1; }
      paste -d, "$out/light/all.csv" "$out/light/sun.csv" "$out/light/sky.csv" | grep '^[0-9]' | awk -F, '
        { for (c = 1; c <= 3; ++c) { whole = $c; parts = $(c + 6) + $(c + 12); d = whole - parts; if (d < 0) d = -d
            if (d > 1e-5 * (whole > 1 ? whole : 1)) bad++ } n++ }
        END { if (n != 32 || bad) { print "the sun and the sky do not add up to the whole: " bad + 0 " of " n " rows"; exit 1 } }' ||
        exit 1
      cp "$out/light/sun.csv" "$out/light/truth_sunrise.csv"
      "$tool" report --presets sunrise --variant "default=" --data "$out/light" --docs "$out/light" --cache "$cache" \
        --quiet >/dev/null || { echo "sun-alone report failed"; exit 1; }
      grep -qF 'Light: **the sun alone**' "$out/light/lighting_truth.md" || { echo "the report does not name its light"; exit 1; }
      sed 's/^# preset: sunrise$/# preset: sunset/' "$out/light/sky.csv" >"$out/light/truth_sunset.csv"
      "$tool" report --presets sunrise,sunset --data "$out/light" --docs "$out/light" --cache "$cache" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 2 ] && grep -q "one report, one light" "$out.err" || { echo "two lights in one report: exit $s"; cat "$out.err"; exit 1; }
      # --orders 1: single scattering. In stratus lit by the sun alone most of the light is
      # scattered more than once: the single-scattering image's sum is well under half the whole's
      # (measured 11.7% at 256 paths a pixel; 64 here, 3 s) and not nil.
      mkdir -p "$out/orders"
      for o in 0 1; do
        "$tool" render --preset stratus --light sun --orders $o --width 8 --height 4 --spp 64 --threads 2 --cache "$cache" --quiet \
          --out "$out/orders/stratus_$o.csv" >/dev/null || { echo "render --orders $o failed"; exit 1; }
      done
      grep -q '^# orders: 1$' "$out/orders/stratus_1.csv" || { echo "no orders line"; exit 1; }
      grep -q '^# orders:' "$out/orders/stratus_0.csv" && { echo "an orders line for every order"; exit 1; }
      paste -d, "$out/orders/stratus_0.csv" "$out/orders/stratus_1.csv" | grep '^[0-9]' | awk -F, '
        { for (c = 1; c <= 3; ++c) { all += $c; single += $(c + 6) } n++ }
        END { if (n != 32 || !(single > 0) || !(single < 0.5 * all)) { print "single " single " against every order " all; exit 1 } }' ||
        exit 1
      "$tool" render --preset sunrise --light sun --orders 1 --width 8 --height 4 --spp 16 --threads 2 --cache "$cache" --quiet \
        --out "$out/orders/truth_sunrise.csv" >/dev/null || { echo "render --orders 1 failed"; exit 1; }
      "$tool" report --presets sunrise --variant "single=lighting=octaves,octaves=1" --data "$out/orders" --docs "$out/orders" \
        --cache "$cache" --quiet >/dev/null || { echo "orders report failed"; exit 1; }
      grep -qF 'Orders: **light scattered at most 1 time**' "$out/orders/lighting_truth.md" || { echo "the report does not name its orders"; exit 1; }
      sed 's/^# preset: sunrise$/# preset: sunset/' "$out/light/sun.csv" >"$out/orders/truth_sunset.csv"
      "$tool" report --presets sunrise,sunset --data "$out/orders" --docs "$out/orders" --cache "$cache" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 2 ] && grep -q "one report, one order limit" "$out.err" || { echo "two order limits in one report: exit $s"; cat "$out.err"; exit 1; }
      "$tool" fit-clouds --fit classic:sunrise,classic:sunset --eval classic:ground --data "$out/orders" --cache "$cache" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "was traced with --orders 1 (a diagnosis" "$out.err" || { echo "fit-clouds on a single-scattering truth: exit $s"; cat "$out.err"; exit 1; }
      # Adaptive sampling: a pilot, then the paths for a noise floor; the file says so.
      "$tool" render --preset ground --width 8 --height 4 --noise-target 0.5 --pilot-spp 4 --min-spp 4 --threads 2 \
        --cache "$cache" --quiet --out "$out/adaptive.csv" >/dev/null || { echo "adaptive render failed"; exit 1; }
      [ "$(grep -c '^[0-9]' "$out/adaptive.csv")" -eq 32 ] || { echo "adaptive: want 32 pixel rows"; exit 1; }
      grep -q '^# allocation: adaptive for a noise floor of 50.0% (pilot 4 spp' "$out/adaptive.csv" || { echo "adaptive: no allocation line"; exit 1; }
      grep -q '^# noise floor: [0-9.]*%$' "$out/adaptive.csv" || { echo "adaptive: no noise floor line"; exit 1; }
      [ ! -e "$out/adaptive.csv.checkpoint" ] || { echo "a finished render left its checkpoint"; exit 1; }
      # A time budget stops the render cleanly (exit 3, the checkpoint kept, no truth file);
      # --resume finishes it with the numbers of the uninterrupted render; a checkpoint is never
      # overwritten without --resume, and one of another run is refused naming what differs.
      ck="--preset ground --width 8 --height 4 --noise-target 0.5 --pilot-spp 4 --min-spp 4 --threads 2 --cache $cache --quiet"
      "$tool" render $ck --budget-minutes 0.0001 --out "$out/resumed.csv" >"$out.log"; s=$?
      [ $s -eq 3 ] && [ -s "$out/resumed.csv.checkpoint" ] && [ ! -e "$out/resumed.csv" ] ||
        { echo "budget: exit $s, want 3 with a checkpoint and no truth"; exit 1; }
      grep -q "continue with --resume" "$out.log" || { echo "budget: no word on resuming"; exit 1; }
      head -c 27 "$out/resumed.csv.checkpoint" | grep -q "cloudmath truth checkpoint" || { echo "not a checkpoint"; exit 1; }
      "$tool" render $ck --out "$out/resumed.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "resumed.csv.checkpoint: a checkpoint of an unfinished render is there" "$out.err" ||
        { echo "an existing checkpoint without --resume: exit $s"; cat "$out.err"; exit 1; }
      "$tool" render $ck --seed 2 --resume --out "$out/resumed.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "the checkpoint's seed is '1', this run's '2'" "$out.err" ||
        { echo "resume with another seed: exit $s"; cat "$out.err"; exit 1; }
      "$tool" render $ck --sky artistic --resume --out "$out/resumed.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "the checkpoint's sky is 'physical', this run's 'artistic'" "$out.err" || { echo "resume under another sky: exit $s"; cat "$out.err"; exit 1; }
      "$tool" render $ck --resume --out "$out/none.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "none.csv.checkpoint: no checkpoint to resume" "$out.err" || { echo "resume nothing: exit $s"; exit 1; }
      cp "$out/resumed.csv.checkpoint" "$out/damaged.checkpoint"
      printf 'x' >>"$out/damaged.checkpoint"
      "$tool" render $ck --resume --checkpoint "$out/damaged.checkpoint" --out "$out/damaged.csv" 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "damaged.checkpoint: bytes after the end line" "$out.err" || { echo "damaged: exit $s"; cat "$out.err"; exit 1; }
      "$tool" render $ck --resume --out "$out/resumed.csv" >/dev/null || { echo "resume failed"; exit 1; }
      [ ! -e "$out/resumed.csv.checkpoint" ] || { echo "the resumed render left its checkpoint"; exit 1; }
      grep -q '^# runs: 2$' "$out/resumed.csv" || { echo "resumed: want 2 runs"; exit 1; }
      grep '^[0-9]' "$out/adaptive.csv" >"$out/a.rows"; grep '^[0-9]' "$out/resumed.csv" >"$out/r.rows"
      cmp -s "$out/a.rows" "$out/r.rows" || { echo "the resumed render differs from the uninterrupted one"; exit 1; }
      for bad in "--budget-minutes 0" "--budget-minutes -1" "--budget-minutes nan"; do
        "$tool" render --preset ground --out x.csv $bad 2>/dev/null; s=$?
        [ $s -eq 2 ] || { echo "render $bad: exit $s, want 2"; exit 1; }
      done
      "$tool" report --presets ground --variant "default=" --variant "march=light=march" --data "$out" \
        --docs "$out/docs" --cache "$cache" --quiet >/dev/null || { echo "report failed"; exit 1; }
      for f in lighting_truth.md images/truth_ground.png; do
        [ -s "$out/docs/$f" ] || { echo "missing $f"; exit 1; }
      done
      grep -q "| march |" "$out/docs/lighting_truth.md" || { echo "report lacks the variant"; exit 1; }
      # One image a preset unless --variant-images asks for the other variants' too.
      [ ! -e "$out/docs/images/truth_ground_march.png" ] || { echo "an image of the second variant without --variant-images"; exit 1; }
      grep -q "truth_ground_march.png" "$out/docs/lighting_truth.md" && { echo "the report links an image it did not write"; exit 1; }
      "$tool" report --presets ground --variant "default=" --variant "march=light=march" --data "$out" \
        --docs "$out/all" --cache "$cache" --quiet --variant-images >/dev/null || { echo "report --variant-images failed"; exit 1; }
      [ -s "$out/all/images/truth_ground_march.png" ] || { echo "--variant-images wrote no image of the second variant"; exit 1; }
      grep -q "(images/truth_ground_march.png)" "$out/all/lighting_truth.md" || { echo "--variant-images: no link to it"; exit 1; }
      cmp -s "$out/all/images/truth_ground.png" "$out/docs/images/truth_ground.png" || { echo "--variant-images changed the first image"; exit 1; }
      # The stored form (docs/data/truth_*.csv.gz): the report reads a gzip-compressed truth
      # as it reads the plain one, to the byte; render --out F.csv.gz writes gzip; a damaged
      # file is an error naming it.
      mkdir -p "$out/gz"
      gzip -9nc "$out/truth_ground.csv" >"$out/gz/truth_ground.csv.gz"
      "$tool" report --presets ground --variant "default=" --variant "march=light=march" --data "$out/gz" \
        --docs "$out/gzdocs" --cache "$cache" --quiet >/dev/null || { echo "report over .csv.gz failed"; exit 1; }
      cmp -s "$out/gzdocs/lighting_truth.md" "$out/docs/lighting_truth.md" || { echo "the report over .csv.gz differs"; exit 1; }
      cmp -s "$out/gzdocs/images/truth_ground.png" "$out/docs/images/truth_ground.png" || { echo "its image differs"; exit 1; }
      "$tool" render --preset ground --sky artistic --width 8 --height 4 --spp 2 --threads 2 --cache "$cache" --quiet \
        --out "$out/gz/rendered.csv.gz" >/dev/null || { echo "render to .csv.gz failed"; exit 1; }
      [ "$(od -An -tx1 -N2 "$out/gz/rendered.csv.gz" | tr -d ' ')" = 1f8b ] || { echo "render --out .csv.gz wrote no gzip"; exit 1; }
      gzip -dc "$out/gz/rendered.csv.gz" | grep '^[0-9]' >"$out/gz.rows"
      grep '^[0-9]' "$out/truth_ground.csv" | cmp -s - "$out/gz.rows" || { echo "the .csv.gz's pixels are not the plain render's"; exit 1; }
      head -c 300 "$out/gz/truth_ground.csv.gz" >"$out/gz/cut" && mv "$out/gz/cut" "$out/gz/truth_ground.csv.gz"
      "$tool" report --presets ground --variant "default=" --data "$out/gz" --docs "$out/gzdocs" --cache "$cache" --quiet \
        >/dev/null 2>"$out.err"; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv.gz: the gzip stream is truncated" "$out.err" || { echo "truncated .csv.gz: exit $s"; cat "$out.err"; exit 1; }
      for section in "## Excess error" "## PSNR of the display images" "| variant | rms | excess | bias |"; do
        grep -qF "$section" "$out/docs/lighting_truth.md" || { echo "report lacks '$section'"; exit 1; }
      done
      # fit-clouds: bad command lines -> 2; a fit over two tiny truths writes every number,
      # --check accepts its own file and rejects a changed one (exit 1).
      for bad in "--fit classic:ground" "--fit ground,inside" "--fit classic:ground,classic:nowhere" \
                 "--fit classic:ground,flat:inside" "--ridge -1" "--ridge nan" "--variant lighting=octaves" \
                 "--fit classic:ground,classic:inside --eval classic:ground"; do
        "$tool" fit-clouds $bad 2>/dev/null; s=$?
        [ $s -eq 2 ] || { echo "fit-clouds $bad: exit $s, want 2"; exit 1; }
      done
      "$tool" fit-clouds --data "$out/none" --cache "$cache" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "none/truth_sun_behind.csv" "$out.err" || { echo "fit-clouds, missing truth: exit $s"; exit 1; }
      "$tool" render --preset inside --sky artistic --width 8 --height 4 --spp 2 --threads 2 --cache "$cache" --quiet \
        --out "$out/truth_inside.csv" >/dev/null || { echo "render inside failed"; exit 1; }
      "$tool" fit-clouds --fit classic:ground,classic:inside --data "$out" --cache "$cache" --quiet \
        --out "$out/fit.txt" >/dev/null || { echo "fit-clouds failed"; exit 1; }
      [ "$(grep -c '^table,' "$out/fit.txt")" -eq 135 ] && [ "$(grep -c '^peak,' "$out/fit.txt")" -eq 6 ] ||
        { echo "fit-clouds: want 135 table and 6 peak rows"; exit 1; }
      grep -q '^# chosen ridge' "$out/fit.txt" || { echo "fit-clouds: no chosen ridge"; exit 1; }
      "$tool" fit-clouds --fit classic:ground,classic:inside --data "$out" --cache "$cache" --quiet \
        --check "$out/fit.txt" >/dev/null 2>&1 || { echo "fit-clouds --check rejects its own fit"; exit 1; }
      sed 's/^peak,0,.*/peak,0,123/' "$out/fit.txt" >"$out/changed.txt"
      "$tool" fit-clouds --fit classic:ground,classic:inside --data "$out" --cache "$cache" --quiet \
        --check "$out/changed.txt" >/dev/null 2>&1; s=$?
      [ $s -eq 1 ] || { echo "fit-clouds --check accepts a changed fit: exit $s"; exit 1; }
      ]=] sh $<TARGET_FILE:cloudmath_volume_truth> "${CMAKE_CURRENT_BINARY_DIR}/volume_truth_cli_test"
        "${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache")
endif()

if(CLOUDMATH_BUILD_TESTS)
  # Truth files are read strictly (sscanf took "0.3xyz" and nan, std::stoi "8xyz"): each
  # malformed file exits 1 naming the path and line, before any texture is loaded; render
  # checks --out before tracing.
  add_test(NAME reference.volume_truth_malformed
    COMMAND sh -c [=[
      set -u
      tool=$1 out=$2
      rm -rf "$out"; mkdir -p "$out"
      head='# preset: ground
# shape: classic
# width: 2
# height: 1
x,y,r,g,b,se_r,se_g,se_b'
      for row in "0,0,0.1,0.2,0.3xyz,0,0,0" "0,0,nan,0.2,0.3,0,0,0" "0,0,0.1,0.2,0.3,0,0,0," "0,0,0.1,0.2,0.3,0,0" \
                 " 0,0,0.1,0.2,0.3,0,0,0" "2,0,0.1,0.2,0.3,0,0,0"; do
        printf '%s\n%s\n' "$head" "$row" >"$out/truth_ground.csv"
        "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
        [ $s -eq 1 ] || { echo "row '$row': exit $s, want 1"; exit 1; }
        grep -q "truth_ground.csv:6: malformed row" "$out.err" || { echo "row '$row': no message naming the line"; cat "$out.err"; exit 1; }
      done
      # A truncated file (one of the 2 pixels) and a pixel given twice: exit 1 naming the file.
      printf '%s\n%s\n' "$head" "0,0,0.1,0.2,0.3,0,0,0" >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv: 1 of 2 pixels" "$out.err" || { echo "truncated: exit $s"; cat "$out.err"; exit 1; }
      printf '%s\n%s\n%s\n' "$head" "1,0,0.1,0.2,0.3,0,0,0" "1,0,0.1,0.2,0.3,0,0,0" >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv:7: pixel 1,0 appears twice" "$out.err" || { echo "duplicate: exit $s"; cat "$out.err"; exit 1; }
      printf '%s\n%s\n%s\n' "$head" "0,0,0.1,0.2,0.3,0,0,0" "1,0,0.1,0.2,0.3,0,0,0" | sed 's/# shape: classic/# shape: classic\n# sky: blue/' \
        >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv: unknown sky 'blue'" "$out.err" || { echo "sky blue: exit $s"; cat "$out.err"; exit 1; }
      # The compact rows (no x, y: the row's place is the pixel), as render writes them now.
      compact=$(printf '%s\n' "$head" | sed 's/^x,y,r,g,b,se_r,se_g,se_b$/r,g,b,se_r,se_g,se_b/')
      printf '%s\n%s\n' "$compact" "0,0,0.1,0.2,0.3,0,0,0" >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv:6: malformed row: expected 6 comma-separated cells" "$out.err" || { echo "compact, 8 cells: exit $s"; cat "$out.err"; exit 1; }
      printf '%s\n%s\n' "$compact" "0.1,0.2,0.3,0,0,0" >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv: 1 of 2 pixels" "$out.err" || { echo "compact, truncated: exit $s"; cat "$out.err"; exit 1; }
      printf '%s\n%s\n%s\n%s\n' "$compact" "0.1,0.2,0.3,0,0,0" "0.1,0.2,0.3,0,0,0" "0.1,0.2,0.3,0,0,0" >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv:8: more rows than the 2 pixels" "$out.err" || { echo "compact, a row too many: exit $s"; cat "$out.err"; exit 1; }
      printf '%s\n%s\n%s\n' "$compact" "0.1,0.2,nan,0,0,0" "0.1,0.2,0.3,0,0,0" >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "truth_ground.csv:6: malformed row: 'nan' is not a finite number" "$out.err" || { echo "compact, nan: exit $s"; cat "$out.err"; exit 1; }
      printf '%s\n' "$head" | sed 's/# width: 2/# width: 2xyz/' >"$out/truth_ground.csv"
      "$tool" report --presets ground --data "$out" --docs "$out" --quiet 2>"$out.err" >/dev/null; s=$?
      [ $s -eq 1 ] && grep -q "width and height metadata" "$out.err" || { echo "width 2xyz: exit $s"; cat "$out.err"; exit 1; }
      "$tool" render --preset ground --out "$out/no_such_dir/t.csv" --cache none --quiet 2>"$out.err"; s=$?
      [ $s -eq 1 ] && grep -q "no_such_dir/t.csv" "$out.err" || { echo "render into a missing directory: exit $s"; cat "$out.err"; exit 1; }
      "$tool" render --preset ground --width " 8" --out "$out/t.csv" 2>/dev/null; s=$?
      [ $s -eq 2 ] || { echo "--width ' 8': exit $s, want 2"; exit 1; }
      exit 0
      ]=] sh $<TARGET_FILE:cloudmath_volume_truth> "${CMAKE_CURRENT_BINARY_DIR}/volume_truth_malformed")
endif()

if(CLOUDMATH_BUILD_TESTS)
  # The error by source (docs/lighting_research.md, "The error by source under the physical
  # sky") is what scripts/split_by_source.sh makes of the two stored reports, line for line;
  # an unreadable report is an error.
  add_test(NAME reference.split_by_source
    COMMAND bash -c [=[
      set -u
      src=$1
      cd "$src" || exit 1
      bash scripts/split_by_source.sh docs/none.md 2>/dev/null && { echo "a missing report accepted"; exit 1; }
      bash scripts/split_by_source.sh >"$2" || { echo "split_by_source.sh failed"; exit 1; }
      [ "$(grep -c '^| [a-z_]* | [0-9]' "$2")" -eq 11 ] || { echo "want 11 presets"; cat "$2"; exit 1; }
      while IFS= read -r line; do
        grep -qxF -- "$line" docs/lighting_research.md || { echo "docs/lighting_research.md lacks: $line"; exit 1; }
      done <"$2"
      ]=] bash "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_BINARY_DIR}/split_by_source.md")
  # The documented whole-cloud errors (docs/lighting_truth.md's summary table: the default's
  # row and the table before it) are what the renderer gives against the stored truth images
  # (docs/data/truth_*.csv), and the whole-cloud fit (docs/data/diffusion_clouds.txt) is what
  # the stored truths give: rerun from the stored data by scripts/truth.sh --check (about a
  # minute each on 2 cores: 8 frames per image).
  add_test(NAME reference.volume_truth_report
    COMMAND bash "${PROJECT_SOURCE_DIR}/scripts/truth.sh" --check $<TARGET_FILE:cloudmath_volume_truth>
            --cache "${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache")
  # The same for the detailed field's truth (docs/data/detailed, docs/detailed).
  add_test(NAME reference.volume_truth_report_detailed
    COMMAND bash "${PROJECT_SOURCE_DIR}/scripts/truth.sh" --check $<TARGET_FILE:cloudmath_volume_truth>
            --shape detailed --cache "${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache")
  # The presets under the physical sky (docs/data/physical, docs/physical_sky; scripts/truth.sh
  # --sky physical): the whole report regenerated from the stored truths must be the documented
  # one to the byte (seconds a preset on 2 cores), so a change to the renderer's physical sun,
  # sky or far shadow, or to the truth's sky, cannot leave it stale.
  add_test(NAME reference.volume_truth_report_physical
    COMMAND bash "${PROJECT_SOURCE_DIR}/scripts/truth.sh" --check $<TARGET_FILE:cloudmath_volume_truth>
            --sky physical --cache "${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache")
  # The detailed field under the physical sky (docs/data/physical/detailed,
  # docs/physical_sky/detailed; every truth at its 5% target): the same byte check, about 90 s
  # on 2 cores.
  add_test(NAME reference.volume_truth_report_physical_detailed
    COMMAND bash "${PROJECT_SOURCE_DIR}/scripts/truth.sh" --check $<TARGET_FILE:cloudmath_volume_truth>
            --sky physical --shape detailed --cache "${CMAKE_CURRENT_BINARY_DIR}/truth_texture_cache")
endif()
