// cloudmath/wgsl/reprojection.wgsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// Parity with the C++ in docs/wgsl_parity.md. WGSL has no overloads: the first GLSL overload
// keeps the name, later ones add their parameter types (cm_saturate_v3, docs/shading_languages.md).
// The comments below are the GLSL twin's: docs/shading_languages.md says what its #include,
// #define configuration and overloads become in WGSL.
// Requires, before this file: core.wgsl.
//
// cloudmath/glsl/reprojection.glsl: GLSL twin of cloudmath/reprojection.hpp: the pixel of
// each 4 x 4 block a frame renders (Bayer order), the projection of a point into a previous
// camera, the bilinear footprint of a history lookup and the running-mean blend weight.
// Use: uvec2 o = cm_temporal_update_offset(frame);
//      vec3 uvz = cm_camera_project(p_prev, fwd, right, up, tan_half_fov, aspect);
//      vec4 fp = cm_texel_bilinear(uvz.xy, vec2(textureSize(history, 0)));  // texelFetch taps

// Rank of (x mod 4, y mod 4) in the 4 x 4 Bayer matrix: 4 [0 2; 3 1](low bits) + (high bits).
fn cm_bayer_index_4x4(x: u32, y: u32) -> u32 {
    let lo: u32 = (((x ^ y) & 1u) << 1u) | (y & 1u);
    let hi: u32 = ((((x >> 1u) ^ (y >> 1u)) & 1u) << 1u) | ((y >> 1u) & 1u);
    return 4u * lo + hi;
}

// The pixel of each 4 x 4 block with Bayer rank frame mod 16.
fn cm_temporal_update_offset(frame: u32) -> vec2u {
    let i: u32 = frame & 15u;
    let lo: u32 = i >> 2u;
    let hi: u32 = i & 3u;
    return vec2u(((lo >> 1u) ^ lo) & 1u, lo & 1u) + 2u * vec2u(((hi >> 1u) ^ hi) & 1u, hi & 1u);
}

// (u, v, depth) of camera-relative p in the pinhole camera; (-1, -1, z) when z <= 0 or NaN.
fn cm_camera_project(p: vec3f, forward: vec3f, right: vec3f, up: vec3f, tan_half_fov: f32, aspect: f32) -> vec3f {
    let z: f32 = dot(p, forward);
    if (!(z > 0.0)) { return vec3f(-1.0, -1.0, z); }
    let s: f32 = 0.5 / (z * tan_half_fov);
    return vec3f(0.5 + dot(p, right) * s / aspect, 0.5 + dot(p, up) * s, z);
}

// (x0, y0, fx, fy): texels x0..x0+1, y0..y0+1 weighted like GL_LINEAR, for texelFetch.
fn cm_texel_bilinear(uv: vec2f, size: vec2f) -> vec4f {
    let scaled: vec2f = uv * size;
    var st: vec2f = scaled - 0.5;
    // Within 4 ulp of uv * size of an integer: that integer (a texel centre, uv rounded).
    let nearest: vec2f = floor(st + 0.5);
    let tolerance: vec2f = 4.0 * 1.1920929e-7 * max(abs(scaled), vec2f(1.0));
    if (abs(st.x - nearest.x) <= tolerance.x) { st.x = nearest.x; }
    if (abs(st.y - nearest.y) <= tolerance.y) { st.y = nearest.y; }
    let base: vec2f = floor(st);
    return vec4f(base, st - base);
}

// 1 / (min(history_samples, max_samples - 1) + 1); 1 for an empty (or NaN) history.
fn cm_temporal_blend_weight(history_samples: f32, max_samples: f32) -> f32 {
    let cap: f32 = select(0.0, max_samples - 1.0, max_samples > 1.0);
    let n: f32 = select(0.0, (select(cap, history_samples, history_samples < cap)), history_samples > 0.0);
    return 1.0 / (n + 1.0);
}
