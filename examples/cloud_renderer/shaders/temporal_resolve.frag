// temporal_resolve.frag: the second pass of the temporal scheme (cpu_renderer.hpp,
// cpu_temporal_renderer, is its C++ twin, line for line). clouds.frag with u_pass = 1 has
// shaded the cloud layer at one pixel of every 4 x 4 block into u_fresh (its own linear
// radiance, opacity) and u_fresh_depth, and with u_pass = 3 what lies behind the layer at
// every pixel into u_background. This pass writes the full-resolution layer: the shaded
// pixels blended into their reprojected history (a running mean of at most u_max_samples),
// the other 15 taken from the history where their point was on the previous screen and the
// history there is theirs, and filled from the block's new samples where it is not. Outputs
// the new history: the full-resolution layer, which composite.frag lays over the background.
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
uniform float u_tolerance;        // scene.hpp's temporal_reprojection_tolerance (pixels)
uniform float u_fill_blend;       // ... temporal_fill_blend

uniform sampler2D u_fresh;         // quarter resolution: rgb linear radiance, a opacity
uniform sampler2D u_fresh_depth;   // quarter resolution: cloud depth (0: none)
uniform sampler2D u_history;       // full resolution: rgb linear radiance, a opacity
uniform sampler2D u_history_aux;   // full resolution: depth, samples in the running mean
uniform sampler2D u_background;    // full resolution: rgb what lies behind the layer, a 1 where the ray meets the band
uniform sampler2D u_scene_depth;   // full resolution: the scene's distance (the terrain's; 0: none)

layout(location = 0) out vec4 out_history;
layout(location = 1) out vec2 out_aux;

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

