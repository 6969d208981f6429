#!/usr/bin/env bash
# web.npm_pack: `npm pack` of web/, installed into a throwaway project, imports and returns
# the GLSL sources (resolved modules, the resolver, the ./resolve entry point). The tarball
# carries the repository's LICENSE and TypeScript declarations for both entry points: each
# .d.ts declares every export of its .js and nothing else, and a TypeScript use of the
# package type-checks with tsc (Debian's node-typescript; scripts/install-deps.sh).
# Usage: bash web/test/pack.sh WORK_DIR
set -euo pipefail
web="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="${1:?usage: pack.sh WORK_DIR}"
rm -rf "$work"
mkdir -p "$work/project"
tarball="$(cd "$web" && npm pack --silent --pack-destination "$work")"
echo "packed $tarball ($(wc -c < "$work/$tarball") bytes)"
tar -tzf "$work/$tarball" | sort > "$work/contents.txt"
# web/LICENSE is a copy of the repository's (npm packs only what is under web/).
cmp -s "$web/LICENSE" "$web/../LICENSE" || { echo "FAIL: web/LICENSE differs from the repository's LICENSE"; exit 1; }
for f in package/package.json package/README.md package/LICENSE package/dist/index.js package/dist/index.d.ts \
         package/src/resolve.js package/src/resolve.d.ts; do
  grep -qx "$f" "$work/contents.txt" || { echo "FAIL: $f missing from the tarball"; exit 1; }
done
if grep -q "node_modules\|package/demo/\|package/test/" "$work/contents.txt"; then
  echo "FAIL: the tarball ships files that are not the package's"; exit 1
fi
cd "$work/project"
printf '{ "name": "throwaway", "version": "1.0.0", "private": true, "type": "module" }\n' > package.json
npm install --no-audit --no-fund --loglevel=error "$work/$tarball" >/dev/null
cat > check.mjs <<'JS'
import { modules, sources, phase, multipleScattering, resolve, version, wgsl, wgslSources } from 'cloudmath-glsl';
import { resolveIncludes } from 'cloudmath-glsl/resolve';
const fail = (m) => { console.log('FAIL: ' + m); process.exit(1); };
const names = Object.keys(modules);
if (names.length !== 17) fail(`want 17 modules, got ${names.join(',')}`);
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
const w = wgsl('multiple_scattering_hooks');
for (const part of ['fn cm_saturate(', 'fn cm_phase_hg(', 'fn cm_multiple_scattering(', 'fn cm_multiple_scattering_with('])
  if (!w.includes(part)) fail(`wgsl('multiple_scattering_hooks') lacks ${part}`);
if (w.indexOf('fn cm_saturate(') > w.indexOf('fn cm_phase_hg(') || w.split('fn cm_saturate(').length !== 2) fail('wgsl() does not put each dependency once, first');
if (wgsl('cloudmath') !== wgslSources['cloudmath.wgsl']) fail("wgsl('cloudmath') is not cloudmath.wgsl alone");
threw = false;
try { wgsl('nope'); } catch (e) { threw = /nope/.test(e.message); }
if (!threw) fail('an unknown WGSL module does not throw an error naming it');
console.log(`ok: cloudmath-glsl ${version}, ${names.length} modules, ${Object.keys(sources).length} sources, ${modules.cloudmath.length} characters in cloudmath`);
JS
node check.mjs

# TypeScript: every entry point's "types" file declares exactly the values its module exports
# (parsed here, so a missing or stale declaration fails even where tsc would accept it).
cat > check-declarations.mjs <<'JS'
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
const fail = (m) => { console.log('FAIL: ' + m); process.exit(1); };
const root = join(process.cwd(), 'node_modules', 'cloudmath-glsl');  // as npm installed it
const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8'));
if (pkg.types !== pkg.exports['.'].types) fail(`"types" (${pkg.types}) is not exports["."].types`);
// The value names a .d.ts exports: declared consts/functions/classes and `export { a, b as c }`.
function declaredValues(text) {
  const names = new Set();
  for (const m of text.matchAll(/^export\s+(?:declare\s+)?(?:const|let|var|function|class|enum)\s+([A-Za-z_$][\w$]*)/gm))
    names.add(m[1]);
  for (const m of text.matchAll(/^export\s*\{([^}]*)\}/gm))
    for (const item of m[1].split(',').map((x) => x.trim()).filter(Boolean))
      names.add(item.split(/\s+as\s+/).pop());
  return names;
}
for (const [entry, conditions] of Object.entries(pkg.exports)) {
  const specifier = entry === '.' ? 'cloudmath-glsl' : 'cloudmath-glsl/' + entry.slice(2);
  if (!conditions.types) fail(`exports["${entry}"] has no "types"`);
  const declared = declaredValues(readFileSync(join(root, conditions.types), 'utf8'));
  const exported = Object.keys(await import(specifier));
  const undeclared = exported.filter((n) => !declared.has(n));
  const extra = [...declared].filter((n) => !exported.includes(n));
  if (undeclared.length) fail(`${conditions.types} does not declare ${undeclared.join(', ')} (exported by ${specifier})`);
  if (extra.length) fail(`${conditions.types} declares ${extra.join(', ')}, which ${specifier} does not export`);
  console.log(`ok: ${conditions.types} declares each of the ${exported.length} export(s) of ${specifier}`);
}
JS
node check-declarations.mjs

# And a strict TypeScript use of both entry points compiles; the @ts-expect-error lines fail
# the check if the declarations were too loose (any) to catch those mistakes.
command -v tsc >/dev/null 2>&1 || { echo "FAIL: tsc not found (Debian package node-typescript; bash scripts/install-deps.sh)"; exit 1; }
cat > tsconfig.json <<'JSON'
{
  "compilerOptions": {
    "target": "es2020", "lib": ["es2020"], "module": "node16", "moduleResolution": "node16",
    "strict": true, "noEmit": true, "types": [], "skipLibCheck": false
  },
  "files": ["check.mts"]
}
JSON
cat > check.mts <<'TS'
import { modules, sources, phase, coneSampling, resolve, resolveIncludes, version, wgsl, wgslSources } from 'cloudmath-glsl';
import type { ModuleName, SourceName, WgslModuleName } from 'cloudmath-glsl';
import { resolveIncludes as resolveOnly } from 'cloudmath-glsl/resolve';
import type { ResolveIncludesOptions } from 'cloudmath-glsl/resolve';
const name: ModuleName = 'multiple_scattering';
const file: SourceName = 'phase.glsl';
const wgslName: WgslModuleName = 'phase';
const texts: string[] = [modules[name], sources[file], phase, coneSampling, version, wgsl(wgslName, ['core']), wgslSources['core.wgsl']];
const options: ResolveIncludesOptions = { name: 'mine.frag' };
const shader: string = resolve('#include "cloudmath/glsl/phase.glsl"\n', { 'mine.glsl': 'x' });
const same: string = resolveIncludes('#include "core.glsl"\n', sources) + resolveOnly('x', { 'a.glsl': 'y' }, options);
// @ts-expect-error: there is no module of that name
const wrong: string = modules.no_such_module;
// @ts-expect-error: resolve takes a string
resolve(42);
// @ts-expect-error: there is no WGSL module of that name
wgsl('no_such_module');
// @ts-expect-error: file texts are strings
resolveOnly('x', { 'a.glsl': 1 });
export { texts, shader, same, wrong };
TS
tsc -p tsconfig.json || { echo "FAIL: the TypeScript use of the package does not type-check"; exit 1; }
echo "ok: tsc $(tsc --version | sed 's/Version //') type-checks a strict use of both entry points"
