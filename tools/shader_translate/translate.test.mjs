// Unit tests of the GLSL -> HLSL / WGSL translator (ctest shaders.translator):
//   node --test tools/shader_translate/translate.test.mjs
// Each test states the exact text a construct must become; the parity tests (hlsl.parity,
// web.wgsl_parity) prove that the translated library computes what the C++ does.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { moduleFiles, preprocessWgsl, translateUnit, TranslateError } from './translate.mjs';

const hlsl = (src, opts = {}) => translateUnit([{ name: 'a.glsl', text: src }], { target: 'hlsl', ...opts }).text;
const wgsl = (src, opts = {}) => translateUnit([{ name: 'a.glsl', text: src }], { target: 'wgsl', ...opts });
const has = (text, part) => assert.ok(text.includes(part), `expected\n${part}\nin\n${text}`);
const lacks = (text, part) => assert.ok(!text.includes(part), `did not expect\n${part}\nin\n${text}`);

test('types and vector constructors', () => {
  const src = 'vec3 f(vec4 v, float s, ivec2 i) { vec3 a = vec3(s); vec3 b = vec3(0.0); vec3 c = vec3(v); vec2 d = vec2(i); return a + b + c + vec3(d, s); }';
  const h = hlsl(src);
  has(h, 'float3 f(float4 v, float s, int2 i)');
  has(h, 'float3 a = float3(s, s, s);');
  has(h, 'float3 b = float3(0.0, 0.0, 0.0);');
  has(h, 'float3 c = v.xyz;');
  has(h, 'float2 d = float2(i);');
  const w = wgsl(src).text;
  has(w, 'fn f(v: vec4f, s: f32, i: vec2i) -> vec3f');
  has(w, 'let a: vec3f = vec3f(s);');
  has(w, 'let c: vec3f = v.xyz;');
  has(w, 'let d: vec2f = vec2f(i);');
});

test('a complex scalar splat is a cast in HLSL', () => {
  has(hlsl('vec3 f(float s) { return vec3(s * 2.0); }'), 'return ((float3)(s * 2.0));');
});

test('overloads: WGSL names, HLSL keeps them', () => {
  const src = 'float g(float x) { return x; }\nvec3 g(vec3 x) { return x; }\nvec3 g(vec3 x, int n, uint s) { return x; }\n' +
    'vec3 h(vec3 v) { return g(v) + g(v, 1, 0u) + vec3(g(1.0)); }';
  const w = wgsl(src).text;
  has(w, 'fn g(x: f32) -> f32');
  has(w, 'fn g_v3(x: vec3f) -> vec3f');
  has(w, 'fn g_v3iu(x: vec3f, n: i32, s: u32) -> vec3f');
  has(w, 'return g_v3(v) + g_v3iu(v, 1, 0u) + vec3f(g(1.0));');
  has(hlsl(src), 'return g(v) + g(v, 1, 0u) + float3(g(1.0), g(1.0), g(1.0));'.replace('float3(g(1.0), g(1.0), g(1.0))', '((float3)(g(1.0)))'));
});

test('a call no overload takes is an error naming the line', () => {
  assert.throws(() => hlsl('float g(float x) { return x; }\nfloat h() {\n  return g(1);\n}'), (e) => e instanceof TranslateError && /:3: no overload of g takes \(int\)/.test(e.message));
});

test('out and inout parameters become pointers in WGSL', () => {
  const src = 'struct S { float a; };\nvoid add(inout S s, float x, out float y) { s.a += x; y = s.a; }\n' +
    'float f() { S s = S(1.0); float y; add(s, 2.0, y); return y; }';
  const w = wgsl(src).text;
  has(w, 'fn add(s: ptr<function, S>, x: f32, y: ptr<function, f32>)');
  has(w, '(*s).a += x;');
  has(w, '(*y) = (*s).a;');
  has(w, 'var s: S = S(1.0);');
  has(w, 'add(&s, 2.0, &y);');
  const h = hlsl(src);
  has(h, 'void add(inout S s, float x, out float y)');
  has(h, 'S s = cm_make_S(1.0);');
  has(h, 'S cm_make_S(float a) {');
});

