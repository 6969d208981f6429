#!/usr/bin/env bash
# Benchmarks every lighting module and writes docs/bench.md: per module, ns per evaluation in
# float and double of each variant (library, textbook "naive" form, fast approximation) and
# its speed-up over the naive form; the batch entry points over 2^20 elements as ns per
# element, as a multiple of a plain copy of the same size and as a speed-up over the naive
# scalar loop, all measured in one run of each executable; the issue's 3x target for batch
# HG and Beer-Lambert; and whether their inner loops are vectorised (objdump of the timed
# code). Also the machine, compiler, flags, date and command.
#
# Usage: bash scripts/bench.sh [OUTPUT]      (default: docs/bench.md)
#        CLOUDMATH_BENCH_MIN_TIME=0.5 bash scripts/bench.sh   (longer, steadier runs)
# Builds the six module benchmarks (bench/bench_<module>.cpp) in a Release tree (build/bench)
# and runs them with --benchmark_min_time=0.1 (about a minute on 2 cores, build included).
# The noise benchmark has its own script, scripts/bench-noise.sh. Needs no Python: the JSON
# output is read with POSIX awk, the disassembly with objdump (binutils).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build/bench"
out=${1:-"$root/docs/bench.md"}
min_time=${CLOUDMATH_BENCH_MIN_TIME:-0.1}
modules=(phase transmittance integration multiple_scattering cone_sampling geometry)

source "$root/scripts/bench-build.sh"
targets=()
for m in "${modules[@]}"; do targets+=("cloudmath_bench_$m"); done
cloudmath_build_bench "$root" "${targets[@]}"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One tab-separated line per benchmark from each JSON file (one "key": value per line):
# module, name (without /manual_time), items_per_second, label, x_copy, speedup_vs_naive,
# error message, ns_per_element. (POSIX awk: Debian's default awk is mawk.)
: > "$work/rows.tsv"
for m in "${modules[@]}"; do
    echo "bench: running cloudmath_bench_$m" >&2
    "$build/bench/cloudmath_bench_$m" --benchmark_min_time="$min_time" \
        --benchmark_out="$work/$m.json" --benchmark_out_format=json > "$work/$m.txt" 2>&1
    awk -v module="$m" '
        /"benchmarks": \[/ { in_list = 1; next }
        !in_list { next }
        /^ *\{ *$/ { name = ""; items = ""; label = ""; xcopy = ""; speedup = ""; error = ""; ns = ""; next }
        /^ *"[a-z_]+": / {
            key = $0; sub(/^ *"/, "", key); sub(/".*$/, "", key)
            value = $0; sub(/^ *"[a-z_]+": */, "", value); sub(/,? *$/, "", value); gsub(/"/, "", value)
            if (key == "name") { name = value; sub(/\/manual_time$/, "", name) }
            if (key == "items_per_second") items = value
            if (key == "label") label = value
            if (key == "x_copy") xcopy = value
            if (key == "speedup_vs_naive") speedup = value
            if (key == "error_message") error = value
            if (key == "ns_per_element") ns = value
            next
        }
        /^ *\},? *$/ && name != "" {
            printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", module, name, items, label, xcopy, speedup, error, ns
            name = ""
        }' "$work/$m.json" >> "$work/rows.tsv"
done
[[ -s "$work/rows.tsv" ]] || { echo "bench: no results parsed from the benchmark JSON" >&2; exit 1; }

# Per-module table of the scalar benchmarks "<group>/<variant>/<type>": one row per group and
# variant in registration order; the baseline of a group is its first variant named naive*.
scalar_table() {
    awk -F'\t' -v module="$1" '
        function ns_text(key, type,    v) {
            if ((key, type) in failed) return "failed"
            if (!((key, type) in ns)) return "-"
            v = ns[key, type]
            return v < 10 ? sprintf("%.2f", v) : (v < 100 ? sprintf("%.1f", v) : sprintf("%.0f", v))
        }
        function speedup_text(group, key, type,    b) {
            if (!(group in base)) return "-"
            b = base[group]
            if (!((b, type) in ns) || !((key, type) in ns)) return "-"
            return sprintf("%.2fx", ns[b, type] / ns[key, type])
        }
        $1 == module && $2 !~ /^batch\// {
            split($2, part, "/")
            key = part[1] "/" part[2]
            if (!(key in seen)) { seen[key] = 1; order[++count] = key; group_of[key] = part[1]; label[key] = $4 }
            if ($7 != "") failed[key, part[3]] = $7
            else if ($3 + 0 > 0) ns[key, part[3]] = 1e9 / $3
            if (part[2] ~ /^naive/ && !(part[1] in base)) base[part[1]] = key
        }
        END {
            print "| Function | Variant | float ns | double ns | float speed-up over naive | double speed-up over naive |"
            print "|---|---|---:|---:|---:|---:|"
            for (i = 1; i <= count; i++) {
                key = order[i]; g = group_of[key]
                printf "| `%s` | %s | %s | %s | %s | %s |\n", g, label[key], ns_text(key, "float"), ns_text(key, "double"),
                    speedup_text(g, key, "float"), speedup_text(g, key, "double")
            }
        }' "$work/rows.tsv"
}

# All batch benchmarks "batch/<function>/<variant>/<type>", module by module.
batch_table() {
    awk -F'\t' '
        function num(v, digits) { return v == "" ? "-" : sprintf("%." digits "f", v) }
        function ns_text(key, type,    v) {
            if ((key, type) in failed) return "failed"
            if (!((key, type) in ns)) return "-"
            v = ns[key, type]
            return v < 10 ? sprintf("%.3f", v) : sprintf("%.1f", v)
        }
        $2 ~ /^batch\// {
            split($2, part, "/")
            key = $1 "/" part[2] "/" part[3]
            if (!(key in seen)) { seen[key] = 1; order[++count] = key; module_of[key] = $1; fn[key] = part[2]; label[key] = $4 }
            type = part[4]
            if ($7 != "") failed[key, type] = $7
            else if ($8 + 0 > 0) ns[key, type] = $8
            xcopy[key, type] = $5
            speedup[key, type] = $6
        }
        END {
            print "| Module | Function | Variant | float ns/element | float time / copy | float speed-up over naive loop | double ns/element | double time / copy | double speed-up over naive loop |"
            print "|---|---|---|---:|---:|---:|---:|---:|---:|"
            for (i = 1; i <= count; i++) {
                key = order[i]
                f = fn[key] == "copy" ? "copy" : "`" fn[key] "`"
                printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", module_of[key], f, label[key],
                    ns_text(key, "float"), num(xcopy[key, "float"], 2), fn[key] == "copy" ? "" : num(speedup[key, "float"], 2),
                    ns_text(key, "double"), num(xcopy[key, "double"], 2), fn[key] == "copy" ? "" : num(speedup[key, "double"], 2)
            }
        }' "$work/rows.tsv"
}

