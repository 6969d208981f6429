// cloudmath/wgsl/cone_sampling_hooks.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl, cone_sampling.wgsl.
// and your function(s):
//   fn cm_cone_extinction(p: vec3f, i: i32) -> f32  (GLSL: #define CM_CONE_EXTINCTION)
//
// Optical depth toward the light: sum of CM_CONE_EXTINCTION(p_i, i) * length_i.
fn cm_cone_optical_depth(origin: vec3f, light_dir: vec3f, cfg: CmConeLightConfig) -> f32 {
    var tau: f32 = 0.0;
    let count: i32 = cfg.sample_count;
    for (var i: i32 = 0; i < count; i++) {
        let p: vec3f = cm_cone_sample_position(origin, light_dir, cfg, i);
        tau += cm_cone_extinction(p, i) * cm_cone_sample_length(cfg, i);
    }
    return tau;
}
