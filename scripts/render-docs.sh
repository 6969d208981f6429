#!/usr/bin/env bash
# Renders the cloud renderer's documentation: every scene preset before (the renderer as it
# was: classic field, octaves, one frame) and after (the default, the temporal scheme
# converged over 128 frames), a set of lighting variants and a temporal frame sequence as
# PNGs in docs/images/, the --bench table (ms per frame of every variant and its PSNR against
# the reference variant) and the --convergence table (every preset against a converged
# render of the same lighting model) into docs/renderer.md, with the device, date and
# command. Headless (EGL): on Mesa's llvmpipe where there is no GPU.
# Usage: bash scripts/render-docs.sh [WIDTH HEIGHT]     (default 480 270; about 25 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
width=${1:-480}
height=${2:-270}

bash scripts/install-deps.sh
cmake -S . -B build/main -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=OFF -DCLOUDMATH_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/main --target cloudmath_cloud_renderer >/dev/null
renderer=build/main/examples/cloud_renderer/cloudmath_cloud_renderer
common=(--width "$width" --height "$height" --cache build/main/texture-cache --quiet)
mkdir -p docs/images

presets=$("$renderer" --list-presets | awk '{ print $1 }')
# Before: what the renderer drew when the work on its images began (the artistic sky, the
# classic field, the octaves with the cone, flat sky light, no haze, no shadows, no dither, one
# frame). After: the default, the physical sky included.
before=(--sky artistic --shape classic --variant lighting=octaves,powder=on,light=cone,ambient=flat,refine=1 --without haze,shadows,dither)
for p in $presets; do
  "$renderer" --headless --preset "$p" "${common[@]}" --temporal 128 --out "docs/images/clouds_$p.png" >/dev/null
  "$renderer" --headless --preset "$p" "${common[@]}" "${before[@]}" --out "docs/images/before_$p.png" >/dev/null
done
# The temporal scheme in motion: the ground preset panning 0.5 degrees a frame with 30 m of
# wind, every 8th of 48 frames; and what it costs against full frames of the same motion.
rm -f docs/images/sequence_f*.png
"$renderer" --headless --preset ground "${common[@]}" --temporal 48 --pan 0.5 --drift 30 --save-every 8 \
  --out docs/images/sequence.png >/dev/null
rm -f docs/images/sequence.png
motion=$("$renderer" --cpu --preset ground --width 320 --height 180 --cache build/main/texture-cache --quiet \
  --temporal 48 --pan 0.5 --drift 30 --out build/main/sequence_cpu.png | grep '^temporal:')
still=$("$renderer" --cpu --preset ground --width 320 --height 180 --cache build/main/texture-cache --quiet \
  --temporal 128 --out build/main/still_cpu.png | grep '^temporal:')
temporal_compare=$("$renderer" --compare --preset ground "${common[@]}" --temporal 48 --pan 0.5 --drift 30 \
  --out build/main/compare_temporal.png | grep 'GPU vs CPU')
# Where a temporal frame's time goes (each pass ended by glFinish), and what shading a quarter-
# resolution grid costs per pixel: a full frame at a quarter of the size in each direction
# (the same content, the same 4-pixel spacing between neighbouring rays) against the full size,
# both without the shadow map's pass.
profile=$("$renderer" --headless --preset ground "${common[@]}" --temporal 32 --out build/main/profile.png)
profile_frame=$(grep '^GPU temporal:' <<< "$profile" | sed 's/^GPU temporal: //')
profile_passes=$(grep '^GPU temporal passes' <<< "$profile" | sed 's/^[^:]*: //')
frame_ms() { "$renderer" --headless --preset ground --width "$1" --height "$2" --cache build/main/texture-cache --quiet \
  --without shadows --out build/main/frame_ms.png | sed -n 's/^GPU: .*: \([0-9.]*\) ms per frame.*/\1/p'; }
