// cloudmath/reprojection.hpp: temporal reprojection for a ray march rendered at reduced cost:
// which pixel of each 4 x 4 block a frame renders, where a point of this frame was on the
// previous frame's screen, the bilinear footprint of a history lookup there, and the weight
// of a new sample in a capped running mean.
//
// Use:      #include <cloudmath/reprojection.hpp>
//           // Frame f renders one pixel per 4 x 4 block, at offset o (16 frames cover all):
//           glm::uvec2 o = cloudmath::temporal_update_offset(f);
//           // Every other pixel takes the history where its point was last frame:
//           glm::vec3 uvz = cloudmath::camera_project(p_prev, fwd, right, up, tan_half_fov, aspect);
//           glm::vec4 fp = cloudmath::texel_bilinear(glm::vec2(uvz), glm::vec2(width, height));
//           // A rendered pixel joins its history as a running mean of at most 8 samples:
//           colour = mix(history, fresh, cloudmath::temporal_blend_weight(samples, 8.0f));
// Scheme:   Horizon Zero Dawn's clouds (Schneider 2015, "The real-time volumetric cloudscapes
//           of Horizon Zero Dawn", SIGGRAPH Advances): a quarter-resolution pass updates 1 of
//           16 pixels per frame, the rest are reprojected from a full-resolution history by
//           the camera's motion. The order within a block is the 4 x 4 Bayer matrix (Bayer
//           1973), so consecutive frames land far apart and any 4 consecutive frames cover
//           each 2 x 2 quarter of the block once.
// Camera:   the pinhole of `camera_project`: a ray through normalised screen point (u, v) in
//           [0, 1]^2 has direction forward + right (2u - 1) aspect tan_half_fov
//           + up (2v - 1) tan_half_fov (v = 0 the bottom row), the camera at the origin.
// GLSL twin: cloudmath/glsl/reprojection.glsl.
#ifndef CLOUDMATH_REPROJECTION_HPP
#define CLOUDMATH_REPROJECTION_HPP

#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace cloudmath {

// bayer_index_4x4(x, y): the rank 0..15 of pixel (x mod 4, y mod 4) in the 4 x 4 Bayer
// matrix (rows y = 0..3: 0 8 2 10 / 12 4 14 6 / 3 11 1 9 / 15 7 13 5): the 2 x 2 matrix
// [0 2; 3 1] of the low bits, times 4, plus the same of the high bits.
[[nodiscard]] constexpr std::uint32_t bayer_index_4x4(std::uint32_t x, std::uint32_t y) noexcept {
    const auto m2 = [](std::uint32_t a, std::uint32_t b) { return (((a ^ b) & 1U) << 1U) | (b & 1U); };
    return 4U * m2(x & 1U, y & 1U) + m2((x >> 1U) & 1U, (y >> 1U) & 1U);
}

// temporal_update_offset(frame): the pixel (x, y) in [0, 4)^2 of every 4 x 4 block that frame
// renders: the one whose bayer_index_4x4 is frame mod 16. Frames 16 k .. 16 k + 15 render
// each pixel of the screen exactly once.
[[nodiscard]] constexpr glm::uvec2 temporal_update_offset(std::uint32_t frame) noexcept {
    const std::uint32_t i = frame & 15U;
    // Inverse of [0 2; 3 1]: rank m -> (x, y) = ((m >> 1) ^ (m & 1), m & 1).
    const auto inv = [](std::uint32_t m) { return glm::uvec2(((m >> 1U) ^ m) & 1U, m & 1U); };
    return inv(i >> 2U) + inv(i & 3U) * 2U;
}

// camera_project(p, forward, right, up, tan_half_fov, aspect): the normalised screen point
// (u, v) where the camera-relative point p appears, and its depth z = dot(p, forward): the
// inverse of the pinhole ray above. forward, right, up: an orthonormal camera basis;
// aspect = width / height. On screen when z > 0 and u, v in [0, 1]. A point on or behind
// the camera plane (z <= 0, or NaN) gives (-1, -1, z): off screen, never a mirrored image.
template <class T>
[[nodiscard]] inline glm::vec<3, T> camera_project(const glm::vec<3, T>& p, const glm::vec<3, T>& forward,
                                                   const glm::vec<3, T>& right, const glm::vec<3, T>& up, T tan_half_fov,
                                                   T aspect) noexcept {
    const T z = glm::dot(p, forward);
    if (!(z > T(0))) return glm::vec<3, T>(T(-1), T(-1), z);
    const T s = T(0.5) / (z * tan_half_fov);  // from view-plane offsets to half-screens
    return glm::vec<3, T>(T(0.5) + glm::dot(p, right) * s / aspect, T(0.5) + glm::dot(p, up) * s, z);
}

// texel_bilinear(uv, size): the bilinear footprint of a lookup at normalised point uv in a
// texture of size (width, height) texels whose centres are at (i + 1/2) / size:
// (x0, y0, fx, fy) where texels (x0, y0) .. (x0 + 1, y0 + 1) are weighted (1 - fx, fx) by
// (1 - fy, fy). What GL_LINEAR computes, as numbers a shader and the CPU share (texelFetch
// with explicit weights: no 8-bit weight quantisation, and the caller decides what to do
// at the border). All four texels exist when 0 <= x0 and x0 + 1 < width (same for y): the
// caller's test for "history available". At a texel centre, uv = (i + 1/2) / size as a
// caller computes it, x0 = i and fx = 0 exactly: uv carries a rounding, so uv * size - 1/2
// lands a few ulp either side of i (below it in about 4% of (i, width) pairs, which gave
// x0 = i - 1 and fx = 1, and made column 0's own centre fail the border test); values within
// 4 ulp of uv * size of an integer are taken as that integer.
template <class T>
[[nodiscard]] inline glm::vec<4, T> texel_bilinear(const glm::vec<2, T>& uv, const glm::vec<2, T>& size) noexcept {
    const glm::vec<2, T> scaled = uv * size;
    glm::vec<2, T> st = scaled - T(0.5);
    for (int c = 0; c < 2; ++c) {
        const T nearest = std::floor(st[c] + T(0.5));
        const T magnitude = std::fabs(scaled[c]);
        const T tolerance = T(4) * std::numeric_limits<T>::epsilon() * (magnitude > T(1) ? magnitude : T(1));
        if (std::fabs(st[c] - nearest) <= tolerance) st[c] = nearest;
    }
    const glm::vec<2, T> base(std::floor(st.x), std::floor(st.y));
    return glm::vec<4, T>(base.x, base.y, st.x - base.x, st.y - base.y);
}

// temporal_blend_weight(history_samples, max_samples): the weight of a new sample against a
// history that averages history_samples of them, 1 / (min(history_samples, max_samples - 1)
// + 1): a running mean (each sample weighs the same) up to max_samples, then an exponential
// average with weight 1 / max_samples, which forgets stale light. 1 for an empty history
// (history_samples <= 0, or NaN); max_samples < 1 acts as 1 (no history).
template <class T>
[[nodiscard]] inline T temporal_blend_weight(T history_samples, T max_samples) noexcept {
    const T cap = max_samples > T(1) ? max_samples - T(1) : T(0);
    const T n = history_samples > T(0) ? (history_samples < cap ? history_samples : cap) : T(0);
    return T(1) / (n + T(1));
}

}  // namespace cloudmath

#endif  // CLOUDMATH_REPROJECTION_HPP
