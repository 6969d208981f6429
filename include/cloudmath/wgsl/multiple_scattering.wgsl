// cloudmath/wgsl/multiple_scattering.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, phase.wgsl, transmittance.wgsl.
//
// cloudmath/glsl/multiple_scattering.glsl: GLSL twin of cloudmath/multiple_scattering.hpp,
// Wrenninge's octaves: sum_{i<N} b^i phase(mu, c^i g) exp(-a^i tau).
// Letters: a scales extinction, b the contribution, c the eccentricity (b <= a conserves
// energy); Frostbite's notes swap a and b.
//
// Configuration (#define before the include):
//   CM_MS_OCTAVES   octave count of the overloads without an `octaves` argument (default 3),
//                   a compile-time constant, so drivers unroll the loop.
//   CM_MS_PHASE     name of a user function `float f(float mu, float scale)` returning the
//                   phase function with eccentricities scaled by `scale` = c^i. When defined,
//                   cm_multiple_scattering_with(...) is available (the C++ generic form).
override CM_MS_OCTAVES: i32 = 3;

fn cm_multiple_scattering(optical_depth: f32, mu: f32, g: f32, a: f32, b: f32, c: f32, octaves: i32) -> f32 {
    var sum: f32 = 0.0;
    var ai: f32 = 1.0;
    var bi: f32 = 1.0;
    var ci: f32 = 1.0;
    for (var i: i32 = 0; i < octaves; i++) {
        sum += bi * cm_phase_hg(mu, ci * g) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}

// CM_MS_OCTAVES octaves (the C++ multiple_scattering<N>).
fn cm_multiple_scattering_ffffff(optical_depth: f32, mu: f32, g: f32, a: f32, b: f32, c: f32) -> f32 {
    return cm_multiple_scattering(optical_depth, mu, g, a, b, c, CM_MS_OCTAVES);
}

// Presets (the C++ multiple_scattering_preset without its name): a, b, c, octave count, the
// optical thickness range and the error measured there against the Monte Carlo reference
// (rms and max of (L_model - L_MC) / mean L_MC; see multiple_scattering.hpp).
struct CmMsPreset {
    a: f32,
    b: f32,
    c: f32,
    octaves: i32,
    tau_min: f32,
    tau_max: f32,
    rms_error: f32,
    max_error: f32,
}
const CM_MS_PRESET_PRODUCTION: CmMsPreset = CmMsPreset(0.5, 0.5, 0.5, 3, 1.0, 100.0, 1.034, 3.726);
const CM_MS_PRESET_FITTED: CmMsPreset = CmMsPreset(0.197, 0.409, 0.800, 5, 1.0, 100.0, 0.7096, 3.649);
const CM_MS_PRESET_CHEAP: CmMsPreset = CmMsPreset(0.0639, 0.582, 0.676, 2, 1.0, 100.0, 0.7394, 3.657);
const CM_MS_PRESET_THIN: CmMsPreset = CmMsPreset(0.173, 0.435, 0.805, 3, 1.0, 10.0, 0.5524, 1.311);
const CM_MS_PRESET_THICK: CmMsPreset = CmMsPreset(0.299, 0.625, 0.529, 6, 10.0, 100.0, 0.5431, 2.180);

// The octave sum with a preset's a, b, c and octave count.
fn cm_multiple_scattering_fffMsPreset(optical_depth: f32, mu: f32, g: f32, preset: CmMsPreset) -> f32 {
    return cm_multiple_scattering(optical_depth, mu, g, preset.a, preset.b, preset.c, preset.octaves);
}
