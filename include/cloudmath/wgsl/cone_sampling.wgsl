// cloudmath/wgsl/cone_sampling.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/cone_sampling.glsl: GLSL twin of cloudmath/cone_sampling.hpp, Schneider's
// cone of light samples toward the sun (near samples at (i + 1/2) step_length, offset across
// the light by a Vogel spiral scaled with distance; the last one far away on the axis).
//
// Configuration (#define before the include):
//   CM_CONE_EXTINCTION  name of a user function `float f(vec3 p, int i)` giving the
//                       extinction (1/m) at sample i; when defined, cm_cone_optical_depth()
//                       is available.
//   CM_CONE_SAMPLES     when defined, cm_cone_optical_depth uses this compile-time sample
//                       count (the driver can unroll the loop) in place of cfg.sample_count
//                       (default: not defined; cfg.sample_count is used).

struct CmConeLightConfig {
    sample_count: i32, // all samples, the far one included
    step_length: f32, // length of each near segment
    cone_spread: f32, // cone radius per unit distance (tan of the half-angle)
    far_distance: f32, // distance of the far sample; <= 0: no far sample
    far_segment_length: f32, // optical-depth weight of the far sample
}

fn cmi_cone_has_far(cfg: CmConeLightConfig) -> bool { return cfg.far_distance > 0.0 && cfg.sample_count > 0; }
fn cmi_cone_near_count(cfg: CmConeLightConfig) -> i32 {
    return max(select(cfg.sample_count, cfg.sample_count - 1, cmi_cone_has_far(cfg)), 0);
}

// Point i of n of the Vogel spiral in the unit disc; i modulo n, n < 1 treated as 1; every
// int i and n (GLSL leaves % of negative operands undefined, hence the explicit wrap, which
// never overflows: -(i + 1) >= 0 for every negative i).
fn cm_cone_kernel_offset(i: i32, n: i32) -> vec2f {
    let count: i32 = max(n, 1);
    let k: i32 = select(count - 1 - (-(i + 1)) % count, i % count, i >= 0);
    let radius: f32 = sqrt((f32(k) + 0.5) / f32(count));
    let sc: vec2f = cmi_sin_cos(f32(k) * 2.39996322972865); // the golden angle, k times
    return radius * vec2f(sc.y, sc.x);
}

fn cm_cone_sample_distance(cfg: CmConeLightConfig, i: i32) -> f32 {
    let n_near: i32 = cmi_cone_near_count(cfg);
    if (cmi_cone_has_far(cfg) && i >= n_near) { return cfg.far_distance; }
    let k: i32 = clamp(i, 0, max(n_near - 1, 0));
    return (f32(k) + 0.5) * cfg.step_length;
}

fn cm_cone_sample_length(cfg: CmConeLightConfig, i: i32) -> f32 {
    return select(cfg.step_length, cfg.far_segment_length, cmi_cone_has_far(cfg) && i >= cmi_cone_near_count(cfg));
}

// Orthonormal u, v across the unit vector n (Duff et al., JCGT 2017).
fn cmi_orthonormal_basis(n: vec3f, u: ptr<function, vec3f>, v: ptr<function, vec3f>) {
    let s: f32 = select(-1.0, 1.0, n.z >= 0.0);
    let a: f32 = -1.0 / (s + n.z);
    let b: f32 = n.x * n.y * a;
    (*u) = vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    (*v) = vec3f(b, s + n.y * n.y * a, -n.y);
}

fn cm_cone_sample_position(origin: vec3f, light_dir: vec3f, cfg: CmConeLightConfig, i: i32) -> vec3f {
    let d: f32 = cm_cone_sample_distance(cfg, i);
    let n_near: i32 = cmi_cone_near_count(cfg);
    if (cmi_cone_has_far(cfg) && i >= n_near) { return origin + light_dir * d; }
    var u: vec3f;
    var v: vec3f;
    cmi_orthonormal_basis(light_dir, &u, &v);
    let k: vec2f = cm_cone_kernel_offset(i, n_near);
    return origin + light_dir * d + (u * k.x + v * k.y) * (cfg.cone_spread * d);
}
