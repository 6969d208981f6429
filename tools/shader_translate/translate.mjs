// tools/shader_translate/translate.mjs: GLSL -> HLSL / WGSL for the subset cloudmath's twins
// are written in. One source of truth: include/cloudmath/hlsl and include/cloudmath/wgsl are
// generated from include/cloudmath/glsl by generate.mjs with this module; the parity tests
// translate their GLSL cases with it too.
//
//   import { translateUnit } from './translate.mjs';
//   const text = translateUnit([{ name: 'core.glsl', text }], { target: 'hlsl' | 'wgsl', ... });
//
// A unit is a list of GLSL files in dependency order (each once). Options:
//   target   'hlsl' or 'wgsl'
//   emit     file names whose items are printed (default: all); the others only declare
//            (the included modules of a module file)
//   flatten  HLSL: drop #include lines (the unit is self-contained)
//   defines  WGSL: { NAME: value } as if #defined before the first file
//   hooks    configuration callbacks: { CM_MS_PHASE: { fn: 'cm_ms_phase', ret: 'float',
//            params: [['float', 'mu'], ['float', 'scale']] }, ... }; in WGSL the macro is
//            the function fn the user defines, and the #ifdef CM_MS_PHASE sections are
//            returned apart (result.hooked) unless hooksInline
// Returns { text, hooked } for WGSL, { text } for HLSL. Throws TranslateError naming the file
// and line of any construct outside the subset.
import { parse, TranslateError } from './glsl_parse.mjs';
import { Analysis } from './analysis.mjs';
import { emitHlsl } from './emit_hlsl.mjs';
import { emitWgsl } from './emit_wgsl.mjs';
import { joinItems } from './emit_common.mjs';

export { TranslateError };
export { overloadName, wgslType } from './emit_wgsl.mjs';
export { hlslType, makerName } from './emit_hlsl.mjs';

// The configuration callbacks of the twins (the GLSL #define CM_X my_function hooks).
export const HOOKS = {
  CM_CONE_EXTINCTION: { fn: 'cm_cone_extinction', ret: 'float', params: [['vec3', 'p'], ['int', 'i']] },
  CM_MS_PHASE: { fn: 'cm_ms_phase', ret: 'float', params: [['float', 'mu'], ['float', 'scale']] },
  CM_DIFFUSION_PHASE: { fn: 'cm_diffusion_phase', ret: 'float', params: [['float', 'mu'], ['float', 'scale']] },
  CM_ATMOSPHERE_TABLE: { fn: 'cm_atmosphere_table', ret: 'vec3', params: [['int', 'part'], ['int', 'x'], ['int', 'y']] },
};

const FILE_MARK = '#pragma cm_file';

