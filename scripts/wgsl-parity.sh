#!/usr/bin/env bash
# Runs the WGSL twins on a real WebGPU implementation (Debian's headless Chromium: WebGPU on
# SwiftShader's Vulkan through Dawn, no GPU needed) against the C++ float functions, and writes
# the table to docs/wgsl_parity.md (or the file given as $1). The same check as ctest
# `web.wgsl_parity`: the cases and C++ outputs from `test_glsl_parity --dump-cases`, one WGSL
# body per program of the dump from tests/shader_parity/make_parity_shader.mjs --target wgsl
# (the main cases in programs of at most 64, then the configuration-macro cases), run by
# web/test/wgsl_parity.mjs. The table is written only when every row passes.
# Usage: bash scripts/wgsl-parity.sh [OUTPUT.md]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out="${1:-docs/wgsl_parity.md}"

bash scripts/install-deps.sh
if [ ! -f build/test/CMakeCache.txt ]; then
  cmake -S . -B build/test -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOUDMATH_BUILD_TESTS=ON >/dev/null
fi
cmake --build build/test -j "$(nproc 2>/dev/null || echo 2)" --target test_glsl_parity >/dev/null
work=build/test/wgsl_parity
mkdir -p "$work"
build/test/tests/test_glsl_parity --dump-cases "$work/cases.json"
# One WGSL body per program of the dump (its "programs": main cases, then configuration ones).
count="$(node -e 'console.log(JSON.parse(require("fs").readFileSync(process.argv[1], "utf8")).programs.length)' "$work/cases.json")"
bodies=()
for ((k = 0; k < count; ++k)); do
  node tests/shader_parity/make_parity_shader.mjs --target wgsl --cases "$work/cases.json" --program "$k" --out "$work/program$k.wgsl"
  bodies+=(--program "$k" "$work/program$k.wgsl")
done
node web/test/wgsl_parity.mjs --cases "$work/cases.json" "${bodies[@]}" --chromium "$(command -v chromium)" --markdown "$out"
echo "wrote $out"
