// cloudmath/glsl/reprojection.glsl: GLSL twin of cloudmath/reprojection.hpp: the pixel of
// each 4 x 4 block a frame renders (Bayer order), the projection of a point into a previous
// camera, the bilinear footprint of a history lookup and the running-mean blend weight.
// Use: uvec2 o = cm_temporal_update_offset(frame);
//      vec3 uvz = cm_camera_project(p_prev, fwd, right, up, tan_half_fov, aspect);
//      vec4 fp = cm_texel_bilinear(uvz.xy, vec2(textureSize(history, 0)));  // texelFetch taps
#ifndef CM_REPROJECTION_GLSL
#define CM_REPROJECTION_GLSL

#include "core.glsl"

// Rank of (x mod 4, y mod 4) in the 4 x 4 Bayer matrix: 4 [0 2; 3 1](low bits) + (high bits).
uint cm_bayer_index_4x4(uint x, uint y) {
    uint lo = (((x ^ y) & 1u) << 1u) | (y & 1u);
    uint hi = ((((x >> 1u) ^ (y >> 1u)) & 1u) << 1u) | ((y >> 1u) & 1u);
    return 4u * lo + hi;
}

// The pixel of each 4 x 4 block with Bayer rank frame mod 16.
uvec2 cm_temporal_update_offset(uint frame) {
    uint i = frame & 15u;
    uint lo = i >> 2u, hi = i & 3u;
    return uvec2(((lo >> 1u) ^ lo) & 1u, lo & 1u) + 2u * uvec2(((hi >> 1u) ^ hi) & 1u, hi & 1u);
}

// (u, v, depth) of camera-relative p in the pinhole camera; (-1, -1, z) when z <= 0 or NaN.
vec3 cm_camera_project(vec3 p, vec3 forward, vec3 right, vec3 up, float tan_half_fov, float aspect) {
    float z = dot(p, forward);
    if (!(z > 0.0)) return vec3(-1.0, -1.0, z);
    float s = 0.5 / (z * tan_half_fov);
    return vec3(0.5 + dot(p, right) * s / aspect, 0.5 + dot(p, up) * s, z);
}

// (x0, y0, fx, fy): texels x0..x0+1, y0..y0+1 weighted like GL_LINEAR, for texelFetch.
vec4 cm_texel_bilinear(vec2 uv, vec2 size) {
    vec2 scaled = uv * size;
    vec2 st = scaled - 0.5;
    // Within 4 ulp of uv * size of an integer: that integer (a texel centre, uv rounded).
    vec2 nearest = floor(st + 0.5);
    vec2 tolerance = 4.0 * 1.1920929e-7 * max(abs(scaled), vec2(1.0));
    if (abs(st.x - nearest.x) <= tolerance.x) st.x = nearest.x;
    if (abs(st.y - nearest.y) <= tolerance.y) st.y = nearest.y;
    vec2 base = floor(st);
    return vec4(base, st - base);
}

// 1 / (min(history_samples, max_samples - 1) + 1); 1 for an empty (or NaN) history.
float cm_temporal_blend_weight(float history_samples, float max_samples) {
    float cap = max_samples > 1.0 ? max_samples - 1.0 : 0.0;
    float n = history_samples > 0.0 ? (history_samples < cap ? history_samples : cap) : 0.0;
    return 1.0 / (n + 1.0);
}

#endif  // CM_REPROJECTION_GLSL
