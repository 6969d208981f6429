#!/usr/bin/env bash
# scripts/recompress-images.sh: rewrites the stored PNGs through the encoder every cloudmath
# tool writes with (cloudmath_recompress_png: zlib level 9, pixel for pixel, checked), so that
# they are what their generators write today (ctest tools.recompress_png). The browser's
# screenshot docs/images/web_demo.png is Chromium's and is left alone.
# Usage: bash scripts/recompress-images.sh [BUILD_DIR]   (default build/main, configured with the examples)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build/main}
if [[ ! -f $build/CMakeCache.txt ]]; then
    bash scripts/install-deps.sh
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOUDMATH_BUILD_EXAMPLES=ON >/dev/null
fi
cmake --build "$build" --target cloudmath_recompress_png >/dev/null
git ls-files -z '*.png' | grep -zv 'docs/images/web_demo.png$' | xargs -0 "$build/tools/cloudmath_recompress_png" | tail -1
