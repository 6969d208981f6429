#!/usr/bin/env bash
# Runs the GLSL parity harness on this machine's OpenGL driver (headless EGL: Mesa llvmpipe
# without a GPU) and writes its table to docs/glsl_parity.md (or the file given as $1).
# Usage: bash scripts/glsl-parity.sh [OUTPUT.md]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out="${1:-docs/glsl_parity.md}"

bash scripts/install-deps.sh
if [ ! -f build/test/CMakeCache.txt ]; then
  cmake -S . -B build/test -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOUDMATH_BUILD_TESTS=ON >/dev/null
fi
cmake --build build/test -j "$(nproc 2>/dev/null || echo 2)" --target test_glsl_parity >/dev/null
build/test/tests/test_glsl_parity --markdown "$out"
echo "wrote $out"
