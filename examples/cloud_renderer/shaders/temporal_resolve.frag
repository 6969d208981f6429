// temporal_resolve.frag: the second pass of the temporal scheme (cpu_renderer.hpp,
// cpu_temporal_renderer, is its C++ twin, line for line). clouds.frag with u_temporal_pass = 1
// has shaded one pixel of every 4 x 4 block into u_fresh (linear radiance, opacity) and
// u_fresh_depth; this pass writes the full-resolution image: the shaded pixels blended into
// their reprojected history (a running mean of at most u_max_samples), the other 15 taken
// from the history where their point was on the previous screen, and the block's new sample
// where it was not. Outputs the new history and the display colour.
//
// The host (gl_renderer.cpp) prepends `#version 410 core` and resolves the include below.

uniform vec2 u_resolution;                        // the full image
uniform vec3 u_forward, u_right, u_up;            // this frame's camera
uniform vec3 u_prev_forward, u_prev_right, u_prev_up;  // the previous frame's
uniform float u_tan_half_fov, u_prev_tan_half_fov;
uniform vec3 u_motion;            // where a point of this frame was, camera-relative, last frame: p + u_motion
uniform uvec2 u_update_offset;    // the pixel of each block shaded this frame
uniform int u_has_history;        // 0 on the first frame
uniform float u_max_samples;
uniform float u_exposure;
uniform uint u_frame;
uniform int u_dither;

uniform sampler2D u_fresh;         // quarter resolution: rgb linear radiance, a opacity
uniform sampler2D u_fresh_depth;   // quarter resolution: cloud depth (0: none)
uniform sampler2D u_history;       // full resolution: rgb linear radiance, a opacity
uniform sampler2D u_history_aux;   // full resolution: depth, samples in the running mean

layout(location = 0) out vec4 out_history;
layout(location = 1) out vec2 out_aux;
layout(location = 2) out vec4 out_display;

#include "cloudmath.glsl"

// GL_LINEAR's four taps of texture t for footprint fp = (x0, y0, fx, fy) (cm_texel_bilinear),
// clamped to texels [0, last] (cpu_renderer.cpp's bilinear_taps).
vec4 cr_bilinear(sampler2D t, vec4 fp, ivec2 last) {
    vec4 sum = vec4(0.0);
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx)
            sum += texelFetch(t, clamp(ivec2(fp.xy) + ivec2(dx, dy), ivec2(0), last), 0) *
                   ((dx != 0 ? fp.z : 1.0 - fp.z) * (dy != 0 ? fp.w : 1.0 - fp.w));
    return sum;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = ivec2(u_resolution);
    ivec2 block = p / 4;
    vec4 fresh = texelFetch(u_fresh, block, 0);
    float fresh_depth = texelFetch(u_fresh_depth, block, 0).r;
    bool is_fresh = uvec2(p & 3) == u_update_offset;
    float depth = fresh_depth > 0.0 ? fresh_depth : 1e7;

    // The pixel's ray (clouds.frag), at the block's depth, moved into the previous camera.
    vec2 ndc = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
    float aspect = u_resolution.x / u_resolution.y;
    vec3 dir = normalize(u_forward + u_right * (ndc.x * aspect * u_tan_half_fov) + u_up * (ndc.y * u_tan_half_fov));
    vec3 uvz = cm_camera_project(dir * depth + u_motion, u_prev_forward, u_prev_right, u_prev_up, u_prev_tan_half_fov, aspect);
    bool valid = u_has_history != 0 && uvz.z > 0.0 && uvz.x >= 0.0 && uvz.x <= 1.0 && uvz.y >= 0.0 && uvz.y <= 1.0;
    vec4 hc = vec4(0.0);
    vec2 ha = vec2(0.0);
    if (valid) {
        // Bilinear taps clamped to the image (a point on screen always has its texels).
        vec4 fp = cm_texel_bilinear(uvz.xy, u_resolution);
        hc = cr_bilinear(u_history, fp, size - 1);
        ha = cr_bilinear(u_history_aux, fp, size - 1).xy;
    }
    vec4 c;
    vec2 a;
    if (is_fresh) {
        float weight = valid ? cm_temporal_blend_weight(ha.y, u_max_samples) : 1.0;
        c = mix(hc, fresh, weight);
        a = vec2(fresh_depth, valid ? min(ha.y, u_max_samples - 1.0) + 1.0 : 1.0);
    } else if (valid) {
        c = hc;
        a = ha;
    } else {
        // No history (first frame, or the point was off the previous screen): the new
        // samples interpolated bilinearly (they sit at 4 (i, j) + offset) until this
        // pixel's turn; 0 samples, so its own sample replaces this one.
        vec2 q = (vec2(p) - vec2(u_update_offset)) * 0.25;
        vec2 q0 = floor(q);
        c = cr_bilinear(u_fresh, vec4(q0, q - q0), (size + 3) / 4 - 1);
        a = vec2(fresh_depth, 0.0);
    }
    out_history = c;
    out_aux = a;
    // Display: clouds.frag's tonemap and dither.
    vec3 shown = pow(vec3(1.0) - exp(-c.rgb * u_exposure), vec3(1.0 / 2.2));
    if (u_dither != 0) {
        uint index = uint(p.x) + uint(p.y) * 8192u;
        shown += cm_triangular_dither(cm_noise_hash(cm_noise_hash(index) + u_frame * 0x9e3779b9u)) * (1.0 / 255.0);
    }
    out_display = vec4(shown, c.a);
}