# The issue target: batch (exact, float) at least 3x faster than the naive scalar loop.
target_row() {  # module function variant description
    awk -F'\t' -v module="$1" -v function_name="$2" -v variant="$3" -v description="$4" '
        $1 == module && $2 == "batch/" function_name "/naive_loop/float" && $8 + 0 > 0 { naive = $8 }
        $1 == module && $2 == "batch/" function_name "/" variant "/float" && $8 + 0 > 0 { exact = $8; speedup = $6 }
        END {
            if (speedup == "") { if (variant == "exact") printf "| %s | - | - | - | not measured |\n", description; exit }
            verdict = (speedup + 0 >= 3) ? "met" : "NOT met"
            if (variant != "exact") verdict = verdict " (for information: not what users get by default)"
            printf "| %s | %.3f | %.3f | %.2fx | %s |\n", description, exact, naive, speedup, verdict
        }' "$work/rows.tsv"
}

# Disassembles one out-of-line function of a bench binary (and cloudmath functions it calls
# directly, one level down) and summarises its floating-point instructions.
inspect_row() {  # executable symbol description
    local exe=$1 symbol=$2 description=$3 asm="$work/$2.s" target
    objdump -d --no-show-raw-insn --disassemble="$symbol" "$exe" > "$asm"
    for target in $(grep -oE '<_ZN9cloudmath[^>+]*>' "$asm" | tr -d '<>' | sort -u || true); do
        objdump -d --no-show-raw-insn --disassemble="$target" "$exe" >> "$asm"
    done
    awk -F'\t' -v description="$description" -v symbol="$symbol" '
        /^ *[0-9a-f]+:\t/ {
            split($2, word, " "); m = word[1]; base = m; sub(/^v/, "", base)
            instructions++
            # Packed float arithmetic and conversions (logical ops like xorps are left out: scalar
            # code uses them too, to negate or to zero a register).
            if (base ~ /^(add|sub|mul|div|sqrt|min|max|rsqrt|rcp|cmp[a-z]*|blendv)ps$/ ||
                base ~ /^f(n)?m(add|sub)[0-9]+ps$/ || base == "cvttps2dq" || base == "cvtdq2ps" || base == "cvtps2dq") {
                packed[base]++; packed_total++
                if ($2 ~ /%ymm/) width = width < 256 ? 256 : width
                else if ($2 ~ /%zmm/) width = 512
                else if (width < 128) width = 128
            }
            if (base ~ /^(add|sub|mul|div|sqrt|min|max|rsqrt|rcp|cmp[a-z]*)ss$/ || base ~ /^f(n)?m(add|sub)[0-9]+ss$/) scalar_total++
            if (m ~ /^(call|jmp)/ && $2 ~ /@plt>/) {
                callee = $2; sub(/^.*</, "", callee); sub(/@plt>.*$/, "", callee)
                if (!(callee in called)) { called[callee] = 1; calls = calls (calls == "" ? "" : ", ") callee }
            }
        }
        END {
            n = split("mulps addps subps divps sqrtps rsqrtps rcpps minps maxps cmpltps cmpleps cmpnleps cmpnltps cmpeqps cmpneqps cmpps blendvps fmadd132ps fmadd213ps fmadd231ps cvttps2dq cvtps2dq cvtdq2ps", name, " ")
            list = ""
            for (i = 1; i <= n; i++) if (name[i] in packed) list = list (list == "" ? "" : ", ") name[i] " " packed[name[i]]
            verdict = packed_total > 0 ? sprintf("yes, packed %d-bit (%d floats per instruction)", width, width / 32) : "no, scalar"
            printf "| %s (`%s`) | %s | %d | %d | %s | %s |\n", description, symbol, verdict, packed_total + 0,
                scalar_total + 0, list == "" ? "-" : list, calls == "" ? "none" : calls
        }' "$asm"
}

