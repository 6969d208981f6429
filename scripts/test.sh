#!/usr/bin/env bash
# Builds everything with tests on and runs the whole ctest suite (unit tests in three
# build variants, header self-containment, coverage, install/consumer tests).
# Usage: bash scripts/test.sh        (from any directory; non-interactive, CI-safe)
# ctest runs last, so its summary ("100% tests passed, ...") is the final line of output.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

jobs="$(nproc 2>/dev/null || echo 2)"
# Release only affects bench/ and examples/: the tests set their own flags per variant.
cmake -S . -B build/test -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCLOUDMATH_BUILD_TESTS=ON -DCLOUDMATH_BUILD_BENCH=ON -DCLOUDMATH_BUILD_EXAMPLES=ON
cmake --build build/test -j "$jobs"
ctest --test-dir build/test --output-on-failure -j "$jobs"
