#!/usr/bin/env bash
# Ground truth for whole cloud images: the example renderer's presets path-traced over its
# own density field, and its lighting variants measured against them.
#   docs/data/truth_PRESET.csv     linear radiance and standard error per pixel
#                                  (cloudmath_volume_truth render; 160 x 90 pixels; the
#                                  evaluation presets at 1536 paths per pixel, 4 to 7 minutes
#                                  each on 2 cores; the selection presets, on which the
#                                  renderer's lighting variants were chosen, at 384, under
#                                  a minute each)
#   docs/lighting_truth.md         the renderer's CPU reference (render_cpu_linear) for each
#   docs/images/truth_PRESET.png   variant against them, with truth | model | difference
#                                  images (cloudmath_volume_truth report; seconds)
#   --shape detailed               the same for the renderer's default density field (per-cloud
#                                  types and tops, crisp edges; 6 times slower to trace): data
#                                  in docs/data/detailed/, report docs/detailed/lighting_truth.md,
#                                  every preset at 384 paths per pixel (about 45 minutes)
# Usage: bash scripts/truth.sh [--reports-only] [--build DIR] [--shape S] [--variant NAME=SPEC ...]
#        bash scripts/truth.sh --check TOOL [--shape S] [--cache DIR]
#   --reports-only  keeps docs/data/truth_*.csv, reruns the report
#   --check TOOL    reruns the report with the built cloudmath_volume_truth TOOL from the
#                   stored truth into a temporary directory and fails unless its summary
#                   table (every variant's rms on every preset) is docs/lighting_truth.md's
#                   to 0.15 points: the documented errors come from the stored data (ctest
#                   reference.volume_truth_report)
#   --build DIR     an existing build tree (configured with the examples) to build the tool
#                   in; without it build/reference is configured as scripts/reference.sh does
#   --variant       one more lighting variant for the report (the renderer's --variant
#                   notation), after the ones below
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
presets=(ground horizon inside above)
selection=(sun_behind cumulus stratus)
# default: the diffusion model (6-step marches toward the sun and away from it, quadratic
# and jittered, opaque view steps refined, occluded sky light); previous_estimators: the
# same model with the estimators it had before (no refinement, uniform light steps at their
# midpoints, the cone behind); cone_behind: the default with the cone behind; octaves: the
# production octaves it replaced (flat sky light); octaves_march: the octaves given an
# accurate light march; flat_ambient: the default without the sky light's occlusion.
variants=(default= previous_estimators=refine=1,light-spacing=uniform,light-jitter=off,behind=cone
          octaves=lighting=octaves,powder=on,light=cone,ambient=flat,refine=1
          octaves_march=lighting=octaves,powder=on,light=march,light-steps=64,ambient=flat
          single=lighting=octaves,octaves=1,light=cone,ambient=flat mie=phase=mie
          diffusion_cone=light=cone,behind=cone cone_behind=behind=cone flat_ambient=ambient=flat)
width=160 height=90 spp=1536 selection_spp=384
reports_only=0 build="" check="" cache=() shape=classic
while [[ $# -gt 0 ]]; do
    case "$1" in
        --reports-only) reports_only=1 ;;
        --check) check="${2:?--check needs the tool}"; shift ;;
        --cache) cache=(--cache "${2:?--cache needs a directory}"); shift ;;
        --build) build="${2:?--build needs a directory}"; shift ;;
        --variant) variants+=("${2:?--variant needs NAME=SPEC}"); shift ;;
        --shape) shape="${2:?--shape needs classic or detailed}"; shift ;;
        *) echo "usage: bash scripts/truth.sh [--reports-only] [--build DIR] [--variant NAME=SPEC ...]" >&2; exit 2 ;;
    esac
    shift
done
case "$shape" in
    classic) data=docs/data docs=docs ;;
    detailed) data=docs/data/detailed docs=docs/detailed spp=384 ;;
    *) echo "truth.sh: --shape must be classic or detailed, not '$shape'" >&2; exit 2 ;;
esac
variant_args=()
for v in "${variants[@]}"; do variant_args+=(--variant "$v"); done
report_args=(--presets "$(IFS=,; echo "${presets[*]}")" --selection "$(IFS=,; echo "${selection[*]}")"
             "${variant_args[@]}" "${cache[@]}" --shape "$shape" --quiet)

# The summary table's rows of a report: "variant rms rms ..." with the % signs dropped.
summary_rows() { awk '/^## Summary/ { on = 1; next } on && /^## / { exit } on && /^\| [^v-]/ {
    gsub(/%/, ""); n = split($0, c, "|"); row = c[2]; for (i = 3; i < n; ++i) row = row " " c[i]; gsub(/  +/, " ", row); print row }' "$1"; }

if [[ -n $check ]]; then
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    mkdir -p "$tmp/images"
    "$check" report "${report_args[@]}" --data "$data" --docs "$tmp" >/dev/null
    paste -d '\n' <(summary_rows "$docs/lighting_truth.md") <(summary_rows "$tmp/lighting_truth.md") | awk '
        NR % 2 == 1 { split($0, want, " "); wanted = $0; next }
        { n = split($0, got, " "); rows++
          if (got[1] != want[1] || n != length(want)) { print "truth.sh --check: row \"" $0 "\" against \"" wanted "\""; bad = 1; next }
          for (i = 2; i <= n; ++i) if (got[i] - want[i] > 0.15 || want[i] - got[i] > 0.15) {
              print "truth.sh --check: " got[1] ", column " i - 1 ": " got[i] "% measured, " want[i] "% documented"; bad = 1 } }
        END { if (rows == 0) { print "truth.sh --check: no summary rows"; exit 1 }
              if (!bad) print "truth.sh --check: " rows " variants reproduce the documented report"; exit bad }'
    exit
fi

if [[ -z $build ]]; then
    build=build/reference
    bash scripts/install-deps.sh
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=OFF -DCLOUDMATH_BUILD_EXAMPLES=ON >/dev/null
fi
cmake --build "$build" --target cloudmath_volume_truth >/dev/null
tool="$build/tools/reference/cloudmath_volume_truth"
mkdir -p "$data" "$docs/images"

if [[ $reports_only == 0 ]]; then
    for p in "${presets[@]}"; do
        "$tool" render --preset "$p" --shape "$shape" --width "$width" --height "$height" --spp "$spp" \
            --out "$data/truth_$p.csv"
    done
    for p in "${selection[@]}"; do
        "$tool" render --preset "$p" --shape "$shape" --width "$width" --height "$height" --spp "$selection_spp" \
            --out "$data/truth_$p.csv"
    done
fi
"$tool" report "${report_args[@]}" --data "$data" --docs "$docs"
