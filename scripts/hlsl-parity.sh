#!/usr/bin/env bash
# Runs the HLSL parity harness (tests/hlsl/hlsl_parity.cmake: the HLSL twins through glslang's
# HLSL front end, spirv-val and spirv-cross, on this machine's OpenGL driver; Mesa llvmpipe
# without a GPU) and writes its table to docs/hlsl_parity.md (or the file given as $1).
# The generated shaders stay in build/test/tests/hlsl_parity.
# Usage: bash scripts/hlsl-parity.sh [OUTPUT.md]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out="${1:-docs/hlsl_parity.md}"

bash scripts/install-deps.sh
if [ ! -f build/test/CMakeCache.txt ]; then
  cmake -S . -B build/test -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOUDMATH_BUILD_TESTS=ON >/dev/null
fi
cmake --build build/test -j "$(nproc 2>/dev/null || echo 2)" --target test_glsl_parity >/dev/null
tool() { command -v "$1" || { echo "hlsl-parity.sh: $1 not found (bash scripts/install-deps.sh installs it)" >&2; exit 1; }; }
node="$(tool node)"; glslang="$(tool glslangValidator)"; spirv_val="$(tool spirv-val)"; spirv_cross="$(tool spirv-cross)"
# CI=true: no OpenGL context is a failure here (cm_gl::no_context_exit_code), not a skip
# that would leave the old table behind. The table is written beside $out and moved there
# only when every function is within budget: a failing run leaves the old table.
table="$out.new"
trap 'rm -f "$table"' EXIT
CI=true cmake -DPARITY=build/test/tests/test_glsl_parity -DNODE="$node" -DGLSLANG="$glslang" \
  -DSPIRV_VAL="$spirv_val" -DSPIRV_CROSS="$spirv_cross" \
  -DMAKE_SHADER=tests/shader_parity/make_parity_shader.mjs \
  -DWORK_DIR=build/test/tests/hlsl_parity -DMARKDOWN="$table" \
  -P tests/hlsl/hlsl_parity.cmake
mv "$table" "$out"
echo "wrote $out"
