#!/usr/bin/env bash
# Ground truth for whole cloud images: the example renderer's presets path-traced over its
# own density field, and its lighting variants measured against them.
#   docs/data/truth_PRESET.csv.gz  linear radiance and standard error per pixel (gzip-compressed
#                                  CSV: zcat shows it)
#                                  (cloudmath_volume_truth render; 160 x 90 pixels; adaptive
#                                  sampling for a noise floor of 3% of the image mean:
#                                  a 64-path pilot, then each pixel's paths by its variance
#                                  and cost; 6 to 18 minutes a preset on 2 cores for the
#                                  classic field. Files from before it (uniform 384 or 1536
#                                  paths per pixel, say so in their "allocation" line or
#                                  lack it) stay until their preset is rerun: --only)
#   docs/lighting_truth.md         the renderer's CPU reference (render_cpu_linear) for each
#   docs/images/truth_PRESET.png   variant against them, with the first variant's truth |
#                                  model | difference image (cloudmath_volume_truth report;
#                                  seconds; report --variant-images writes the others' too,
#                                  which are not stored)
#   --shape detailed               the same for the renderer's default density field (per-cloud
#                                  types and tops, crisp edges; 6 times slower to trace): data
#                                  in docs/data/detailed/, report docs/detailed/lighting_truth.md
#                                  (the same noise target: hours on 2 cores)
#   --only P1,P2                   renders only these presets, keeps the other stored ones,
#                                  then reruns the report
#   --noise F                      the noise target (default 0.03; 0.05 with --sky physical
#                                  --shape detailed)
#   --sky physical                 the presets under the renderer's physical sky (--sky physical,
#                                  the atmosphere module's sun and sky; docs/atmosphere.md): data
#                                  in docs/data/physical/, report docs/physical_sky/lighting_truth.md
#                                  with the tool's four default variants, the physical presets
#                                  sunrise and sunset added to the evaluation split; presets not
#                                  traced yet are left out with a note. With --shape detailed: data
#                                  in docs/data/physical/detailed/, report
#                                  docs/physical_sky/detailed/lighting_truth.md, noise target 5%
#   --light sun|sky                with --sky physical: the truths of one light alone (the sun, or
#                                  the sky: cloudmath_volume_truth render --light), for research
#                                  that splits the model's error by source; data in
#                                  docs/data/physical/light_L/, report docs/physical_sky/light_L/
#                                  lighting_truth.md (the default variant rendered with the
#                                  same light)
#   --budget-minutes N             stop tracing after N minutes in all: the render under way stops
#                                  cleanly and keeps its checkpoint (docs/data/.../truth_P.csv.gz.checkpoint,
#                                  about 1.2 MB: commit it); the report is regenerated when a truth
#                                  was finished, else left as it is. A preset with a checkpoint is always resumed
#                                  (cloudmath_volume_truth render --resume), so the same command in
#                                  the next session goes on where this one stopped
#   --pending                      trace only the presets still to do (cloudmath_volume_truth
#                                  status): no truth, a checkpoint, a noise floor short of the
#                                  target, or a truth or checkpoint over a scene that changed since
#                                  (a stale checkpoint is deleted, with a word). For traces longer
#                                  than a session: bash scripts/truth.sh --sky physical --pending
#                                  --budget-minutes 120, then commit docs/data, session after session
#   --fit                          first refits diffusion_models::clouds, the renderer's
#                                  default table, on the selection presets of both fields
#                                  into docs/data/diffusion_clouds.txt (cloudmath_volume_truth
#                                  fit-clouds; seconds), then regenerates the model headers
#                                  (cloudmath_lighting_error fit-diffusion), their HLSL/WGSL
#                                  twins, the embedded GLSL and the web bundles, and rebuilds
#                                  the tool before the report
# Usage: bash scripts/truth.sh [--reports-only] [--fit] [--only PRESETS] [--noise F] [--build DIR]
#                              [--shape S] [--sky S] [--variant NAME=SPEC ...] [--pending]
#                              [--budget-minutes N]
#        bash scripts/truth.sh --check TOOL [--shape S] [--sky S] [--cache DIR]
#   --reports-only  keeps docs/data/truth_*.csv.gz, reruns the report
#   --check TOOL    reruns the report for the default and fitted_table variants with the built
#                   cloudmath_volume_truth TOOL from the stored truth into a temporary
#                   directory and fails unless their summary rows (rms on every preset) are
#                   docs/lighting_truth.md's to 0.15 points: the documented errors come from
#                   the stored data (ctest reference.volume_truth_report); for the classic
#                   field also that
#                   docs/data/diffusion_clouds.txt is what fit-clouds gives from the stored truths;
#                   with --sky physical the whole report, images included, must be the stored one
#                   to the byte
#   --build DIR     an existing build tree (configured with the examples) to build the tool
#                   in; without it build/reference is configured as scripts/reference.sh does
#   --variant       one more lighting variant for the report (the renderer's --variant
#                   notation), after the ones below
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
presets=(ground horizon inside above)
# The selection split: the presets lighting choices are made on. low_sun_ahead and
# low_sun_behind (a sun 3 degrees up, facing it and behind the camera) keep the low sun's
# choice off the horizon preset.
selection=(sun_behind cumulus stratus low_sun_ahead low_sun_behind)
# default: the diffusion model (6-step marches toward the sun and away from it, quadratic
# and jittered, opaque view steps refined, occluded sky light, the far field toward a low sun
# in 12 full-density steps); octaves: the production octaves it replaced (the cone, flat sky
# light); octaves_march: the octaves given an accurate light march; diffusion_cone and
# cone_behind: the cone both ways or behind the sample only; flat_ambient: the default without
# the sky light's occlusion; reach_band: the march's 6 steps stretched to the band's end, up to
# 30 km, instead of the far steps; fitted_table: the default with the diffusion model's table
# fitted to homogeneous spheres and slabs (diffusion_models::fitted, the default before the
# whole-cloud fit diffusion_models::clouds). The rows of switches the renderer no longer has
# (previous_estimators, capped, reach_map): docs/lighting_research.md, "Switches removed".
variants=(default= octaves=lighting=octaves,powder=on,light=cone,ambient=flat,refine=1
          octaves_march=lighting=octaves,powder=on,light=march,light-steps=64,ambient=flat
          single=lighting=octaves,octaves=1,light=cone,ambient=flat mie=phase=mie
          diffusion_cone=light=cone,behind=cone cone_behind=behind=cone flat_ambient=ambient=flat
          reach_band=reach=band fitted_table=table=fitted)