title_of() {
    case $1 in
        phase) echo "Phase functions" ;;
        transmittance) echo "Transmittance" ;;
        integration) echo "Step integration" ;;
        multiple_scattering) echo "Multiple scattering" ;;
        cone_sampling) echo "Cone light sampling" ;;
        geometry) echo "Planet-scale geometry" ;;
    esac
}
notes_of() {
    case $1 in
        phase) echo "4096 cosines mu evenly spread over [-1, 1]; g = 0.8 (Draine: g = 0.5, alpha = 1); Mie fit at 10 um. The naive Mie form is what engines do with measured data: a 1800-entry table over the angle (acos, then linear interpolation)." ;;
        transmittance) echo "4096 optical depths evenly spread over [0, 10]; powder with k = 2 (powder has no textbook form in naive.hpp). The exp rows compare the exponentials themselves; exp_vectorizable is what the exact batch functions use, and is slower than the libm call when not vectorised." ;;
        integration) echo "4096 steps: S in [0, 1], sigma_t in [0, 0.1] 1/m, ds = 25 m. The two naive forms are cheaper and wrong: the clamp is biased for thin media, the Riemann sum ignores the decay within the step (their errors: speed_vs_error.md)." ;;
        multiple_scattering) echo "4096 (tau, mu) pairs, tau in [0, 10], mu in [-1, 1]; g = 0.8, a = b = c = 0.5; parameters and the run-time octave count are opaque to the compiler." ;;
        cone_sampling) echo "One optical depth toward the sun per point, 4096 points in a 2 km box, through a Gaussian puff of extinction (one exp per lookup). Cone: 6 samples, 60 m steps, spread 0.5, the far sample at 600 m standing for 60 m; the marches cover the same 630 m. Baseline: the 8-step march." ;;
        geometry) echo "4096 rays: altitude in [0, 4000] m, cos_zenith in [-1, 1], Earth radius 6371 km, sphere (layer top) at 4000 m, layer bottom at 1500 m. The naive first hit returns one distance and loses tens of metres in float here; the library returns both roots accurately." ;;
    esac
}

