#!/usr/bin/env bash
# scripts/split_by_source.sh: the default lighting's error under the physical sky split by
# light source (issue 37), from two reports of cloudmath_volume_truth: the whole light's
# (docs/physical_sky/lighting_truth.md) and the sky's alone
# (docs/physical_sky/light_sky/lighting_truth.md, bash scripts/truth.sh --sky physical
# --light sky). The tracer and the model are both linear in the two lights, so the sun's bias
# is the whole's minus the sky's, each in points of the whole's mean. Prints a markdown table
# (docs/lighting_research.md, "The error by source").
# Usage: bash scripts/split_by_source.sh [ALL.md [SKY.md]]
set -euo pipefail
all=${1:-docs/physical_sky/lighting_truth.md}
sky=${2:-docs/physical_sky/light_sky/lighting_truth.md}
for f in "$all" "$sky"; do [[ -r $f ]] || { echo "split_by_source.sh: cannot read $f" >&2; exit 1; }; done
# Per preset section: "name excess bias mean" (the default variant's row, the truth's mean).
sections() {
    awk '/^## [a-z_]+ \(/ { name = $2; next }
         name != "" && /^\| default \| / { gsub(/%/, ""); split($0, c, "|"); excess[name] = c[4] + 0; bias[name] = c[5] + 0 }
         name != "" && /^Truth mean radiance / { m = $4; sub(/,$/, "", m); mean[name] = m + 0; order[++n] = name }
         END { for (i = 1; i <= n; ++i) { p = order[i]; if (p in excess) print p, excess[p], bias[p], mean[p] } }' "$1"
}
echo "| preset | the whole light: excess / bias | the sky's share of the truth | the sky alone: excess / bias (of its own mean) | the sky's bias, points of the whole | the sun's bias, points of the whole (the difference) |"
echo "|---|---:|---:|---:|---:|---:|"
join <(sections "$all" | sort) <(sections "$sky" | sort) | sort -k1,1 |
    awk '{ share = $7 / $4; skyb = $6 * share
           printf "| %s | %.1f%% / %+.1f%% | %.0f%% | %.1f%% / %+.1f%% | %+.1f | %+.1f |\n", $1, $2, $3, 100 * share, $5, $6, skyb, $3 - skyb }'
