#!/bin/sh
# The ctest drivers of web/test/wgsl_parity.mjs (web/CMakeLists.txt).
#
#   sh wgsl_parity_check.sh run TEST_GLSL_PARITY WORK_DIR NODE CHROMIUM
#     web.wgsl_parity: the cases and C++ outputs (test_glsl_parity --dump-cases), one WGSL body
#     per program of the dump (make_parity_shader.mjs --target wgsl --program K), then every
#     case on Chromium's WebGPU within its budget (what scripts/wgsl-parity.sh does, without
#     writing docs/wgsl_parity.md).
#   sh wgsl_parity_check.sh detects-error WORK_DIR NODE CHROMIUM
#     web.wgsl_parity_detects_error: the runner itself can fail. On a small hand-written fixture
#     (program 0: two main cases, program 1: one configuration case): the correct bodies pass,
#     given as --program K FILE; a body with a WGSL
#     type error fails with the compiler's message and the offending source line; a body that
#     returns a + 1.0 for one case and Inf for another fails with those rows out of budget and
#     with NaN/Inf.
set -eu
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
mode="${1:?usage: wgsl_parity_check.sh run|detects-error ...}"
shift

case "$mode" in
run)
  parity="$1" work="$2" node="$3" chromium="$4"
  rm -rf "$work" && mkdir -p "$work"
  "$parity" --dump-cases "$work/cases.json"
  count="$("$node" -e 'console.log(JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")).programs.length)' "$work/cases.json")"
  bodies="" k=0
  while [ "$k" -lt "$count" ]; do
    "$node" "$root/tests/shader_parity/make_parity_shader.mjs" --target wgsl --cases "$work/cases.json" --program "$k" --out "$work/program$k.wgsl"
    bodies="$bodies --program $k $work/program$k.wgsl"
    k=$((k + 1))
  done
  # shellcheck disable=SC2086 # $bodies: words on purpose (the work dir has no spaces: cmake's binary dir)
  exec "$node" "$here/wgsl_parity.mjs" --cases "$work/cases.json" $bodies --chromium "$chromium"
  ;;
detects-error)
  work="$1" node="$2" chromium="$3"
  rm -rf "$work" && mkdir -p "$work"
  # Exactly representable values: the expected outputs are exact.
  cat > "$work/cases.json" <<'JSON'
{"prelude": "", "after": "", "config_defines": "", "programs": [{"config": false, "cases": 2}, {"config": true, "cases": 1}], "cases": [
 {"function": "fixture_saturate", "glsl": "vec4(clamp(a.xyz, 0.0, 1.0), 0.0)", "components": 3, "floor": 1e-30, "budget": 1e-05, "config": false, "program": 0, "index": 0,
  "inputs": [[-2,0.25,1.5,0, 0,0,0,0], [0.5,-0.5,1,0, 0,0,0,0], [3,0,0.75,0, 0,0,0,0]],
  "expected": [[0,0.25,1,0], [0.5,0,1,0], [1,0,0.75,0]]},
 {"function": "fixture_mad", "glsl": "vec4(a.x * b.x + a.y)", "components": 1, "floor": 1, "budget": 0, "config": false, "program": 0, "index": 1,
  "inputs": [[2,1,0,0, 3,0,0,0], [-0.5,4,0,0, 2,0,0,0], [0,7,0,0, 9,0,0,0]],
  "expected": [[7,0,0,0], [3,0,0,0], [7,0,0,0]]},
 {"function": "fixture_mad [CONFIG]", "glsl": "vec4(a.x * b.x + a.y)", "components": 1, "floor": 1, "budget": 0, "config": true, "program": 1, "index": 0,
  "inputs": [[2,1,0,0, 3,0,0,0], [0.25,0,0,0, 4,0,0,0]],
  "expected": [[7,0,0,0], [1,0,0,0]]}
]}
JSON
  cat > "$work/main.wgsl" <<'WGSL'
