// tools/shader_translate/emit_wgsl.mjs: prints a preprocessed GLSL unit (wgsl_preprocess.mjs)
// as WGSL.
//
// What changes:
// - types: float -> f32, vec3 -> vec3f, ivec2 -> vec2i, uvec2 -> vec2u, bvec3 -> vec3<bool>,
//   T x[N] -> array<T, N>; declarations become `let` (never assigned) or `var`;
// - overloads (WGSL has none): the overload declared first keeps the name, each later one
//   gets _ + the codes of its parameter types (f i u b, v2 v3 v4, iv2 uv3 bv4, a struct by
//   its name without Cm): cm_saturate_v3, cm_integrate_scattering_v3v3f;
// - out / inout parameters -> ptr<function, T>, called with &x; parameters the body assigns
//   are copied to a local var (WGSL parameters are immutable);
// - c ? a : b -> select(b, a, c); when a branch calls a function, a ternary that is a whole
//   initialiser, assignment or return becomes if / else, so only one branch runs;
// - built-ins: scalars are splatted where WGSL wants equal types (max(v, 0.0) ->
//   max(v, vec3f(0.0))), inversesqrt -> inverseSqrt, atan(y, x) -> atan2, lessThan(a, b) ->
//   (a < b), floatBitsToUint -> bitcast<u32>; == and != on vectors -> all() / any();
// - arrays indexed at run time are vars (global arrays var<private>): older naga indexes
//   arrays only behind a pointer;
// - #define N <number> -> const N = <number>; a configurable default (#ifndef N / #define N v)
//   -> override N: T = v; identifiers that are WGSL keywords get a trailing underscore;
// - CM_PRECISE / precise is dropped: WGSL has no such qualifier (docs/shading_languages.md).
import { isScalar, isVector, dim, mutatedNames } from './analysis.mjs';
import { arrayParts, component, literalType } from './types.mjs';
import { INDENT, oneLine, withComments } from './emit_common.mjs';

// WGSL keywords and reserved words that are plausible GLSL identifiers.
const RESERVED = new Set(['fn', 'let', 'var', 'loop', 'override', 'enable', 'requires', 'diagnostic', 'alias', 'const_assert',
  'continuing', 'fallthrough', 'private', 'storage', 'uniform', 'workgroup', 'function', 'ptr', 'array', 'atomic', 'sampler',
  'texture', 'ref', 'type', 'target', 'mod', 'module', 'move', 'mut', 'new', 'null', 'of', 'operator', 'package', 'pass', 'patch',
  'precise', 'precision', 'public', 'self', 'set', 'shared', 'smooth', 'static', 'std', 'super', 'template', 'this', 'throw',
  'trait', 'try', 'typedef', 'union', 'unless', 'unsafe', 'use', 'using', 'virtual', 'where', 'with', 'yield', 'filter',
  'final', 'handle', 'layout', 'match', 'macro', 'meta', 'impl', 'in', 'out', 'inout', 'auto', 'as', 'async', 'await', 'become',
  'cast', 'catch', 'class', 'const_cast', 'demote', 'do', 'dynamic_cast', 'enum', 'explicit', 'export', 'extends', 'extern',
  'external', 'friend', 'from', 'fxgroup', 'get', 'goto', 'groupshared', 'highp', 'implements', 'import', 'inline',
  'instanceof', 'interface', 'lowp', 'mediump', 'namespace', 'nil', 'noexcept', 'noinline', 'nointerpolation',
  'noperspective', 'nullptr', 'premerge', 'protected', 'pub', 'readonly', 'regardless', 'register', 'reinterpret_cast',
  'resource', 'restrict', 'sizeof', 'snorm', 'static_assert', 'static_cast', 'subroutine', 'switch', 'typeid', 'typename',
  'typeof', 'unorm', 'unsized', 'varying', 'volatile', 'wgsl', 'writeonly', 'active', 'asm', 'attribute', 'binding_array',
  'co_await', 'co_return', 'co_yield', 'coherent', 'column_major', 'common', 'compile', 'compile_fragment', 'concept', 'f16',
  'f32', 'i32', 'u32', 'vec2', 'vec3', 'vec4', 'mat2x2', 'bitcast', 'select', 'default', 'case', 'break', 'if',
  'else', 'for', 'while', 'return', 'struct', 'const', 'discard', 'diagnostic', 'bool', 'delete', 'mutable', 'abstract',
  'partition', 'require', 'finally']);
