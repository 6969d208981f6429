// cloudmath/wgsl/integration.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, transmittance.wgsl.
//
// cloudmath/glsl/integration.glsl: GLSL twin of cloudmath/integration.hpp: the
// energy-conserving step integral (Hillaire 2015) and a front-to-back march accumulator.
//
// Use:      CmMarchAccumulator acc = cm_march_accumulator();
//           for (...) { cm_march_add_segment(acc, S, sigma_t, ds); if (cm_march_is_opaque(acc, 0.01)) break; }
//           color = background * acc.transmittance + acc.luminance;
// S is radiance per metre (sigma_s * phase * light); sigma_t in 1/m; ds in m.

// S (1 - exp(-sigma_t ds)) / sigma_t, exactly S ds at sigma_t = 0, no clamp constant.
fn cm_integrate_scattering(S: f32, sigma_t: f32, ds: f32) -> f32 {
    return S * ds * cm_one_minus_exp_neg_over_x(max(sigma_t * ds, 0.0));
}
fn cm_integrate_scattering_v3v3f(S: vec3f, sigma_t: vec3f, ds: f32) -> vec3f {
    return S * ds * cm_one_minus_exp_neg_over_x_v3(max(sigma_t * ds, vec3f(0.0)));
}
fn cm_integrate_scattering_v3ff(S: vec3f, sigma_t: f32, ds: f32) -> vec3f {
    return S * cm_integrate_scattering(1.0, sigma_t, ds);
}

// The C++ march_accumulator<vec3, vec3>; grey extinction uses the float overload below.
struct CmMarchAccumulator {
    luminance: vec3f,
    transmittance: vec3f,
}

fn cm_march_accumulator() -> CmMarchAccumulator { return CmMarchAccumulator(vec3f(0.0), vec3f(1.0)); }

fn cm_march_add_segment(acc: ptr<function, CmMarchAccumulator>, S: vec3f, sigma_t: vec3f, ds: f32) {
    (*acc).luminance += (*acc).transmittance * cm_integrate_scattering_v3v3f(S, sigma_t, ds);
    (*acc).transmittance *= cm_beer_lambert_v3(sigma_t * ds);
}
fn cm_march_add_segment_MarchAccumulatorv3ff(acc: ptr<function, CmMarchAccumulator>, S: vec3f, sigma_t: f32, ds: f32) {
    (*acc).luminance += (*acc).transmittance * cm_integrate_scattering_v3ff(S, sigma_t, ds);
    (*acc).transmittance *= vec3f(cm_beer_lambert(sigma_t * ds));
}

// True once every channel's transmittance is below min_transmittance.
fn cm_march_is_opaque(acc: CmMarchAccumulator, min_transmittance: f32) -> bool {
    return all((acc.transmittance < vec3f(min_transmittance)));
}

fn cm_march_opacity(acc: CmMarchAccumulator) -> vec3f { return vec3f(1.0) - acc.transmittance; }

// Distance of fraction u of a march over [t_start, t_end] whose steps grow with distance:
// t_start + (t_end - t_start) (e^(u L) - 1) / (e^L - 1),
// L = ln((t_end + near_distance) / (t_start + near_distance));
// ends exact, results within them. (GLSL has no log1p: L = log(1 + x) loses relative precision for tiny x, which
// only bends the spacing of a nearly uniform schedule.)
fn cm_march_schedule_distance(u: f32, t_start: f32, t_end: f32, near_distance: f32) -> f32 {
    let v: f32 = cm_saturate(u);
    if (v <= 0.0) { return t_start; }
    if (v >= 1.0) { return t_end; }
    let base: f32 = t_start + near_distance;
    let ratio: f32 = (t_end - t_start) / base;
    // The ends' ratio near overflow (near_distance tiny): the difference of two logs (1e38, not
    // FLT_MAX: WGSL refuses the literal 3.4028235e38 as beyond f32).
    let L: f32 = select(log(t_end + near_distance) - log(base), log(1.0 + ratio), ratio < 1e38);
    let g: f32 = v * exp((v - 1.0) * L) * cm_one_minus_exp_neg_over_x(v * L) / cm_one_minus_exp_neg_over_x(L);
    // Within [t_start, t_end]: the sum rounds past t_end for u near 1.
    return clamp(t_start + (t_end - t_start) * g, t_start, t_end);
}

// Light steps placed quadratically: fraction u of a march of `length` (integration.hpp).
fn cm_light_march_distance(u: f32, length: f32) -> f32 {
    let v: f32 = cm_saturate(u);
    return length * (v * v);
}

// Sub-steps of optical depth <= 1 for a view step: ceil(tau) in [1, max_substeps]; NaN -> 1.
fn cm_refine_substeps(step_optical_depth: f32, max_substeps: i32) -> i32 {
    let most: i32 = max(max_substeps, 1);
    if (!(step_optical_depth > 1.0)) { return 1; }
    if (step_optical_depth >= f32(most)) { return most; }
    // Clamped after the conversion too: in [1, most] even where a compiler folds the NaN test.
    return clamp(i32(ceil(step_optical_depth)), 1, most);
}
