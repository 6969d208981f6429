// tools/shader_translate/emit_hlsl.mjs: prints a parsed GLSL unit as HLSL that DXC (shader
// model 5 and 6), FXC and glslang's HLSL front end accept: Unity and Unreal include it as is.
//
// What changes (everything else is printed as written, preprocessor lines included, so the
// #define configuration works as in GLSL):
// - types: vecN -> floatN, ivecN -> intN, uvecN -> uintN, bvecN -> boolN;
// - global const -> static const (a plain global const is a uniform in HLSL);
// - vecN(scalar) -> floatN(s, s, s) for a literal or a name, ((floatN)(e)) otherwise (HLSL
//   has no one-argument splat constructor); vecN(wider vector) -> .xyz;
// - struct and array constructors: brace initialisers in a global const; elsewhere a struct
//   S(...) calls cm_make_S(...), a function printed after each struct;
// - built-ins: mix -> lerp, fract -> frac, inversesqrt -> rsqrt, atan(y, x) -> atan2,
//   lessThan(a, b) -> (a < b) and the other comparisons, floatBitsToUint -> asuint, ...;
// - == and != on vectors -> all(a == b) / any(a != b) (HLSL compares per component);
// - names that are HLSL keywords get a trailing underscore;
// - #include "x.glsl" -> #include "x.hlsl", include guards CM_*_GLSL -> CM_*_HLSL;
// - CM_PRECISE locals keep the macro, which HLSL defines as precise (no fused multiply-add).
import { isScalar, isVector, dim, vectorOf } from './analysis.mjs';
import { INDENT, oneLine, withComments } from './emit_common.mjs';

const KEYWORDS = new Set(['sample', 'line', 'point', 'triangle', 'lineadj', 'triangleadj', 'linear', 'centroid', 'nointerpolation',
  'noperspective', 'precise', 'shared', 'groupshared', 'static', 'uniform', 'extern', 'volatile', 'inline', 'export', 'vector',
  'matrix', 'register', 'packoffset', 'snorm', 'unorm', 'string', 'texture', 'sampler', 'technique', 'pass', 'compile', 'half',
  'double', 'dword', 'min16float', 'row_major', 'column_major', 'class', 'interface', 'namespace', 'this', 'template', 'typedef',
  'globallycoherent', 'cbuffer', 'tbuffer', 'asm', 'auto', 'case', 'catch', 'char', 'const_cast', 'default', 'delete',
  'dynamic_cast', 'enum', 'explicit', 'friend', 'goto', 'long', 'mutable', 'new', 'operator', 'private', 'protected', 'public',
  'reinterpret_cast', 'short', 'signed', 'sizeof', 'static_cast', 'switch', 'throw', 'try', 'typename', 'union', 'unsigned',
  'using', 'virtual', 'Texture', 'Buffer', 'pixelfragment', 'vertexfragment', 'stateblock', 'technique10', 'technique11']);

const RENAME = { mix: 'lerp', fract: 'frac', inversesqrt: 'rsqrt', floatBitsToUint: 'asuint', floatBitsToInt: 'asint',
  uintBitsToFloat: 'asfloat', intBitsToFloat: 'asfloat', roundEven: 'round' };
const COMPARE = { lessThan: '<', lessThanEqual: '<=', greaterThan: '>', greaterThanEqual: '>=', equal: '==', notEqual: '!=' };

export function hlslType(t) {
  if (isVector(t)) return { v: 'float', i: 'int', u: 'uint', b: 'bool' }[t[0]] + t[t.length - 1];
  return t;
}
export const hlslName = (n) => (KEYWORDS.has(n) ? n + '_' : n);
export const makerName = (struct) => `cm_make_${struct}`;

