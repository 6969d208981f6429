#!/usr/bin/env bash
# Writes docs/glsl_cost.md: a static SPIR-V instruction count per GLSL twin, a proxy for its
# GPU cost (not a timing). For each line of tests/glsl/calls.txt it compiles a Vulkan compute
# shader that stores the expression, optimises it with `spirv-opt -O`, and counts the
# instructions in the function bodies, minus those of a baseline shader storing a.x + b.x.
#
# Usage: bash scripts/spirv-cost.sh [OUTPUT]      (default: docs/glsl_cost.md)
# Needs: glslangValidator, spirv-opt, spirv-dis (glslang-tools, spirv-tools) and the
# cloudmath_glsl_flatten tool, which it builds in build/test (configuring it if needed).
# Prints only the output path and the count range; on a compile error, the tool's output.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build/test"
out=${1:-"$root/docs/glsl_cost.md"}
calls="$root/tests/glsl/calls.txt"

for tool in glslangValidator spirv-opt spirv-dis cmake; do
    command -v "$tool" >/dev/null || { echo "spirv-cost: $tool not found (bash scripts/install-deps.sh)" >&2; exit 1; }
done

# --- the flattened module, from the flatten tool (what raw OpenGL users compile) ------------
if [[ ! -f "$build/CMakeCache.txt" ]]; then
    generator=()
    command -v ninja >/dev/null && generator=(-G Ninja)
    cmake -S "$root" -B "$build" "${generator[@]}" -DCLOUDMATH_BUILD_TESTS=ON >/dev/null
fi
cmake --build "$build" --target cloudmath_glsl_flatten >/dev/null
flatten="$build/tests/glsl/cloudmath_glsl_flatten"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$flatten" cloudmath > "$work/module.glsl"

