// tools/shader_translate/analysis.mjs: what the emitters need to know about a parsed GLSL
// unit: structs and their fields, functions and their overloads, global constants and
// macros, and the type of every expression (scoped local variables). The emitters call
// typeOf() while they print, inside the scopes they open.
import { TranslateError } from './glsl_parse.mjs';
import {
  arrayParts, builtinResult, BUILTIN_FUNCTIONS, dim, isScalar, isVector, literalType, swizzleType, vectorOf, wider,
} from './types.mjs';

export class Analysis {
  // hooks: { MACRO: { fn, ret, params: [[type, name], ...] } } (configuration callbacks).
  constructor(items, { file, hooks = {} } = {}) {
    this.file = file;
    this.structs = new Map();    // name -> fields [{ type, name, array }]
    this.functions = new Map();  // name -> overloads [{ ret, params, item, index }]
    this.globals = new Map();    // name -> type
    this.hooks = hooks;
    this.scopes = [];
    this.current = null;  // the overload whose body is being printed (enter / leave)
    this.calls = [];      // { from, to, line }: the calls typed inside printed bodies
    for (const [macro, h] of Object.entries(hooks)) {
      this.addFunction({ ret: h.ret, name: macro, params: h.params.map(([type, name]) => ({ qual: '', type, name })), hook: true });
      this.addFunction({ ret: h.ret, name: h.fn, params: h.params.map(([type, name]) => ({ qual: '', type, name })), hook: true });
    }
    for (const item of items) this.declare(item);
  }

  error(message, line) { throw new TranslateError(message, line, this.file); }

  declare(item) {
    if (item.kind === 'struct') this.structs.set(item.name, item.fields);
    else if (item.kind === 'global') for (const d of item.declarators) this.globals.set(d.name, d.array ? `${item.type}[]` : item.type);
    else if (item.kind === 'function') this.addFunction(item);
    else if (item.kind === 'directive') {
      const m = /^#\s*(?:define|pragma\s+cm_override)\s+(\w+)\s+(\S+)\s*$/.exec(item.text);
      if (m && /^[-+]?[0-9.]/.test(m[2])) this.globals.set(m[1], literalType(m[2].replace(/^[-+]/, '')));
    }
  }

  addFunction(item) {
    const list = this.functions.get(item.name) || [];
    const sig = item.params.map((p) => p.type).join(',');
    const same = list.find((o) => o.params.map((p) => p.type).join(',') === sig);
    if (same) {  // a prototype and its definition; two definitions are an error (GLSL's too)
      if (item.body && same.item.body && same.item !== item && (same.item.section || '') === (item.section || ''))
        this.error(`${item.name}(${sig}) is defined twice`, item.line);
      if (item.body) same.item = item;
      return;
    }
    list.push({ ret: item.ret, params: item.params, item, index: list.length, hook: item.hook });
    this.functions.set(item.name, list);
  }

  // --- scopes -------------------------------------------------------------------------------
  push() { this.scopes.push(new Map()); }
  pop() { this.scopes.pop(); }
  bind(name, type, extra = {}) { this.scopes[this.scopes.length - 1].set(name, { type, ...extra }); }
  lookup(name) {
    for (let i = this.scopes.length - 1; i >= 0; i--) if (this.scopes[i].has(name)) return this.scopes[i].get(name);
    if (this.globals.has(name)) return { type: this.globals.get(name), global: true };
    return null;
  }

  // --- overloads ------------------------------------------------------------------------------
  resolve(name, argTypes, line) {
    const list = this.functions.get(name);
    if (!list) return null;
    const matches = list.filter((o) => o.params.length === argTypes.length &&
      o.params.every((p, i) => argTypes[i] === null || p.type === argTypes[i]));
    if (matches.length === 1) return matches[0];
    if (matches.length === 0) this.error(`no overload of ${name} takes (${argTypes.map((t) => t || '?').join(', ')})`, line);
    this.error(`ambiguous call of ${name} (${argTypes.map((t) => t || '?').join(', ')})`, line);
  }

  // --- expression types -----------------------------------------------------------------------
  typeOf(e) {
    switch (e.kind) {
      case 'num': return literalType(e.text);
      case 'paren': return this.typeOf(e.expr);
      case 'ident': {
        if (e.name === 'true' || e.name === 'false') return 'bool';
        const v = this.lookup(e.name);
        return v ? v.type : null;
      }
      case 'member': {
        const t = this.typeOf(e.obj);
        if (t && this.structs.has(t)) {
          const f = this.structs.get(t).find((x) => x.name === e.name);
          if (!f) this.error(`${t} has no field ${e.name}`, e.line);
          return f.array ? `${f.type}[]` : f.type;
        }
        if (!t || !(isVector(t) || isScalar(t))) return null;
        const swizzled = swizzleType(t, e.name);
        if (!swizzled) this.error(`.${e.name} is not a swizzle of a ${t}`, e.line);
        return swizzled;
      }
      case 'index': {
        const t = this.typeOf(e.obj);
        const a = arrayParts(t);
        if (a) return a.base;
        if (isVector(t)) return vectorOf(t[0] === 'v' ? 'float' : { i: 'int', u: 'uint', b: 'bool' }[t[0]], 1);
        return null;
      }
      case 'unary': return e.op === '!' ? 'bool' : this.typeOf(e.arg);
      case 'postfix': return this.typeOf(e.arg);
      case 'binary': {
        if (['==', '!=', '<', '>', '<=', '>=', '&&', '||', '^^'].includes(e.op)) return 'bool';
        const l = this.typeOf(e.left), r = this.typeOf(e.right);
        if (e.op === '<<' || e.op === '>>') return l;
        return wider(l, r);
      }
      case 'ternary': return this.typeOf(e.then) || this.typeOf(e.else);
      case 'assign': return this.typeOf(e.left);
      case 'call': return this.callType(e);
      default: return null;
    }
  }

