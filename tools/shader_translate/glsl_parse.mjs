// tools/shader_translate/glsl_parse.mjs: tokenizer and parser for the GLSL subset cloudmath's
// twins are written in (include/cloudmath/glsl/*.glsl), for translate.mjs.
//
// The subset: structs, const globals (scalars, vectors, structs, arrays), functions with
// in/out/inout parameters and prototypes, local declarations, if/else, for, while, return,
// break, continue, expression statements; C operators without the comma operator; vector and
// array constructors; swizzles. Preprocessor lines are tokens of their own (kind 'directive'),
// allowed between top-level items and between statements. Anything else is an error that
// names the line: the translator refuses what it does not understand rather than guessing.
// Comments are kept: a comment is attached to the next token (leading) or, when it follows a
// token on the same line, to that token (trailing).

const PUNCT = ['<<=', '>>=', '<<', '>>', '<=', '>=', '==', '!=', '&&', '||', '^^', '++', '--', '+=', '-=', '*=', '/=', '%=',
  '&=', '|=', '^=', '(', ')', '[', ']', '{', '}', ';', ',', '.', '?', ':', '+', '-', '*', '/', '%', '<', '>', '=', '!', '~', '&',
  '|', '^'];

export class TranslateError extends Error {
  constructor(message, line, file) {
    super(`${file || '<glsl>'}:${line || '?'}: ${message}`);
    this.line = line;
    this.raw = message;
  }
}

// Tokens: { kind: 'ident' | 'number' | 'punct' | 'directive' | 'eof', text, line, leading: [], trailing: null }
export function tokenize(source, file, aliases = {}) {
  const tokens = [];
  // lastLine: the last line holding a token or comment; a token (or its first leading
  // comment) more than one line below it had a blank line before it (blankBefore).
  let i = 0, line = 1, pending = [], atLineStart = true, lastTokenLine = 0, lastLine = 0, pendingBlank = false;
  const n = source.length;
  const push = (kind, text, startLine) => {
    const blankBefore = pending.length ? pendingBlank : startLine > lastLine + 1 && lastLine > 0;
    tokens.push({ kind, text, line: startLine, leading: pending, trailing: null, blankBefore });
    pending = [];
    lastTokenLine = startLine;
    lastLine = startLine;
  };
  const comment = (text, startLine) => {
    const prev = tokens[tokens.length - 1];
    const endLine = startLine + (text.match(/\n/g) || []).length;
    if (prev && prev.kind !== 'directive' && lastTokenLine === startLine && prev.trailing === null && !text.includes('\n')) prev.trailing = text;
    else if (prev && prev.kind === 'directive' && lastTokenLine === startLine && !prev.trailing) prev.trailing = text;
    else {
      if (!pending.length) pendingBlank = startLine > lastLine + 1 && lastLine > 0;
      pending.push(text);
    }
    lastLine = endLine;
  };
  while (i < n) {
    const c = source[i];
    if (c === '\n') { line++; i++; atLineStart = true; continue; }
    if (c === ' ' || c === '\t' || c === '\r') { i++; continue; }
    if (c === '/' && source[i + 1] === '/') {
      let j = source.indexOf('\n', i);
      if (j < 0) j = n;
      comment(source.slice(i, j), line);
      i = j;
      continue;
    }
    if (c === '/' && source[i + 1] === '*') {
      const j = source.indexOf('*/', i + 2);
      if (j < 0) throw new TranslateError('unterminated comment', line, file);
      const text = source.slice(i, j + 2);
      comment(text, line);
      line += (text.match(/\n/g) || []).length;
      i = j + 2;
      continue;
    }
    if (c === '#' && atLineStart) {
      const startLine = line;
      let j = i, text = '';
      for (;;) {
        let k = source.indexOf('\n', j);
        if (k < 0) k = n;
        const part = source.slice(j, k);
        if (part.endsWith('\\')) { text += part.slice(0, -1); j = k + 1; line++; continue; }
        text += part;
        j = k;
        break;
      }
      // A trailing // comment of the directive stays with it.
      const cut = text.indexOf('//');
      const body = (cut >= 0 ? text.slice(0, cut) : text).trim();
      push('directive', body, startLine);
      if (cut >= 0) tokens[tokens.length - 1].trailing = text.slice(cut).trim();
      lastLine = line;
      i = j;
      continue;
    }
    atLineStart = false;
    if (/[A-Za-z_]/.test(c)) {
      let j = i + 1;
      while (j < n && /[A-Za-z0-9_]/.test(source[j])) j++;
      const word = source.slice(i, j);
      push('ident', Object.hasOwn(aliases, word) ? aliases[word] : word, line);
      i = j;
      continue;
    }
    if (/[0-9]/.test(c) || (c === '.' && /[0-9]/.test(source[i + 1]))) {
      const m = /^(0[xX][0-9a-fA-F]+[uU]?|([0-9]+\.[0-9]*|\.[0-9]+|[0-9]+)([eE][+-]?[0-9]+)?[fFuU]?)/.exec(source.slice(i));
      push('number', m[0], line);
      i += m[0].length;
      continue;
    }
    const p = PUNCT.find((q) => source.startsWith(q, i));
    if (!p) throw new TranslateError(`unexpected character '${c}'`, line, file);
    push('punct', p, line);
    i += p.length;
  }
  tokens.push({ kind: 'eof', text: '', line, leading: pending, trailing: null });
  return tokens;
}

