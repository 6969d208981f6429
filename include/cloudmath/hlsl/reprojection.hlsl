// cloudmath/hlsl/reprojection.hlsl: generated from the GLSL twin by tools/shader_translate; do not edit.
// Regenerate with: node tools/shader_translate/generate.mjs (shaders.generated_current fails while it is stale).
// HLSL for DXC and FXC (shader model 5 and 6), Unity and Unreal; parity with the C++ in
// docs/hlsl_parity.md. GLSL S(...) struct constructors are cm_make_S(...) here. The comments
// below are the GLSL twin's (file names made .hlsl).
//
// cloudmath/hlsl/reprojection.hlsl: GLSL twin of cloudmath/reprojection.hpp: the pixel of
// each 4 x 4 block a frame renders (Bayer order), the projection of a point into a previous
// camera, the bilinear footprint of a history lookup and the running-mean blend weight.
// Use: uvec2 o = cm_temporal_update_offset(frame);
//      vec3 uvz = cm_camera_project(p_prev, fwd, right, up, tan_half_fov, aspect);
//      vec4 fp = cm_texel_bilinear(uvz.xy, vec2(textureSize(history, 0)));  // texelFetch taps
#ifndef CM_REPROJECTION_HLSL
#define CM_REPROJECTION_HLSL

#include "core.hlsl"

// Rank of (x mod 4, y mod 4) in the 4 x 4 Bayer matrix: 4 [0 2; 3 1](low bits) + (high bits).
uint cm_bayer_index_4x4(uint x, uint y) {
    uint lo = (((x ^ y) & 1u) << 1u) | (y & 1u);
    uint hi = ((((x >> 1u) ^ (y >> 1u)) & 1u) << 1u) | ((y >> 1u) & 1u);
    return 4u * lo + hi;
}

// The pixel of each 4 x 4 block with Bayer rank frame mod 16.
uint2 cm_temporal_update_offset(uint frame) {
    uint i = frame & 15u;
    uint lo = i >> 2u;
    uint hi = i & 3u;
    return uint2(((lo >> 1u) ^ lo) & 1u, lo & 1u) + 2u * uint2(((hi >> 1u) ^ hi) & 1u, hi & 1u);
}

// (u, v, depth) of camera-relative p in the pinhole camera; (-1, -1, z) when z <= 0 or NaN.
float3 cm_camera_project(float3 p, float3 forward, float3 right, float3 up, float tan_half_fov, float aspect) {
    float z = dot(p, forward);
    if (!(z > 0.0)) return float3(-1.0, -1.0, z);
    float s = 0.5 / (z * tan_half_fov);
    return float3(0.5 + dot(p, right) * s / aspect, 0.5 + dot(p, up) * s, z);
}

// (x0, y0, fx, fy): texels x0..x0+1, y0..y0+1 weighted like GL_LINEAR, for texelFetch.
float4 cm_texel_bilinear(float2 uv, float2 size) {
    float2 scaled = uv * size;
    float2 st = scaled - 0.5;
    // Within 4 ulp of uv * size of an integer: that integer (a texel centre, uv rounded).
    float2 nearest = floor(st + 0.5);
    float2 tolerance = 4.0 * 1.1920929e-7 * max(abs(scaled), float2(1.0, 1.0));
    if (abs(st.x - nearest.x) <= tolerance.x) st.x = nearest.x;
    if (abs(st.y - nearest.y) <= tolerance.y) st.y = nearest.y;
    float2 base = floor(st);
    return float4(base, st - base);
}

// 1 / (min(history_samples, max_samples - 1) + 1); 1 for an empty (or NaN) history.
float cm_temporal_blend_weight(float history_samples, float max_samples) {
    float cap = max_samples > 1.0 ? max_samples - 1.0 : 0.0;
    float n = history_samples > 0.0 ? (history_samples < cap ? history_samples : cap) : 0.0;
    return 1.0 / (n + 1.0);
}

#endif // CM_REPROJECTION_HLSL
