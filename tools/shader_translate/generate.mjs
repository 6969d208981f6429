// tools/shader_translate/generate.mjs: writes the HLSL and WGSL twins from the GLSL twins.
//
//   node tools/shader_translate/generate.mjs           write the generated files
//   node tools/shader_translate/generate.mjs --check   exit 1 naming each stale or extra file
//
// include/cloudmath/hlsl/<module>.hlsl   one per GLSL module, with its #include lines
//                                        (include guards, #define configuration as in GLSL)
// include/cloudmath/hlsl/CloudMath.ush   the whole library in one file without includes
//                                        (Unreal: a plugin's Shaders/ directory)
// include/cloudmath/wgsl/<module>.wgsl   one per module: its own declarations only (WGSL has
//                                        no #include); the header lists what to put before it
// include/cloudmath/wgsl/<module>_hooks.wgsl  the functions that call a configuration
//                                        callback, which you define (named in its header)
// include/cloudmath/wgsl/cloudmath.wgsl  the whole library without the hook files
import { readFileSync, writeFileSync, readdirSync, existsSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { HOOKS, moduleFiles, translateUnit, wgslType } from './translate.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const glslDir = join(root, 'include', 'cloudmath', 'glsl');
const hlslDir = join(root, 'include', 'cloudmath', 'hlsl');
const wgslDir = join(root, 'include', 'cloudmath', 'wgsl');

export function readGlsl(dir = glslDir) {
  const sources = {};
  for (const f of readdirSync(dir).filter((x) => x.endsWith('.glsl')).sort()) sources[f] = readFileSync(join(dir, f), 'utf8');
  return sources;
}

const stale = '(shaders.generated_current fails while it is stale)';
const hlslBanner = (name) =>
  `// cloudmath/hlsl/${name}: generated from the GLSL twin by tools/shader_translate; do not edit.\n` +
  `// Regenerate with: node tools/shader_translate/generate.mjs ${stale}.\n` +
  `// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in\n` +
  `// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments\n` +
  `// below are the GLSL twin's (file names made .hlsl).\n//\n`;
const wgslBanner = (name, requires) =>
  `// cloudmath/wgsl/${name}: generated from the GLSL twin by tools/shader_translate; do not edit.\n` +
  `// Regenerate with: node tools/shader_translate/generate.mjs ${stale}.\n` +
  `// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload\n` +
  `// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).\n` +
  `// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,\n` +
  `// #define configuration and overloads become in WGSL.\n` +
  (requires.length ? `// Requires, before this file: ${requires.join(', ')}.\n` : `// Requires nothing else.\n`) + `//\n`;

export function generate(sources = readGlsl()) {
  const out = new Map();  // path -> text
  const modules = Object.keys(sources);
  for (const name of modules) {
    const files = moduleFiles(name, sources);
    const base = name.replace(/\.glsl$/, '');
    out.set(join(hlslDir, `${base}.hlsl`), hlslBanner(`${base}.hlsl`) + translateUnit(files, { target: 'hlsl', emit: [name] }).text);
    if (name === 'cloudmath.glsl') continue;
    const w = translateUnit(files, { target: 'wgsl', emit: [name] });
    const requires = files.filter((f) => f.name !== name).map((f) => f.name.replace(/\.glsl$/, '.wgsl'));
    out.set(join(wgslDir, `${base}.wgsl`), wgslBanner(`${base}.wgsl`, requires) + w.text);
    if (w.hooked.trim()) {
      const need = w.hooksUsed.map((h) => {
        const k = HOOKS[h];
        return `//   fn ${k.fn}(${k.params.map(([t, n]) => `${n}: ${wgslType(t)}`).join(', ')}) -> ${wgslType(k.ret)}  (GLSL: #define ${h})`;
      });
      out.set(join(wgslDir, `${base}_hooks.wgsl`), wgslBanner(`${base}_hooks.wgsl`, [...requires, `${base}.wgsl`]).replace(/\/\/\n$/, '') +
        `// and your function(s):\n${need.join('\n')}\n//\n` + w.hooked);
    }
  }
  const all = moduleFiles('cloudmath.glsl', sources);
  out.set(join(hlslDir, 'CloudMath.ush'), hlslBanner('CloudMath.ush').replace('GLSL twin', 'GLSL twins (cloudmath.glsl and its includes, in one file)') +
    translateUnit(all, { target: 'hlsl', flatten: true }).text);
  const allWgsl = translateUnit(all, { target: 'wgsl' });
  out.set(join(wgslDir, 'cloudmath.wgsl'), wgslBanner('cloudmath.wgsl', []).replace('GLSL twin', 'GLSL twins (every module, in dependency order)') + allWgsl.text);
  return out;
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const out = generate();
  if (process.argv.includes('--check')) {
    const problems = [];
    for (const [path, text] of out)
      if (!existsSync(path) || readFileSync(path, 'utf8') !== text) problems.push(`${path.replace(root + '/', '')} is stale`);
    for (const dir of [hlslDir, wgslDir])
      if (existsSync(dir)) for (const f of readdirSync(dir)) if (!out.has(join(dir, f))) problems.push(`${join(dir, f).replace(root + '/', '')} is not generated (remove it)`);
    for (const p of problems) console.error(`generate.mjs --check: ${p}; run node tools/shader_translate/generate.mjs`);
    if (problems.length) process.exit(1);
    console.log(`generate.mjs --check: ${out.size} generated files are current`);
  } else {
    for (const dir of [hlslDir, wgslDir]) mkdirSync(dir, { recursive: true });
    for (const [path, text] of out) writeFileSync(path, text);
    console.log(`generate.mjs: wrote ${out.size} files in include/cloudmath/hlsl and include/cloudmath/wgsl`);
  }
}
