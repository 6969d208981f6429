// cloudmath/cone_sampling.hpp: Schneider's cone-shaped light sampling, the cheap stand-in
// for a second full ray march toward the sun.
//
// Use:      #include <cloudmath/cone_sampling.hpp>
//           cloudmath::cone_light_config<float> cone{6, 60.f, 0.5f, 600.f, 60.f};
//           float tau = cloudmath::cone_optical_depth(p, sun_dir, cone,
//               [&](const glm::vec3& q) { return sigma_t * density(q); });
//           float T_light = cloudmath::beer_lambert(tau);
// Source:   Schneider, "The real-time volumetric cloudscapes of Horizon Zero Dawn",
//           SIGGRAPH 2015 Advances: 6 samples in a cone toward the sun whose radius grows
//           with distance, the last one placed far away to catch shadows of distant clouds.
// Layout:   near sample i (0 <= i < n_near) lies at distance (i + 1/2) step_length along the
//           light (the midpoint of its segment, so constant density is integrated exactly),
//           offset sideways by cone_spread * distance * k_i, where k_i is point i of a
//           Vogel (golden-angle) spiral filling the unit disc: deterministic, evenly spread,
//           the same in C++ and GLSL. The far sample, when far_distance > 0, is the last
//           one, on the cone's axis at far_distance, and stands for far_segment_length.
// Units:    distances in metres (any consistent unit); light_dir is a unit vector from the
//           sample toward the light; cone_spread is the tangent of the cone's half-angle.
// GLSL twin: cloudmath/glsl/cone_sampling.glsl (#define CM_CONE_SAMPLES sets the count).
#ifndef CLOUDMATH_CONE_SAMPLING_HPP
#define CLOUDMATH_CONE_SAMPLING_HPP

#include <cmath>
#include <type_traits>

#include <glm/geometric.hpp>

#include "core.hpp"

