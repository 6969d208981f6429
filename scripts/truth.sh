#!/usr/bin/env bash
# Ground truth for whole cloud images: the example renderer's presets path-traced over its
# own density field, and its lighting variants measured against them.
#   docs/data/truth_PRESET.csv     linear radiance and standard error per pixel
#                                  (cloudmath_volume_truth render; 160 x 90 pixels, 1536
#                                  paths per pixel: 3 to 6 minutes per preset on 2 cores)
#   docs/lighting_truth.md         the renderer's CPU reference (render_cpu_linear) for each
#   docs/images/truth_PRESET.png   variant against them, with truth | model | difference
#                                  images (cloudmath_volume_truth report; seconds)
# Usage: bash scripts/truth.sh [--reports-only] [--build DIR] [--variant NAME=SPEC ...]
#   --reports-only  keeps docs/data/truth_*.csv, reruns the report
#   --build DIR     an existing build tree (configured with the examples) to build the tool
#                   in; without it build/reference is configured as scripts/reference.sh does
#   --variant       one more lighting variant for the report (the renderer's --variant
#                   notation), after the four below
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
presets=(ground horizon inside above)
variants=(default= march=light=march,light-steps=64 single=octaves=1,powder=off mie=phase=mie
          diffusion=lighting=diffusion,powder=off
          diffusion_march=lighting=diffusion,powder=off,light=march,light-steps=6)
width=160 height=90 spp=1536
reports_only=0 build=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --reports-only) reports_only=1 ;;
        --build) build="${2:?--build needs a directory}"; shift ;;
        --variant) variants+=("${2:?--variant needs NAME=SPEC}"); shift ;;
        *) echo "usage: bash scripts/truth.sh [--reports-only] [--build DIR] [--variant NAME=SPEC ...]" >&2; exit 2 ;;
    esac
    shift
done

if [[ -z $build ]]; then
    build=build/reference
    bash scripts/install-deps.sh
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=OFF -DCLOUDMATH_BUILD_EXAMPLES=ON >/dev/null
fi
cmake --build "$build" --target cloudmath_volume_truth >/dev/null
tool="$build/tools/reference/cloudmath_volume_truth"
mkdir -p docs/data docs/images

if [[ $reports_only == 0 ]]; then
    for p in "${presets[@]}"; do
        "$tool" render --preset "$p" --width "$width" --height "$height" --spp "$spp" \
            --out "docs/data/truth_$p.csv"
    done
fi
variant_args=()
for v in "${variants[@]}"; do variant_args+=(--variant "$v"); done
"$tool" report --presets "$(IFS=,; echo "${presets[*]}")" "${variant_args[@]}" --quiet
