// cloudmath/noise.hpp: tileable cloud noise: improved Perlin (2D, 3D, with analytic
// derivatives), Worley, their fBm, Nubis's Worley fBm and Perlin-Worley, and curl noise.
//
// Use:      #include <cloudmath/noise.hpp>
//           float n = cloudmath::perlin_noise(glm::vec3(x, y, z), 8);   // 8 cells per tile
// Domain:   p is in lattice cells. `period` (an int >= 1, cells per tile; smaller values are
//           treated as 1) makes every function periodic: f(p + period e_i) == f(p), up to the
//           rounding of p itself. fBm octave i uses frequency lacunarity^i and period
//           period * lacunarity^i, so an integer lacunarity keeps the tiling.
// Seeds:    every function takes an optional 32-bit seed; different seeds give independent
//           fields. fBm octaves use seed + i.
// Hashing:  unsigned 32-bit integer arithmetic only (wrap-around multiply, xor, shift), so
//           GLSL 3.30 / ES 3.00 reproduce every hash bit for bit (cloudmath/glsl/noise.glsl),
//           and no signed arithmetic can overflow: lattice coordinates are wrapped into
//           [0, period) before they are hashed. Hash to float uses the top 24 bits, which
//           float represents exactly on both sides.
// Ranges:   perlin_noise in [-1, 1] (scaled so the measured extremes are +-1, then clamped
//           against rounding), worley_noise, worley_fbm, worley_fbm_nubis and
//           perlin_worley in [0, 1], perlin_fbm in [-1, 1] (normalised by the sum of the
//           octave amplitudes).
// Sources:  Perlin, "Improving noise", SIGGRAPH 2002 (quintic fade, 12 edge gradients);
//           Worley, "A cellular texture basis function", SIGGRAPH 1996; Schneider 2015/2017
//           (cloud Worley 1 - F1/sqrt(3), Nubis fBm weights 0.625/0.25/0.125, Perlin-Worley);
//           Bridson, Hourihan & Nordenstam, "Curl-noise for procedural fluid flow", 2007.
// GLSL twin: cloudmath/glsl/noise.glsl.
#ifndef CLOUDMATH_NOISE_HPP
#define CLOUDMATH_NOISE_HPP

#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core.hpp"

