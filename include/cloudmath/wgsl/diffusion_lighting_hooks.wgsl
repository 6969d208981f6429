// cloudmath/wgsl/diffusion_lighting_hooks.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, phase.wgsl, diffusion_lighting_models.wgsl, diffusion_lighting.wgsl.
// and your function(s):
//   fn cm_diffusion_phase(mu: f32, scale: f32) -> f32  (GLSL: #define CM_DIFFUSION_PHASE)
//
fn cm_diffusion_scattering_with(tau_sun: f32, tau_behind: f32, tau_view: f32, mu: f32, g: f32, albedo: f32, m: CmDiffusionModel) -> f32 {
    let mc: f32 = clamp(mu, -1.0, 1.0);
    return cmi_diffusion_scattering_phases(tau_sun, tau_behind, tau_view, mu, g, albedo, m, cm_diffusion_phase(mc, 1.0), cm_diffusion_phase(mc, 0.5), cm_diffusion_phase(mc, 0.8));
}
