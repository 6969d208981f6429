// cloudmath/hlsl/transmittance.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/transmittance.hlsl: GLSL twin of cloudmath/transmittance.hpp.
// Optical depth tau >= 0; negative tau is clamped to 0. float and vec3 (RGB) overloads.
#ifndef CM_TRANSMITTANCE_HLSL
#define CM_TRANSMITTANCE_HLSL

#include "core.hlsl"

// exp(-tau), in [0, 1].
float cm_beer_lambert(float optical_depth) { return exp(-max(optical_depth, 0.0)); }
float3 cm_beer_lambert(float3 optical_depth) { return exp(-max(optical_depth, float3(0.0, 0.0, 0.0))); }

// 1 - exp(-k tau) (Schneider 2015), full precision for tiny tau; every finite input, 1 where
// k tau overflows (cm_one_minus_exp_neg of Inf is 1).
float cm_powder(float optical_depth, float k) { return cm_one_minus_exp_neg(max(k * optical_depth, 0.0)); }
float3 cm_powder(float3 optical_depth, float k) {
    return cm_one_minus_exp_neg(max(k * optical_depth, float3(0.0, 0.0, 0.0)));
}

// 2 exp(-tau) (1 - exp(-2 tau)) (Schneider, GPU Pro 7): peak 0.7698 at ln(3)/2; every
// finite tau, 0 for huge tau (also where 2 tau overflows, from 1.7e38).
float cm_beer_powder(float optical_depth) {
    float tau = max(optical_depth, 0.0);
    return 2.0 * exp(-tau) * cm_one_minus_exp_neg(2.0 * tau);
}
float3 cm_beer_powder(float3 optical_depth) {
    float3 tau = max(optical_depth, float3(0.0, 0.0, 0.0));
    return 2.0 * exp(-tau) * cm_one_minus_exp_neg(2.0 * tau);
}

// max(exp(-tau), 0.7 exp(-0.25 tau)) (Schneider, Nubis 2017).
float cm_nubis_attenuation(float optical_depth) {
    float tau = max(optical_depth, 0.0);
    return max(exp(-tau), 0.7 * exp(-0.25 * tau));
}
float3 cm_nubis_attenuation(float3 optical_depth) {
    float3 tau = max(optical_depth, float3(0.0, 0.0, 0.0));
    return max(exp(-tau), 0.7 * exp(-0.25 * tau));
}

// 1 / (1 + 3/4 (1 - g) tau): isotropic light through a conservative layer (two-stream).
float cm_diffuse_transmittance(float optical_depth, float g) {
    return 1.0 / (1.0 + 0.75 * (1.0 - clamp(g, -1.0, 1.0)) * max(optical_depth, 0.0));
}
float3 cm_diffuse_transmittance(float3 optical_depth, float g) {
    return 1.0 / (1.0 + 0.75 * (1.0 - clamp(g, -1.0, 1.0)) * max(optical_depth, float3(0.0, 0.0, 0.0)));
}

#endif // CM_TRANSMITTANCE_HLSL