test('an assigned parameter gets a local copy in WGSL', () => {
  const w = wgsl('float f(float x) { x = x * 2.0; return x; }').text;
  has(w, 'fn f(x_in: f32) -> f32 {\n    var x: f32 = x_in;');
});

test('ternaries: select, or if/else when a branch calls a function', () => {
  const src = 'float g(float x) { return x; }\nfloat f(float x, int k) { float a = x > 0.0 ? 1.0 : 2.0; float b = k == 0 ? g(x) : (k == 1 ? g(2.0) : 3.0); return k > 2 ? g(a) : b; }';
  const w = wgsl(src).text;
  has(w, 'let a: f32 = select(2.0, 1.0, x > 0.0);');
  has(w, 'var b: f32;\n    if (k == 0) {\n        b = g(x);\n    } else if (k == 1) {\n        b = g(2.0);\n    } else {\n        b = 3.0;\n    }');
  has(w, 'if (k > 2) {\n        return g(a);\n    }\n    return b;');
  has(hlsl(src), 'float a = x > 0.0 ? 1.0 : 2.0;');
});

test('built-ins: splats, renames and comparisons', () => {
  const src = 'vec3 f(vec3 v, vec3 u, float s) { bool e = v == u; bvec3 l = lessThan(v, u); return mix(v, u, s) + max(v, 0.0) + clamp(v, 0.0, s) + fract(v) + inversesqrt(v) + vec3(atan(s, 1.0)); }';
  const h = hlsl(src);
  has(h, 'bool e = all(v == u);');
  has(h, 'bool3 l = (v < u);');
  has(h, 'lerp(v, u, s) + max(v, 0.0) + clamp(v, 0.0, s) + frac(v) + rsqrt(v) + ((float3)(atan2(s, 1.0)))');
  const w = wgsl(src).text;
  has(w, 'let e: bool = all(v == u);');
  has(w, 'let l: vec3<bool> = (v < u);');
  has(w, 'mix(v, u, s) + max(v, vec3f(0.0)) + clamp(v, vec3f(0.0), vec3f(s)) + fract(v) + inverseSqrt(v) + vec3f(atan2(s, 1.0))');
  assert.throws(() => hlsl('float f(float x) { return mod(x, 2.0); }'), /mod\(\) has no HLSL twin/);
});

test('bit operations: WGSL parentheses and u32 shift counts', () => {
  const w = wgsl('uint f(uint x, int n) { return x >> 16u ^ x << n & 255u; }').text;
  has(w, 'return (x >> 16u) ^ ((x << u32(n)) & 255u);');
});

test('globals: static const in HLSL, const in WGSL, brace initialisers', () => {
  const src = 'struct P { float a; int n; float t[2]; };\nconst P Q = P(0.5, 3, float[2](1.0, 2.0));\nconst vec2 G[2] = vec2[2](vec2(1.0, 0.0), vec2(0.0, 1.0));\nfloat f(int i) { return Q.t[i] + G[i].x; }';
  const h = hlsl(src);
  has(h, 'static const P Q = {0.5, 3, {1.0, 2.0}};');
  has(h, 'static const float2 G[2] = {float2(1.0, 0.0), float2(0.0, 1.0)};');
  const w = wgsl(src).text;
  has(w, 'struct P {\n    a: f32,\n    n: i32,\n    t: array<f32, 2>,\n}');
  has(w, 'const Q: P = P(0.5, 3, array<f32, 2>(1.0, 2.0));');
  has(w, 'var<private> G: array<vec2f, 2> = array<vec2f, 2>(vec2f(1.0, 0.0), vec2f(0.0, 1.0));');
});