// WGSL has no preprocessor. This evaluates #ifdef / #ifndef / #else / #endif with the
// defines seen so far and returns GLSL text without them:
// - #define N <number> stays (the emitter prints const N = <number>), or becomes
//   #pragma cm_override N <number> when it is the default of an #ifndef N (a setting);
// - #define N <identifier> becomes an alias (substituted in the tokens);
// - #ifdef HOOK sections are kept between #pragma cm_hook_begin / cm_hook_end lines;
// - #include, include guards, #version and #extension lines disappear.
// Removed directive lines become `#pragma cm_removed` (which the emitter drops with the
// comments above it, which spoke of the directive), `#pragma cm_removed keep` for an include
// guard (whose comments are the file's header); other removed lines become blank, so line
// numbers in errors stay those of the input.
export function preprocessWgsl(text, { defines = {}, hooks = {}, file } = {}) {
  const defined = new Map(Object.entries(defines));
  const aliases = {};
  for (const [k, v] of defined) if (/^[A-Za-z_]\w*$/.test(String(v))) aliases[k] = String(v);
  const stack = [];  // { active, parentActive, name, kind, hook }
  const active = () => stack.every((f) => f.active);
  const out = [];
  const lines = text.split('\n');
  const fail = (msg, i) => { throw new TranslateError(msg, i + 1, file); };
  for (let i = 0; i < lines.length; i++) {
    const line = lines[i];
    const m = /^\s*#\s*(\w+)\s*(.*?)\s*(\/\/.*)?$/.exec(line);
    if (!m) { out.push(active() ? line : ''); continue; }
    const [, dir, rest] = m;
    if (dir === 'pragma' && rest.startsWith('cm_')) { out.push(active() ? line : ''); continue; }
    if (dir === 'ifdef' || dir === 'ifndef') {
      const name = rest;
      const isHook = dir === 'ifdef' && Object.hasOwn(hooks, name);
      const on = isHook || (dir === 'ifdef' ? defined.has(name) : !defined.has(name));
      const wasActive = active();
      stack.push({ active: on, name, kind: dir, hook: isHook });
      out.push(isHook && wasActive ? `#pragma cm_hook_begin ${name}` : !wasActive ? '' : /^CM_\w+_GLSL$/.test(name) ? '#pragma cm_removed keep' : '#pragma cm_removed');
      continue;
    }
    if (dir === 'if' || dir === 'elif') fail(`#${dir} is not supported (use #ifdef / #ifndef)`, i);
    if (dir === 'else') {
      const f = stack[stack.length - 1];
      if (!f) fail('#else without #ifdef', i);
      if (f.hook) fail(`#else in a #ifdef ${f.name} hook section`, i);
      f.active = !f.active;
      out.push(stack.slice(0, -1).every((x) => x.active) ? '#pragma cm_removed' : '');
      continue;
    }
    if (dir === 'endif') {
      const f = stack.pop();
      if (!f) fail('#endif without #ifdef', i);
      out.push(!active() ? '' : f.hook ? '#pragma cm_hook_end' : '#pragma cm_removed');
      continue;
    }
    if (!active()) { out.push(''); continue; }
    if (dir === 'define') {
      const d = /^(\w+)(\(.*)?\s*(.*)$/.exec(rest);
      if (!d || d[2]) fail(`function-like macros are not supported: ${line.trim()}`, i);
      const [, name, , value] = d;
      defined.set(name, value);
      if (value === '') out.push('#pragma cm_removed');
      else if (/^[A-Za-z_]\w*$/.test(value)) { aliases[name] = value; out.push('#pragma cm_removed'); }
      else if (/^[-+]?[0-9.][0-9a-fA-FxX.eE+-]*[uUfF]?$/.test(value)) {
        const f = stack[stack.length - 1];
        const setting = f && f.kind === 'ifndef' && f.name === name;
        out.push(setting ? `#pragma cm_override ${name} ${value}${m[3] ? ' ' + m[3] : ''}` : line);
      } else fail(`#define ${name} with a value WGSL cannot express: ${value}`, i);
      continue;
    }
    if (dir === 'undef') { defined.delete(rest); delete aliases[rest]; out.push('#pragma cm_removed'); continue; }
    if (['include', 'version', 'extension', 'pragma'].includes(dir)) { out.push('#pragma cm_removed'); continue; }
    fail(`#${dir} is not supported`, i);
  }
  if (stack.length) fail(`#${stack[stack.length - 1].kind} ${stack[stack.length - 1].name} without #endif`, lines.length - 1);
  return { text: out.join('\n'), aliases, defined };
}

// HLSL keeps the preprocessor lines, so nothing else checks them: every #ifdef / #ifndef
// needs its #endif, and #else and #endif their #ifdef (a dangling one was emitted as it was).
function checkConditionals(text, file) {
  const open = [];
  text.split('\n').forEach((line, i) => {
    const m = /^\s*#\s*(\w+)/.exec(line);
    if (!m) return;
    if (m[1] === 'ifdef' || m[1] === 'ifndef' || m[1] === 'if') open.push(i + 1);
    else if (m[1] === 'else' || m[1] === 'elif') { if (!open.length) throw new TranslateError(`#${m[1]} without #ifdef`, i + 1, file); }
    else if (m[1] === 'endif') { if (!open.pop()) throw new TranslateError('#endif without #ifdef', i + 1, file); }
  });
  if (open.length) throw new TranslateError('#ifdef without #endif', open[open.length - 1], file);
}

// Comments keep their text; paths and names of the GLSL files become the target's.
// HLSL keeps the GLSL's files, #includes and guards, so its comments name the .hlsl files.
// WGSL's comments stay as the GLSL twin wrote them (there is no #include to rename).
export function commentRewriter(target) {
  if (target !== 'hlsl') return (c) => c;
  return (c) => c.replace(/cloudmath\/glsl\/(\w+)\.glsl/g, 'cloudmath/hlsl/$1.hlsl')
    .replace(/\b(\w+)\.glsl\b/g, '$1.hlsl').replace(/\b(CM_\w+)_GLSL\b/g, '$1_HLSL');
}

export function translateUnit(files, options = {}) {
  // Errors name the file and line of the input, not of the concatenated unit.
  const starts = [];
  let line = 1;
  for (const f of files) { starts.push({ name: f.name, first: line + 1 }); line += 1 + f.text.split('\n').length; }
  try {
    return translateLines(files, options);
  } catch (e) {
    if (!(e instanceof TranslateError) || !e.line) throw e;
    const f = [...starts].reverse().find((x) => x.first <= e.line);
    if (!f) throw e;
    throw new TranslateError(e.raw, e.line - f.first + 1, f.name);
  }
}

function translateLines(files, { target, emit, flatten = false, defines = {}, hooks = HOOKS, hooksInline = false } = {}) {
  if (target !== 'hlsl' && target !== 'wgsl') throw new Error(`target must be 'hlsl' or 'wgsl', not ${target}`);
  const emitSet = emit ? new Set(emit) : null;
  // One parse of all files, each item tagged with its file (and, in WGSL, its hook).
  let source = '';
  for (const f of files) source += `${FILE_MARK} ${f.name}\n${f.text}\n`;
  let aliases = {};
  if (target === 'wgsl') {
    const pre = preprocessWgsl(source, { defines, hooks: hooksInline ? {} : hooks, file: 'unit' });
    source = pre.text;
    aliases = pre.aliases;
    if (!hooksInline) for (const [macro, h] of Object.entries(hooks)) if (!Object.hasOwn(aliases, macro) || aliases[macro] === macro) aliases[macro] = h.fn;
  }
  const unit = parse(source, 'unit', { aliases });
  if (target === 'wgsl') {  // the defines given as options, as if #defined before the unit
    const userDefines = Object.entries(defines).filter(([, v]) => !/^[A-Za-z_]\w*$/.test(String(v)));
    unit.items.unshift(...userDefines.map(([k, v]) => ({ kind: 'directive', text: `#define ${k} ${v}`, leading: [] })));
  }
  let file = null, hook = null;
  // The preprocessor sections an item lies in (HLSL keeps them: the same function may be
  // defined once per branch of an #ifdef / #else).
  const sections = [];
  for (const it of unit.items) {
    if (it.kind === 'directive') {
      const m = /^#\s*pragma\s+cm_file\s+(\S+)/.exec(it.text);
      if (m) { file = m[1]; it.marker = true; }
      const h = /^#\s*pragma\s+cm_hook_(begin|end)\s*(\w*)/.exec(it.text);
      if (h) { hook = h[1] === 'begin' ? h[2] : null; it.marker = true; }
      const d = /^#\s*(ifdef|ifndef|if|else|elif|endif)\b\s*(.*)$/.exec(it.text);
      if (d && (d[1] === 'ifdef' || d[1] === 'ifndef' || d[1] === 'if')) sections.push(`${d[1]} ${d[2]}`);
      else if (d && (d[1] === 'else' || d[1] === 'elif') && sections.length) sections.push(`${sections.pop()} / ${d[1]} ${d[2]}`);
      else if (d && d[1] === 'endif') sections.pop();
    }
    it.file = file || '(defines)';
    it.hook = hook;
    it.section = sections.join(' > ');
  }
  const analysis = new Analysis(unit.items.filter((it) => !it.marker), { file: 'unit', hooks });
  const wanted = (it) => !it.marker && (!emitSet || emitSet.has(it.file) || it.file === '(defines)' && target === 'wgsl');
  const comment = commentRewriter(target);
  if (target === 'hlsl') {
    checkConditionals(source, 'unit');
    const printed = emitHlsl({ items: unit.items }, analysis, { emit: wanted, flatten, comment });
    analysis.checkRecursion();
    return { text: joinItems(printed).replace(/\n{3,}/g, '\n\n') };
  }
  const printed = emitWgsl({ items: unit.items }, analysis, { emit: wanted, comment });
  analysis.checkRecursion();
  const main = printed.filter((p) => !p.item.hook);
  const hooked = printed.filter((p) => p.item.hook);
  return {
    text: joinItems(main).replace(/\n{3,}/g, '\n\n'),
    hooked: joinItems(hooked).replace(/\n{3,}/g, '\n\n'),
    hooksUsed: [...new Set(hooked.map((p) => p.item.hook))],
  };
}

// The files of a module and its includes, dependencies first, each once.
export function moduleFiles(name, sources) {
  const order = [];
  const seen = new Set();
  const visit = (n, chain) => {
    if (seen.has(n)) return;
    if (chain.includes(n)) throw new Error(`#include cycle: ${[...chain, n].join(' -> ')}`);
    if (!Object.hasOwn(sources, n)) throw new Error(`#include "${n}": no such file (from ${chain[chain.length - 1] || 'the unit'})`);
    for (const m of sources[n].matchAll(/^\s*#\s*include\s+"([^"]+)"/gm)) visit(m[1], [...chain, n]);
    seen.add(n);
    order.push({ name: n, text: sources[n] });
  };
  visit(name, []);
  return order;
}
