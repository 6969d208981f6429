// cloudmath/wgsl/multiple_scattering_hooks.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, phase.wgsl, transmittance.wgsl, multiple_scattering.wgsl.
// and your function(s):
//   fn cm_ms_phase(mu: f32, scale: f32) -> f32  (GLSL: #define CM_MS_PHASE)
//
fn cm_multiple_scattering_with(optical_depth: f32, mu: f32, a: f32, b: f32, c: f32, octaves: i32) -> f32 {
    var sum: f32 = 0.0;
    var ai: f32 = 1.0;
    var bi: f32 = 1.0;
    var ci: f32 = 1.0;
    for (var i: i32 = 0; i < octaves; i++) {
        sum += bi * cm_ms_phase(mu, ci) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}
fn cm_multiple_scattering_with_fffff(optical_depth: f32, mu: f32, a: f32, b: f32, c: f32) -> f32 {
    return cm_multiple_scattering_with(optical_depth, mu, a, b, c, CM_MS_OCTAVES);
}
