#!/usr/bin/env bash
# Regenerates the physical references and the error reports built on them:
#   docs/data/mie_*.csv            Lorenz-Mie phase tables of droplet distributions
#                                  (cloudmath_mie; about 5 minutes on 2 cores, 3.5 of them
#                                  for r_eff = 20 um)
#   docs/phase_error.{md,csv}      analytic phase functions against the tables, with SVGs in
#                                  docs/images (cloudmath_phase_error; 1 s)
#   docs/data/lighting_reference.csv  Monte Carlo radiances of spheres and slabs
#                                  (cloudmath_lighting_error reference; about 6.5 minutes)
#   docs/lighting_error.{md,csv}   lighting models against it, fits, presets, with SVGs
#                                  (cloudmath_lighting_error report; about 2 minutes)
#   docs/data/lighting_train_g{0.8,0.93}.csv  the reference's rays at two more phase
#                                  functions, fitted on with it (about 15 minutes)
#   docs/data/lighting_holdout_g{0.75,0.85,0.9}.csv, lighting_holdout_g0.85_albedo0.99.csv,
#   lighting_holdout_renderer_phase.csv  the held-out split (other thicknesses, angles and
#                                  views; three HG phase functions; albedo 0.99; the example
#                                  renderer's dual-lobe phase and albedo), never fitted on
#                                  (cloudmath_lighting_error reference --holdout; 13 minutes)
#   include/cloudmath/diffusion_lighting_models.hpp, glsl/diffusion_lighting_models.glsl and
#   docs/data/diffusion_fit.txt    the diffusion model fitted on the three training sets and
#                                  measured on all six (cloudmath_lighting_error fit-diffusion;
#                                  seconds); ctest -R reference.lighting_diffusion checks that
#                                  the headers are what the stored data gives
#   docs/data/truth_*.csv.gz, docs/lighting_truth.md  whole cloud images of the example
#                                  renderer against their path-traced truth (scripts/truth.sh)
# Usage: bash scripts/reference.sh [--reports-only]
#   --reports-only  keeps the tables, the Monte Carlo reference and the truth images, reruns
#                   the three reports
# Afterwards: the presets' documented errors in include/cloudmath/multiple_scattering.hpp
# must match docs/lighting_error.md (ctest -R reference.lighting_presets checks it), and
# bash scripts/speed-vs-error.sh refreshes the report's physical-reference column.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
reports_only=0
for arg in "$@"; do
    case "$arg" in
        --reports-only) reports_only=1 ;;
        *) echo "usage: bash scripts/reference.sh [--reports-only]" >&2; exit 2 ;;
    esac
done

bash scripts/install-deps.sh
cmake -S . -B build/reference -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=OFF -DCLOUDMATH_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/reference --target cloudmath_mie cloudmath_phase_error cloudmath_lighting_error >/dev/null
bin=build/reference/tools/reference
mkdir -p docs/data docs/images

tables=(docs/data/mie_c1_0.55um.csv docs/data/mie_c1_0.70um.csv
        docs/data/mie_gamma_reff5um_0.55um.csv docs/data/mie_gamma_reff10um_0.55um.csv
        docs/data/mie_gamma_reff20um_0.55um.csv)
if [[ $reports_only == 0 ]]; then
    "$bin/cloudmath_mie" --distribution c1 --wavelength 0.55 --out "${tables[0]}"
    "$bin/cloudmath_mie" --distribution c1 --wavelength 0.70 --out "${tables[1]}"
    for r in 5 10 20; do
        "$bin/cloudmath_mie" --distribution gamma --reff "$r" --wavelength 0.55 \
            --out "docs/data/mie_gamma_reff${r}um_0.55um.csv"
    done
fi
"$bin/cloudmath_phase_error" "${tables[@]}"

if [[ $reports_only == 0 ]]; then
    "$bin/cloudmath_lighting_error" reference --out docs/data/lighting_reference.csv
fi

# The diffusion model (include/cloudmath/diffusion_lighting.hpp): two more training sets over
# the reference's geometry (g = 0.8, 0.93) and the held-out split (other thicknesses, angles
# and views; g = 0.75, 0.85, 0.9), then the fit, which rewrites the generated model headers.
if [[ $reports_only == 0 ]]; then
    "$bin/cloudmath_lighting_error" reference --phase hg:0.8 --seed 3 --out docs/data/lighting_train_g0.8.csv
    "$bin/cloudmath_lighting_error" reference --phase hg:0.93 --seed 4 --out docs/data/lighting_train_g0.93.csv
    for g in 0.75 0.85 0.9; do
        "$bin/cloudmath_lighting_error" reference --holdout --phase "hg:$g" \
            --out "docs/data/lighting_holdout_g$g.csv"
    done
    "$bin/cloudmath_lighting_error" reference --holdout --phase hg:0.85 --albedo 0.99 \
        --out docs/data/lighting_holdout_g0.85_albedo0.99.csv
    "$bin/cloudmath_lighting_error" reference --holdout --phase dual_hg:0.8,-0.25,0.2 --albedo 0.99 \
        --out docs/data/lighting_holdout_renderer_phase.csv
fi
"$bin/cloudmath_lighting_error" fit-diffusion \
    --header include/cloudmath/diffusion_lighting_models.hpp \
    --glsl include/cloudmath/glsl/diffusion_lighting_models.glsl > docs/data/diffusion_fit.txt.tmp
mv docs/data/diffusion_fit.txt.tmp docs/data/diffusion_fit.txt
# The report measures the models compiled into the tool: rebuild it with the new headers.
cmake --build build/reference --target cloudmath_lighting_error >/dev/null
"$bin/cloudmath_lighting_error" report --choice-header include/cloudmath/lighting_choice_data.hpp

# Whole cloud images against their path-traced truth (docs/lighting_truth.md; about 21
# minutes, the report alone seconds).
truth_args=(--build build/reference)
if [[ $reports_only == 1 ]]; then truth_args+=(--reports-only); fi
bash scripts/truth.sh "${truth_args[@]}"
