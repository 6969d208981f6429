#!/usr/bin/env bash
# Measures the speed against the error of every lighting variant (library, textbook and
# fast forms, scalar and batch) and writes docs/speed_vs_error.md (table and method),
# docs/speed_vs_error.csv (the same data) and docs/speed_vs_error.svg (log-log plot with the
# Pareto fronts). Every number in them is measured by the program; nothing is typed in.
#
# Usage: bash scripts/speed-vs-error.sh [--quick] [OUTPUT_DIR]     (default: docs)
# Builds cloudmath_speed_vs_error in the Release tree build/bench (as scripts/bench-noise.sh
# does) and runs it: errors first (a few seconds), then 31 interleaved timing rounds of every
# variant (about 15 s). --quick times 5 short rounds instead, for a smoke test.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build/bench"
out="$root/docs"
extra=()
for arg in "$@"; do
    case "$arg" in
        --quick) extra+=(--quick) ;;
        -*) echo "usage: bash scripts/speed-vs-error.sh [--quick] [OUTPUT_DIR]" >&2; exit 2 ;;
        *) out=$arg ;;
    esac
done

source "$root/scripts/bench-build.sh"
cloudmath_build_bench "$root" cloudmath_speed_vs_error

mkdir -p "$out"
"$build/bench/report/cloudmath_speed_vs_error" --out-dir "$out" --glsl-cost "$root/docs/glsl_cost.md" \
    --phase-error "$root/docs/phase_error.csv" --lighting-error "$root/docs/lighting_error.csv" \
    --command "bash scripts/speed-vs-error.sh" "${extra[@]}"
