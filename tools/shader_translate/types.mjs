// tools/shader_translate/types.mjs: GLSL types and the result types of the GLSL built-ins the
// twins use, for translate.mjs's type inference (overload resolution, scalar splats, vector
// comparisons). Types are GLSL spellings ('float', 'vec3', 'uvec2', 'CmMsPreset',
// 'float[135]'); null means unknown (a macro the HLSL output leaves to the preprocessor).
import { SCALARS, VECTORS } from './glsl_parse.mjs';

export const isScalar = (t) => SCALARS.has(t);
export const isVector = (t) => VECTORS.has(t);
export const dim = (t) => (isVector(t) ? Number(t[t.length - 1]) : 1);
export function component(t) {
  if (isScalar(t)) return t;
  if (!isVector(t)) return null;
  return { v: 'float', i: 'int', u: 'uint', b: 'bool' }[t[0]];
}
export function vectorOf(comp, n) {
  if (n === 1) return comp;
  return { float: '', int: 'i', uint: 'u', bool: 'b' }[comp] + 'vec' + n;
}
export function arrayParts(t) {
  const m = /^(\w+)\[(.*)\]$/.exec(t || '');
  return m ? { base: m[1], size: m[2] } : null;
}
export const literalType = (text) => {
  if (/^0[xX]/.test(text)) return /[uU]$/.test(text) ? 'uint' : 'int';
  if (/[uU]$/.test(text)) return 'uint';
  return /[.eEfF]/.test(text) ? 'float' : 'int';
};

// The wider of two operand types: a vector wins over a scalar.
export const wider = (a, b) => (isVector(b) && !isVector(a) ? b : a || b);

const FIRST_ARG = new Set(['abs', 'sign', 'floor', 'ceil', 'fract', 'trunc', 'round', 'roundEven', 'exp', 'exp2', 'log', 'log2', 'sqrt',
  'inversesqrt', 'sin', 'cos', 'tan', 'asin', 'acos', 'sinh', 'cosh', 'tanh', 'radians', 'degrees', 'normalize', 'fma']);
const WIDEST_OF_TWO = new Set(['min', 'max', 'pow', 'mod', 'atan', 'clamp', 'mix']);
const COMPARE = new Set(['lessThan', 'lessThanEqual', 'greaterThan', 'greaterThanEqual', 'equal', 'notEqual']);

export const BUILTIN_FUNCTIONS = new Set([...FIRST_ARG, ...WIDEST_OF_TWO, ...COMPARE, 'step', 'smoothstep', 'length', 'distance',
  'dot', 'cross', 'all', 'any', 'not', 'isnan', 'isinf', 'floatBitsToUint', 'floatBitsToInt', 'uintBitsToFloat', 'intBitsToFloat']);

// Result type of built-in `name` applied to argument types `args` (null when unknown).
export function builtinResult(name, args) {
  if (FIRST_ARG.has(name)) return args[0];
  if (WIDEST_OF_TWO.has(name)) return wider(args[0], args[1]);
  if (name === 'step') return wider(args[1], args[0]);
  if (name === 'smoothstep') return args[2];
  if (name === 'length' || name === 'distance' || name === 'dot') return 'float';
  if (name === 'cross') return 'vec3';
  if (name === 'all' || name === 'any') return 'bool';
  if (name === 'not') return args[0];
  if (COMPARE.has(name) || name === 'isnan' || name === 'isinf') return vectorOf('bool', dim(args[0]));
  if (name === 'floatBitsToUint') return vectorOf('uint', dim(args[0]));
  if (name === 'floatBitsToInt') return vectorOf('int', dim(args[0]));
  if (name === 'uintBitsToFloat' || name === 'intBitsToFloat') return vectorOf('float', dim(args[0]));
  return null;
}

// Swizzle result: component type of `t`, as many components as letters.
// Null when the letters are no swizzle of t: more than 4, a component past t's size (.z of a
// vec2, .w of a vec3), or letters mixed from two sets (.xg).
export function swizzleType(t, letters) {
  const c = component(t);
  if (!c || !/^([xyzw]{1,4}|[rgba]{1,4}|[stpq]{1,4})$/.test(letters)) return null;
  const n = dim(t);
  const highest = Math.max(...[...letters].map((l) => 'xyzwrgbastpq'.indexOf(l) % 4));
  if (highest >= n) return null;
  return vectorOf(c, letters.length);
}
