#!/usr/bin/env bash
# The main job: builds cloudmath's examples in release mode (the benchmarks and the reference
# tools have their own scripts), runs the two small examples, and renders the demo clouds
# image headlessly (examples/cloud_renderer through EGL; Mesa's llvmpipe where there is no
# GPU) to build/main/clouds.png: the converged image, the mean of 8 frames with their own
# jitter (--accumulate 8, what the temporal scheme converges to for a still camera).
# About 50 s on 2 cores from a fresh clone once the packages are installed (the build about
# half of it), under 20 s when built.
# Usage: bash scripts/main.sh        (from any directory)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S . -B build/main -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=OFF -DCLOUDMATH_BUILD_EXAMPLES=ON
# Only what the job runs (the texture baker and the reference tools are tested by the suite).
cmake --build build/main -j "$jobs" --target cloudmath_minimal cloudmath_lighting_choice cloudmath_cloud_renderer

# Every example executable with its arguments, run in this order. The renderer bakes its
# textures on the first run (about 6 s on 2 cores) into build/main/texture-cache.
examples=(
  build/main/examples/minimal/cloudmath_minimal
  build/main/examples/lighting_choice/cloudmath_lighting_choice
  "build/main/examples/cloud_renderer/cloudmath_cloud_renderer --headless --accumulate 8 --out build/main/clouds.png --cache build/main/texture-cache"
)
for example in "${examples[@]}"; do
  echo "==> running $example"
  read -r -a command <<< "$example"
  "${command[@]}"
done
echo "==> ran ${#examples[@]} example(s): ${examples[*]}"
echo "==> the demo clouds image: $(pwd)/build/main/clouds.png"
