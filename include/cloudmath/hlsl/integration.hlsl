// cloudmath/hlsl/integration.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/integration.hlsl: GLSL twin of cloudmath/integration.hpp: the
// energy-conserving step integral (Hillaire 2015) and a front-to-back march accumulator.
//
// Use:      CmMarchAccumulator acc = cm_march_accumulator();
//           for (...) { cm_march_add_segment(acc, S, sigma_t, ds); if (cm_march_is_opaque(acc, 0.01)) break; }
//           color = background * acc.transmittance + acc.luminance;
// S is radiance per metre (sigma_s * phase * light); sigma_t in 1/m; ds in m.
#ifndef CM_INTEGRATION_HLSL
#define CM_INTEGRATION_HLSL

#include "core.hlsl"
#include "transmittance.hlsl"

// S (1 - exp(-sigma_t ds)) / sigma_t, exactly S ds at sigma_t = 0, no clamp constant.
float cm_integrate_scattering(float S, float sigma_t, float ds) {
    return S * ds * cm_one_minus_exp_neg_over_x(max(sigma_t * ds, 0.0));
}
float3 cm_integrate_scattering(float3 S, float3 sigma_t, float ds) {
    return S * ds * cm_one_minus_exp_neg_over_x(max(sigma_t * ds, float3(0.0, 0.0, 0.0)));
}
float3 cm_integrate_scattering(float3 S, float sigma_t, float ds) {
    return S * cm_integrate_scattering(1.0, sigma_t, ds);
}

// The C++ march_accumulator<vec3, vec3>; grey extinction uses the float overload below.
struct CmMarchAccumulator {
    float3 luminance;
    float3 transmittance;
};
// CmMarchAccumulator(...) of the GLSL: HLSL has no struct constructors.
CmMarchAccumulator cm_make_CmMarchAccumulator(float3 luminance, float3 transmittance) {
    CmMarchAccumulator r;
    r.luminance = luminance;
    r.transmittance = transmittance;
    return r;
}

CmMarchAccumulator cm_march_accumulator() {
    return cm_make_CmMarchAccumulator(float3(0.0, 0.0, 0.0), float3(1.0, 1.0, 1.0));
}

void cm_march_add_segment(inout CmMarchAccumulator acc, float3 S, float3 sigma_t, float ds) {
    acc.luminance += acc.transmittance * cm_integrate_scattering(S, sigma_t, ds);
    acc.transmittance *= cm_beer_lambert(sigma_t * ds);
}
void cm_march_add_segment(inout CmMarchAccumulator acc, float3 S, float sigma_t, float ds) {
    acc.luminance += acc.transmittance * cm_integrate_scattering(S, sigma_t, ds);
    acc.transmittance *= cm_beer_lambert(sigma_t * ds);
}

// True once every channel's transmittance is below min_transmittance.
bool cm_march_is_opaque(CmMarchAccumulator acc, float min_transmittance) {
    return all((acc.transmittance < float3(min_transmittance, min_transmittance, min_transmittance)));
}

float3 cm_march_opacity(CmMarchAccumulator acc) { return float3(1.0, 1.0, 1.0) - acc.transmittance; }

// Distance of fraction u of a march over [t_start, t_end] whose steps grow with distance:
// t_start + (t_end - t_start) (e^(u L) - 1) / (e^L - 1),
// L = ln((t_end + near_distance) / (t_start + near_distance));
// ends exact, results within them. (GLSL has no log1p: L = log(1 + x) loses relative precision for tiny x, which
// only bends the spacing of a nearly uniform schedule.)
float cm_march_schedule_distance(float u, float t_start, float t_end, float near_distance) {
    float v = cm_saturate(u);
    if (v <= 0.0) return t_start;
    if (v >= 1.0) return t_end;
    float base = t_start + near_distance;
    float ratio = (t_end - t_start) / base;
    // The ends' ratio near overflow (near_distance tiny): the difference of two logs (1e38, not
    // FLT_MAX: WGSL refuses the literal 3.4028235e38 as beyond f32).
    float L = ratio < 1e38 ? log(1.0 + ratio) : log(t_end + near_distance) - log(base);
    float g = v * exp((v - 1.0) * L) * cm_one_minus_exp_neg_over_x(v * L) / cm_one_minus_exp_neg_over_x(L);
    // Within [t_start, t_end]: the sum rounds past t_end for u near 1.
    return clamp(t_start + (t_end - t_start) * g, t_start, t_end);
}

// Light steps placed quadratically: fraction u of a march of `length` (integration.hpp).
float cm_light_march_distance(float u, float length) {
    float v = cm_saturate(u);
    return length * (v * v);
}

// Sub-steps of optical depth <= 1 for a view step: ceil(tau) in [1, max_substeps]; NaN -> 1.
int cm_refine_substeps(float step_optical_depth, int max_substeps) {
    int most = max(max_substeps, 1);
    if (!(step_optical_depth > 1.0)) return 1;
    if (step_optical_depth >= float(most)) return most;
    // Clamped after the conversion too: in [1, most] even where a compiler folds the NaN test.
    return clamp(int(ceil(step_optical_depth)), 1, most);
}

#endif // CM_INTEGRATION_HLSL