namespace cloudmath {

template <class T>
struct cone_light_config {
    int sample_count = 6;      // all samples, the far one included
    T step_length = T(0);      // length of each near segment
    T cone_spread = T(0);      // cone radius per unit distance (tan of the half-angle)
    T far_distance = T(0);     // distance of the far sample; <= 0: no far sample
    T far_segment_length = T(0);  // optical-depth weight (length) of the far sample
};

namespace detail {

// The golden angle pi (3 - sqrt 5), the angular step of the Vogel spiral.
template <class T> inline constexpr T golden_angle_v = T(2.399963229728653322231555506633613853L);

template <class T>
constexpr bool has_far_sample(const cone_light_config<T>& cfg) noexcept {
    return cfg.far_distance > T(0) && cfg.sample_count > 0;
}

template <class T>
constexpr int near_sample_count(const cone_light_config<T>& cfg) noexcept {
    const int n = has_far_sample(cfg) ? cfg.sample_count - 1 : cfg.sample_count;
    return n > 0 ? n : 0;
}

// Orthonormal u, v perpendicular to the unit vector n, branch-free apart from the sign and
// continuous except across n.z = 0 (Duff et al., "Building an orthonormal basis,
// revisited", JCGT 6(1), 2017).
template <class T, glm::qualifier Q>
inline void orthonormal_basis(const glm::vec<3, T, Q>& n, glm::vec<3, T, Q>& u,
                              glm::vec<3, T, Q>& v) noexcept {
    const T sign = n.z >= T(0) ? T(1) : T(-1);
    const T a = T(-1) / (sign + n.z);
    const T b = n.x * n.y * a;
    u = glm::vec<3, T, Q>(T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x);
    v = glm::vec<3, T, Q>(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace detail

// Point i of n of the Vogel spiral in the unit disc: radius sqrt((i + 1/2) / n), angle
// i times the golden angle pi (3 - sqrt 5).
// Domain: every int i and n. i is taken modulo n (into [0, n), negative i included);
// n < 1 is treated as 1. The wrap uses % on non-negative operands only and never adds to
// a value near INT_MAX (the former ((i % n) + n) % n overflowed, undefined behaviour, for
// n > INT_MAX / 2). Every point lies strictly inside the disc for n <= 2^23 in float and
// for every n in double; above 2^23 float rounding can put the last points on the circle
// (radius 1). The angle of a large index carries the rounding of float(k) * golden angle.
template <class T>
[[nodiscard]] inline glm::vec<2, T> cone_kernel_offset(int i, int n) noexcept {
    const int count = n > 0 ? n : 1;
    const int k = i >= 0 ? i % count : count - 1 - (-(i + 1)) % count;
    const T golden_angle = detail::golden_angle_v<T>;
    const T radius = std::sqrt((T(k) + T(0.5)) / T(count));
    const T angle = T(k) * golden_angle;
    return glm::vec<2, T>(radius * std::cos(angle), radius * std::sin(angle));
}

// Distance along the light of sample i (0 <= i < sample_count): (i + 1/2) step_length for
// near samples, far_distance for the far one. Indices outside the range are clamped.
template <class T>
[[nodiscard]] constexpr T cone_sample_distance(const cone_light_config<T>& cfg, int i) noexcept {
    const int n_near = detail::near_sample_count(cfg);
    if (detail::has_far_sample(cfg) && i >= n_near) return cfg.far_distance;
    const int last = n_near > 0 ? n_near - 1 : 0;  // no near samples: the first position
    const int k = i < 0 ? 0 : (i > last ? last : i);
    return (T(k) + T(0.5)) * cfg.step_length;
}

// Length of ray that sample i stands for in the optical depth: step_length for near
// samples, far_segment_length for the far one.
template <class T>
[[nodiscard]] constexpr T cone_sample_length(const cone_light_config<T>& cfg, int i) noexcept {
    return detail::has_far_sample(cfg) && i >= detail::near_sample_count(cfg)
               ? cfg.far_segment_length
               : cfg.step_length;
}

// World position of sample i: origin + light_dir * d_i + spread * d_i * (k.x u + k.y v)
// for near samples, origin + light_dir * far_distance for the far one.
template <class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<3, T, Q> cone_sample_position(const glm::vec<3, T, Q>& origin,
                                                            const glm::vec<3, T, Q>& light_dir,
                                                            const cone_light_config<T>& cfg,
                                                            int i) noexcept {
    const T d = cone_sample_distance(cfg, i);
    const int n_near = detail::near_sample_count(cfg);
    if (detail::has_far_sample(cfg) && i >= n_near) return origin + light_dir * d;
    glm::vec<3, T, Q> u, v;
    detail::orthonormal_basis(light_dir, u, v);
    const glm::vec<2, T> k = cone_kernel_offset<T>(i, n_near);
    return origin + light_dir * d + (u * k.x + v * k.y) * (cfg.cone_spread * d);
}

// Optical depth toward the light: sum over samples of extinction(p_i) * length_i, where
// extinction is a callable taking the sample position, or the position and the sample
// index (so it can switch to a cheaper density for later samples, as Schneider does once
// the view ray's opacity passes 0.3). Returns tau for beer_lambert.
template <class T, glm::qualifier Q, class Extinction>
[[nodiscard]] inline T cone_optical_depth(const glm::vec<3, T, Q>& origin,
                                          const glm::vec<3, T, Q>& light_dir,
                                          const cone_light_config<T>& cfg,
                                          Extinction&& extinction) {
    glm::vec<3, T, Q> u, v;
    detail::orthonormal_basis(light_dir, u, v);  // once, not per sample
    const int n_near = detail::near_sample_count(cfg);
    // The Vogel angles k * golden_angle advance by a rotation, so the loop takes two trig
    // calls per call instead of two per sample (the cost of the cone was in them). After 16
    // samples the rotated directions are within 2e-6 (float) of cone_kernel_offset's.
    const T golden_angle = detail::golden_angle_v<T>;
    const T step_cos = std::cos(golden_angle), step_sin = std::sin(golden_angle);
    T dir_cos = T(1), dir_sin = T(0);
    T tau = T(0);
    for (int i = 0; i < cfg.sample_count; ++i) {
        glm::vec<3, T, Q> p;
        const T d = cone_sample_distance(cfg, i);
        if (detail::has_far_sample(cfg) && i >= n_near) {
            p = origin + light_dir * d;
        } else {
            const T radius = std::sqrt((T(i) + T(0.5)) / T(n_near));
            p = origin + light_dir * d + (u * (radius * dir_cos) + v * (radius * dir_sin)) * (cfg.cone_spread * d);
            const T next_cos = dir_cos * step_cos - dir_sin * step_sin;
            dir_sin = dir_sin * step_cos + dir_cos * step_sin;
            dir_cos = next_cos;
        }
        T sigma;
        if constexpr (std::is_invocable_v<Extinction&, const glm::vec<3, T, Q>&, int>)
            sigma = static_cast<T>(extinction(p, i));
        else
            sigma = static_cast<T>(extinction(p));
        tau += sigma * cone_sample_length(cfg, i);
    }
    return tau;
}

}  // namespace cloudmath

#endif  // CLOUDMATH_CONE_SAMPLING_HPP