test('preprocessor: HLSL keeps it, WGSL evaluates it', () => {
  const src = '#ifndef CM_A_GLSL\n#define CM_A_GLSL\n#include "b.glsl"\n#define PI 3.14159\n#ifndef N\n#define N 3\n#endif\n' +
    '#ifdef HOOK\nfloat h(float x) { return HOOK(x); }\n#endif\n#ifdef OPT\nfloat o() { return 1.0; }\n#else\nfloat o() { return 2.0; }\n#endif\nfloat f() { return PI * float(N); }\n#endif\n';
  const hooks = { HOOK: { fn: 'cm_hook', ret: 'float', params: [['float', 'x']] } };
  const h = translateUnit([{ name: 'b.glsl', text: '' }, { name: 'a.glsl', text: src }], { target: 'hlsl', emit: ['a.glsl'], hooks }).text;
  has(h, '#ifndef CM_A_HLSL\n#define CM_A_HLSL\n#include "b.hlsl"\n#define PI 3.14159');
  has(h, '#ifdef HOOK\nfloat h(float x) { return HOOK(x); }\n#endif');
  const w = translateUnit([{ name: 'a.glsl', text: src }], { target: 'wgsl', hooks });
  has(w.text, 'const PI = 3.14159;');
  has(w.text, 'override N: i32 = 3;');
  has(w.text, 'fn o() -> f32 { return 2.0; }');
  lacks(w.text, 'fn h(');
  lacks(w.text, 'return 1.0');
  has(w.hooked, 'fn h(x: f32) -> f32 { return cm_hook(x); }');
  const d = translateUnit([{ name: 'a.glsl', text: src }], { target: 'wgsl', hooks, defines: { OPT: '1', N: '5' } }).text;
  has(d, 'fn o() -> f32 { return 1.0; }');
  has(d, 'const N = 5;');
  lacks(d, 'override N');
});

