// cloudmath/hlsl/density.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/density.hlsl: GLSL twin of cloudmath/density.hpp: height gradients and
// presets, coverage, erosion, exponential height fog and its analytic optical depth.
#ifndef CM_DENSITY_HLSL
#define CM_DENSITY_HLSL

#include "core.hlsl"

float cm_height_gradient(float h, float4 profile) {
    return cm_smoothstep_safe(profile.x, profile.y, h) - cm_smoothstep_safe(profile.z, profile.w, h);
}

float4 cm_height_profile_stratus() { return float4(0.02, 0.05, 0.09, 0.11); }
float4 cm_height_profile_stratocumulus() { return float4(0.02, 0.2, 0.48, 0.625); }
float4 cm_height_profile_cumulus() { return float4(0.01, 0.0625, 0.78, 1.0); }

// Type 0 stratus, 0.5 stratocumulus, 1 cumulus; profiles blended with weights summing to 1.
float4 cm_height_profile_for_type(float cloud_type) {
    float t = cm_saturate(cloud_type);
    float w_stratus = 1.0 - cm_saturate(2.0 * t);
    float w_stratocumulus = 1.0 - abs(t - 0.5) * 2.0;
    float w_cumulus = cm_saturate(t - 0.5) * 2.0;
    return cm_height_profile_stratus() * w_stratus + cm_height_profile_stratocumulus() * w_stratocumulus + cm_height_profile_cumulus() * w_cumulus;
}

float cm_height_gradient_for_type(float h, float cloud_type) {
    return cm_height_gradient(h, cm_height_profile_for_type(cloud_type));
}

// The height fractions outside which cm_height_gradient_for_type is exactly 0: clamp a
// march to them.
float2 cm_height_range_for_type(float cloud_type) {
    float4 p = cm_height_profile_for_type(cloud_type);
    return float2(p.x, p.w);
}

// (1 - exp(-a h)) exp(-b h) (Olajos 2016: a = 50, b = 4), in [0, 1] for every finite input:
// h <= 0 gives 0, a < 0 and b < 0 act as 0 (h clamped before either exponential: no 0 * Inf).
float cm_height_gradient_exponential(float h, float a, float b) {
    float height = max(h, 0.0);
    return cm_one_minus_exp_neg(max(a, 0.0) * height) * exp(-max(b, 0.0) * height);
}

// max(0, base + coverage - 1): monotonic in coverage; coverage clamped to [0, 1].
float cm_apply_coverage(float base, float coverage) {
    float c = cm_saturate(coverage);
    return cmi_remap_unit(base, 1.0 - c, 1.0) * c; // cm_remap_clamped(..., 0.0, 1.0)
}

float cm_erode(float base, float erosion) { return cmi_remap_unit(base, erosion, 1.0); } // cm_remap_clamped(..., 0, 1)

// The exponent is floored at -104 (exp gives 0 there in float, as in C++) before exp: a driver
// that folds exp's log2(e) into the product would otherwise compute (-falloff log2 e) *
// altitude, which is Inf * 0 = NaN for a huge falloff at altitude 0 (glsl.fuzz found it).
float cm_height_fog_density(float altitude, float density_at_zero, float falloff) {
    return density_at_zero * exp(max(-falloff * altitude, -104.0));
}

// rho0 L exp(-k h_low) (1 - exp(-x)) / x, x = k |mu| L, from the lower end of the ray.
float cm_height_fog_optical_depth(float altitude, float cos_zenith, float distance, float density_at_zero, float falloff) {
    float mu = clamp(cos_zenith, -1.0, 1.0);
    float rise = mu * distance;
    float h_low = rise < 0.0 ? altitude + rise : altitude;
    return density_at_zero * distance * exp(max(-falloff * h_low, -104.0)) * cm_one_minus_exp_neg_over_x(falloff * abs(rise));
}

// Clear air's optical depth (r, g, b): Rayleigh (5.802, 13.558, 33.1) 1e-6 /m, scale height
// 8 km, plus aerosols 4.40e-6 /m, scale height 1.2 km (Bruneton 2017, Hillaire 2020).
float3 cm_air_optical_depth(float altitude, float cos_zenith, float distance) {
    float rayleigh = cm_height_fog_optical_depth(altitude, cos_zenith, distance, 1.0, 1.0 / 8000.0);
    float aerosol = cm_height_fog_optical_depth(altitude, cos_zenith, distance, 4.40e-6, 1.0 / 1200.0);
    return float3(5.802e-6, 13.558e-6, 33.1e-6) * rayleigh + float3(aerosol, aerosol, aerosol);
}

// L e^-tau + L_air (1 - e^-tau): radiance seen through air that scatters L_air.
// The two weighted terms (no L_air - L: it lost L_air when L >> L_air), clamped to the
// interval between L and L_air; tau < 0 taken as 0.
float cm_aerial_perspective(float L, float L_air, float tau) {
    float t = max(tau, 0.0);
    return clamp(L * exp(-t) + L_air * cm_one_minus_exp_neg(t), min(L, L_air), max(L, L_air));
}
float3 cm_aerial_perspective(float3 L, float3 L_air, float3 tau) {
    float3 t = max(tau, float3(0.0, 0.0, 0.0));
    return clamp(L * exp(-t) + L_air * cm_one_minus_exp_neg(t), min(L, L_air), max(L, L_air));
}

// Nubis density model (density.hpp): steps on already-sampled texture values.
float cm_nubis_low_frequency_fbm(float4 base) { return base.y * 0.625 + base.z * 0.25 + base.w * 0.125; }
float cm_nubis_base_cloud(float4 base) {
    return cm_remap(base.x, cm_nubis_low_frequency_fbm(base) - 1.0, 1.0, 0.0, 1.0);
}
float cm_nubis_high_frequency_fbm(float3 detail) { return detail.x * 0.625 + detail.y * 0.25 + detail.z * 0.125; }
float cm_nubis_detail_erosion(float3 detail, float h) {
    float hf = cm_nubis_high_frequency_fbm(detail);
    float t = cm_saturate(h * 10.0);
    return (hf + t * ((1.0 - hf) - hf)) * 0.2;
}
// 0.6 + 0.4 saturate(weather_b): a cloud's top as a share of its type's profile.
float cm_cloud_top_fraction(float weather_b) { return 0.6 + 0.4 * cm_saturate(weather_b); }

// Base shape with per-cloud type (G), top (B) and coverage narrowing with height (rounded tops).
float cm_cloud_shape_density(float4 base, float3 weather, float h, float coverage, float cloud_type, float type_spread, float top_rounding) {
    float hc = h / cm_cloud_top_fraction(weather.z);
    if (!(hc < 1.0)) return 0.0;
    float t = cm_saturate(cloud_type + (weather.y - 0.5) * type_spread);
    float hr = max(hc, 0.0); // under the layer nothing to round (hc^2 overflowed: NaN)
    float c = cm_saturate(weather.x - 0.5 + coverage) * (1.0 - top_rounding * hr * hr);
    return cm_apply_coverage(cm_nubis_base_cloud(base) * cm_height_gradient_for_type(hc, t), c);
}

float cm_nubis_density(float4 base, float3 detail, float coverage, float cloud_type, float h) {
    float shaped = cm_nubis_base_cloud(base) * cm_height_gradient_for_type(h, cloud_type);
    return cm_erode(cm_apply_coverage(shaped, coverage), cm_nubis_detail_erosion(detail, h));
}

#endif // CM_DENSITY_HLSL
