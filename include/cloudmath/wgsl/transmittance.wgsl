// cloudmath/wgsl/transmittance.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/transmittance.glsl: GLSL twin of cloudmath/transmittance.hpp.
// Optical depth tau >= 0; negative tau is clamped to 0. float and vec3 (RGB) overloads.

// exp(-tau), in [0, 1].
fn cm_beer_lambert(optical_depth: f32) -> f32 { return exp(-max(optical_depth, 0.0)); }
fn cm_beer_lambert_v3(optical_depth: vec3f) -> vec3f { return exp(-max(optical_depth, vec3f(0.0))); }

// 1 - exp(-k tau) (Schneider 2015), full precision for tiny tau; every finite input, 1 where
// k tau overflows (cm_one_minus_exp_neg of Inf is 1).
fn cm_powder(optical_depth: f32, k: f32) -> f32 { return cm_one_minus_exp_neg(max(k * optical_depth, 0.0)); }
fn cm_powder_v3f(optical_depth: vec3f, k: f32) -> vec3f {
    return cm_one_minus_exp_neg_v3(max(k * optical_depth, vec3f(0.0)));
}

// 2 exp(-tau) (1 - exp(-2 tau)) (Schneider, GPU Pro 7): peak 0.7698 at ln(3)/2; every
// finite tau, 0 for huge tau (also where 2 tau overflows, from 1.7e38).
fn cm_beer_powder(optical_depth: f32) -> f32 {
    let tau: f32 = max(optical_depth, 0.0);
    return 2.0 * exp(-tau) * cm_one_minus_exp_neg(2.0 * tau);
}
fn cm_beer_powder_v3(optical_depth: vec3f) -> vec3f {
    let tau: vec3f = max(optical_depth, vec3f(0.0));
    return 2.0 * exp(-tau) * cm_one_minus_exp_neg_v3(2.0 * tau);
}

// max(exp(-tau), 0.7 exp(-0.25 tau)) (Schneider, Nubis 2017).
fn cm_nubis_attenuation(optical_depth: f32) -> f32 {
    let tau: f32 = max(optical_depth, 0.0);
    return max(exp(-tau), 0.7 * exp(-0.25 * tau));
}
fn cm_nubis_attenuation_v3(optical_depth: vec3f) -> vec3f {
    let tau: vec3f = max(optical_depth, vec3f(0.0));
    return max(exp(-tau), 0.7 * exp(-0.25 * tau));
}

// 1 / (1 + 3/4 (1 - g) tau): isotropic light through a conservative layer (two-stream).
fn cm_diffuse_transmittance(optical_depth: f32, g: f32) -> f32 {
    return 1.0 / (1.0 + 0.75 * (1.0 - clamp(g, -1.0, 1.0)) * max(optical_depth, 0.0));
}
fn cm_diffuse_transmittance_v3f(optical_depth: vec3f, g: f32) -> vec3f {
    return 1.0 / (1.0 + 0.75 * (1.0 - clamp(g, -1.0, 1.0)) * max(optical_depth, vec3f(0.0)));
}
