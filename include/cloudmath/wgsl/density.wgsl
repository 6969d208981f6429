// cloudmath/wgsl/density.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/density.glsl: GLSL twin of cloudmath/density.hpp: height gradients and
// presets, coverage, erosion, exponential height fog and its analytic optical depth.

fn cm_height_gradient(h: f32, profile: vec4f) -> f32 {
    return cm_smoothstep_safe(profile.x, profile.y, h) - cm_smoothstep_safe(profile.z, profile.w, h);
}

fn cm_height_profile_stratus() -> vec4f { return vec4f(0.02, 0.05, 0.09, 0.11); }
fn cm_height_profile_stratocumulus() -> vec4f { return vec4f(0.02, 0.2, 0.48, 0.625); }
fn cm_height_profile_cumulus() -> vec4f { return vec4f(0.01, 0.0625, 0.78, 1.0); }

// Type 0 stratus, 0.5 stratocumulus, 1 cumulus; profiles blended with weights summing to 1.
fn cm_height_profile_for_type(cloud_type: f32) -> vec4f {
    let t: f32 = cm_saturate(cloud_type);
    let w_stratus: f32 = 1.0 - cm_saturate(2.0 * t);
    let w_stratocumulus: f32 = 1.0 - abs(t - 0.5) * 2.0;
    let w_cumulus: f32 = cm_saturate(t - 0.5) * 2.0;
    return cm_height_profile_stratus() * w_stratus + cm_height_profile_stratocumulus() * w_stratocumulus + cm_height_profile_cumulus() * w_cumulus;
}

fn cm_height_gradient_for_type(h: f32, cloud_type: f32) -> f32 {
    return cm_height_gradient(h, cm_height_profile_for_type(cloud_type));
}

// The height fractions outside which cm_height_gradient_for_type is exactly 0: clamp a
// march to them.
fn cm_height_range_for_type(cloud_type: f32) -> vec2f {
    let p: vec4f = cm_height_profile_for_type(cloud_type);
    return vec2f(p.x, p.w);
}

// (1 - exp(-a h)) exp(-b h) (Olajos 2016: a = 50, b = 4), in [0, 1] for every finite input:
// h <= 0 gives 0, a < 0 and b < 0 act as 0 (h clamped before either exponential: no 0 * Inf).
fn cm_height_gradient_exponential(h: f32, a: f32, b: f32) -> f32 {
    let height: f32 = max(h, 0.0);
    return cm_one_minus_exp_neg(max(a, 0.0) * height) * exp(-max(b, 0.0) * height);
}

// max(0, base + coverage - 1): monotonic in coverage; coverage clamped to [0, 1].
fn cm_apply_coverage(base: f32, coverage: f32) -> f32 {
    let c: f32 = cm_saturate(coverage);
    return cmi_remap_unit(base, 1.0 - c, 1.0) * c; // cm_remap_clamped(..., 0.0, 1.0)
}

fn cm_erode(base: f32, erosion: f32) -> f32 { return cmi_remap_unit(base, erosion, 1.0); } // cm_remap_clamped(..., 0, 1)

// The exponent is floored at -104 (exp gives 0 there in float, as in C++) before exp: a driver
// that folds exp's log2(e) into the product would otherwise compute (-falloff log2 e) *
// altitude, which is Inf * 0 = NaN for a huge falloff at altitude 0 (glsl.fuzz found it).
fn cm_height_fog_density(altitude: f32, density_at_zero: f32, falloff: f32) -> f32 {
    return density_at_zero * exp(max(-falloff * altitude, -104.0));
}

// rho0 L exp(-k h_low) (1 - exp(-x)) / x, x = k |mu| L, from the lower end of the ray.
fn cm_height_fog_optical_depth(altitude: f32, cos_zenith: f32, distance: f32, density_at_zero: f32, falloff: f32) -> f32 {
    let mu: f32 = clamp(cos_zenith, -1.0, 1.0);
    let rise: f32 = mu * distance;
    let h_low: f32 = select(altitude, altitude + rise, rise < 0.0);
    return density_at_zero * distance * exp(max(-falloff * h_low, -104.0)) * cm_one_minus_exp_neg_over_x(falloff * abs(rise));
}

