// cloudmath/wgsl/core.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires nothing else.
//
// cloudmath/glsl/core.glsl: GLSL twin of cloudmath/core.hpp (constants, saturate, remap,
// smoothstep_safe, stable exponential helpers).
//
// Use:      #include "cloudmath/glsl/core.glsl"   (GL_GOOGLE_include_directive, shaderc,
//           GL_ARB_shading_language_include), or cloudmath::glsl_source("core") for raw GL.
// Targets:  function bodies valid in GLSL 3.30 core, GLSL ES 3.00 and Vulkan GLSL 4.50;
//           float only. Same names as the C++ with the cm_ prefix, same argument order.
// Bad input: handled with comparisons, as in C++; nothing relies on NaN or Inf behaviour,
//           which differs between drivers.

const CM_PI = 3.14159265358979;
const CM_TWO_PI = 6.28318530717959;
const CM_FOUR_PI = 12.5663706143592;
const CM_INV_PI = 0.318309886183791;
const CM_INV_FOUR_PI = 0.0795774715459477;

fn cm_saturate(x: f32) -> f32 { return clamp(x, 0.0, 1.0); }
fn cm_saturate_v2(x: vec2f) -> vec2f { return clamp(x, vec2f(0.0), vec2f(1.0)); }
fn cm_saturate_v3(x: vec3f) -> vec3f { return clamp(x, vec3f(0.0), vec3f(1.0)); }
fn cm_saturate_v4(x: vec4f) -> vec4f { return clamp(x, vec4f(0.0), vec4f(1.0)); }

// Unclamped remap; a degenerate old range is the step of the clamped remap (finite).
fn cm_remap(x: f32, old_min: f32, old_max: f32, new_min: f32, new_max: f32) -> f32 {
    if (old_max == old_min) { return select(new_max, new_min, x < old_min); }
    return new_min + (x - old_min) / (old_max - old_min) * (new_max - new_min);
}

// saturate((x - old_min) / (old_max - old_min)), a degenerate range as cm_remap's step:
// cm_remap_clamped to [0, 1] (core.hpp's detail::remap_unit). When an input exceeds
// FLT_MAX / 4 the halved inputs are used, so the differences cannot overflow to Inf / Inf
// (the C++ uses double there). A driver that re-associated x/2 - m/2 into (x - m)/2 would
// lose that (Mesa keeps it: the parity cases with inputs up to FLT_MAX).
fn cmi_remap_unit(x: f32, old_min: f32, old_max: f32) -> f32 {
    if (old_max == old_min) { return select(1.0, 0.0, x < old_min); }
    let s: f32 = select(1.0, 0.5, max(max(abs(x), abs(old_min)), abs(old_max)) > 8.50705917e37);
    return cm_saturate((x * s - old_min * s) / (old_max * s - old_min * s));
}

// Remap clamped to the new range; t is clamped before scaling, end points exact. Finite
// and inside [min(new_min, new_max), max(new_min, new_max)] for every finite input: the
// blend, which can round an ulp past an end, is clamped (core.hpp).
fn cm_remap_clamped(x: f32, old_min: f32, old_max: f32, new_min: f32, new_max: f32) -> f32 {
    let t: f32 = cmi_remap_unit(x, old_min, old_max);
    return clamp((1.0 - t) * new_min + t * new_max, min(new_min, new_max), max(new_min, new_max));
}

// GLSL smoothstep defined for every pair of edges (GLSL leaves edge0 >= edge1 undefined).
fn cm_smoothstep_safe(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t: f32 = cmi_remap_unit(x, edge0, edge1); // cm_remap_clamped(x, edge0, edge1, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t);
}

// (1 - exp(-x)) / x, 1 at x = 0. GLSL has no expm1, and the u = exp(-x); (u - 1) / log(u)
// trick fails where exp and log are approximations near 0 and 1 (measured on Mesa llvmpipe:
// errors up to 1e23). Below |x| = 0.25 the degree-6 Taylor polynomial in Horner form
// (truncation error below 1.6e-9); above, the quotient, whose cancellation is then at most
// a factor 4.5. Agrees with the C++ expm1 form to about 1e-7.
fn cmi_one_minus_exp_neg_over_x_taylor(x: f32) -> f32 {
    return 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x * (1.0 / 120.0 + x * (-1.0 / 720.0 + x * (1.0 / 5040.0))))));
}
fn cm_one_minus_exp_neg_over_x(x: f32) -> f32 {
    if (abs(x) < 0.25) {
        return cmi_one_minus_exp_neg_over_x_taylor(x);
    }
    return (1.0 - exp(-x)) / x;
}
fn cm_one_minus_exp_neg_over_x_v3(x: vec3f) -> vec3f {
    return vec3f(cm_one_minus_exp_neg_over_x(x.x), cm_one_minus_exp_neg_over_x(x.y), cm_one_minus_exp_neg_over_x(x.z));
}

// 1 - exp(-x) with full relative precision for tiny x: below |x| = 0.25, x times the Taylor
// polynomial above; from there, 1 - exp(-x) itself (its cancellation is at most a factor
// 3.5). Not x * cm_one_minus_exp_neg_over_x(x) for all x: above 8.5e37 the quotient's 1/x
// is a denormal that GPUs flush to 0 (result 0), and at x = Inf, where 2 tau or k tau
// overflowed, it is Inf * 0 = NaN (cm_beer_powder from tau = 1.7e38, cm_powder(1e30,
// 1e10)); this form gives 1 there, as the C++ does.
// Domain: every finite x (1 for x >= 17; below x = -88.7 exp(-x) overflows and the result
// is -Inf, as the C++ -expm1 gives).
fn cm_one_minus_exp_neg(x: f32) -> f32 {
    if (abs(x) < 0.25) {
        return x * cmi_one_minus_exp_neg_over_x_taylor(x);
    }
    return 1.0 - exp(-x);
}
fn cm_one_minus_exp_neg_v3(x: vec3f) -> vec3f {
    return vec3f(cm_one_minus_exp_neg(x.x), cm_one_minus_exp_neg(x.y), cm_one_minus_exp_neg(x.z));
}

// (sin x, cos x) to about 2 float ulps for |x| <= 8192. Why not sin() and cos(): Vulkan, GLSL
// and WGSL promise only an absolute error of 2^-11 on [-pi, pi], and drivers use it
// (measured: SwiftShader's sin(0.0023262) is 1.6e-4 off relative, which moved the Sun's disc
// radiance 4% near its limb). Cody-Waite reduction by pi/2 in three parts whose products
// with the quadrant n are exact for |n| < 2^13 (Moshier's Cephes constants, doubled), then
// Taylor polynomials on [-pi/4, pi/4] (truncation below 2.2e-9 relative). Beyond 8192 the
// reduction is inexact, so the built-ins are used (finite, in [-1, 1]).
fn cmi_sin_cos(x: f32) -> vec2f {
    if (!(abs(x) <= 8192.0)) { return vec2f(sin(x), cos(x)); }
    let n: f32 = floor(x * 0.636619772367581 + 0.5);
    let r: f32 = ((x - n * 1.5703125) - n * 4.837512969970703125e-4) - n * 7.54978995489188216e-8;
    let r2: f32 = r * r;
    let s: f32 = r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0))));
    let c: f32 = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0 + r2 * (-1.0 / 3628800.0)))));
    let q: f32 = n - 4.0 * floor(n * 0.25); // the quadrant, 0 to 3
    if (q == 0.0) { return vec2f(s, c); }
    if (q == 1.0) { return vec2f(c, -s); }
    if (q == 2.0) { return vec2f(-s, -c); }
    return vec2f(-c, s);
}