quarter_ms=$(frame_ms $((width / 4)) $((height / 4)))
full_ms=$(frame_ms "$width" "$height")
quarter_premium=$(awk -v q="$quarter_ms" -v f="$full_ms" 'BEGIN { printf "%.2f", q / (f / 16) }')
# name|variant spec|caption, all on the "horizon" preset (low sun ahead: phase and powder show)
variants=(
  "default||default: diffusion model, dual-lobe HG, 6-step marches both ways (quadratic, jittered), 64 steps refined where opaque"
  "octaves|lighting=octaves,powder=on,light=cone,ambient=flat,refine=1|octaves: 3, powder, cone, flat sky light (the previous default)"
  "flat_ambient|ambient=flat|sky light not occluded inside the clouds"
  "hg|phase=hg|phase: HG"
  "mie|phase=mie|phase: Mie fit (15 um droplets)"
  "octaves1|lighting=octaves,octaves=1,light=cone|1 octave (single scattering), cone"
  "powder_off|lighting=octaves,light=cone|octaves without powder"
  "march|light-steps=32,behind=march|light: 32-step march both ways"
  "reach|reach=band|light: the march toward the sun to the band's end (30 km)"
  "no_shadows|--without shadows|no cloud shadows on the ground"
  "naive16|integration=naive,steps=16|naive Riemann integration, 16 steps"
  "analytic16|steps=16|energy-conserving integration, 16 steps"
)
for v in "${variants[@]}"; do
  IFS='|' read -r name spec caption <<< "$v"
  args=(--headless --preset horizon "${common[@]}" --out "docs/images/clouds_variant_$name.png")
  if [[ "$spec" == --* ]]; then read -ra extra <<< "$spec"; args+=("${extra[@]}")
  elif [[ -n "$spec" ]]; then args+=(--variant "$spec"); fi
  "$renderer" "${args[@]}" >/dev/null
done
compare=$("$renderer" --compare --preset ground "${common[@]}" --out build/main/compare.png | grep 'GPU vs CPU')
accumulated=$("$renderer" --compare --preset ground --accumulate 8 "${common[@]}" --out build/main/compare_accumulated.png | grep 'GPU vs CPU')
bench=$("$renderer" --bench --preset ground "${common[@]}")
# Convergence at 160 x 90 on the CPU (the reference takes 1024 view steps and 128-step light
# marches: about 10 minutes on 2 cores for the seven presets).
convergence=$("$renderer" --convergence --width 160 --height 90 --cache build/main/texture-cache --quiet)
cost=$(bash scripts/shader-cost.sh "$renderer")

