#!/usr/bin/env bash
# Builds cloudmath's examples (and benchmarks) in release mode and runs every example.
# Usage: bash scripts/main.sh        (from any directory)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S . -B build/main -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=ON -DCLOUDMATH_BUILD_EXAMPLES=ON
cmake --build build/main -j "$jobs"

# Every example executable with its arguments, run in this order; add new examples here.
# The texture baker writes raw textures and PNG previews to build/main/textures (about 5 s
# for the full default set on 2 cores).
examples=(
  build/main/examples/minimal/cloudmath_minimal
  "build/main/tools/cloudmath_bake_textures --out build/main/textures"
)
for example in "${examples[@]}"; do
  echo "==> running $example"
  read -r -a command <<< "$example"
  "${command[@]}"
done
echo "==> ran ${#examples[@]} example(s): ${examples[*]}"
