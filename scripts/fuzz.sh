#!/usr/bin/env bash
# A longer fuzz run than the test suite's: tests/test_fuzz.cpp (every public function on
# random inputs, inside and far outside their domains) built plain, with -ffast-math and with
# AddressSanitizer + UBSan, run with more rounds per case and on other random streams than
# the suite's fixed 4000 rounds. Installs what it needs (scripts/install-deps.sh), builds in
# build/fuzz. Not run by CI (the suite runs the short form, ctest fuzz.*).
#
# Usage: bash scripts/fuzz.sh [ROUNDS] [STREAMS]
#        ROUNDS per case (default 200000, 50 times the suite's), STREAMS seeds 1..STREAMS
#        (default 4; one stream of the three builds took 30 s on 2 cores, after the build).
#        Exits 1 at the first failing run, naming it.
set -euo pipefail
rounds=${1:-200000}
streams=${2:-4}
[[ "$rounds" =~ ^[0-9]+$ && "$streams" =~ ^[0-9]+$ ]] || {
  echo "fuzz: usage: bash scripts/fuzz.sh [ROUNDS] [STREAMS] (whole numbers)" >&2; exit 2; }
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/install-deps.sh
mkdir -p build
if ! { cmake -S . -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOUDMATH_BUILD_TESTS=ON &&
       cmake --build build/fuzz -j "$(nproc 2>/dev/null || echo 2)" --target test_fuzz_plain test_fuzz_fastmath test_fuzz_sanitize; } \
     > build/fuzz-build.log 2>&1; then
  tail -n 30 build/fuzz-build.log >&2
  echo "fuzz: the build failed (log: build/fuzz-build.log)" >&2
  exit 1
fi
for seed in $(seq 1 "$streams"); do
  for variant in plain fastmath sanitize; do
    echo "fuzz: $variant, stream $seed, $rounds rounds per case"
    if ! CLOUDMATH_FUZZ_ROUNDS=$rounds CLOUDMATH_FUZZ_SEED=$seed build/fuzz/tests/test_fuzz_$variant > build/fuzz-last.log 2>&1; then
      tail -n 40 build/fuzz-last.log >&2
      echo "fuzz: FAILED: build/fuzz/tests/test_fuzz_$variant with CLOUDMATH_FUZZ_ROUNDS=$rounds CLOUDMATH_FUZZ_SEED=$seed (log: build/fuzz-last.log)" >&2
      exit 1
    fi
    grep -a 'test cases' build/fuzz-last.log
  done
done
echo "fuzz: every run passed"