width=160 height=90 noise=""
reports_only=0 build="" check="" cache=() shape=classic sky=artistic only="" fit=0 added_variants=0 pending=0 budget="" light=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --reports-only) reports_only=1 ;;
        --fit) fit=1 ;;
        --only) only="${2:?--only needs a comma-separated list of presets}"; shift ;;
        --noise) noise="${2:?--noise needs a fraction}"; shift ;;
        --check) check="${2:?--check needs the tool}"; shift ;;
        --cache) cache=(--cache "${2:?--cache needs a directory}"); shift ;;
        --build) build="${2:?--build needs a directory}"; shift ;;
        --variant) variants+=("${2:?--variant needs NAME=SPEC}"); added_variants=1; shift ;;
        --shape) shape="${2:?--shape needs classic or detailed}"; shift ;;
        --sky) sky="${2:?--sky needs artistic or physical}"; shift ;;
        --pending) pending=1 ;;
        --light) light="${2:?--light needs sun or sky}"; shift ;;
        --budget-minutes) budget="${2:?--budget-minutes needs a number of minutes}"; shift
            [[ $budget =~ ^[0-9]+$ && $budget -gt 0 ]] || { echo "truth.sh: --budget-minutes must be a whole number of minutes > 0, not '$budget'" >&2; exit 2; } ;;
        *) echo "usage: bash scripts/truth.sh [--reports-only] [--fit] [--only PRESETS] [--noise F] [--build DIR] [--shape S] [--sky S] [--variant NAME=SPEC ...] [--pending] [--budget-minutes N] [--light sun|sky]" >&2; exit 2 ;;
    esac
    shift
done
case "$shape" in
    classic) data=docs/data docs=docs ;;
    detailed) data=docs/data/detailed docs=docs/detailed ;;
    *) echo "truth.sh: --shape must be classic or detailed, not '$shape'" >&2; exit 2 ;;