export const SCALARS = new Set(['float', 'int', 'uint', 'bool']);
export const VECTORS = new Set(['vec2', 'vec3', 'vec4', 'ivec2', 'ivec3', 'ivec4', 'uvec2', 'uvec3', 'uvec4', 'bvec2', 'bvec3', 'bvec4']);
export const isBuiltinType = (t) => SCALARS.has(t) || VECTORS.has(t) || t === 'void';

// Precedence climbing table (C / GLSL).
const BINARY = {
  '||': 1, '^^': 2, '&&': 3, '|': 4, '^': 5, '&': 6, '==': 7, '!=': 7, '<': 8, '>': 8, '<=': 8, '>=': 8,
  '<<': 9, '>>': 9, '+': 10, '-': 10, '*': 11, '/': 11, '%': 11,
};
const ASSIGN = new Set(['=', '+=', '-=', '*=', '/=', '%=', '<<=', '>>=', '&=', '|=', '^=']);
// The deepest nesting the parser accepts (see enter() below).
export const MAX_NESTING = 256;

// options.aliases: identifier -> identifier substitutions (object-like #defines that name a
// function, resolved by the WGSL preprocessor).
export function parse(source, file, options = {}) {
  const toks = tokenize(source, file, options.aliases || {});
  let pos = 0;
  const peek = (k = 0) => toks[pos + k];
  const err = (msg, t = peek()) => { throw new TranslateError(`${msg} (at '${t.text}')`, t.line, file); };
  const next = () => toks[pos++];
  const is = (text, k = 0) => peek(k).kind !== 'directive' && peek(k).text === text && peek(k).kind !== 'eof';
  const expect = (text) => { if (!is(text)) err(`expected '${text}'`); return next(); };
  const ident = () => { if (peek().kind !== 'ident') err('expected an identifier'); return next().text; };
  const structs = new Set();
  const isTypeName = (t) => t.kind === 'ident' && (isBuiltinType(t.text) || structs.has(t.text));
  // Nesting (parentheses, calls, unary operators, blocks, ifs, ternaries, and chains of binary
  // operators, which nest as deep as they are long) is capped: the parser and the emitters
  // recurse over it, and JavaScript's stack overflowed with no location past about 1,400
  // parentheses or 5,800 terms. The twins nest about 20 deep.
  let depth = 0;
  const enter = () => { if (++depth > MAX_NESTING) err(`nesting deeper than ${MAX_NESTING} levels is not supported`); };
  const leave = () => { depth--; };

  function arraySuffix() {
    if (!is('[')) return null;
    next();
    const size = expression();
    expect(']');
    return size;
  }

  // --- expressions --------------------------------------------------------------------------
  function primary() {
    const t = peek();
    if (t.kind === 'number') {
      next();
      if (/[.eEfF]/.test(t.text) && !/^0[xX]/.test(t.text) && !Number.isFinite(Math.fround(parseFloat(t.text))))
        err('a float literal that rounds to infinity in float', t);
      return { kind: 'num', text: t.text, line: t.line };
    }
    if (is('(')) { next(); enter(); const e = expression(); leave(); expect(')'); return { kind: 'paren', expr: e }; }
    if (t.kind === 'ident') {
      next();
      // Array constructor: float[135](...)
      if (isTypeName(t) && is('[')) {  // after a type name, '[' can only start an array constructor
        next();
        const size = is(']') ? null : expression();
        expect(']');
        expect('(');
        const args = callArgs();
        return { kind: 'call', callee: t.text, array: size, args, line: t.line };
      }
      if (is('(')) { next(); enter(); const args = callArgs(); leave(); return { kind: 'call', callee: t.text, args, line: t.line }; }
      return { kind: 'ident', name: t.text, line: t.line };
    }
    err('expected an expression');
  }
  function callArgs() {
    const args = [];
    if (is(')')) { next(); return args; }
    if (is('void') && peek(1).text === ')') { next(); next(); return args; }
    for (;;) {
      args.push(assignment());
      if (is(',')) { next(); continue; }
      expect(')');
      return args;
    }
  }
  function postfix() {
    let e = primary();
    for (;;) {
      if (is('.')) { next(); const line = peek().line; e = { kind: 'member', obj: e, name: ident(), line }; continue; }
      if (is('[')) { next(); const index = expression(); expect(']'); e = { kind: 'index', obj: e, index }; continue; }
      if (is('++') || is('--')) { e = { kind: 'postfix', op: next().text, arg: e }; continue; }
      return e;
    }
  }
  function unary() {
    if (is('-') || is('+') || is('!') || is('~') || is('++') || is('--')) {
      const op = next().text;
      enter();
      const arg = unary();
      leave();
      return { kind: 'unary', op, arg };
    }
    return postfix();
  }
  function binary(minPrec) {
    let left = unary();
    let chain = 0;  // operators in this chain: the tree is as deep as the chain is long
    try {
      for (;;) {
        const t = peek();
        const prec = t.kind === 'punct' ? BINARY[t.text] : undefined;
        if (prec === undefined || prec < minPrec) return left;
        next();
        enter();
        chain++;
        const right = binary(prec + 1);
        left = { kind: 'binary', op: t.text, left, right };
      }
    } finally {
      depth -= chain;
    }
  }
  function conditional() {
    const cond = binary(1);
    if (!is('?')) return cond;
    next();
    enter();
    const then = assignment();
    expect(':');
    const otherwise = assignment();
    leave();
    return { kind: 'ternary', cond, then, else: otherwise };
  }
  function assignment() {
    const left = conditional();
    if (peek().kind === 'punct' && ASSIGN.has(peek().text)) {
      const op = next().text;
      enter();
      const right = assignment();
      leave();
      return { kind: 'assign', op, left, right };
    }
    return left;
  }
  function expression() {
    const e = assignment();
    if (is(',')) err('the comma operator is not supported');
    return e;
  }

  // --- statements ---------------------------------------------------------------------------
  // Qualifiers before a local's type: const, precision (dropped) and precise / CM_PRECISE
  // (kept as decl.precise: values to round exactly as written, no fused multiply-add).
  function startsDeclaration() {
    let k = 0;
    if (is('precise', k) || is('CM_PRECISE', k)) k++;
    if (is('const', k)) k++;
    if (is('highp', k) || is('mediump', k) || is('lowp', k)) k++;
    const t = peek(k);
    return isTypeName(t) && peek(k + 1).kind === 'ident';
  }
  function declaration() {
    const first = peek();
    let isConst = false, precise = false;
    if (is('precise') || is('CM_PRECISE')) { next(); precise = true; }
    if (is('const')) { next(); isConst = true; }
    if (is('highp') || is('mediump') || is('lowp')) next();
    const type = next().text;
    const declarators = [];
    for (;;) {
      const name = ident();
      const array = arraySuffix();
      let init = null;
      if (is('=')) { next(); init = assignment(); }
      declarators.push({ name, array, init });
      if (is(',')) { next(); continue; }
      break;
    }
    const end = expect(';');
    return { kind: 'decl', const: isConst, precise, type, declarators, leading: first.leading, trailing: end.trailing, line: first.line, blankBefore: first.blankBefore };
  }
  function statement() {
    enter();
    try {
      return statementBody();
    } finally {
      leave();
    }
  }
  function statementBody() {
    const t = peek();
    const lead = t.leading;
    if (t.kind === 'directive') { next(); return { kind: 'directive', text: t.text, leading: lead, blankBefore: t.blankBefore, trailing: t.trailing, line: t.line }; }
    if (is('{')) return block();
    if (is(';')) { next(); return { kind: 'empty', leading: lead }; }
    if (is('if')) {
      next(); expect('(');
      const cond = expression();
      expect(')');
      const then = statement();
      let otherwise = null;
      if (is('else')) { next(); otherwise = statement(); }
      return { kind: 'if', cond, then, else: otherwise, leading: lead, blankBefore: t.blankBefore, line: t.line };
    }
    if (is('for')) {
      next(); expect('(');
      let init = null;
      if (startsDeclaration()) init = declaration();
      else if (is(';')) next();
      else { init = { kind: 'expr', expr: expression() }; expect(';'); }
      const cond = is(';') ? null : expression();
      expect(';');
      const step = is(')') ? null : expression();
      expect(')');
      const body = statement();
      return { kind: 'for', init, cond, step, body, leading: lead, blankBefore: t.blankBefore, line: t.line };
    }
    if (is('while')) {
      next(); expect('(');
      const cond = expression();
      expect(')');
      return { kind: 'while', cond, body: statement(), leading: lead, blankBefore: t.blankBefore, line: t.line };
    }
    if (is('return')) {
      next();
      const expr = is(';') ? null : expression();
      const end = expect(';');
      return { kind: 'return', expr, leading: lead, blankBefore: t.blankBefore, trailing: end.trailing, line: t.line };
    }
    if (is('break') || is('continue')) { const k = next().text; const end = expect(';'); return { kind: k, leading: lead, blankBefore: t.blankBefore, trailing: end.trailing }; }
    if (is('discard') || is('switch') || is('do')) err(`'${t.text}' is not supported`);
    if (startsDeclaration()) return declaration();
    const expr = expression();
    const end = expect(';');
    return { kind: 'expr', expr, leading: lead, blankBefore: t.blankBefore, trailing: end.trailing, line: t.line };
  }
  function block() {
    const open = expect('{');
    const stmts = [];
    while (!is('}')) {
      if (peek().kind === 'eof') err('unterminated block');
      stmts.push(statement());
    }
    const close = next();
    return { kind: 'block', stmts, leading: open.leading, closeLeading: close.leading, trailing: close.trailing };
  }

  // --- top level ----------------------------------------------------------------------------
  const items = [];
  while (peek().kind !== 'eof') {
    const t = peek();
    const lead = t.leading;
    if (t.kind === 'directive') { next(); items.push({ kind: 'directive', text: t.text, leading: lead, blankBefore: t.blankBefore, trailing: t.trailing, line: t.line }); continue; }
    if (is('precision')) { while (!is(';')) next(); next(); continue; }
    if (is('struct')) {
      next();
      const name = ident();
      structs.add(name);
      expect('{');
      const fields = [];
      while (!is('}')) {
        const ft = peek();
        const type = next().text;
        for (;;) {
          const fname = ident();
          const array = arraySuffix();
          fields.push({ type, name: fname, array, leading: ft.leading, trailing: null });
          if (is(',')) { next(); continue; }
          break;
        }
        const end = expect(';');
        fields[fields.length - 1].trailing = end.trailing;
      }
      next();
      const end = expect(';');
      items.push({ kind: 'struct', name, fields, leading: lead, blankBefore: t.blankBefore, trailing: end.trailing, line: t.line });
      continue;
    }
    if (is('const') || is('uniform')) {
      if (is('uniform')) err('uniform declarations are not supported');
      const d = declaration();
      items.push({ ...d, kind: 'global', blankBefore: t.blankBefore });
      continue;
    }
    // A function: <type> <name>(params) { body } | ;
    if (!isTypeName(t)) err('expected a declaration');
    const ret = next().text;
    const name = ident();
    expect('(');
    const params = [];
    if (is('void') && peek(1).text === ')') next();
    while (!is(')')) {
      let qual = '';
      if (is('in') || is('out') || is('inout')) qual = next().text;
      if (is('const')) next();
      if (is('highp') || is('mediump') || is('lowp')) next();
      if (!isTypeName(peek())) err('expected a parameter type');
      const type = next().text;
      const pname = ident();
      const array = arraySuffix();
      if (array) err('array parameters are not supported');
      params.push({ qual: qual === 'in' ? '' : qual, type, name: pname });
      if (is(',')) next();
      else if (!is(')')) err("expected ',' or ')'");
    }
    next();
    if (is(';')) { next(); items.push({ kind: 'function', ret, name, params, body: null, leading: lead, blankBefore: t.blankBefore, line: t.line }); continue; }
    const body = block();
    items.push({ kind: 'function', ret, name, params, body, leading: lead, blankBefore: t.blankBefore, trailing: body.trailing, line: t.line });
  }
  return { items, trailingComments: peek().leading, structs };
}