// Catmull-Rom around footprint fp, clamped to texels [0, last], the result clamped to the
// range of the four bilinear taps (no ringing): a sharper reconstruction than GL_LINEAR,
// which, repeated every frame on a moving history, blurs it. Five GL_LINEAR reads instead of
// 16 texel reads (the form of Jimenez, "Filmic SMAA", SIGGRAPH 2016): along each axis the two
// middle taps, whose weights are both positive, are one linear read between them at
// w2 / (w1 + w2); the four corner taps (each weight at most 0.0055) are dropped and the rest
// renormalised. t must be filtered GL_LINEAR with GL_CLAMP_TO_EDGE (the clamp of the texel
// indices). cpu_renderer.cpp's catmull_rom_clamped is its twin.
vec4 cr_catmull_rom(sampler2D t, vec4 fp, ivec2 last) {
    vec2 f = fp.zw;
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2;
    // Texel-space positions (texel i's centre at i + 0.5), as uv.
    vec2 texel = 1.0 / vec2(last + 1);
    vec2 p0 = (fp.xy - 0.5) * texel, p12 = (fp.xy + 0.5 + w2 / w12) * texel, p3 = (fp.xy + 2.5) * texel;
    float k0 = w12.x * w0.y, k1 = w0.x * w12.y, k2 = w12.x * w12.y, k3 = w3.x * w12.y, k4 = w12.x * w3.y;
    vec4 sum = texture(t, vec2(p12.x, p0.y)) * k0 + texture(t, vec2(p0.x, p12.y)) * k1 + texture(t, p12) * k2 +
               texture(t, vec2(p3.x, p12.y)) * k3 + texture(t, vec2(p12.x, p3.y)) * k4;
    sum /= k0 + k1 + k2 + k3 + k4;
    vec4 lo = vec4(1e30), hi = vec4(-1e30);
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            vec4 texel_value = texelFetch(t, clamp(ivec2(fp.xy) + ivec2(dx, dy), ivec2(0), last), 0);
            lo = min(lo, texel_value);
            hi = max(hi, texel_value);
        }
    return clamp(sum, lo, hi);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = ivec2(u_resolution);
    ivec2 block = p / 4;
    vec4 fresh = texelFetch(u_fresh, block, 0);
    float fresh_depth = texelFetch(u_fresh_depth, block, 0).r;
    bool is_fresh = uvec2(p & 3) == u_update_offset;
    float depth = fresh_depth > 0.0 ? fresh_depth : 1e7;
    vec4 behind = texelFetch(u_background, p, 0);

    // The pixel's ray (clouds.frag), at the block's depth, moved into the previous camera.
    vec2 ndc = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
    float aspect = u_resolution.x / u_resolution.y;
    vec3 dir = normalize(u_forward + u_right * (ndc.x * aspect * u_tan_half_fov) + u_up * (ndc.y * u_tan_half_fov));
    vec3 uvz = cm_camera_project(dir * depth + u_motion, u_prev_forward, u_prev_right, u_prev_up, u_prev_tan_half_fov, aspect);
    bool valid = u_has_history != 0 && uvz.z > 0.0 && uvz.x >= 0.0 && uvz.x <= 1.0 && uvz.y >= 0.0 && uvz.y <= 1.0;
    if (valid) {
        // The history there must be this pixel's: carried by its own motion (its nearest
        // texel's depth, the sky's at 1e7), it lands within u_tolerance of this pixel; else a
        // cloud has moved in or out, and the new samples fill it.
        ivec2 nearest = clamp(ivec2(uvz.xy * u_resolution), ivec2(0), size - 1);
        float stored = texelFetch(u_history_aux, nearest, 0).r;
        vec2 was_ndc = uvz.xy * 2.0 - 1.0;
        vec3 was = normalize(u_prev_forward + u_prev_right * (was_ndc.x * aspect * u_prev_tan_half_fov) +
                             u_prev_up * (was_ndc.y * u_prev_tan_half_fov));
        // Under a metre is the sky's 0 blended by bilinear taps (a depth mixed across a cloud's
        // edge): the sky's infinity, not a point at the camera.
        vec3 now = cm_camera_project(was * (stored >= 1.0 ? stored : 1e7) - u_motion, u_forward, u_right, u_up, u_tan_half_fov, aspect);
        vec2 miss = now.xy * u_resolution - (vec2(p) + 0.5);
        valid = now.z > 0.0 && dot(miss, miss) <= u_tolerance * u_tolerance;
        // ... and lie in front of the scene there: a cloud the terrain now hides is not this
        // pixel's (the composite's use of the scene's depth; the march itself ends there).
        float scene = texelFetch(u_scene_depth, p, 0).r;
        valid = valid && !(scene > 0.0 && stored > scene);
    }
    vec4 hc = vec4(0.0);
    vec2 ha = vec2(0.0);
    if (valid) {
        // Catmull-Rom for the layer, bilinear for the depth and the sample count.
        vec4 fp = cm_texel_bilinear(uvz.xy, u_resolution);
        hc = cr_catmull_rom(u_history, fp, size - 1);
        ha = cr_bilinear(u_history_aux, fp, size - 1).xy;
    }
    vec4 c;
    vec2 a;
    if (is_fresh) {
        float weight = valid ? cm_temporal_blend_weight(ha.y, u_max_samples) : 1.0;
        c = mix(hc, fresh, weight);
        a = vec2(fresh_depth, valid ? min(ha.y, u_max_samples - 1.0) + 1.0 : 1.0);
    } else if (valid && ha.y >= 0.5) {
        c = hc;
        a = ha;
    } else {
        // The fill: this frame's new samples (at 4 (i, j) + offset) interpolated likewise.
        // Not shaded yet (valid, 0 samples: filled): the fills of successive frames, each from
        // other pixels of the block, averaged until this pixel's own turn replaces them. No
        // history (first frame, off the previous screen, or not this pixel's): the fill alone.
        // One copy of its taps for both cases: on SIMD hardware (llvmpipe too) a branch's
        // body is paid by the whole group, so two copies cost twice.
        vec2 q = (vec2(p) - vec2(u_update_offset)) * 0.25;
        vec4 fill = cr_catmull_rom(u_fresh, vec4(floor(q), q - floor(q)), (size + 3) / 4 - 1);
        c = valid ? mix(hc, fill, u_fill_blend) : fill;
        a = vec2(fresh_depth, 0.0);
    }
    if (behind.a == 0.0) c = vec4(0.0);  // a ray that meets no cloud carries none
    out_history = c;
    out_aux = a;
}