esac
# Presets added to the selection split after a field's truth was traced: left out of that
# field's report, with a note, until traced (--only NAME).
late=(low_sun_ahead low_sun_behind)
case "$sky" in
    artistic) ;;
    physical)
        if [[ $fit == 1 || $added_variants == 1 ]]; then
            echo "truth.sh: --sky physical reports the tool's default variants (no --fit or --variant)" >&2
            exit 2
        fi
        data=docs/data/physical docs=docs/physical_sky
        if [[ $shape == detailed ]]; then
            data=docs/data/physical/detailed docs=docs/physical_sky/detailed
            noise=${noise:-0.05}
        fi
        presets+=(sunrise sunset)
        variants=()
        # Traced preset by preset (hours for all): any not traced yet is left out.
        late=("${selection[@]}" "${presets[@]}") ;;
    *) echo "truth.sh: --sky must be artistic or physical, not '$sky'" >&2; exit 2 ;;
esac
case "$light" in
    "") light_args=() ;;
    sun|sky)
        [[ $sky == physical ]] || { echo "truth.sh: --light $light needs --sky physical (the artistic sky has no split by source)" >&2; exit 2; }
        data=$data/light_$light docs=$docs/light_$light
        mkdir -p "$data" "$docs/images"
        variants=(default=)  # research: the default's error by source, one image a preset
        light_args=(--light "$light") ;;
    *) echo "truth.sh: --light must be sun or sky, not '$light'" >&2; exit 2 ;;