export function emitHlsl(unit, analysis, { emit = () => true, flatten = false, comment = (c) => c } = {}) {
  const A = analysis;
  const simple = (e) => e.kind === 'num' || e.kind === 'ident' || (e.kind === 'unary' && e.op === '-' && e.arg.kind === 'num');

  function expr(e, ctx = {}) {
    switch (e.kind) {
      case 'num': return e.text;
      case 'ident': return hlslName(e.name);
      case 'paren': return `(${expr(e.expr)})`;
      case 'member': return `${expr(e.obj)}.${A.structs.has(A.typeOf(e.obj)) ? hlslName(e.name) : e.name}`;
      case 'index': return `${expr(e.obj)}[${expr(e.index)}]`;
      case 'unary': { const a = expr(e.arg); return `${e.op}${/^[-+]/.test(a) && (e.op === '-' || e.op === '+') ? ' ' : ''}${a}`; }
      case 'postfix': return `${expr(e.arg)}${e.op}`;
      case 'ternary': return `${expr(e.cond)} ? ${expr(e.then)} : ${expr(e.else)}`;
      case 'assign': return `${expr(e.left)} ${e.op} ${expr(e.right)}`;
      case 'binary': {
        const l = expr(e.left), r = expr(e.right);
        // x != x is GLSL's NaN test; DXC and FXC may fold it to false under their default
        // float optimisations, isnan() they keep.
        if ((e.op === '!=' || e.op === '==') && l === r && !isVector(A.typeOf(e.left)) && A.typeOf(e.left) === 'float')
          return e.op === '!=' ? `isnan(${l})` : `!isnan(${l})`;
        if ((e.op === '==' || e.op === '!=') && (isVector(A.typeOf(e.left)) || isVector(A.typeOf(e.right))))
          return `${e.op === '==' ? 'all' : 'any'}(${l} ${e.op} ${r})`;
        if (e.op === '^^') return `((${l}) != (${r}))`;
        return `${l} ${e.op} ${r}`;
      }
      case 'call': return call(e, ctx);
      default: throw new Error(`unknown expression ${e.kind}`);
    }
  }

  function braces(e) {  // a constructor as a brace initialiser (global const initialisers)
    if (e.kind === 'call' && (e.array !== undefined || A.structs.has(e.callee))) return `{${e.args.map(braces).join(', ')}}`;
    return expr(e);
  }

  function call(e, ctx) {
    const args = e.args.map((a) => expr(a));
    if (e.array !== undefined) {
      if (ctx.initialiser) return braces(e);
      A.error('an array constructor outside a global const initialiser has no HLSL form', e.line);
    }
    if (A.structs.has(e.callee)) return ctx.initialiser ? braces(e) : `${makerName(e.callee)}(${args.join(', ')})`;
    if (isVector(e.callee)) {
      const T = hlslType(e.callee);
      if (e.args.length === 1) {
        const at = A.typeOf(e.args[0]);
        if (at === null || isScalar(at)) {
          if (simple(e.args[0])) return `${T}(${Array(dim(e.callee)).fill(args[0]).join(', ')})`;
          return `((${T})(${args[0]}))`;
        }
        if (dim(at) > dim(e.callee)) {
          const sw = 'xyzw'.slice(0, dim(e.callee));
          const inner = simple(e.args[0]) || e.args[0].kind === 'member' || e.args[0].kind === 'call' ? args[0] : `(${args[0]})`;
          return at[0] === e.callee[0] ? `${inner}.${sw}` : `${T}(${inner}.${sw})`;
        }
      }
      return `${T}(${args.join(', ')})`;
    }
    if (isScalar(e.callee)) return `${e.callee}(${args.join(', ')})`;
    if (COMPARE[e.callee] && !A.functions.has(e.callee)) return `(${args[0]} ${COMPARE[e.callee]} ${args[1]})`;
    if (e.callee === 'not' && !A.functions.has('not')) return `(!${args[0]})`;
    if (e.callee === 'atan' && args.length === 2 && !A.functions.has('atan')) return `atan2(${args.join(', ')})`;
    if (e.callee === 'fma' && !A.functions.has('fma')) A.error('fma() has no float HLSL form (HLSL fma takes doubles; mad may round differently)', e.line);
    if (e.callee === 'mod' && !A.functions.has('mod')) A.error('mod() has no HLSL twin here (fmod truncates); write x - y * floor(x / y)', e.line);
    A.typeOf(e);  // checks the overload exists and is unique
    const name = !A.functions.has(e.callee) && RENAME[e.callee] ? RENAME[e.callee] : e.callee;
    return `${name}(${args.join(', ')})`;
  }

  function declarators(d, indent, isGlobal) {
    const lines = [];
    const prefix = (d.precise ? 'CM_PRECISE ' : '') + (isGlobal ? 'static const ' : d.const ? 'const ' : '');
    for (const x of d.declarators) {
      const size = x.array !== null ? `[${expr(x.array)}]` : '';
      const init = x.init ? ` = ${isGlobal ? braces(x.init) : expr(x.init)}` : '';
      lines.push(`${indent}${prefix}${hlslType(d.type)} ${hlslName(x.name)}${size}${init};`);
      if (!isGlobal) A.bind(x.name, x.array !== null ? `${d.type}[]` : d.type);
    }
    return lines.join('\n');
  }

  function directive(text) {
    if (/^#\s*include/.test(text)) return flatten ? null : text.replace(/\.glsl"/, '.hlsl"');
    if (/^#\s*(version|extension)/.test(text)) return null;
    // HLSL has precise in every shader model: the default of CM_PRECISE (core.glsl).
    if (/^#\s*define\s+CM_PRECISE\s*$/.test(text)) return '#define CM_PRECISE precise';
    return text.replace(/\b(CM_\w+)_GLSL\b/g, '$1_HLSL');
  }

  function stmt(s, indent) {
    const c = (text) => withComments(s, text, indent, comment);
    switch (s.kind) {
      case 'directive': { const d = directive(s.text); return d === null ? '' : c(d); }
      case 'empty': return c(`${indent};`);
      case 'block': {
        A.push();
        const body = s.stmts.map((x) => stmt(x, indent + INDENT)).filter(Boolean).join('\n');
        A.pop();
        const close = (s.closeLeading || []).map((x) => indent + INDENT + comment(x)).join('\n');
        return withComments(s, `${indent}{\n${body}${close ? '\n' + close : ''}\n${indent}}`, indent, comment);
      }
      case 'decl': return withComments(s, declarators(s, indent, false), indent, comment);
      case 'expr': return c(`${indent}${expr(s.expr)};`);
      case 'return':
        A.checkReturn(s.expr, s.line);
        return c(`${indent}return${s.expr ? ' ' + expr(s.expr) : ''};`);
      case 'break': case 'continue': return c(`${indent}${s.kind};`);
      case 'if': {
        let text = `${indent}if (${expr(s.cond)})${sep(body(s.then, indent))}`;
        if (s.else) text += `${s.then.kind === 'block' ? ' ' : `\n${indent}`}else${s.else.kind === 'if' ? ' ' + stmt({ ...s.else, leading: [] }, indent).trimStart() : sep(body(s.else, indent))}`;
        return c(text);
      }
      case 'for': {
        A.push();
        const init = s.init ? (s.init.kind === 'decl' ? declarators(s.init, '', false).replace(/;$/, '') : expr(s.init.expr)) : '';
        const text = `${indent}for (${init}; ${s.cond ? expr(s.cond) : ''}; ${s.step ? expr(s.step) : ''})${sep(body(s.body, indent))}`;
        A.pop();
        return c(text);
      }
      case 'while': return c(`${indent}while (${expr(s.cond)})${sep(body(s.body, indent))}`);
      default: throw new Error(`unknown statement ${s.kind}`);
    }
  }
  const sep = (b) => (b.startsWith('\n') ? b : ` ${b}`);
  // A sub-statement: a block as is, a single statement on its own indented line.
  function body(s, indent) {
    if (s.kind === 'block') return stmt({ ...s, leading: [] }, indent).trimStart();
    A.push();
    const inner = stmt(s, indent + INDENT);
    A.pop();
    // A short jump or expression stays on the line of its if, as in the GLSL.
    if (['return', 'break', 'continue', 'expr'].includes(s.kind) && !(s.leading || []).length && inner.length < 100) return inner.trimStart();
    return `\n${inner}`;
  }

  function item(it) {
    switch (it.kind) {
      case 'directive': { const d = directive(it.text); return d === null ? '' : withComments(it, d, '', comment); }
      case 'struct': {
        const fields = it.fields.map((f) => withComments(f, `${INDENT}${hlslType(f.type)} ${hlslName(f.name)}${f.array ? `[${expr(f.array)}]` : ''};`, INDENT, comment));
        const params = it.fields.map((f) => `${hlslType(f.type)} ${hlslName(f.name)}${f.array ? `[${expr(f.array)}]` : ''}`);
        // No maker for a struct with array fields: HLSL copies arrays into members poorly
        // (DXC has asserted on it), and the twins construct such structs only as constants.
        if (it.fields.some((f) => f.array)) return withComments(it, `struct ${it.name} {\n${fields.join('\n')}\n};`, '', comment);
        const maker = `// ${it.name}(...) of the GLSL: HLSL has no struct constructors.\n` +
          `${it.name} ${makerName(it.name)}(${params.join(', ')}) {\n${INDENT}${it.name} r;\n` +
          it.fields.map((f) => `${INDENT}r.${hlslName(f.name)} = ${hlslName(f.name)};\n`).join('') + `${INDENT}return r;\n}`;
        return withComments(it, `struct ${it.name} {\n${fields.join('\n')}\n};`, '', comment) + '\n' + maker;
      }
      case 'global': return withComments(it, declarators(it, '', true), '', comment);
      case 'function': {
        A.push();
        A.enter(it);
        for (const p of it.params) A.bind(p.name, p.type);
        const params = it.params.map((p) => `${p.qual ? p.qual + ' ' : ''}${hlslType(p.type)} ${hlslName(p.name)}`).join(', ');
        const head = `${hlslType(it.ret)} ${it.name}(${params})`;
        const text = it.body ? oneLine(head, stmt({ ...it.body, leading: [], trailing: null }, '').trimStart()) : `${head};`;
        A.leave();
        A.pop();
        return withComments(it, text, '', comment);
      }
      default: throw new Error(`unknown item ${it.kind}`);
    }
  }

  const printed = [];
  for (const it of unit.items) if (emit(it)) printed.push({ text: item(it), blankBefore: it.blankBefore });
  return printed;
}