{
  echo "# The example cloud renderer: scenes, variants and timings"
  echo
  echo "Generated by \`bash scripts/render-docs.sh $width $height\` on $(date -u +"%Y-%m-%d %H:%M UTC") (do not edit by hand)."
  echo "Source: [examples/cloud_renderer](../examples/cloud_renderer) (the shader is"
  echo "[shaders/clouds.frag](../examples/cloud_renderer/shaders/clouds.frag)). Images are $width x $height,"
  echo "rendered headlessly through EGL."
  echo
  echo "## Presets, before and after"
  echo
  echo "Before: the renderer as it was when the work on its images began (\`${before[*]}\`, one"
  echo "frame). After: the default, the temporal scheme's frame 127 of a still camera (\`--temporal 128\`)."
  echo
  echo "| Preset | Before | After |"
  echo "|---|---|---|"
  "$renderer" --list-presets | while read -r name rest; do
    echo "| \`$name\`: $rest | ![$name before](images/before_$name.png) | ![$name](images/clouds_$name.png) |"
  done
  echo
  echo "## The temporal scheme"
  echo
  echo "Each frame shades the cloud layer at one pixel of every 4 x 4 block (Bayer order,"
  echo "\`temporal_update_offset\`) and resolves the rest from the full-resolution history of the layer"
  echo "(its own light and opacity), reprojected by the camera's rotation, its altitude and the wind at"
  echo "the block's cloud depth (\`camera_project\`, Catmull-Rom taps clamped to the bilinear ones);"
  echo "shaded pixels join a running mean of at most 8 samples (\`temporal_blend_weight\`). What lies"
  echo "behind the layer (sky, sun, ground and the clouds' shadows on it) is drawn at full resolution"
  echo "every frame and the layer composited over it, so it never lags. Frames 7, 15, ..., 47 of"
  echo "\`--preset ground --temporal 48 --pan 0.5 --drift 30\` (0.5 degrees of pan and 30 m of wind a frame):"
  echo
  echo "| frame 7 | frame 15 | frame 23 |"
  echo "|---|---|---|"
  echo "| ![](images/sequence_f007.png) | ![](images/sequence_f015.png) | ![](images/sequence_f023.png) |"
  echo "| **frame 31** | **frame 39** | **frame 47** |"
  echo "| ![](images/sequence_f031.png) | ![](images/sequence_f039.png) | ![](images/sequence_f047.png) |"
  echo
  echo "In motion (CPU, 320 x 180, the same sequence): $motion."
  echo "A still camera (CPU, 320 x 180, 128 frames): $still."
  echo "GPU against CPU over the moving sequence at $width x $height: $temporal_compare."
  echo
  echo "Where a frame's time goes (\`--headless --preset ground --temporal 32\`, GPU, $width x $height): $profile_frame;"
  echo "each pass ended by glFinish and timed apart: $profile_passes. The shading pass shades a"
  echo "compact quarter-resolution image (the resolve takes the frame's offset), so it costs what a"
  echo "quarter-resolution frame does: a full frame at $((width / 4)) x $((height / 4)) takes $quarter_ms ms against"
  echo "$full_ms ms at $width x $height (both \`--without shadows\`), $quarter_premium times a sixteenth of it. Neighbouring"
  echo "rays 4 pixels apart diverge more within a SIMD group than neighbouring pixels do. The resolve"
  echo "reads its Catmull-Rom taps as five linear reads (the 16 taps less the corners, renormalised)."
  echo
  echo "The resolve keeps a pixel's history only where it is that pixel's: carried by its own motion"
  echo "(the history's depth there, the sky's at infinity) it must land within one pixel of it; else a"
  echo "cloud has moved in or out, and the block's new samples fill it. Pixels not yet shaded (the edge"
  echo "the camera pans toward, and rejected ones) take the new samples interpolated, averaged over"
  echo "frames (10% of each frame's fill) until their own turn. What remains in motion: a cloud edge"
  echo "lags by up to 16 frames where its block's newest sample lies on the other side of it, and a"
  echo "faint 4 x 4 texture shows where single new samples sit among filled pixels, at the edge the"
  echo "camera pans toward."
  echo
  echo "## Lighting variants (preset \`horizon\`)"
  echo
  echo "| Variant | \`--variant\` | Image |"
  echo "|---|---|---|"
  for v in "${variants[@]}"; do
    IFS='|' read -r name spec caption <<< "$v"
    echo "| $caption | \`${spec:-(default)}\` | ![$name](images/clouds_variant_$name.png) |"
  done
  echo
  echo "## GPU against the CPU reference"
  echo
  echo "\`cloudmath_cloud_renderer --compare --preset ground\` at $width x $height: $compare."
  echo "With \`--accumulate 8\` (the average of frames 0 to 7, each with its own march jitter and"
  echo "dither): $accumulated."
  echo
  echo "## Convergence"
  echo
  echo "\`cloudmath_cloud_renderer --convergence --width 160 --height 90\`: every preset against a"
  echo "converged render of the same lighting model, with one setting changed per row (the view"
  echo "march's error against the light estimate's)."
  echo
  echo "$convergence"
  echo
  echo "The switches the renderer no longer has (empty-space skipping, texture LOD, a fixed view jitter,"
  echo "uniform and unjittered light steps, the light's far samples on the base shape, the"
  echo "capped and shadow-map reaches, the run-time uber-shader) and the measurements that removed"
  echo "them: [lighting_research.md](lighting_research.md), \"Switches removed\"."
  echo
  echo "## Frame time of every variant"
  echo
  echo "\`cloudmath_cloud_renderer --bench --preset ground --width $width --height $height\`:"
  echo
  echo "$bench" | grep -v '^wrote'
  echo
  echo "## Static cost of the fragment shader"
  echo
  echo "\`bash scripts/shader-cost.sh $renderer\` (the peer's row: [peer_bench.md](peer_bench.md)). SPIR-V"
  echo "instructions in function bodies after \`spirv-opt -O\`, texture operations and loops, each counted"
  echo "once where it is written (a static count, not a timing):"
  echo
  echo "$cost"
} > docs/renderer.md
echo "render-docs: wrote docs/renderer.md and docs/images/clouds_*.png"