# Shader header: prelude, module, helpers, then the compute entry point.
{
    echo "#version 450"
    cat "$root/tests/glsl/calls_prelude.glsl" "$work/module.glsl" "$root/tests/glsl/calls_helpers.glsl"
    cat <<'EOF'
layout(local_size_x = 64) in;
struct CmTestInput {
    vec4 a;
    vec4 b;
    int n;
};
layout(std430, set = 0, binding = 0) readonly buffer CmTestInputs { CmTestInput cm_test_in[]; };
layout(std430, set = 0, binding = 1) writeonly buffer CmTestOutputs { float cm_test_out[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    vec4 a = cm_test_in[i].a;
    vec4 b = cm_test_in[i].b;
    int n = cm_test_in[i].n;
EOF
} > "$work/head.glsl"

# measure ID EXPRESSION: writes the instruction count to $work/ID.count, or the tools'
# output to $work/ID.error.
measure() {
    local expression=$2 base="$work/$1"
    { cat "$work/head.glsl"; printf '    cm_test_out[i] = (%s);\n}\n' "$expression"; } > "$base.comp"
    if ! glslangValidator -V "$base.comp" -o "$base.spv" > "$base.log" 2>&1 ||
       grep -q -e WARNING -e ERROR "$base.log" ||
       ! spirv-opt -O "$base.spv" -o "$base.opt.spv" >> "$base.log" 2>&1 ||
       ! spirv-dis "$base.opt.spv" -o "$base.spvasm" >> "$base.log" 2>&1; then
        { echo "expression: $expression"; cat "$base.log"; } > "$base.error"
        return 0
    fi
    # Instructions inside function bodies, without the structural ones.
    awk '{ op = ($2 == "=") ? $3 : $1 }
         op == "OpFunction" { inside = 1; next }
         op == "OpFunctionEnd" { inside = 0; next }
         inside && op != "OpLabel" && op != "OpFunctionParameter" { count++ }
         END { print count + 0 }' "$base.spvasm" > "$base.count"
}
export -f measure
export work

# --- the calls ---------------------------------------------------------------------------------
names=()
expressions=()
while IFS= read -r line || [[ -n "$line" ]]; do
    [[ "$line" =~ ^[[:space:]]*(#|$) ]] && continue
    name=${line%%|*}
    expression=${line#*|}
    name=$(echo "$name" | xargs)
    expression=$(sed -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' <<<"$expression")
    names+=("$name")
    expressions+=("$expression")
done < "$calls"

# Job list: "baseline" first, then one per call; NUL-separated pairs for xargs.
# shellcheck disable=SC2016  # $1 and $2 belong to the inner bash
{
    printf '%s\0%s\0' baseline 'a.x + b.x'
    for k in "${!expressions[@]}"; do printf '%s\0%s\0' "$k" "${expressions[$k]}"; done
} | xargs -0 -n 2 -P "$(nproc 2>/dev/null || echo 2)" bash -c 'measure "$1" "$2"' _

if compgen -G "$work/*.error" >/dev/null; then
    for f in "$work"/*.error; do echo "spirv-cost: compile failed:" >&2; cat "$f" >&2; done
    exit 1
fi

# --- the table ------------------------------------------------------------------------------------
baseline=$(cat "$work/baseline.count")
module_of() {  # GLSL file that defines function $1
    local file
    file=$(grep -lE "^[A-Za-z_][A-Za-z0-9_]*[[:space:]]+$1[[:space:]]*\(" "$root"/include/cloudmath/glsl/*.glsl | head -n 1)
    basename "${file:-unknown}" .glsl
}
rows="$work/rows.tsv"
: > "$rows"
for k in "${!names[@]}"; do
    count=$(( $(cat "$work/$k.count") - baseline ))
    printf '%s\t%05d\t%s\t%s\t%s\n' "$(module_of "${names[$k]}")" "$k" "${names[$k]}" \
        "${expressions[$k]}" "$count" >> "$rows"
done
sort -t $'\t' -k1,1 -k2,2 "$rows" > "$rows.sorted"

glslang_version=$(glslangValidator --version | head -n 1 | sed 's/^Glslang Version: [0-9]*://')
spirv_tools_version=$(spirv-opt --version 2>&1 | head -n 1 | sed 's/ unknown hash//')
mkdir -p "$(dirname "$out")"
{
    cat <<EOF
# SPIR-V cost of the GLSL twins

Generated by \`bash scripts/spirv-cost.sh\` (rerun it after changing
include/cloudmath/glsl/ or tests/glsl/calls.txt; do not edit by hand).
Tools: glslangValidator (glslang $glslang_version), spirv-opt and spirv-dis ($spirv_tools_version).

**What it measures.** For each line of [tests/glsl/calls.txt](../tests/glsl/calls.txt) (one
per public function overload), a Vulkan compute shader (\`local_size_x = 64\`; std430 buffers
holding \`vec4 a, b; int n\` per invocation in, one \`float\` out) stores the expression. It is
compiled with \`glslangValidator -V\`, optimised with \`spirv-opt -O\` (which inlines every
call) and disassembled with \`spirv-dis\`. The count is the number of instructions between
\`OpFunction\` and \`OpFunctionEnd\`, not counting \`OpLabel\`, \`OpFunction\`, \`OpFunctionEnd\` and
\`OpFunctionParameter\` (control flow such as \`OpBranch\`, \`OpPhi\` and merges counts), minus
the $baseline instructions of the same shader storing \`a.x + b.x\` (loading the inputs, one add,
the store).

**A proxy for GPU cost, not a timing.** It is a static count: a loop body counts once
whatever its trip count (\`n\` octaves or cone samples), both sides of a branch count, a
transcendental (\`exp\`, \`sqrt\`, \`sin\`) counts as one instruction although it costs several
ALU cycles, and the driver's own compiler optimises further. Vector results are summed with one
\`dot\`; struct, bool and void results go through the small helpers of
tests/glsl/calls_helpers.glsl. Small or negative values mean that the call folds to (nearly)
a constant or reads fewer inputs than the baseline.

EOF
    current=""
    while IFS=$'\t' read -r module _ name expression count; do
        if [[ "$module" != "$current" ]]; then
            [[ -n "$current" ]] && echo
            printf '## %s.glsl\n\n' "$module"
            echo "| Function | Expression | SPIR-V instructions after -O |"
            echo "|---|---|---:|"
            current=$module
        fi
        # shellcheck disable=SC2016  # the backquotes are markdown
        printf '| %s | `%s` | %s |\n' "$name" "${expression//|/\\|}" "$count"
    done < "$rows.sorted"
} > "$out"

read -r min max < <(cut -f5 "$rows" | sort -n | awk 'NR == 1 { min = $1 } { max = $1 } END { print min, max }')
echo "spirv-cost: wrote $out (${#names[@]} calls, $min to $max instructions over a baseline of $baseline)"