compiler=$(grep -E '^CMAKE_CXX_COMPILER:' "$build/CMakeCache.txt" | cut -d= -f2-)
compiler_version=$("$compiler" --version | head -n 1)
cxx_flags=$(grep -E '^CMAKE_CXX_FLAGS:' "$build/CMakeCache.txt" | cut -d= -f2-)
release_flags=$(grep -E '^CMAKE_CXX_FLAGS_RELEASE:' "$build/CMakeCache.txt" | cut -d= -f2-)
flags=$(echo "$cxx_flags $release_flags -std=c++17" | sed 's/^ *//; s/  */ /g')
cpu=$(lscpu 2>/dev/null | awk -F: '/^Model name/ { sub(/^ */, "", $2); print $2; exit }')
[[ -n "$cpu" ]] || cpu=$(grep -m 1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2- | sed 's/^ *//')
cores=$(nproc 2>/dev/null || echo "?")
caches=$(lscpu 2>/dev/null | awk -F: '/^L[23] cache/ { v = $2; sub(/^ */, "", v); printf "%s%s %s", sep, $1, v; sep = ", " }')
benchmark_version=$(dpkg-query -W -f='${Version}' libbenchmark-dev 2>/dev/null || echo "unknown")
if grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo 2>/dev/null; then
    isa_line="AVX2 and FMA present, so the rows marked \"avx2+fma, dispatched\" ran that copy and the \"baseline code only\" rows the SSE2 one"
else
    isa_line="no AVX2 + FMA, so every batch row ran the SSE2 code"
fi
date_utc=$(date -u +"%Y-%m-%d %H:%M UTC")
command_line="bash scripts/bench.sh"
[[ "$min_time" == "0.1" ]] || command_line="CLOUDMATH_BENCH_MIN_TIME=$min_time $command_line"