  callType(e) {
    if (e.array !== undefined) return `${e.callee}[${e.array ? e.array.text || '' : e.args.length}]`;
    if (isScalar(e.callee) || isVector(e.callee)) return e.callee;
    if (this.structs.has(e.callee)) return e.callee;
    const args = e.args.map((a) => this.typeOf(a));
    if (BUILTIN_FUNCTIONS.has(e.callee) && !this.functions.has(e.callee)) return builtinResult(e.callee, args);
    if (!this.functions.has(e.callee)) this.error(`call of ${e.callee}, which is not defined (nor a built-in the translator knows)`, e.line);
    const o = this.resolve(e.callee, args, e.line);
    if (o && this.current && !o.hook) this.calls.push({ from: this.current, to: o, line: e.line });
    return o ? o.ret : null;
  }

  // --- the function being printed: its calls (recursion) and its returns -------------------
  // The emitters call enter() and leave() around each function body they print, and
  // checkReturn() at each return statement.
  enter(item) {
    this.current = (this.functions.get(item.name) || []).find((o) => o.item === item) || null;
  }
  leave() { this.current = null; }
  checkReturn(expr, line) {
    if (!this.current) return;
    const want = this.current.ret;
    if (!expr) {
      if (want !== 'void') this.error(`return without a value in ${this.current.item.name}, which returns ${want}`, line);
      return;
    }
    const got = this.typeOf(expr);
    if (!got || !want) return;
    // GLSL converts int and uint to float implicitly; vectors and structs must match.
    const same = got === want || (isScalar(got) && isScalar(want) && want === 'float' && got !== 'bool') ||
      (isVector(got) && isVector(want) && dim(got) === dim(want) && want[0] === 'v' && got[0] !== 'b');
    if (!same) this.error(`${this.current.item.name} returns ${want}, not ${got}`, line);
  }
  // Recursion, direct or through other functions, is illegal in GLSL, HLSL and WGSL: after
  // the emitters have printed (and so typed every call), a cycle in the calls is an error at
  // the call that closes it.
  checkRecursion() {
    const edges = new Map();
    for (const c of this.calls) {
      if (!edges.has(c.from)) edges.set(c.from, []);
      edges.get(c.from).push(c);
    }
    const state = new Map();  // 1 on the path, 2 done
    const visit = (o) => {
      state.set(o, 1);
      for (const c of edges.get(o) || []) {
        if (state.get(c.to) === 1) this.error(`recursion: ${c.from.item.name} calls ${c.to.item.name}, which leads back to it`, c.line);
        if (!state.get(c.to)) visit(c.to);
      }
      state.set(o, 2);
    };
    for (const o of edges.keys()) if (!state.get(o)) visit(o);
  }

  // The overload a call refers to (null for constructors, built-ins and unknown macros).
  overloadOf(e) {
    if (isScalar(e.callee) || isVector(e.callee) || this.structs.has(e.callee) || e.array !== undefined) return null;
    if (!this.functions.has(e.callee)) return null;
    return this.resolve(e.callee, e.args.map((a) => this.typeOf(a)), e.line);
  }
}

// Names a function assigns to, increments or passes as out/inout arguments (their root
// variables): these must be WGSL `var`s, and parameters among them need a local copy.
// With runtimeIndexed, also the roots of arrays indexed by a non-literal (WGSL: such arrays
// must be vars for older naga). The caller has bound the parameters.
export function mutatedNames(body, analysis, { runtimeIndexed = false } = {}) {
  const out = new Set();
  const locals = new Map();  // local declarations, for the types of indexed arrays
  const declared = (s) => {
    if (!s || typeof s !== 'object') return;
    if (s.kind === 'decl') for (const d of s.declarators) locals.set(d.name, d.array ? `${s.type}[]` : s.type);
    for (const v of Object.values(s)) if (Array.isArray(v)) v.forEach(declared); else if (v && typeof v === 'object') declared(v);
  };
  if (runtimeIndexed) declared(body);
  const root = (e) => {
    while (e.kind === 'member' || e.kind === 'index' || e.kind === 'paren') e = e.obj || e.expr;
    return e.kind === 'ident' ? e.name : null;
  };
  const expr = (e) => {
    if (!e || typeof e !== 'object') return;
    if (e.kind === 'assign') { const r = root(e.left); if (r) out.add(r); }
    if (runtimeIndexed && e.kind === 'index' && e.index.kind !== 'num') {
      const r = root(e.obj);
      if (r) {
        analysis.push();
        for (const [n, t] of locals) analysis.bind(n, t);
        const isArray = /\[/.test(analysis.typeOf(e.obj) || '');
        analysis.pop();
        if (isArray) out.add(r);
      }
    }
    if ((e.kind === 'postfix' || e.kind === 'unary') && (e.op === '++' || e.op === '--')) { const r = root(e.arg); if (r) out.add(r); }
    if (e.kind === 'call' && analysis.functions.has(e.callee)) {
      for (const o of analysis.functions.get(e.callee))
        if (o.params.length === e.args.length)
          o.params.forEach((p, i) => { if (p.qual) { const r = root(e.args[i]); if (r) out.add(r); } });
    }
    for (const [k, v] of Object.entries(e)) {
      if (k === 'leading' || k === 'trailing') continue;
      if (Array.isArray(v)) v.forEach(expr);
      else if (v && typeof v === 'object') expr(v);
    }
  };
  expr(body);
  return out;
}

export { dim, isScalar, isVector, vectorOf };