// Clear air's optical depth (r, g, b): Rayleigh (5.802, 13.558, 33.1) 1e-6 /m, scale height
// 8 km, plus aerosols 4.40e-6 /m, scale height 1.2 km (Bruneton 2017, Hillaire 2020).
fn cm_air_optical_depth(altitude: f32, cos_zenith: f32, distance: f32) -> vec3f {
    let rayleigh: f32 = cm_height_fog_optical_depth(altitude, cos_zenith, distance, 1.0, 1.0 / 8000.0);
    let aerosol: f32 = cm_height_fog_optical_depth(altitude, cos_zenith, distance, 4.40e-6, 1.0 / 1200.0);
    return vec3f(5.802e-6, 13.558e-6, 33.1e-6) * rayleigh + vec3f(aerosol);
}

// L e^-tau + L_air (1 - e^-tau): radiance seen through air that scatters L_air.
// The two weighted terms (no L_air - L: it lost L_air when L >> L_air), clamped to the
// interval between L and L_air; tau < 0 taken as 0.
fn cm_aerial_perspective(L: f32, L_air: f32, tau: f32) -> f32 {
    let t: f32 = max(tau, 0.0);
    return clamp(L * exp(-t) + L_air * cm_one_minus_exp_neg(t), min(L, L_air), max(L, L_air));
}
fn cm_aerial_perspective_v3v3v3(L: vec3f, L_air: vec3f, tau: vec3f) -> vec3f {
    let t: vec3f = max(tau, vec3f(0.0));
    return clamp(L * exp(-t) + L_air * cm_one_minus_exp_neg_v3(t), min(L, L_air), max(L, L_air));
}

// Nubis density model (density.hpp): steps on already-sampled texture values.
fn cm_nubis_low_frequency_fbm(base: vec4f) -> f32 { return base.y * 0.625 + base.z * 0.25 + base.w * 0.125; }
fn cm_nubis_base_cloud(base: vec4f) -> f32 {
    return cm_remap(base.x, cm_nubis_low_frequency_fbm(base) - 1.0, 1.0, 0.0, 1.0);
}
fn cm_nubis_high_frequency_fbm(detail: vec3f) -> f32 {
    return detail.x * 0.625 + detail.y * 0.25 + detail.z * 0.125;
}
fn cm_nubis_detail_erosion(detail: vec3f, h: f32) -> f32 {
    let hf: f32 = cm_nubis_high_frequency_fbm(detail);
    let t: f32 = cm_saturate(h * 10.0);
    return (hf + t * ((1.0 - hf) - hf)) * 0.2;
}
// 0.6 + 0.4 saturate(weather_b): a cloud's top as a share of its type's profile.
fn cm_cloud_top_fraction(weather_b: f32) -> f32 { return 0.6 + 0.4 * cm_saturate(weather_b); }

// Base shape with per-cloud type (G), top (B) and coverage narrowing with height (rounded tops).
fn cm_cloud_shape_density(base: vec4f, weather: vec3f, h: f32, coverage: f32, cloud_type: f32, type_spread: f32, top_rounding: f32) -> f32 {
    let hc: f32 = h / cm_cloud_top_fraction(weather.z);
    if (!(hc < 1.0)) { return 0.0; }
    let t: f32 = cm_saturate(cloud_type + (weather.y - 0.5) * type_spread);
    let hr: f32 = max(hc, 0.0); // under the layer nothing to round (hc^2 overflowed: NaN)
    let c: f32 = cm_saturate(weather.x - 0.5 + coverage) * (1.0 - top_rounding * hr * hr);
    return cm_apply_coverage(cm_nubis_base_cloud(base) * cm_height_gradient_for_type(hc, t), c);
}

fn cm_nubis_density(base: vec4f, detail: vec3f, coverage: f32, cloud_type: f32, h: f32) -> f32 {
    let shaped: f32 = cm_nubis_base_cloud(base) * cm_height_gradient_for_type(h, cloud_type);
    return cm_erode(cm_apply_coverage(shaped, coverage), cm_nubis_detail_erosion(detail, h));
}