test('the preprocessor refuses what WGSL cannot express', () => {
  assert.throws(() => preprocessWgsl('#if X > 1\n#endif\n'), /#if is not supported/);
  assert.throws(() => preprocessWgsl('#define F(x) (x)\n'), /function-like macros/);
  assert.throws(() => preprocessWgsl('#ifdef X\n'), /without #endif/);
});

test('unsupported syntax is an error with its line', () => {
  assert.throws(() => hlsl('float f(float x) {\n  switch (1) { }\n}'), /:2: 'switch' is not supported/);
  assert.throws(() => hlsl('float f(float x) { return x, x; }'), /comma operator/);
  assert.throws(() => wgsl('float f(float x) { float y = x++; return y; }'), /\+\+\/-- inside an expression/);
  assert.throws(() => hlsl('uniform float u;'), /uniform declarations are not supported/);
});

test('CM_PRECISE: precise in HLSL (its default), dropped in WGSL', () => {
  const src = '#ifndef CM_PRECISE\n#define CM_PRECISE\n#endif\nfloat f(float a) { CM_PRECISE float s = a * 4097.0; precise float h = s - (s - a); return h; }';
  const h = hlsl(src);
  has(h, '#ifndef CM_PRECISE\n#define CM_PRECISE precise\n#endif');
  has(h, 'CM_PRECISE float s = a * 4097.0;');
  has(h, 'CM_PRECISE float h = s - (s - a);');
  has(wgsl(src).text, 'let s: f32 = a * 4097.0;');
});

test('review fixes: NaN tests, signs, ^^, relational chains, fields, overload clashes, out arguments', () => {
  has(hlsl('float f(float d) { if (d != d) return d; return 0.0; }'), 'if (isnan(d)) return d;');
  has(hlsl('float f(float x) { return - -x; }'), 'return - -x;');
  has(wgsl('float f(float x) { return - -x; }').text, 'return -(-x);');
  has(hlsl('bool f(bool a, bool b, bool c) { return a && b ^^ c; }'), 'return ((a && b) != (c));');
  has(wgsl('bool f(bool a, float x, float y) { return a == x < y; }').text, 'return a == (x < y);');
  const fields = 'struct S { float type; float sample; };\nfloat f(S s) { return s.type + s.sample; }';
  has(hlsl(fields), 'return s.type + s.sample_;');
  has(wgsl(fields).text, 'return s.type_ + s.sample;');
  assert.throws(() => wgsl('float f(float x) { return 0.0; }\nfloat f(int a, vec2 b) { return 1.0; }\nfloat f(ivec2 a) { return 2.0; }'), /both become f_iv2/);
  assert.throws(() => wgsl('void h(out float y) { y = 1.0; }\nfloat f() { vec2 v; h(v.x); return v.x; }'), /not a whole variable/);
  has(wgsl('vec3 f(int i) { return vec3(i); }').text, 'return vec3f(f32(i));');
  assert.throws(() => wgsl('bool f(float x) { return isnan(x); }'), /isnan\(\) has no WGSL form/);
  assert.throws(() => hlsl('float f(float x) { return fma(x, x, x); }'), /fma\(\) has no float HLSL form/);
});

test('WGSL: arrays indexed at run time are vars; comments of removed directives go with them', () => {
  const w = wgsl('struct M { float t[2]; };\nfloat f(M m, int i) { return m.t[i] + m.t[0]; }').text;
  has(w, 'fn f(m_in: M, i: i32) -> f32 {\n    var m: M = m_in;');
  const g = wgsl('// header\n#ifndef CM_X_GLSL\n#define CM_X_GLSL\n// about the include\n#include "y.glsl"\nfloat f() { return 1.0; }\n#endif\n').text;
  assert.equal(g, '// header\nfn f() -> f32 { return 1.0; }\n');
});

test('keywords of the target language are renamed', () => {
  has(hlsl('float f(float sample, float line) { return sample + line; }'), 'float f(float sample_, float line_) { return sample_ + line_; }');
  has(wgsl('float f(float ref, float type) { return ref + type; }').text, 'fn f(ref_: f32, type_: f32) -> f32 { return ref_ + type_; }');
});

test('comments and blank lines are kept', () => {
  const w = wgsl('// lead\nfloat f(float x) {\n    // inside\n    return x; // trailing\n}\n\n// next\nfloat g() { return 1.0; }\n').text;
  assert.equal(w, '// lead\nfn f(x: f32) -> f32 {\n    // inside\n    return x; // trailing\n}\n\n// next\nfn g() -> f32 { return 1.0; }\n');
});

test('module files: dependencies first, each once, cycles refused', () => {
  const src = { 'a.glsl': '#include "b.glsl"\n#include "c.glsl"\n', 'b.glsl': '#include "c.glsl"\n', 'c.glsl': '' };
  assert.deepEqual(moduleFiles('a.glsl', src).map((f) => f.name), ['c.glsl', 'b.glsl', 'a.glsl']);
  assert.throws(() => moduleFiles('a.glsl', { 'a.glsl': '#include "b.glsl"\n', 'b.glsl': '#include "a.glsl"\n' }), /cycle/);
  assert.throws(() => moduleFiles('a.glsl', { 'a.glsl': '#include "x.glsl"\n' }), /no such file/);
});

// Hardening round 2 (B5-B8): what the translator let through, or crashed on, now refused with
// the file and line.
const refuses = (src, message, line) => {
  for (const target of ['hlsl', 'wgsl'])
    assert.throws(() => translateUnit([{ name: 'a.glsl', text: src }], { target }),
      (e) => e instanceof TranslateError && e.message.includes(message) && e.message.startsWith(`a.glsl:${line}:`),
      `${target}: expected a.glsl:${line}: ... ${message}`);
};

test('deep nesting is an error with its line, not a stack overflow (B5, B8)', () => {
  const parens = `float f(float x) {\n  return ${'('.repeat(1500)}x${')'.repeat(1500)};\n}`;
  refuses(parens, 'nesting deeper than 256 levels', 2);
  const flat = `float f(float x) {\n  return x${' + x'.repeat(6000)};\n}`;
  refuses(flat, 'nesting deeper than 256 levels', 2);
  const nots = `bool f(bool b) {\n  return ${'!'.repeat(2000)}b;\n}`;
  refuses(nots, 'nesting deeper than 256 levels', 2);
  const calls = `float g(float x) { return x; }\nfloat f(float x) {\n  return ${'g('.repeat(1500)}x${')'.repeat(1500)};\n}`;
  refuses(calls, 'nesting deeper than 256 levels', 3);
  const ifs = `float f(float x) {\n${'if (x > 0.0) '.repeat(1600)}x = 1.0;\n  return x;\n}`;
  refuses(ifs, 'nesting deeper than 256 levels', 2);
  const blocks = `float f(float x) {\n${'{'.repeat(1500)}x = 1.0;${'}'.repeat(1500)}\n  return x;\n}`;
  refuses(blocks, 'nesting deeper than 256 levels', 2);
  const ternaries = `float f(float x) {\n  return ${'x > 0.0 ? x : '.repeat(1500)}x;\n}`;
  refuses(ternaries, 'nesting deeper than 256 levels', 2);
  // 200 nested ifs (under the cap) translate, and quickly in HLSL (800 took 3.5 s before).
  const fine = `float f(float x) {\n${'if (x > 0.0) '.repeat(200)}x = 1.0;\n  return x;\n}`;
  const t0 = Date.now();
  has(hlsl(fine), 'x = 1.0;');
  assert.ok(Date.now() - t0 < 2000, 'HLSL: 200 nested ifs took over 2 s');
});

test('a function defined twice with the same signature is an error (B6)', () => {
  refuses('float f(float x) { return x; }\nfloat f(float x) { return 2.0 * x; }', 'f(float) is defined twice', 2);
  // A prototype and its definition stay fine.
  has(hlsl('float f(float x);\nfloat f(float x) { return x; }'), 'float f(float x)');
});

test('what was translated silently though wrong is an error with its line (B7)', () => {
  refuses('float f(float x) {\n  return f(x);\n}', 'recursion: f calls f', 2);
  refuses('float g(float x);\nfloat f(float x) {\n  return g(x);\n}\nfloat g(float x) {\n  return f(x);\n}', 'recursion', 6);
  refuses('float f(float x) {\n  return undefined_thing(x);\n}', 'call of undefined_thing, which is not defined', 2);
  refuses('vec3 f(float x) {\n  return x;\n}', 'f returns vec3, not float', 2);
  refuses('float f(vec3 v) {\n  return v.xyzwq.x;\n}', '.xyzwq is not a swizzle of a vec3', 2);
  refuses('float f(vec3 v) {\n  return v.w;\n}', '.w is not a swizzle of a vec3', 2);
  refuses('float f(vec2 v) {\n  return v.xg.x;\n}', '.xg is not a swizzle of a vec2', 2);
  refuses('float f() {\n  return 1e999;\n}', 'rounds to infinity in float', 2);
  // The float maximum itself, an int returned as float and overloads calling overloads are fine.
  has(hlsl('float f() { return 3.4028235e38; }'), '3.4028235e38');
  has(hlsl('float f() { return 1; }'), 'return 1;');
  has(hlsl('float g(float x) { return x; }\nvec2 g(vec2 v) { return vec2(g(v.x), g(v.y)); }'), 'float2 g(float2 v)');
  // HLSL keeps the preprocessor lines: a dangling one is an error there too.
  assert.throws(() => hlsl('#ifdef A\nfloat f(float x) { return x; }\n'), (e) => e instanceof TranslateError && e.message.includes('#ifdef without #endif'));
  assert.throws(() => hlsl('float f(float x) { return x; }\n#else\n'), (e) => e instanceof TranslateError && e.message.includes('#else without #ifdef'));
  assert.throws(() => hlsl('float f(float x) { return x; }\n#endif\n'), (e) => e instanceof TranslateError && e.message.includes('#endif without #ifdef'));
});
