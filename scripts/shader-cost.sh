#!/usr/bin/env bash
# Prints a Markdown table of the static cost of the example renderer's fragment shader, as
# its host compiles it (cloudmath_cloud_renderer --dump-shader; one program per pass), and of the peer's cloud
# shader when a checkout is given: SPIR-V instructions in function bodies after
# `spirv-opt -O` (calls inlined, dead paths folded), texture operations (OpImageSample*,
# OpImageFetch, OpImageGather, OpImageRead) and loops (OpLoopMerge). A static count, not a
# timing: a loop body counts once. scripts/render-docs.sh and scripts/peer-bench.sh put the
# table in their documents.
#
# Usage: bash scripts/shader-cost.sh RENDERER [--peer DIR]
#        RENDERER: a built cloudmath_cloud_renderer; DIR: a checkout of
#        fede-vaccaro/TerrainEngine-OpenGL (its shaders/volumetric_clouds.comp).
# Needs glslangValidator, spirv-opt and spirv-dis (glslang-tools, spirv-tools).
set -euo pipefail

renderer=${1:-}
[[ -x "$renderer" ]] || { echo "shader-cost: the first argument must be a built cloudmath_cloud_renderer" >&2; exit 2; }
shift
peer=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --peer) [[ $# -ge 2 ]] || { echo "shader-cost: --peer needs a directory" >&2; exit 2; }; peer=$2; shift 2 ;;
    *) echo "shader-cost: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
for tool in glslangValidator spirv-opt spirv-dis; do
  command -v "$tool" >/dev/null || { echo "shader-cost: $tool not found (bash scripts/install-deps.sh)" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# row LABEL STAGE FILE [spirv-opt flags]: compiles FILE for OpenGL (-G, locations and
# bindings assigned automatically), optimises, and prints the table row.
row() {
  local label=$1 stage=$2 file=$3
  shift 3
  if ! glslangValidator -G -S "$stage" --aml --amb "$file" -o "$work/s.spv" > "$work/log" 2>&1 ||
     ! spirv-opt "$@" -O "$work/s.spv" -o "$work/o.spv" >> "$work/log" 2>&1 ||
     ! spirv-dis "$work/o.spv" -o "$work/o.spvasm" >> "$work/log" 2>&1; then
    echo "shader-cost: $label does not compile:" >&2
    tail -n 20 "$work/log" >&2
    exit 1
  fi
  awk -v label="$label" '
    { op = ($2 == "=") ? $3 : $1 }
    op == "OpFunction" { inside = 1; next }
    op == "OpFunctionEnd" { inside = 0; next }
    inside && op != "OpLabel" && op != "OpFunctionParameter" { n++ }
    inside && op ~ /^OpImage(Sample|Fetch|Gather|Read)/ { tex++ }
    inside && op == "OpLoopMerge" { loops++ }
    END { printf "| %s | %d | %d | %d |\n", label, n, tex, loops }' "$work/o.spvasm"
}

for pass in frame temporal shadow background composite; do
  "$renderer" --dump-shader --pass "$pass" > "$work/$pass.frag"
done
echo "| Shader | SPIR-V instructions | texture operations | loops |"
echo "|---|---:|---:|---:|"
row "ours: the default's cloud layer at every pixel (the full frame's cloud pass; one permutation compiled in: the variant, the shape and the pass)" frag "$work/frame.frag"
row "ours: the default's temporal shading pass (\`--pass temporal\`)" frag "$work/temporal.frag"
row "ours: the default's shadow-map pass (\`--pass shadow\`)" frag "$work/shadow.frag"
row "ours: the default's background pass (\`--pass background\`: the sky, the ground and the terrain, every frame)" frag "$work/background.frag"
row "ours: the composite (\`--pass composite\`: the layer over the background, tonemap and dither, every frame)" frag "$work/composite.frag"
if [[ -n "$peer" ]]; then
  [[ -r "$peer/shaders/volumetric_clouds.comp" ]] || { echo "shader-cost: $peer/shaders/volumetric_clouds.comp not found" >&2; exit 2; }
  # Its `uniform bool enablePowder = false;` is an initialised bool uniform, which the SPIR-V
  # validator refuses for OpenGL targets; the optimiser runs without validation for it.
  row "peer: TerrainEngine-OpenGL \`volumetric_clouds.comp\`" comp "$peer/shaders/volumetric_clouds.comp" --skip-validation
fi
