#!/usr/bin/env bash
# Prints the accuracy figures that the unit tests measure (and assert): float/double error
# of each stable form against quad / long double references, beside the textbook forms the
# library replaces. These are the numbers quoted in README.md and docs/accuracy.md.
# Usage: bash scripts/accuracy.sh    (builds the plain-variant tests in build/test if needed)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/install-deps.sh
if [ ! -f build/test/CMakeCache.txt ]; then
  cmake -S . -B build/test -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOUDMATH_BUILD_TESTS=ON >/dev/null
fi
modules=(core phase transmittance integration multiple_scattering cone_sampling geometry density)
targets=()
for m in "${modules[@]}"; do targets+=("test_${m}_plain"); done
cmake --build build/test -j "$(nproc 2>/dev/null || echo 2)" --target "${targets[@]}" >/dev/null

for m in "${modules[@]}"; do
  # doctest prints MESSAGE lines as "file:line: MESSAGE: text"; keep the text.
  out=$("build/test/tests/test_${m}_plain" 2>&1 | sed -n 's/^.*: MESSAGE: //p' || true)
  [ -n "$out" ] && printf '== %s\n%s\n' "$m" "$out"
done
exit 0