namespace cloudmath {

// ---------------------------------------------------------------------------------------
// Hashing.

// A 32-bit integer mixer (xor-shift / multiply rounds with constants from Wellons's hash
// prospector, "lowbias32"): every input bit affects every output bit. Bijective on uint32.
[[nodiscard]] constexpr std::uint32_t noise_hash(std::uint32_t x) noexcept {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// Hash of a lattice cell and a seed (coordinates already wrapped to [0, period)).
[[nodiscard]] constexpr std::uint32_t noise_hash(std::uint32_t x, std::uint32_t y, std::uint32_t z,
                                                 std::uint32_t seed) noexcept {
    return noise_hash(x + noise_hash(y + noise_hash(z + noise_hash(seed))));
}

// ---------------------------------------------------------------------------------------
// Low-discrepancy sequences for per-frame jitter (Roberts 2018, "The unreasonable
// effectiveness of quasirandom sequences"): x_n = fract(1/2 + n alpha). Computed in 32-bit
// fixed point (alpha rounded to 2^-32; uint arithmetic wraps as fract does), so C++ and
// GLSL give the same bits for every n, with no float drift for large frame counts. Values
// are the top 24 bits over 2^24: in [0, 1), exact in float.

// R1: alpha = golden ratio - 1 = 0.6180339887 (0x9e3779b9 / 2^32). Any N consecutive terms
// of the exact sequence split [0, 1) into gaps of at most 3 sizes (the three-distance
// theorem); the 24-bit outputs, each truncated by up to 2^-24, show up to 6 sizes, each
// within 2^-24 of one of the 3.
template <class T = float>
[[nodiscard]] constexpr T low_discrepancy_r1(std::uint32_t n) noexcept {
    return T((0x80000000U + n * 0x9e3779b9U) >> 8U) * T(1.0 / 16777216.0);
}

// R2: alpha = (1/g, 1/g^2) with g = 1.3247179572 the plastic number (0xc13fa9a9 and
// 0x91e10da6 over 2^32): the 2D sequence with the best known packing for any prefix.
template <class T = float>
[[nodiscard]] constexpr glm::vec<2, T> low_discrepancy_r2(std::uint32_t n) noexcept {
    return glm::vec<2, T>(T((0x80000000U + n * 0xc13fa9a9U) >> 8U), T((0x80000000U + n * 0x91e10da6U) >> 8U)) *
           T(1.0 / 16777216.0);
}

// frame_jitter(pixel_hash, frame): a ray-march start offset in [0, 1) for one pixel and
// frame: the pixel's hash (white noise across pixels, so no pattern on screen) advanced by
// R1 each frame (so the frames of one pixel fill [0, 1) evenly: the temporal average of N
// frames converges as 1/N for a smooth integrand, not 1/sqrt(N)). Frame 0 is the hash's
// own top 24 bits over 2^24.
template <class T = float>
[[nodiscard]] constexpr T frame_jitter(std::uint32_t pixel_hash, std::uint32_t frame) noexcept {
    return T((pixel_hash + frame * 0x9e3779b9U) >> 8U) * T(1.0 / 16777216.0);
}

// sample_jitter(pixel_hash, frame, index): an offset in [0, 1) for the index-th sample of a
// pixel's frame (a light march's start, say), decorrelated from the pixel's other samples:
// frame_jitter of the hash advanced by index times the plastic number's R2 constant. For a
// fixed index the frames follow R1 (as frame_jitter: the temporal average converges as 1/N);
// within a frame the indices follow an R-sequence, so consecutive samples do not share one
// offset (which would make their errors add up instead of cancel). Index 0 gives
// frame_jitter(pixel_hash, frame). 32-bit integer arithmetic: bit-identical in GLSL.
template <class T = float>
[[nodiscard]] constexpr T sample_jitter(std::uint32_t pixel_hash, std::uint32_t frame, std::uint32_t index) noexcept {
    return frame_jitter<T>(pixel_hash + index * 0xc13fa9a9U, frame);
}

// triangular_dither(h): a value in (-1, 1) with the triangular distribution (the difference
// of two uniforms from the hash's low and high 16 bits, each (k + 1/2) / 65536), to add in
// units of the output's last bit before quantising: colour + triangular_dither(h) / 255
// before an 8-bit store. Triangular noise of this width makes the quantisation error's mean
// and variance independent of the signal (no banding in slow gradients such as the sky), at
// an rms of 1/sqrt(6) of a step (Lipshitz, Wannamaker and Vanderkooy 1992). Exact in float.
template <class T = float>
[[nodiscard]] constexpr T triangular_dither(std::uint32_t h) noexcept {
    return (T(h & 0xffffU) - T(h >> 16U)) * T(1.0 / 65536.0);
}

// hash_to_unit(h): the top 24 bits of a hash (noise_hash) as a number in [0, 1): k / 2^24,
// exact in float, identical in double and bit-identical in GLSL (cm_hash_to_unit). The
// worley cells place their feature points with it; use it for any random number a shader
// and the host must agree on.
template <class T = float>
[[nodiscard]] constexpr T hash_to_unit(std::uint32_t h) noexcept {
    return T(h >> 8) * T(1.0 / 16777216.0);
}

namespace detail {

// i modulo n in [0, n) for any int i and n >= 1, using % on non-negative operands only
// (GLSL leaves % of negative operands undefined).
constexpr int wrap_cell(int i, int n) noexcept {
    return i >= 0 ? i % n : n - 1 - ((-(i + 1)) % n);
}

constexpr int clamp_period(int period) noexcept { return period < 1 ? 1 : period; }

// floor(x) as an int, clamped to +-2^30 so the conversion (and cell + 1) cannot overflow:
// coordinates beyond a billion cells are outside the documented domain, and give a
// constant lattice cell instead of undefined behaviour; a NaN gives the cell -2^30 (its
// fraction, NaN, then makes the noise NaN).
template <class T>
inline int floor_to_cell(T x) noexcept {
    return floor_to_int(x, -1073741824, 1073741824);
}

// period * factor, saturated at 2^30 (an fBm with absurd octave counts keeps a valid period;
// tiling then holds only up to that octave).
constexpr int grow_period(int period, int factor) noexcept {
    return period > 1073741824 / factor ? 1073741824 : period * factor;
}


// Quintic fade 6t^5 - 15t^4 + 10t^3 and its derivative 30t^2 (t - 1)^2 (Perlin 2002).
template <class T>
constexpr T fade(T t) noexcept {
    return t * t * t * (t * (t * T(6) - T(15)) + T(10));
}
template <class T>
constexpr T fade_derivative(T t) noexcept {
    return T(30) * t * t * (t - T(1)) * (t - T(1));
}

// Improved-noise gradient for a hash: the 12 cube-edge directions, four of them repeated
// to make 16 (Perlin 2002). A table rather than a switch: 2.6x faster Perlin noise.
template <class T>
inline glm::vec<3, T> gradient3(std::uint32_t h) noexcept {
    static constexpr signed char table[16][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                                 {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1},
                                                 {1, 1, 0}, {-1, 1, 0}, {0, -1, 1}, {0, -1, -1}};
    const signed char* g = table[h & 15U];
    return glm::vec<3, T>(T(g[0]), T(g[1]), T(g[2]));
}

// 2D gradients: 8 directions at 45 degree steps, unit length.
template <class T>
constexpr glm::vec<2, T> gradient2(std::uint32_t h) noexcept {
    const T d = T(0.70710678118654752440L);
    switch (h & 7U) {
        case 0: return {T(1), T(0)};
        case 1: return {T(-1), T(0)};
        case 2: return {T(0), T(1)};
        case 3: return {T(0), T(-1)};
        case 4: return {d, d};
        case 5: return {-d, d};
        case 6: return {d, -d};
        default: return {-d, -d};
    }
}

template <class T>
constexpr T lerp(T a, T b, T t) noexcept {
    return a + t * (b - a);
}

// Scale factors that map the raw noise's extremes to +-1. Measured by hill-climbing |n| from
// 400 000 random starts: raw 3D maximum 1.0352764 (1/cos 15 deg = 1.0352762 to 7 digits),
// raw 2D maximum 0.70710678 (1/sqrt 2). tests/test_noise.cpp checks both bounds.
template <class T> inline constexpr T perlin3_scale = T(0.96592582628906829L);  // cos 15 deg
template <class T> inline constexpr T perlin2_scale = T(1.41421356237309505L);  // sqrt 2

}  // namespace detail

// ---------------------------------------------------------------------------------------
// Improved Perlin noise.

// perlin_noise_derivatives(p, period, seed) = (n, dn/dx, dn/dy, dn/dz), the value and its
// analytic gradient (before the final clamp to [-1, 1], which the value never reaches in
// practice). At lattice points n = 0 and the gradient is the corner's gradient times the
// scale factor.
template <class T>
[[nodiscard]] inline glm::vec<4, T> perlin_noise_derivatives(const glm::vec<3, T>& p, int period,
                                                           std::uint32_t seed = 0) noexcept {
    const int n = detail::clamp_period(period);
    const int ix = detail::floor_to_cell(p.x), iy = detail::floor_to_cell(p.y), iz = detail::floor_to_cell(p.z);
    const T x = p.x - std::floor(p.x), y = p.y - std::floor(p.y), z = p.z - std::floor(p.z);
    const std::uint32_t x0 = static_cast<std::uint32_t>(detail::wrap_cell(ix, n));
    const std::uint32_t y0 = static_cast<std::uint32_t>(detail::wrap_cell(iy, n));
    const std::uint32_t z0 = static_cast<std::uint32_t>(detail::wrap_cell(iz, n));
    const std::uint32_t x1 = static_cast<std::uint32_t>(detail::wrap_cell(ix + 1, n));
    const std::uint32_t y1 = static_cast<std::uint32_t>(detail::wrap_cell(iy + 1, n));
    const std::uint32_t z1 = static_cast<std::uint32_t>(detail::wrap_cell(iz + 1, n));
    const glm::vec<3, T> g000 = detail::gradient3<T>(noise_hash(x0, y0, z0, seed));
    const glm::vec<3, T> g100 = detail::gradient3<T>(noise_hash(x1, y0, z0, seed));
    const glm::vec<3, T> g010 = detail::gradient3<T>(noise_hash(x0, y1, z0, seed));
    const glm::vec<3, T> g110 = detail::gradient3<T>(noise_hash(x1, y1, z0, seed));
    const glm::vec<3, T> g001 = detail::gradient3<T>(noise_hash(x0, y0, z1, seed));
    const glm::vec<3, T> g101 = detail::gradient3<T>(noise_hash(x1, y0, z1, seed));
    const glm::vec<3, T> g011 = detail::gradient3<T>(noise_hash(x0, y1, z1, seed));
    const glm::vec<3, T> g111 = detail::gradient3<T>(noise_hash(x1, y1, z1, seed));
    // Corner contributions dot(g, p - corner).
    const T v000 = g000.x * x + g000.y * y + g000.z * z;
    const T v100 = g100.x * (x - T(1)) + g100.y * y + g100.z * z;
    const T v010 = g010.x * x + g010.y * (y - T(1)) + g010.z * z;
    const T v110 = g110.x * (x - T(1)) + g110.y * (y - T(1)) + g110.z * z;
    const T v001 = g001.x * x + g001.y * y + g001.z * (z - T(1));
    const T v101 = g101.x * (x - T(1)) + g101.y * y + g101.z * (z - T(1));
    const T v011 = g011.x * x + g011.y * (y - T(1)) + g011.z * (z - T(1));
    const T v111 = g111.x * (x - T(1)) + g111.y * (y - T(1)) + g111.z * (z - T(1));
    const T u = detail::fade(x), v = detail::fade(y), w = detail::fade(z);
    const T du = detail::fade_derivative(x), dv = detail::fade_derivative(y), dw = detail::fade_derivative(z);
    // Trilinear blend n = sum of corner values times fade weights, written as the
    // polynomial k0 + k1 u + k2 v + k3 w + k4 uv + k5 vw + k6 wu + k7 uvw so that the
    // derivative follows by the product rule.
    const T k0 = v000;
    const T k1 = v100 - v000;
    const T k2 = v010 - v000;
    const T k3 = v001 - v000;
    const T k4 = v000 - v100 - v010 + v110;
    const T k5 = v000 - v010 - v001 + v011;
    const T k6 = v000 - v100 - v001 + v101;
    const T k7 = -v000 + v100 + v010 - v110 + v001 - v101 - v011 + v111;
    const T value = k0 + k1 * u + k2 * v + k3 * w + k4 * u * v + k5 * v * w + k6 * w * u + k7 * u * v * w;
    // d/dx of each corner value is its gradient's x component; blend those the same way,
    // plus the fade derivative terms.
    const glm::vec<3, T> gk0 = g000;
    const glm::vec<3, T> gk1 = g100 - g000;
    const glm::vec<3, T> gk2 = g010 - g000;
    const glm::vec<3, T> gk3 = g001 - g000;
    const glm::vec<3, T> gk4 = g000 - g100 - g010 + g110;
    const glm::vec<3, T> gk5 = g000 - g010 - g001 + g011;
    const glm::vec<3, T> gk6 = g000 - g100 - g001 + g101;
    const glm::vec<3, T> gk7 = -g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111;
    glm::vec<3, T> grad = gk0 + gk1 * u + gk2 * v + gk3 * w + gk4 * (u * v) + gk5 * (v * w) +
                          gk6 * (w * u) + gk7 * (u * v * w);
    grad.x += du * (k1 + k4 * v + k6 * w + k7 * v * w);
    grad.y += dv * (k2 + k4 * u + k5 * w + k7 * u * w);
    grad.z += dw * (k3 + k5 * v + k6 * u + k7 * u * v);
    const T s = detail::perlin3_scale<T>;
    return glm::vec<4, T>(value * s, grad.x * s, grad.y * s, grad.z * s);
}

// perlin_noise(p, period, seed): improved Perlin noise in [-1, 1], 0 at lattice points.
template <class T>
[[nodiscard]] inline T perlin_noise(const glm::vec<3, T>& p, int period, std::uint32_t seed = 0) noexcept {
    return detail::clamp(perlin_noise_derivatives(p, period, seed).x, T(-1), T(1));
}

// 2D improved Perlin noise in [-1, 1] (8 unit gradients), periodic like the 3D one.
template <class T>
[[nodiscard]] inline T perlin_noise(const glm::vec<2, T>& p, int period, std::uint32_t seed = 0) noexcept {
    const int n = detail::clamp_period(period);
    const int ix = detail::floor_to_cell(p.x), iy = detail::floor_to_cell(p.y);
    const T x = p.x - std::floor(p.x), y = p.y - std::floor(p.y);
    const std::uint32_t x0 = static_cast<std::uint32_t>(detail::wrap_cell(ix, n));
    const std::uint32_t y0 = static_cast<std::uint32_t>(detail::wrap_cell(iy, n));
    const std::uint32_t x1 = static_cast<std::uint32_t>(detail::wrap_cell(ix + 1, n));
    const std::uint32_t y1 = static_cast<std::uint32_t>(detail::wrap_cell(iy + 1, n));
    const glm::vec<2, T> g00 = detail::gradient2<T>(noise_hash(x0, y0, 0U, seed));
    const glm::vec<2, T> g10 = detail::gradient2<T>(noise_hash(x1, y0, 0U, seed));
    const glm::vec<2, T> g01 = detail::gradient2<T>(noise_hash(x0, y1, 0U, seed));
    const glm::vec<2, T> g11 = detail::gradient2<T>(noise_hash(x1, y1, 0U, seed));
    const T v00 = g00.x * x + g00.y * y;
    const T v10 = g10.x * (x - T(1)) + g10.y * y;
    const T v01 = g01.x * x + g01.y * (y - T(1));
    const T v11 = g11.x * (x - T(1)) + g11.y * (y - T(1));
    const T u = detail::fade(x), v = detail::fade(y);
    const T value = detail::lerp(detail::lerp(v00, v10, u), detail::lerp(v01, v11, u), v);
    return detail::clamp(value * detail::perlin2_scale<T>, T(-1), T(1));
}

// ---------------------------------------------------------------------------------------
// Worley (cellular) noise.

// worley_f1(p, period, seed): distance from p to the nearest feature point, one point per
// unit cell, placed by the cell's hash, searching the 27 cells around p (Worley 1996; the
// usual real-time choice). Neighbour cells are wrapped by the period for hashing and not for
// position, so the field tiles. The 27-cell search is not exact in every configuration: a
// point two cells away can be nearer than all 27 when p sits near a cell face and the
// near points sit far away. Measured against a 125-cell search: 29 of 20 million random
// points differ, by at most 0.065 in worley_noise (a barely visible crease; REFERENCES.md
// and Nubis use the 27-cell search). Result in [0, sqrt(3)].
template <class T>
[[nodiscard]] inline T worley_f1(const glm::vec<3, T>& p, int period, std::uint32_t seed = 0) noexcept {
    const int n = detail::clamp_period(period);
    const int ix = detail::floor_to_cell(p.x), iy = detail::floor_to_cell(p.y), iz = detail::floor_to_cell(p.z);
    const T x = p.x - std::floor(p.x), y = p.y - std::floor(p.y), z = p.z - std::floor(p.z);
    // The wrapped coordinates and the hash prefixes of noise_hash(x, y, z, seed) are shared
    // by rows of cells: computed 3 and 9 times instead of 27 (same hashes, 1.7x faster).
    std::uint32_t wx[3], hz[3];
    const std::uint32_t hs = noise_hash(seed);
    for (int k = 0; k < 3; ++k) {
        wx[k] = static_cast<std::uint32_t>(detail::wrap_cell(ix + k - 1, n));
        hz[k] = noise_hash(static_cast<std::uint32_t>(detail::wrap_cell(iz + k - 1, n)) + hs);
    }
    T best = T(3);  // squared distance; the feature point of p's own cell is within sqrt(3)
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy) {
            const std::uint32_t hyz = noise_hash(static_cast<std::uint32_t>(detail::wrap_cell(iy + dy, n)) + hz[dz + 1]);
            for (int dx = -1; dx <= 1; ++dx) {
                const std::uint32_t h = noise_hash(wx[dx + 1] + hyz);  // == noise_hash(x, y, z, seed)
                const std::uint32_t h2 = noise_hash(h);
                const std::uint32_t h3 = noise_hash(h2);
                const T ox = T(dx) + hash_to_unit<T>(h) - x;
                const T oy = T(dy) + hash_to_unit<T>(h2) - y;
                const T oz = T(dz) + hash_to_unit<T>(h3) - z;
                const T d2 = ox * ox + oy * oy + oz * oz;
                best = d2 >= best ? best : d2;  // a NaN p (every d2 NaN) keeps NaN: the result is NaN
            }
        }
    return std::sqrt(best);
}

// worley_noise(p, period, seed) = 1 - F1 / sqrt(3), the cloud form of Worley noise in [0, 1]
// (1 at feature points, billowy cells).
template <class T>
[[nodiscard]] inline T worley_noise(const glm::vec<3, T>& p, int period, std::uint32_t seed = 0) noexcept {
    return saturate(T(1) - worley_f1(p, period, seed) * T(0.57735026918962576451L));
}

// ---------------------------------------------------------------------------------------
// fBm. Octave i: amplitude gain^i, frequency and period times lacunarity^i, seed + i; the sum
// is divided by the sum of the amplitudes, so the range of the base noise is kept.
// Domain: every int period and lacunarity, every finite gain, and octaves as long as the last
// octave's coordinate p lacunarity^(octaves - 1) stays finite in T (at lacunarity 2 in float,
// up to about 127 - log2 |p| octaves; beyond, that coordinate is Inf and the result NaN; the
// GLSL twin alike). octaves < 1 is treated as 1,
// lacunarity < 1 as 1 (integer so that tiling holds). gain is clamped to
// [0, 1]: the amplitudes are then non-negative and never grow, so the sum of amplitudes is
// at least 1 and the result is a weighted mean of the octaves, in the base noise's range.
// gain 0 is the first octave alone, gain 1 the plain mean of the octaves. Unclamped, a
// negative gain made the amplitudes cancel (gain -1 with an even octave count: sum / 0 =
// Inf or NaN), and a gain above 1 overflowed them for long octave counts.

namespace detail {

template <class T, class Noise>
inline T fbm(const glm::vec<3, T>& p, int period, int octaves, int lacunarity, T gain_in,
             std::uint32_t seed, Noise noise) noexcept {
    const int count = octaves < 1 ? 1 : octaves;
    const int lac = lacunarity < 1 ? 1 : lacunarity;
    const T gain = clamp(gain_in, T(0), T(1));
    T sum = T(0), norm = T(0), amplitude = T(1), frequency = T(1);
    int octave_period = detail::clamp_period(period);
    for (int i = 0; i < count; ++i) {
        sum += amplitude * noise(p * frequency, octave_period, seed + static_cast<std::uint32_t>(i));
        norm += amplitude;
        amplitude *= gain;
        frequency *= T(lac);
        octave_period = detail::grow_period(octave_period, lac);
    }
    return sum / norm;
}

}  // namespace detail

// perlin_fbm: fBm of 3D Perlin noise, in [-1, 1]; gain clamped to [0, 1] (see fBm above).
template <class T>
[[nodiscard]] inline T perlin_fbm(const glm::vec<3, T>& p, int period, int octaves, int lacunarity = 2,
                                  T gain = T(0.5), std::uint32_t seed = 0) noexcept {
    return detail::fbm(p, period, octaves, lacunarity, gain, seed,
               [](const glm::vec<3, T>& q, int per, std::uint32_t s) { return perlin_noise(q, per, s); });
}

// perlin_fbm for 2D (weather maps), in [-1, 1]; gain clamped to [0, 1].
template <class T>
[[nodiscard]] inline T perlin_fbm(const glm::vec<2, T>& p, int period, int octaves, int lacunarity = 2,
                                  T gain = T(0.5), std::uint32_t seed = 0) noexcept {
    return detail::fbm(glm::vec<3, T>(p, T(0)), period, octaves, lacunarity, gain, seed,
               [](const glm::vec<3, T>& q, int per, std::uint32_t s) {
                   return perlin_noise(glm::vec<2, T>(q.x, q.y), per, s);
               });
}

// worley_fbm: fBm of the cloud Worley noise, in [0, 1]; gain clamped to [0, 1].
template <class T>
[[nodiscard]] inline T worley_fbm(const glm::vec<3, T>& p, int period, int octaves, int lacunarity = 2,
                                  T gain = T(0.5), std::uint32_t seed = 0) noexcept {
    return detail::fbm(p, period, octaves, lacunarity, gain, seed,
               [](const glm::vec<3, T>& q, int per, std::uint32_t s) { return worley_noise(q, per, s); });
}

// Nubis's three-octave Worley fBm: 0.625 W(p) + 0.25 W(2p) + 0.125 W(4p) (Schneider 2015),
// periods doubling with the frequency; in [0, 1].
template <class T>
[[nodiscard]] inline T worley_fbm_nubis(const glm::vec<3, T>& p, int period, std::uint32_t seed = 0) noexcept {
    const int n = detail::clamp_period(period);
    return T(0.625) * worley_noise(p, n, seed) + T(0.25) * worley_noise(p * T(2), detail::grow_period(n, 2), seed + 1U) +
           T(0.125) * worley_noise(p * T(4), detail::grow_period(n, 4), seed + 2U);
}

// Perlin-Worley (Schneider 2015): Perlin fBm (3 octaves, mapped to [0, 1]) dilated by the
// Nubis Worley fBm through remap_clamped(perlin, worley - 1, 1, 0, 1): Worley's cells give
// Perlin's wisps a billowy, connected structure. In [0, 1].
template <class T>
[[nodiscard]] inline T perlin_worley(const glm::vec<3, T>& p, int period, std::uint32_t seed = 0) noexcept {
    const T perlin = perlin_fbm(p, period, 3, 2, T(0.5), seed) * T(0.5) + T(0.5);
    const T worley = worley_fbm_nubis(p, period, seed + 101U);
    return detail::remap_unit(perlin, worley - T(1), T(1));  // remap_clamped(..., 0, 1)
}

// ---------------------------------------------------------------------------------------
// Curl noise (Bridson et al. 2007): the curl of a vector potential made of three
// independent Perlin fields (seeds seed, seed + 1, seed + 2), using their analytic
// derivatives, so the field is divergence-free by construction (div curl = 0) and tiles.
template <class T>
[[nodiscard]] inline glm::vec<3, T> curl_noise(const glm::vec<3, T>& p, int period, std::uint32_t seed = 0) noexcept {
    const glm::vec<4, T> a = perlin_noise_derivatives(p, period, seed);        // psi_x
    const glm::vec<4, T> b = perlin_noise_derivatives(p, period, seed + 1U);   // psi_y
    const glm::vec<4, T> c = perlin_noise_derivatives(p, period, seed + 2U);   // psi_z
    // curl psi = (dpsi_z/dy - dpsi_y/dz, dpsi_x/dz - dpsi_z/dx, dpsi_y/dx - dpsi_x/dy)
    return glm::vec<3, T>(c.z - b.w, a.w - c.y, b.y - a.z);
}

// 2D curl of a scalar Perlin potential psi: (dpsi/dy, -dpsi/dx), divergence-free in the plane
// (the 3D potential evaluated on z = 0, so it tiles in x and y).
template <class T>
[[nodiscard]] inline glm::vec<2, T> curl_noise(const glm::vec<2, T>& p, int period, std::uint32_t seed = 0) noexcept {
    const glm::vec<4, T> d = perlin_noise_derivatives(glm::vec<3, T>(p, T(0)), period, seed);
    return glm::vec<2, T>(d.z, -d.y);
}

}  // namespace cloudmath

#endif  // CLOUDMATH_NOISE_HPP