const RENAME = { inversesqrt: 'inverseSqrt', roundEven: 'round' };
const COMPARE = { lessThan: '<', lessThanEqual: '<=', greaterThan: '>', greaterThanEqual: '>=', equal: '==', notEqual: '!=' };
// Built-ins whose WGSL form needs every argument of the result's type (scalars splatted);
// mix keeps a scalar blend factor, which WGSL accepts.
const SAME_TYPE = new Set(['min', 'max', 'clamp', 'pow', 'step', 'smoothstep', 'atan']);

export function wgslType(t) {
  const a = arrayParts(t);
  if (a) return `array<${wgslType(a.base)}, ${a.size}>`;
  if (t === 'float') return 'f32';
  if (t === 'int') return 'i32';
  if (t === 'uint') return 'u32';
  if (isVector(t)) {
    const n = t[t.length - 1];
    return { v: `vec${n}f`, i: `vec${n}i`, u: `vec${n}u`, b: `vec${n}<bool>` }[t[0]];
  }
  return t;
}
const typeCode = (t) => (isScalar(t) ? t[0] : isVector(t) ? (t[0] === 'v' ? '' : t[0]) + 'v' + t[t.length - 1] : t.replace(/^Cm/, ''));
export const wgslName = (n) => (RESERVED.has(n) ? n + '_' : n);

// The WGSL name of an overload (see the header).
export function overloadName(name, overload) {
  return overload.index === 0 ? name : `${name}_${overload.params.map((p) => typeCode(p.type)).join('')}`;
}
// Two overloads whose codes read the same (f(int, vec2) and f(ivec2) are both f_iv2) would
// be one WGSL function: refused.
function checkOverloadNames(A) {
  const seen = new Map();
  for (const [name, list] of A.functions)
    for (const o of list) {
      if (o.hook) continue;
      const n = overloadName(name, o);
      if (seen.has(n) && seen.get(n) !== o) A.error(`overloads of ${name} both become ${n} in WGSL`, o.item.line);
      seen.set(n, o);
    }
}

