# Sourced by the bench scripts (bench.sh, bench-noise.sh, speed-vs-error.sh): installs the
# dependencies, configures the Release tree build/bench once (tests and examples off) and
# builds the given targets quietly.
# Usage: source scripts/bench-build.sh; cloudmath_build_bench "$root" TARGET...
cloudmath_build_bench() {
    local root=$1
    shift
    local build="$root/build/bench"
    bash "$root/scripts/install-deps.sh"
    local generator=()
    command -v ninja >/dev/null && generator=(-G Ninja)
    if [[ ! -f "$build/CMakeCache.txt" ]]; then
        cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
            -DCLOUDMATH_BUILD_TESTS=OFF -DCLOUDMATH_BUILD_BENCH=ON -DCLOUDMATH_BUILD_EXAMPLES=OFF >/dev/null
    fi
    # Quiet on success; the compiler's messages on failure (ninja prints them to stdout).
    local log
    log=$(mktemp)
    if ! cmake --build "$build" --target "$@" > "$log" 2>&1; then
        cat "$log" >&2
        rm -f "$log"
        echo "bench: the build failed" >&2
        return 1
    fi
    rm -f "$log"
}
