#!/usr/bin/env bash
# web.npm_pack: `npm pack` of web/, installed into a throwaway project, imports and returns
# the GLSL sources (resolved modules, the resolver, the ./resolve entry point).
# Usage: bash web/test/pack.sh WORK_DIR
set -euo pipefail
web="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="${1:?usage: pack.sh WORK_DIR}"
rm -rf "$work"
mkdir -p "$work/project"
tarball="$(cd "$web" && npm pack --silent --pack-destination "$work")"
echo "packed $tarball ($(wc -c < "$work/$tarball") bytes)"
tar -tzf "$work/$tarball" | sort > "$work/contents.txt"
for f in package/package.json package/README.md package/dist/index.js package/src/resolve.js; do
  grep -qx "$f" "$work/contents.txt" || { echo "FAIL: $f missing from the tarball"; exit 1; }
done
if grep -q "node_modules\|package/demo/\|package/test/" "$work/contents.txt"; then
  echo "FAIL: the tarball ships files that are not the package's"; exit 1
fi
cd "$work/project"
printf '{ "name": "throwaway", "version": "1.0.0", "private": true, "type": "module" }\n' > package.json
npm install --no-audit --no-fund --loglevel=error "$work/$tarball" >/dev/null
cat > check.mjs <<'JS'
import { modules, sources, phase, multipleScattering, resolve, version } from 'cloudmath-glsl';
import { resolveIncludes } from 'cloudmath-glsl/resolve';
const fail = (m) => { console.log('FAIL: ' + m); process.exit(1); };
const names = Object.keys(modules);
if (names.length !== 16) fail(`want 16 modules, got ${names.join(',')}`);
for (const [name, text] of Object.entries(modules))
  if (/^[ \t]*#[ \t]*include/m.test(text)) fail(`${name}: unresolved #include`);
if (!phase.includes('float cm_phase_hg(float mu, float g)')) fail('phase lacks cm_phase_hg');
if (!multipleScattering.includes('CM_MS_PRESET_CHEAP') || !multipleScattering.includes('float cm_phase_hg(')) fail('multiple_scattering is not resolved');
if (!modules.cloudmath.includes('cm_perlin_worley')) fail('cloudmath lacks the noise module');
if (!modules.diffusion_lighting.includes('CM_DIFFUSION_MODEL_FITTED') || !modules.diffusion_lighting.includes('float cm_phase_hg(')) fail('diffusion_lighting is not resolved');
const mine = resolve('#define CM_MS_OCTAVES 2\n#include "cloudmath/glsl/phase.glsl"\nvoid main() {}\n');
if (!mine.includes('cm_phase_draine') || /^[ \t]*#[ \t]*include/m.test(mine)) fail('resolve() did not inline phase.glsl');
let threw = false;
try { resolveIncludes('#include "nope.glsl"', sources); } catch (e) { threw = /nope\.glsl/.test(e.message); }
if (!threw) fail('a missing include does not throw an error naming it');
console.log(`ok: cloudmath-glsl ${version}, ${names.length} modules, ${Object.keys(sources).length} sources, ${modules.cloudmath.length} characters in cloudmath`);
JS
node check.mjs
