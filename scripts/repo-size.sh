#!/usr/bin/env bash
# scripts/repo-size.sh: what a user downloads, measured (issue 39's targets; README "Install").
#   the shallow clone       git clone --depth 1 of HEAD: its pack (what CMake FetchContent
#                           with GIT_SHALLOW TRUE downloads) and the checkout on disk
#   docs/                   the tracked files under docs/, bytes on disk
#   the npm package         `npm pack --dry-run` of web/ (the cloudmath-glsl tarball), when npm is here
#   --growth A B            the bytes that the commits A..B add to a packed repository: every
#                           object new in B and not in A, as git stores it compressed (a
#                           regeneration of the reports is measured this way, docs/releasing.md)
# Prints "name: N MB" lines (MB = 10^6 bytes). Needs git (and npm for the package line).
# Usage: bash scripts/repo-size.sh [--growth A B]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mb() { awk -v b="$1" 'BEGIN { printf "%.1f MB", b / 1e6 }'; }

if [[ ${1:-} == --growth ]]; then
    [[ $# == 3 ]] || { echo "usage: bash scripts/repo-size.sh --growth A B" >&2; exit 2; }
    git rev-parse -q --verify "$2^{commit}" >/dev/null || { echo "repo-size.sh: no commit '$2'" >&2; exit 2; }
    git rev-parse -q --verify "$3^{commit}" >/dev/null || { echo "repo-size.sh: no commit '$3'" >&2; exit 2; }
    # Packed alone: a throwaway pack of exactly those objects, deltas against each other only
    # (a real repository may delta them against older objects and store them smaller).
    bytes=$(git rev-list --objects "$2..$3" | git pack-objects --stdout -q | wc -c)
    echo "growth $2..$3: $(mb "$bytes") ($bytes bytes, the new objects packed alone)"
    exit 0
fi
[[ $# == 0 ]] || { echo "usage: bash scripts/repo-size.sh [--growth A B]" >&2; exit 2; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# file:// so that git packs as it does over the network (a plain path hard-links the objects).
git clone -q --depth 1 --no-tags "file://$PWD" "$tmp/clone"
pack=$(find "$tmp/clone/.git/objects/pack" -name '*.pack' -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }')
checkout=$(git -C "$tmp/clone" ls-files -z | (cd "$tmp/clone" && xargs -0 stat -c %s) | awk '{ s += $1 } END { print s + 0 }')
docs=$(git ls-files -z docs | xargs -0 stat -c %s | awk '{ s += $1 } END { print s + 0 }')
echo "shallow clone: $(mb "$pack") downloaded (its pack), $(mb "$checkout") checked out"
echo "docs/: $(mb "$docs") ($(git ls-files docs | wc -l) files)"
if command -v npm >/dev/null 2>&1 && [[ -f web/package.json ]]; then
    npm_bytes=$(cd web && npm pack --dry-run --json 2>/dev/null | awk -F': *' '/"size"/ { gsub(/[^0-9]/, "", $2); print $2; exit }')
    [[ -n $npm_bytes ]] && echo "npm package (cloudmath-glsl): $(mb "$npm_bytes") downloaded"
fi
