#!/usr/bin/env bash
# Builds cloudmath's examples in release mode (the benchmarks have their own scripts), runs every example, and
# renders the demo clouds image headlessly (examples/cloud_renderer through EGL; Mesa's
# llvmpipe where there is no GPU) to build/main/clouds.png.
# Usage: bash scripts/main.sh        (from any directory)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S . -B build/main -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=OFF -DCLOUDMATH_BUILD_EXAMPLES=ON
cmake --build build/main -j "$jobs"

# Every example executable with its arguments, run in this order; add new examples here.
# The texture baker writes raw textures and PNG previews to build/main/textures (about 5 s
# for the full default set on 2 cores).
examples=(
  build/main/examples/minimal/cloudmath_minimal
  build/main/examples/lighting_choice/cloudmath_lighting_choice
  "build/main/tools/cloudmath_bake_textures --out build/main/textures"
  "build/main/examples/cloud_renderer/cloudmath_cloud_renderer --headless --out build/main/clouds.png --cache build/main/texture-cache"
)
for example in "${examples[@]}"; do
  echo "==> running $example"
  read -r -a command <<< "$example"
  "${command[@]}"
done
echo "==> ran ${#examples[@]} example(s): ${examples[*]}"
echo "==> the demo clouds image: $(pwd)/build/main/clouds.png"