esac
noise=${noise:-0.03}
# The presets with a stored truth (the late ones may not have one yet), then the report's flags.
keep_traced() {
    local p
    for p in "$@"; do
        if [[ ! -f $data/truth_$p.csv.gz && ! -f $data/truth_$p.csv && " ${late[*]} " == *" $p "* ]]; then
            echo "truth.sh: no $shape $sky-sky truth for $p yet (bash scripts/truth.sh --shape $shape --sky $sky --only $p); left out of the report" >&2
            continue
        fi
        echo "$p"
    done
}
traced_report_args() {
    mapfile -t selection < <(keep_traced "${selection[@]}")
    mapfile -t presets < <(keep_traced "${presets[@]}")
    # Only selection presets traced so far (a light's truths, say): they are the report's presets.
    if [[ ${#presets[@]} == 0 ]]; then presets=("${selection[@]}"); selection=(); fi
    local v
    variant_args=()
    for v in "${variants[@]}"; do variant_args+=(--variant "$v"); done
    report_args=(--presets "$(IFS=,; echo "${presets[*]}")" --selection "$(IFS=,; echo "${selection[*]}")"
                 "${variant_args[@]}" "${cache[@]}" --shape "$shape" --quiet)
}

# The summary table's rows of a report: "variant rms rms ..." with the % signs dropped.
summary_rows() { awk '/^## Summary/ { on = 1; next } on && /^## / { exit } on && /^\| [^v-]/ {
    gsub(/%/, ""); n = split($0, c, "|"); row = c[2]; for (i = 3; i < n; ++i) row = row " " c[i]; gsub(/  +/, " ", row); print row }' "$1"; }

if [[ -n $check ]]; then
    traced_report_args
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    mkdir -p "$tmp/images"
    if [[ $sky == physical ]]; then
        # The whole report, images included, to the byte (seconds a preset on 2 cores).
        "$check" report "${report_args[@]}" --data "$data" --docs "$tmp" >/dev/null
        diff "$tmp/lighting_truth.md" "$docs/lighting_truth.md"
        for f in "$tmp"/images/*.png; do cmp "$f" "$docs/images/$(basename "$f")"; done
        echo "truth.sh --check: the physical sky's report reproduced (${#selection[@]} + ${#presets[@]} presets)"
        exit
    fi
    if [[ $shape == classic ]]; then
        "$check" fit-clouds --data docs/data "${cache[@]}" --quiet --check docs/data/diffusion_clouds.txt >/dev/null
    fi
    # The default and the table before it: each of their rows must be the documented one (the
    # other variants' rows cost 8 frames a render too, minutes; scripts/truth.sh regenerates them).
    check_args=(--presets "$(IFS=,; echo "${presets[*]}")" --selection "$(IFS=,; echo "${selection[*]}")"
                --variant default= --variant fitted_table=table=fitted "${cache[@]}" --shape "$shape" --quiet)
    "$check" report "${check_args[@]}" --data "$data" --docs "$tmp" >/dev/null
    awk 'FNR == NR { n = split($0, c, " "); got[c[1]] = $0; next }
        { n = split($0, want, " "); if (!(want[1] in got)) next
          m = split(got[want[1]], g, " "); rows++
          if (m != n) { print "truth.sh --check: row \"" got[want[1]] "\" against \"" $0 "\""; bad = 1; next }
          for (i = 2; i <= n; ++i) if (g[i] - want[i] > 0.15 || want[i] - g[i] > 0.15) {
              print "truth.sh --check: " want[1] ", column " i - 1 ": " g[i] "% measured, " want[i] "% documented"; bad = 1 } }
        END { if (rows != 2) { print "truth.sh --check: " rows + 0 " of the 2 checked variants found in the report"; exit 1 }
              if (!bad) print "truth.sh --check: " rows " variants reproduce the documented report"; exit bad }' \
        <(summary_rows "$tmp/lighting_truth.md") <(summary_rows "$docs/lighting_truth.md")
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

if [[ $fit == 1 ]]; then
    # The whole-cloud table from the stored truths of both fields (their selection presets),
    # then everything generated from the model headers.
    "$tool" fit-clouds --data docs/data --quiet --out docs/data/diffusion_clouds.txt >/dev/null
    cmake --build "$build" --target cloudmath_lighting_error >/dev/null
    "$build/tools/reference/cloudmath_lighting_error" fit-diffusion \
        --header include/cloudmath/diffusion_lighting_models.hpp \
        --glsl include/cloudmath/glsl/diffusion_lighting_models.glsl > docs/data/diffusion_fit.txt.tmp
    mv docs/data/diffusion_fit.txt.tmp docs/data/diffusion_fit.txt
    node tools/shader_translate/generate.mjs >/dev/null
    cmake -P cmake/UpdateGlslEmbedded.cmake >/dev/null
    node web/build.mjs >/dev/null
    node web/demo/build_wgsl_demo.mjs >/dev/null
    cmake --build "$build" --target cloudmath_volume_truth >/dev/null
fi

finished=0  # truths written by this run
if [[ $reports_only == 0 ]]; then
    start=$SECONDS
    for p in "${selection[@]}" "${presets[@]}"; do
        [[ -z $only || ",$only," == *",$p,"* ]] || continue
        checkpoint="$data/truth_$p.csv.gz.checkpoint"
        if [[ $pending == 1 ]]; then
            state=$("$tool" status --presets "$p" --data "$data" --shape "$shape" --sky "$sky" "${light_args[@]}" --noise-target "$noise" "${cache[@]}")
            echo "truth.sh: $state" >&2
            case "$(awk '{ print $2 }' <<<"$state")" in
                done) continue ;;
                stale) if [[ -f $checkpoint ]]; then
                           echo "truth.sh: deleting $checkpoint, traced over a scene that changed since" >&2
                           rm -f "$checkpoint"
                       fi ;;
            esac
        fi
        resume=()
        [[ -f $checkpoint ]] && resume=(--resume)
        budget_args=()
        if [[ -n $budget ]]; then
            left=$((budget * 60 - (SECONDS - start)))
            if ((left < 60)); then
                echo "truth.sh: the budget of $budget minutes is spent before $p" >&2
                break
            fi
            budget_args=(--budget-minutes "$((left / 60))")
        fi
        status=0
        "$tool" render --preset "$p" --shape "$shape" --sky "$sky" "${light_args[@]}" --width "$width" --height "$height" --noise-target "$noise" \
            "${cache[@]}" "${resume[@]}" "${budget_args[@]}" --out "$data/truth_$p.csv.gz" || status=$?
        if [[ $status == 3 ]]; then
            echo "truth.sh: $p stopped by the budget, its checkpoint kept in $checkpoint: commit it, and run the same command again to go on" >&2
            break
        fi
        [[ $status == 0 ]] || exit "$status"
        finished=$((finished + 1))
    done
    if [[ $finished == 0 ]]; then
        echo "truth.sh: no truth finished, the report stays as it is" >&2
        exit 0
    fi
fi
traced_report_args
"$tool" report "${report_args[@]}" --data "$data" --docs "$docs"