fn fixture_saturate(x: vec3f) -> vec3f {
    return clamp(x, vec3f(0.0), vec3f(1.0));
}
fn fixture_mad(a: f32, b: f32, c: f32) -> f32 {
    return a * b + c;
}
fn cm_test_case(c: i32, a: vec4f, b: vec4f) -> vec4f {
    if (c == 0) { return vec4f(fixture_saturate(a.xyz), 0.0); }
    if (c == 1) { return vec4f(fixture_mad(a.x, b.x, a.y)); }
    return vec4f(0.0);
}
WGSL
  cat > "$work/config.wgsl" <<'WGSL'
fn cm_test_case(c: i32, a: vec4f, b: vec4f) -> vec4f {
    if (c == 0) { return vec4f(a.x * b.x + a.y); }
    return vec4f(0.0);
}
WGSL
  # A WGSL type error (an f32 initializer for an i32) on line 5 of the body.
  sed 's/return a \* b + c;/let wrong_type: i32 = 1.5; return a * b + c;/' "$work/main.wgsl" > "$work/main_error.wgsl"
  # Wrong values: a + 1.0 for case 0, Inf for case 1 (1 / 0 at run time).
  sed -e 's/return vec4f(fixture_saturate(a.xyz), 0.0);/return vec4f(fixture_saturate(a.xyz), 0.0) + 1.0;/' \
      -e 's/return vec4f(fixture_mad(a.x, b.x, a.y));/return vec4f(fixture_mad(a.x, b.x, a.y) \/ a.z);/' \
      "$work/main.wgsl" > "$work/main_wrong.wgsl"
  cmp -s "$work/main.wgsl" "$work/main_error.wgsl" && { echo "FAIL: the error fixture was not made"; exit 1; }
  cmp -s "$work/main.wgsl" "$work/main_wrong.wgsl" && { echo "FAIL: the wrong-value fixture was not made"; exit 1; }

  run() {  # BODY LOG: the runner's exit status, its output in LOG
    status=0
    "$node" "$here/wgsl_parity.mjs" --cases "$work/cases.json" --program 0 "$1" --program 1 "$work/config.wgsl" --chromium "$chromium" > "$2" 2>&1 || status=$?
    return 0
  }
  expect() {  # LOG PATTERN WHAT
    grep -q -- "$2" "$1" || { echo "FAIL: $3: no line matching '$2' in the runner's output:"; cat "$1"; exit 1; }
  }

  run "$work/main.wgsl" "$work/good.log"
  [ "$status" -eq 0 ] || { echo "FAIL: the correct fixture does not pass (exit $status):"; cat "$work/good.log"; exit 1; }
  expect "$work/good.log" '^PASSED: 3 functions, 3 cases' "the correct fixture"
  echo "ok   the correct fixture passes"

  run "$work/main_error.wgsl" "$work/error.log"
  [ "$status" -eq 1 ] || { echo "FAIL: a body with a WGSL error exits $status, not 1:"; cat "$work/error.log"; exit 1; }
  expect "$work/error.log" "^error: .*main_error.wgsl:5:[0-9]*: " "the compiler's error with file and line"
  expect "$work/error.log" '^ *5 | .*let wrong_type: i32 = 1.5;' "the offending source line"
  expect "$work/error.log" 'does not compile' "the compile failure in the summary"
  echo "ok   a WGSL error fails the run: $(grep -m1 '^error: ' "$work/error.log")"

  run "$work/main_wrong.wgsl" "$work/wrong.log"
  [ "$status" -eq 1 ] || { echo "FAIL: wrong values exit $status, not 1:"; cat "$work/wrong.log"; exit 1; }
  expect "$work/wrong.log" '^  - fixture_saturate: max error .* out of budget' "the a + 1.0 case out of budget"
  expect "$work/wrong.log" '^  - fixture_mad: [0-9]* NaN/Inf where the C++ is finite' "the Inf case counted as NaN/Inf"
  expect "$work/wrong.log" '^fixture_mad \[CONFIG\] .* 0  $' "the untouched configuration case still passing"
  echo "ok   wrong values fail the run: $(grep -c '^  - ' "$work/wrong.log") failures listed"
  echo "the WGSL parity runner detects compile errors, values out of budget and NaN/Inf"
  ;;
*)
  echo "usage: wgsl_parity_check.sh run|detects-error ..." >&2
  exit 2
  ;;
esac