mkdir -p "$(dirname "$out")"
{
    cat <<END_OF_HEAD
# Lighting benchmarks: speed of every variant

Generated by \`$command_line\` on $date_utc (rerun it after changing a header or a
benchmark; do not edit by hand). Sources: [bench/bench_phase.cpp](../bench/bench_phase.cpp),
[bench_transmittance.cpp](../bench/bench_transmittance.cpp),
[bench_integration.cpp](../bench/bench_integration.cpp),
[bench_multiple_scattering.cpp](../bench/bench_multiple_scattering.cpp),
[bench_cone_sampling.cpp](../bench/bench_cone_sampling.cpp),
[bench_geometry.cpp](../bench/bench_geometry.cpp), shared scaffolding in
[bench/bench_support.hpp](../bench/bench_support.hpp), textbook forms in
[bench/naive.hpp](../bench/naive.hpp). The errors of the same variants are in
[speed_vs_error.md](speed_vs_error.md) (\`bash scripts/speed-vs-error.sh\`), the library's own
accuracy in [accuracy.md](accuracy.md).

Machine: ${cpu:-unknown CPU}, $cores cores${caches:+ ($caches)}.
A shared machine: compare ratios within one run rather than absolute times across runs.
Compiler: $compiler_version, CMake Release: \`$flags\`
(no -march: the code is compiled for SSE2, the x86-64 baseline, 4 floats per vector; the
batch functions also carry a copy compiled for AVX2 and FMA, 8 floats per vector, which they
pick at run time on CPUs that have both: on this machine, $isa_line).
Google Benchmark $benchmark_version, \`--benchmark_min_time=$min_time\`.

How to read: scalar rows are ns per call, each call on the next of 4096 pre-generated inputs
(low-discrepancy sequences), its result kept with \`benchmark::DoNotOptimize\`, in CPU time.
"Speed-up over naive" is the naive variant's time over this variant's time, both from the
same run (above 1: faster than the textbook form). Batch rows process 2^20 elements per call,
timed with the thread's CPU clock; their ns/element is that of the fastest call of the run
(interference from the other processes of a shared machine only ever adds time), and the
ratios are of these. "time / copy" is the time over that of \`std::copy\` of 2^20 elements of
the same type in the same run (1 would mean as fast as memory allows). Every batch result
of the library (its scalar loop and the batch functions) is checked against the scalar
function before it is reported; a wrong result shows as "failed".

END_OF_HEAD
    for m in "${modules[@]}"; do
        printf '## %s\n\n%s\n\n' "$(title_of "$m")" "$(notes_of "$m")"
        scalar_table "$m"
        echo
    done
    cat <<END_OF_BATCH
## Batch functions, 2^20 elements

[batch.hpp](../include/cloudmath/batch.hpp) against the naive scalar loop (the textbook
function per element), the library's scalar function per element, and a copy. exact is the
default policy (within float rounding of the scalar functions), fast the approximations of
[fast_math.hpp](../include/cloudmath/fast_math.hpp). Inputs as in the scalar tables, 2^20 of
them (4 MiB per float array, 8 MiB per double array); Mie's naive loop is the table lookup;
multiple scattering uses 3 octaves.

END_OF_BATCH
    batch_table
    cat <<END_OF_TARGET

## Issue target: batch at least 3x faster than the naive scalar loop

Exact policy (the default), float, 2^20 elements, all loops measured in the same run. The
target is about what users get by calling the function: the dispatched rows. The baseline
rows (the SSE2 copy alone, as on a CPU without AVX2) are there for information.

| Function | batch ns/element | naive loop ns/element | speed-up | target (>= 3x) |
|---|---:|---:|---:|---|
END_OF_TARGET
    target_row phase phase_hg exact "batch::phase_hg, dispatched"
    target_row transmittance beer_lambert exact "batch::beer_lambert, dispatched"
    target_row phase phase_hg exact_baseline "batch::phase_hg, baseline code only"
    target_row transmittance beer_lambert exact_baseline "batch::beer_lambert, baseline code only"
    cat <<END_OF_ASM

## Generated code of the timed loops

The float loops timed above are compiled out of line under fixed names in the bench
binaries (\`cloudmath_bench_batch_*\` call the batch function, \`cloudmath_bench_naive_loop_*\`
are the textbook loops), so the disassembly is of the very code that was timed. A batch
symbol holds both copies of its loop: the baseline one inline and the AVX2 + FMA one in the
\`cloudmath::detail::run_avx2_fma<...>\` function it calls, which is disassembled with it
(so its widest vectors are the ymm ones):

    objdump -d --no-show-raw-insn --disassemble=<symbol> build/bench/bench/cloudmath_bench_phase

(and \`cloudmath_bench_transmittance\`; any cloudmath function such a symbol calls is
disassembled too). Packed float arithmetic (\`mulps\`, \`divps\`, \`sqrtps\`, \`minps\`,
conversions such as \`cvtdq2ps\`, ... on xmm/ymm registers) means the loop is vectorised;
\`...ss\` are scalar float arithmetic (a vectorised loop keeps some for its remainder and
for the fallback GCC adds in case the output overlaps the input); a libm call in a loop
(expf, powf) means one call per element. Logical instructions (\`xorps\`, ...) are not
counted: scalar code uses them too.

| Loop | Vectorised | packed float arithmetic | scalar float arithmetic | packed instructions | library calls |
|---|---|---:|---:|---|---|
END_OF_ASM
    inspect_row "$build/bench/cloudmath_bench_phase" cloudmath_bench_batch_phase_hg_exact_float "batch::phase_hg, exact, float"
    inspect_row "$build/bench/cloudmath_bench_phase" cloudmath_bench_naive_loop_phase_hg_float "naive phase_hg loop, float"
    inspect_row "$build/bench/cloudmath_bench_transmittance" cloudmath_bench_batch_beer_lambert_exact_float "batch::beer_lambert, exact, float"
    inspect_row "$build/bench/cloudmath_bench_transmittance" cloudmath_bench_naive_loop_beer_lambert_float "naive beer_lambert loop, float"
} > "$out"

failures=$(awk -F'\t' '$7 != "" { printf "  %s %s: %s\n", $1, $2, $7 }' "$work/rows.tsv")
if [[ -n "$failures" ]]; then
    echo "bench: wrote $out, but some benchmarks failed their result check:" >&2
    echo "$failures" >&2
    exit 1
fi
echo "bench: wrote $out"