export function emitWgsl(unit, analysis, { emit = () => true, comment = (c) => c } = {}) {
  const A = analysis;
  checkOverloadNames(A);
  const simple = (e) => e.kind === 'num' || e.kind === 'ident' || e.kind === 'member' || e.kind === 'call' || e.kind === 'paren' || e.kind === 'index';
  let mutated = new Set();

  const splat = (e, text, to) => (isScalar(A.typeOf(e)) && isVector(to) ? `${wgslType(to)}(${text})` : text);
  const hasCall = (e) => {
    if (!e || typeof e !== 'object') return false;
    if (e.kind === 'call' && A.functions.has(e.callee)) return true;
    return Object.entries(e).some(([k, v]) => k !== 'leading' && (Array.isArray(v) ? v.some(hasCall) : v && typeof v === 'object' && hasCall(v)));
  };

  function expr(e) {
    switch (e.kind) {
      case 'num': return e.text.replace(/[fF]$/, '');
      case 'ident': { const v = A.lookup(e.name); return v && v.pointer ? `(*${wgslName(e.name)})` : wgslName(e.name); }
      case 'paren': return `(${expr(e.expr)})`;
      case 'member': {
        const t = A.typeOf(e.obj);
        return `${expr(e.obj)}.${isVector(t) ? e.name.replace(/[stpq]/g, (c) => ({ s: 'x', t: 'y', p: 'z', q: 'w' })[c]) : A.structs.has(t) ? wgslName(e.name) : e.name}`;
      }
      case 'index': return `${expr(e.obj)}[${expr(e.index)}]`;
      case 'unary': {
        if (e.op === '++' || e.op === '--') A.error('++/-- inside an expression has no WGSL form', e.line);
        if (e.op === '-' && component(A.typeOf(e.arg)) === 'uint') A.error('unary minus on a uint has no WGSL form', e.line);
        const a = expr(e.arg);
        return `${e.op}${/^[-+]/.test(a) && e.op === '-' ? `(${a})` : a}`;
      }
      case 'postfix': A.error('++/-- inside an expression has no WGSL form', e.line); break;
      case 'assign': A.error('an assignment inside an expression has no WGSL form', e.line); break;
      case 'ternary': {
        const t = A.typeOf(e);
        return `select(${splat(e.else, expr(e.else), t)}, ${splat(e.then, expr(e.then), t)}, ${expr(e.cond)})`;
      }
      case 'binary': return binary(e);
      case 'call': return call(e);
      default: throw new Error(`unknown expression ${e.kind}`);
    }
    return '';
  }

  function binary(e) {
    const lt = A.typeOf(e.left), rt = A.typeOf(e.right);
    const wrap = (child, text) => {
      if (child.kind !== 'binary') return text;
      const bitwise = ['&', '|', '^', '<<', '>>'];
      if (bitwise.includes(e.op) || bitwise.includes(child.op)) return `(${text})`;   // WGSL does not mix these
      if ((e.op === '&&' && child.op === '||') || (e.op === '||' && child.op === '&&')) return `(${text})`;
      const relational = ['<', '>', '<=', '>=', '==', '!='];
      if (relational.includes(e.op) && relational.includes(child.op)) return `(${text})`;  // WGSL does not chain them
      return text;
    };
    let l = wrap(e.left, expr(e.left)), r = wrap(e.right, expr(e.right));
    if ((e.op === '<<' || e.op === '>>') && component(rt) === 'int' && e.right.kind !== 'num') r = `u32(${r})`;
    if ((e.op === '==' || e.op === '!=') && (isVector(lt) || isVector(rt))) return `${e.op === '==' ? 'all' : 'any'}(${l} ${e.op} ${r})`;
    if (e.op === '^^') return `((${l}) != (${r}))`;
    return `${l} ${e.op} ${r}`;
  }

  function call(e) {
    if (e.array !== undefined) return `array<${wgslType(e.callee)}, ${e.array ? expr(e.array) : e.args.length}>(${e.args.map(expr).join(', ')})`;
    if (A.structs.has(e.callee)) return `${e.callee}(${e.args.map(expr).join(', ')})`;
    if (isVector(e.callee) || isScalar(e.callee)) {
      const T = wgslType(e.callee), want = component(e.callee);
      if (e.args.length === 1) {
        const at = A.typeOf(e.args[0]);
        if (isVector(at) && dim(at) > dim(e.callee)) {
          const text = expr(e.args[0]);
          const sw = `${simple(e.args[0]) ? text : `(${text})`}.${'xyzw'.slice(0, dim(e.callee))}`;
          return component(at) === want ? sw : `${T}(${sw})`;
        }
      }
      const args = e.args.map((a) => {
        const at = A.typeOf(a);
        return isVector(e.callee) && isScalar(at) && at !== want && !(a.kind === 'num' && literalType(a.text) === 'int')
          ? `${wgslType(want)}(${expr(a)})` : expr(a);
      });
      return `${T}(${args.join(', ')})`;
    }
    if (!A.functions.has(e.callee)) {
      const args = e.args.map(expr);
      if (COMPARE[e.callee]) return `(${args[0]} ${COMPARE[e.callee]} ${args[1]})`;
      if (e.callee === 'not') return `(!${args[0]})`;
      if (e.callee === 'mod') A.error('mod() has no WGSL twin here (% truncates); write x - y * floor(x / y)', e.line);
      if (e.callee === 'isnan' || e.callee === 'isinf') A.error(`${e.callee}() has no WGSL form (WGSL may assume no NaN or Inf)`, e.line);
      if (/^(float|int|uint)BitsTo|^(uint|int)BitsToFloat$/.test(e.callee)) return `bitcast<${wgslType(A.typeOf(e))}>(${args[0]})`;
      if (SAME_TYPE.has(e.callee)) {
        const t = A.typeOf(e);
        const name = e.callee === 'atan' ? (args.length === 2 ? 'atan2' : 'atan') : e.callee;
        return `${name}(${e.args.map((a, i) => splat(a, args[i], t)).join(', ')})`;
      }
      if (e.callee === 'mix' && isVector(A.typeOf(e))) {
        const t = A.typeOf(e);
        return `mix(${splat(e.args[0], args[0], t)}, ${splat(e.args[1], args[1], t)}, ${args[2]})`;
      }
      A.typeOf(e);
      return `${RENAME[e.callee] || e.callee}(${args.join(', ')})`;
    }
    const o = A.overloadOf(e);
    const args = e.args.map((a, i) => {
      if (!o.params[i].qual) return expr(a);
      if (a.kind === 'ident') { const v = A.lookup(a.name); return v && v.pointer ? wgslName(a.name) : `&${wgslName(a.name)}`; }
      // WGSL takes no address of a vector component, and of a struct member or array element
      // only with its unrestricted_pointer_parameters extension: pass a whole variable.
      A.error('an out / inout argument that is not a whole variable has no portable WGSL form', e.line);
      return '';
    });
    return `${o.hook ? A.hooks[e.callee]?.fn || e.callee : overloadName(e.callee, o)}(${args.join(', ')})`;
  }

  function declare(d, x, indent) {
    const type = x.array !== null ? `${d.type}[${expr(x.array)}]` : d.type;
    A.bind(x.name, x.array !== null ? `${d.type}[]` : d.type);
    const name = wgslName(x.name);
    if (x.init && x.init.kind === 'ternary' && (hasCall(x.init.then) || hasCall(x.init.else)))
      return `${indent}var ${name}: ${wgslType(type)};\n${assignTernary(name, x.init, indent, type)}`;
    if (!x.init) return `${indent}var ${name}: ${wgslType(type)};`;
    const keyword = mutated.has(x.name) ? 'var' : 'let';
    return `${indent}${keyword} ${name}: ${wgslType(type)} = ${splat(x.init, expr(x.init), type)};`;
  }
  // target = c ? a : b as if / else (nested ternaries in the else branch become else if).
  function assignTernary(target, t, indent, type, op = '=') {
    let text = `${indent}if (${expr(t.cond)}) {\n${indent}${INDENT}${target} ${op} ${splat(t.then, expr(t.then), type)};\n${indent}} else `;
    const e = t.else.kind === 'paren' ? t.else.expr : t.else;
    if (e.kind === 'ternary') return text + assignTernary(target, e, indent, type, op).trimStart();
    return text + `{\n${indent}${INDENT}${target} ${op} ${splat(e, expr(e), type)};\n${indent}}`;
  }
  function returnTernary(t, indent, type) {
    const e = t.else.kind === 'paren' ? t.else.expr : t.else;
    const rest = e.kind === 'ternary' ? returnTernary(e, indent, type) : `${indent}return ${splat(e, expr(e), type)};`;
    return `${indent}if (${expr(t.cond)}) {\n${indent}${INDENT}return ${splat(t.then, expr(t.then), type)};\n${indent}}\n${rest}`;
  }

  function simpleStatement(e) {  // an expression statement or a for step
    if (e.kind === 'assign') {
      const lt = A.typeOf(e.left);
      const target = expr(e.left);
      return `${target} ${e.op} ${splat(e.right, expr(e.right), lt)}`;
    }
    if ((e.kind === 'postfix' || e.kind === 'unary') && (e.op === '++' || e.op === '--')) return `${expr(e.arg)}${e.op}`;
    if (e.kind === 'call') return call(e);
    A.error('an expression statement without effect', e.line);
    return '';
  }

  let returnType = null;
  function stmt(s, indent) {
    const c = (text) => withComments(s, text, indent, comment);
    switch (s.kind) {
      case 'directive':
        if (/^#\s*pragma\s+cm_removed/.test(s.text)) return '';
        A.error(`a preprocessor line inside a function after preprocessing: ${s.text}`, s.line);
        break;
      case 'empty': return '';
      case 'block': {
        A.push();
        const body = s.stmts.map((x) => stmt(x, indent + INDENT)).filter(Boolean).join('\n');
        A.pop();
        const close = (s.closeLeading || []).map((x) => indent + INDENT + comment(x)).join('\n');
        return withComments(s, `${indent}{\n${body}${close ? '\n' + close : ''}\n${indent}}`, indent, comment);
      }
      case 'decl': return c(s.declarators.map((x) => declare(s, x, indent)).join('\n'));
      case 'expr': {
        const e = s.expr;
        if (e.kind === 'assign' && e.right.kind === 'ternary' && (hasCall(e.right.then) || hasCall(e.right.else)))
          return c(assignTernary(expr(e.left), e.right, indent, A.typeOf(e.left), e.op));
        return c(`${indent}${simpleStatement(e)};`);
      }
      case 'return':
        A.checkReturn(s.expr, s.line);
        if (s.expr && s.expr.kind === 'ternary' && (hasCall(s.expr.then) || hasCall(s.expr.else))) return c(returnTernary(s.expr, indent, returnType));
        return c(`${indent}return${s.expr ? ' ' + splat(s.expr, expr(s.expr), returnType) : ''};`);
      case 'break': case 'continue': return c(`${indent}${s.kind};`);
      case 'if': {
        let text = `${indent}if (${expr(s.cond)}) ${body(s.then, indent)}`;
        if (s.else) text += ` else ${s.else.kind === 'if' ? stmt({ ...s.else, leading: [] }, indent).trimStart() : body(s.else, indent)}`;
        return c(text);
      }
      case 'for': {
        A.push();
        let init = '';
        if (s.init && s.init.kind === 'decl') {
          if (s.init.declarators.length !== 1) A.error('a for loop declaring several variables', s.line);
          const x = s.init.declarators[0];
          A.bind(x.name, s.init.type);
          init = `var ${wgslName(x.name)}: ${wgslType(s.init.type)} = ${expr(x.init)}`;
        } else if (s.init) init = simpleStatement(s.init.expr);
        const text = `${indent}for (${init}; ${s.cond ? expr(s.cond) : ''}; ${s.step ? simpleStatement(s.step) : ''}) ${body(s.body, indent)}`;
        A.pop();
        return c(text);
      }
      case 'while': return c(`${indent}while (${expr(s.cond)}) ${body(s.body, indent)}`);
      default: throw new Error(`unknown statement ${s.kind}`);
    }
    return '';
  }
  // WGSL wants braces around every if / loop body.
  function body(s, indent) {
    if (s.kind === 'block') return stmt({ ...s, leading: [] }, indent).trimStart();
    A.push();
    const inner = stmt(s, indent + INDENT);
    A.pop();
    // A short jump or expression stays on the line of its if, as in the GLSL.
    if (['return', 'break', 'continue', 'expr'].includes(s.kind) && !(s.leading || []).length && !inner.includes('\n') && inner.length < 100)
      return `{ ${inner.trimStart()} }`;
    return `{\n${inner}\n${indent}}`;
  }

  function constant(text, it) {
    let m = /^#\s*define\s+(\w+)\s+(\S+)\s*$/.exec(text);
    if (m) return withComments(it, `const ${m[1]} = ${m[2].replace(/[fF]$/, '')};`, '', comment);
    m = /^#\s*pragma\s+cm_override\s+(\w+)\s+(\S+)\s*$/.exec(text);
    if (m) return withComments(it, `override ${m[1]}: ${wgslType(literalType(m[2]))} = ${m[2]};`, '', comment);
    if (/^#\s*pragma\s+cm_removed\s+keep/.test(text)) return (it.leading || []).map(comment).join('\n');  // a file's header
    if (/^#\s*pragma\s+cm_/.test(text) || /^#\s*define\s+\w+\s*$/.test(text)) return '';
    A.error(`a preprocessor line WGSL cannot express: ${text}`, it.line);
    return '';
  }

  function item(it) {
    switch (it.kind) {
      case 'directive': return constant(it.text, it);
      case 'struct': {
        const fields = it.fields.map((f) => withComments(f, `${INDENT}${wgslName(f.name)}: ${wgslType(f.array ? `${f.type}[${expr(f.array)}]` : f.type)},`, INDENT, comment));
        return withComments(it, `struct ${it.name} {\n${fields.join('\n')}\n}`, '', comment);
      }
      case 'global':
        return withComments(it, it.declarators.map((x) => {
          const type = x.array !== null ? `${it.type}[${expr(x.array)}]` : it.type;
          // An array is a private var: naga before wgpu 23 (Bevy 0.14) indexes arrays at run
          // time only behind a pointer; Tint and newer naga accept both.
          return `${x.array !== null ? 'var<private>' : 'const'} ${wgslName(x.name)}: ${wgslType(type)} = ${expr(x.init)};`;
        }).join('\n'), '', comment);
      case 'function': {
        if (!it.body) return '';  // prototypes: WGSL declarations are order-independent
        const overload = A.functions.get(it.name).find((o) => o.item === it);
        A.push();
        A.enter(it);
        for (const p of it.params) A.bind(p.name, p.type, p.qual ? { pointer: true } : {});
        mutated = mutatedNames(it.body, A, { runtimeIndexed: true });
        const copies = [];
        const params = it.params.map((p) => {
          const name = wgslName(p.name);
          if (p.qual) return `${name}: ptr<function, ${wgslType(p.type)}>`;
          if (mutated.has(p.name)) { copies.push(`${INDENT}var ${name}: ${wgslType(p.type)} = ${name}_in;`); return `${name}_in: ${wgslType(p.type)}`; }
          return `${name}: ${wgslType(p.type)}`;
        });
        returnType = it.ret;
        const head = `fn ${overloadName(it.name, overload)}(${params.join(', ')})${it.ret === 'void' ? '' : ` -> ${wgslType(it.ret)}`}`;
        let text = stmt({ ...it.body, leading: [], trailing: null }, '').trimStart();
        if (copies.length) text = text.replace(/^\{\n/, `{\n${copies.join('\n')}\n`);
        A.leave();
        A.pop();
        return withComments(it, oneLine(head, text), '', comment);
      }
      default: throw new Error(`unknown item ${it.kind}`);
    }
  }

  const printed = [];
  for (const it of unit.items) if (emit(it)) printed.push({ text: item(it), blankBefore: it.blankBefore, item: it });
  return printed;
}
