// cloudmath/hlsl/multiple_scattering.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/multiple_scattering.hlsl: GLSL twin of cloudmath/multiple_scattering.hpp,
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
#ifndef CM_MULTIPLE_SCATTERING_HLSL
#define CM_MULTIPLE_SCATTERING_HLSL

#include "core.hlsl"
#include "phase.hlsl"
#include "transmittance.hlsl"

#ifndef CM_MS_OCTAVES
#define CM_MS_OCTAVES 3
#endif

float cm_multiple_scattering(float optical_depth, float mu, float g, float a, float b, float c, int octaves) {
    float sum = 0.0;
    float ai = 1.0;
    float bi = 1.0;
    float ci = 1.0;
    for (int i = 0; i < octaves; ++i) {
        sum += bi * cm_phase_hg(mu, ci * g) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}

// CM_MS_OCTAVES octaves (the C++ multiple_scattering<N>).
float cm_multiple_scattering(float optical_depth, float mu, float g, float a, float b, float c) {
    return cm_multiple_scattering(optical_depth, mu, g, a, b, c, CM_MS_OCTAVES);
}

// Presets (the C++ multiple_scattering_preset without its name): a, b, c, octave count, the
// optical thickness range and the error measured there against the Monte Carlo reference
// (rms and max of (L_model - L_MC) / mean L_MC; see multiple_scattering.hpp).
struct CmMsPreset {
    float a;
    float b;
    float c;
    int octaves;
    float tau_min;
    float tau_max;
    float rms_error;
    float max_error;
};
// CmMsPreset(...) of the GLSL: HLSL has no struct constructors.
CmMsPreset cm_make_CmMsPreset(float a, float b, float c, int octaves, float tau_min, float tau_max, float rms_error, float max_error) {
    CmMsPreset r;
    r.a = a;
    r.b = b;
    r.c = c;
    r.octaves = octaves;
    r.tau_min = tau_min;
    r.tau_max = tau_max;
    r.rms_error = rms_error;
    r.max_error = max_error;
    return r;
}
static const CmMsPreset CM_MS_PRESET_PRODUCTION = {0.5, 0.5, 0.5, 3, 1.0, 100.0, 1.034, 3.726};
static const CmMsPreset CM_MS_PRESET_FITTED = {0.197, 0.409, 0.800, 5, 1.0, 100.0, 0.7096, 3.649};
static const CmMsPreset CM_MS_PRESET_CHEAP = {0.0639, 0.582, 0.676, 2, 1.0, 100.0, 0.7394, 3.657};
static const CmMsPreset CM_MS_PRESET_THIN = {0.173, 0.435, 0.805, 3, 1.0, 10.0, 0.5524, 1.311};
static const CmMsPreset CM_MS_PRESET_THICK = {0.299, 0.625, 0.529, 6, 10.0, 100.0, 0.5431, 2.180};

// The octave sum with a preset's a, b, c and octave count.
float cm_multiple_scattering(float optical_depth, float mu, float g, CmMsPreset preset) {
    return cm_multiple_scattering(optical_depth, mu, g, preset.a, preset.b, preset.c, preset.octaves);
}

#ifdef CM_MS_PHASE
float cm_multiple_scattering_with(float optical_depth, float mu, float a, float b, float c, int octaves) {
    float sum = 0.0;
    float ai = 1.0;
    float bi = 1.0;
    float ci = 1.0;
    for (int i = 0; i < octaves; ++i) {
        sum += bi * CM_MS_PHASE(mu, ci) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}
float cm_multiple_scattering_with(float optical_depth, float mu, float a, float b, float c) {
    return cm_multiple_scattering_with(optical_depth, mu, a, b, c, CM_MS_OCTAVES);
}
#endif

#endif // CM_MULTIPLE_SCATTERING_HLSL
