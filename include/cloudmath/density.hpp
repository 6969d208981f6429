// cloudmath/density.hpp: cloud density shaping (height gradients, coverage, erosion) and
// exponential height fog with its analytic optical depth.
//
// Use:      #include <cloudmath/density.hpp>
//           float hf = cloudmath::height_fraction(alt, 1500.f, 4000.f);
//           float d = cloudmath::apply_coverage(base * cloudmath::height_gradient_for_type(hf, type), coverage);
//           d = cloudmath::erode(d, detail_noise * 0.2f);
// Inputs:   h is a height fraction in [0, 1] within the cloud layer (geometry.hpp);
//           densities, coverage, erosion and cloud type are in [0, 1] (coverage and type are
//           clamped to it). Fog altitudes and distances in metres, falloff in 1/m.
// Source:   Schneider, "The real-time volumetric cloudscapes of Horizon Zero Dawn", SIGGRAPH
//           2015 Advances, and GPU Pro 7 (2016); Olajos 2016 (height distribution).
// GLSL twin: cloudmath/glsl/density.glsl.
#ifndef CLOUDMATH_DENSITY_HPP
#define CLOUDMATH_DENSITY_HPP

#include <cmath>

#include "core.hpp"

namespace cloudmath {

// height_gradient(h, profile) = smoothstep(p.x, p.y, h) - smoothstep(p.z, p.w, h):
// a ramp up between p.x and p.y and down between p.z and p.w (p.x <= p.y <= p.z <= p.w
// gives a value in [0, 1]). Uses smoothstep_safe, so equal edges are a step, not undefined
// behaviour as in GLSL.
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T height_gradient(T h, const glm::vec<4, T, Q>& profile) noexcept {
    return smoothstep_safe(profile.x, profile.y, h) - smoothstep_safe(profile.z, profile.w, h);
}

// Height profiles of the three cloud types (community convention following Schneider 2015,
// for smoothstep(x, y, h) - smoothstep(z, w, h)).
template <class T>
[[nodiscard]] constexpr glm::vec<4, T> height_profile_stratus() noexcept {
    return glm::vec<4, T>(T(0.02), T(0.05), T(0.09), T(0.11));
}
template <class T>
[[nodiscard]] constexpr glm::vec<4, T> height_profile_stratocumulus() noexcept {
    return glm::vec<4, T>(T(0.02), T(0.2), T(0.48), T(0.625));
}
template <class T>
[[nodiscard]] constexpr glm::vec<4, T> height_profile_cumulus() noexcept {
    return glm::vec<4, T>(T(0.01), T(0.0625), T(0.78), T(1.0));
}

// Profile for a cloud type t in [0, 1] (clamped): stratus at 0, stratocumulus at 0.5,
// cumulus at 1, with the weights stratus 1 - saturate(2t), stratocumulus 1 - |t - 0.5| 2,
// cumulus saturate(t - 0.5) 2, which sum to 1. The profiles (edge heights) are blended,
// not the gradients, so intermediate types morph the shape continuously and cost one
// gradient evaluation.
template <class T>
[[nodiscard]] constexpr glm::vec<4, T> height_profile_for_type(T cloud_type) noexcept {
    const T t = saturate(cloud_type);
    const T w_stratus = T(1) - saturate(T(2) * t);
    const T w_stratocumulus = T(1) - detail::abs(t - T(0.5)) * T(2);
    const T w_cumulus = saturate(t - T(0.5)) * T(2);
    return height_profile_stratus<T>() * w_stratus +
           height_profile_stratocumulus<T>() * w_stratocumulus +
           height_profile_cumulus<T>() * w_cumulus;
}

// height_gradient_for_type(h, cloud_type) = height_gradient(h, height_profile_for_type(t)).
template <class T>
[[nodiscard]] constexpr T height_gradient_for_type(T h, T cloud_type) noexcept {
    return height_gradient(h, height_profile_for_type(cloud_type));
}

// height_range_for_type(cloud_type) = (p.x, p.w) of height_profile_for_type(t): the
// height fractions outside which height_gradient_for_type(h, t) is exactly 0 (below p.x
// both smoothsteps are 0, above p.w both are 1). A ray march can clamp its range to these
// altitudes (layer_bottom + h (layer_top - layer_bottom), then cloud_layer_segment) and
// lose nothing: a stratus sheet fills 9% of the layer, and a march over the whole layer
// spends 91% of its steps where the density is 0. NaN type gives NaN.
template <class T>
[[nodiscard]] constexpr glm::vec<2, T> height_range_for_type(T cloud_type) noexcept {
    const glm::vec<4, T> p = height_profile_for_type(cloud_type);
    return glm::vec<2, T>(p.x, p.w);
}

// height_gradient_exponential(h, a, b) = (1 - exp(-a h)) exp(-b h) (Olajos 2016, with
// a = 50, b = 4): a fast rise above the layer bottom and a slow exponential decay.
// The rise uses -expm1 so small a h keeps full precision.
// Domain: every finite h, a and b; the result is in [0, 1]. h <= 0 (below the layer) gives
// exactly 0; a < 0 and b < 0 act as 0 (no rise: 0 everywhere; no decay). h is clamped to
// >= 0 before it enters either exponential: with the clamp on a h alone, exp(-b h) still
// overflowed below the layer and 0 * Inf gave NaN (float from h = -22.2 with b = 4,
// double from h = -177.5).
template <class T>
[[nodiscard]] inline T height_gradient_exponential(T h, T a, T b) noexcept {
    const T height = detail::max(h, T(0));
    return one_minus_exp_neg(detail::max(a, T(0)) * height) * std::exp(-detail::max(b, T(0)) * height);
}

// apply_coverage(base, coverage) = remap_clamped(base, 1 - coverage, 1, 0, 1) * coverage
// (Schneider 2016 with the GPU Pro 7 text's inversion fixed): for base in [0, 1] this is
// max(0, base + coverage - 1), increasing in both base and coverage. coverage is clamped
// to [0, 1]; coverage 0 gives 0 and coverage 1 gives base. Domain: every finite input
// (the remap is remap_clamped's, finite for huge inputs).
template <class T>
[[nodiscard]] constexpr T apply_coverage(T base, T coverage) noexcept {
    const T c = saturate(coverage);
    return detail::remap_unit(base, T(1) - c, T(1)) * c;  // remap_clamped(..., 0, 1)
}

// erode(base, erosion) = remap_clamped(base, erosion, 1, 0, 1): removes density below
// `erosion` and stretches the rest back to [0, 1] (detail-noise erosion of Nubis).
// erosion = 1 is the degenerate step: only base >= 1 survives. Domain: every finite input;
// the result is in [0, 1].
template <class T>
[[nodiscard]] constexpr T erode(T base, T erosion) noexcept {
    return detail::remap_unit(base, erosion, T(1));  // remap_clamped(base, erosion, 1, 0, 1)
}

// ---------------------------------------------------------------------------------------
// Exponential height fog: density(h) = density_at_zero exp(-falloff h).
template <class T>
[[nodiscard]] inline T height_fog_density(T altitude, T density_at_zero, T falloff) noexcept {
    return density_at_zero * std::exp(-falloff * altitude);
}

// Optical depth of exponential height fog along a straight ray from `altitude` with
// vertical direction cosine cos_zenith over `distance`:
//   integral_0^L rho0 exp(-k (h0 + t mu)) dt = rho0 L exp(-k h_low) (1 - exp(-x)) / x,
//   x = k |mu| L,  h_low = the lower end's altitude, min(h0, h0 + mu L).
// Written from the lower end so the exponential never grows, and with the stable
// (1 - exp(-x))/x of core.hpp, which makes horizontal rays (mu = 0, or k = 0) exact:
// rho0 L exp(-k h0). Domain: distance >= 0, falloff >= 0; cos_zenith is clamped to [-1, 1].
// Multiply by the extinction per unit density to get tau.
template <class T>
[[nodiscard]] inline T height_fog_optical_depth(T altitude, T cos_zenith, T distance,
                                                T density_at_zero, T falloff) noexcept {
    const T mu = detail::clamp(cos_zenith, T(-1), T(1));
    const T rise = mu * distance;
    const T h_low = rise < T(0) ? altitude + rise : altitude;
    return density_at_zero * distance * std::exp(-falloff * h_low) *
           one_minus_exp_neg_over_x(falloff * detail::abs(rise));
}

// ---------------------------------------------------------------------------------------
// Aerial perspective: the air between the camera and what it sees.

// air_optical_depth(altitude, cos_zenith, distance): optical depth (r, g, b) of clear air
// along a straight ray, Rayleigh plus aerosol (Mie) extinction with exponential height
// profiles: sea-level Rayleigh scattering (5.802, 13.558, 33.1) 1e-6 /m at 680, 550 and 440
// nm with scale height 8 km, aerosol extinction 4.40e-6 /m with scale height 1.2 km (the Earth
// constants of Bruneton 2017 and Hillaire 2020). Each term is height_fog_optical_depth, so
// horizontal rays are exact; the ray is straight (over 35 km the Earth's curvature lifts it
// by 96 m, 1% of the Rayleigh scale height). Domain as height_fog_optical_depth.
template <class T>
[[nodiscard]] inline glm::vec<3, T> air_optical_depth(T altitude, T cos_zenith, T distance) noexcept {
    const T rayleigh = height_fog_optical_depth(altitude, cos_zenith, distance, T(1), T(1) / T(8000));
    const T aerosol = height_fog_optical_depth(altitude, cos_zenith, distance, T(4.40e-6), T(1) / T(1200));
    return glm::vec<3, T>(T(5.802e-6), T(13.558e-6), T(33.1e-6)) * rayleigh + glm::vec<3, T>(aerosol);
}

// aerial_perspective(L, L_air, tau) = L e^-tau + L_air (1 - e^-tau): radiance L seen through
// air of optical depth tau that scatters L_air toward the camera (its single-scattered
// radiance over a long path, for example the sky's radiance at the horizon), with
// one_minus_exp_neg so tau -> 0 returns L exactly and tau = +Inf returns L_air. For a ray-marched
// cloud apply it to the cloud's light at its transmittance-weighted depth
// (sum of T_i (1 - e^(-sigma_t ds)) t_i over the march, divided by 1 - T) and weight L_air by
// the cloud's opacity: the sky behind it already holds its air. Per channel for vectors.
// Written as the two weighted terms, not L + (L_air - L) (1 - e^-tau): that difference lost
// L_air when L >> L_air (1.5e6 through tau 30 gave 0.25 for L_air 0.2) and gave 0 for
// L = 1e13 through tau = +Inf. The result is clamped to [min(L, L_air), max(L, L_air)] against
// the rounding of the weights; tau < 0 is taken as 0; NaN propagates.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T aerial_perspective(T L, T L_air, T tau) noexcept {
    const T t = detail::max(tau, T(0));
    const T r = L * std::exp(-t) + L_air * one_minus_exp_neg(t);
    return detail::clamp(r, detail::min(L, L_air), detail::max(L, L_air));
}
template <glm::length_t N, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<N, T, Q> aerial_perspective(const glm::vec<N, T, Q>& L, const glm::vec<N, T, Q>& L_air,
                                                          const glm::vec<N, T, Q>& tau) noexcept {
    glm::vec<N, T, Q> out;
    for (glm::length_t i = 0; i < N; ++i) out[i] = aerial_perspective(L[i], L_air[i], tau[i]);
    return out;
}

// ---------------------------------------------------------------------------------------
// The Nubis density model (Schneider 2015 and GPU Pro 7 2016; Nubis 2017), as functions of
// already-sampled texture values, so it works with any texture layout or noise source:
//   base   = base volume RGBA (R Perlin-Worley, G/B/A Worley fBm at rising frequencies),
//   detail = detail volume RGB (Worley fBm at rising frequencies),
//   coverage, cloud_type from the weather map, h the height fraction in the layer.
// Each step is callable on its own; nubis_density composes them in the published order.

// Low-frequency fBm of the base volume: G 0.625 + B 0.25 + A 0.125.
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T nubis_low_frequency_fbm(const glm::vec<4, T, Q>& base) noexcept {
    return base.y * T(0.625) + base.z * T(0.25) + base.w * T(0.125);
}

// Base cloud shape: remap(R, low_fbm - 1, 1, 0, 1): the Worley octaves carve the
// Perlin-Worley channel. In [0, 1] for channels in [0, 1] (the old range is never empty:
// its width 2 - low_fbm is at least 1).
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T nubis_base_cloud(const glm::vec<4, T, Q>& base) noexcept {
    return remap(base.x, nubis_low_frequency_fbm(base) - T(1), T(1), T(0), T(1));
}

// High-frequency fBm of the detail volume: R 0.625 + G 0.25 + B 0.125.
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T nubis_high_frequency_fbm(const glm::vec<3, T, Q>& detail) noexcept {
    return detail.x * T(0.625) + detail.y * T(0.25) + detail.z * T(0.125);
}

// Detail erosion threshold: 0.2 mix(hf, 1 - hf, saturate(10 h)): the inverted (billowy)
// detail noise above the lowest tenth of the layer, the plain (wispy) one at the bottom.
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T nubis_detail_erosion(const glm::vec<3, T, Q>& detail, T h) noexcept {
    const T hf = nubis_high_frequency_fbm(detail);
    const T t = saturate(h * T(10));
    return (hf + t * ((T(1) - hf) - hf)) * T(0.2);
}

// Full density in [0, 1]: base cloud times the type's height gradient, coverage, then
// detail erosion (erode = remap_clamped(density, threshold, 1, 0, 1)). coverage and
// cloud_type are clamped to [0, 1].
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T nubis_density(const glm::vec<4, T, Q>& base, const glm::vec<3, T, Q>& detail,
                                        T coverage, T cloud_type, T h) noexcept {
    const T shaped = nubis_base_cloud(base) * height_gradient_for_type(h, cloud_type);
    return erode(apply_coverage(shaped, coverage), nubis_detail_erosion(detail, h));
}

// cloud_top_fraction(weather_b) = 0.6 + 0.4 saturate(weather_b): a cloud's top as a share of
// its type's profile, from a weather-map channel (the shortest clouds reach 60% as high).
template <class T>
[[nodiscard]] constexpr T cloud_top_fraction(T weather_b) noexcept {
    return T(0.6) + T(0.4) * saturate(weather_b);
}

// cloud_shape_density(base, weather, h, coverage, cloud_type, type_spread, top_rounding):
// the base shape (before detail erosion) of a field whose weather map carries each cloud's
// coverage (R), type (G) and top (B), so that neighbouring clouds differ instead of being one
// profile extruded from a 2D shape:
//   type  t  = saturate(cloud_type + (G - 0.5) type_spread)
//   top   hc = h / cloud_top_fraction(B)      (the profile compressed under a lower top)
//   cover c  = saturate(R - 0.5 + coverage) (1 - top_rounding hc^2)
//   apply_coverage(nubis_base_cloud(base) * height_gradient_for_type(hc, t), c)
// The coverage that falls with height narrows each cloud toward its top: rounded tops
// instead of flat ones (top_rounding 0 keeps them flat; 0.6 leaves 40% of the coverage at
// the top). 0 at and above the cloud's top (hc >= 1). Densities where h is outside the
// union of height_range_for_type over the spread of types, scaled by 0.6 below, are 0.
template <class T, glm::qualifier Q>
[[nodiscard]] constexpr T cloud_shape_density(const glm::vec<4, T, Q>& base, const glm::vec<3, T, Q>& weather, T h,
                                              T coverage, T cloud_type, T type_spread, T top_rounding) noexcept {
    const T hc = h / cloud_top_fraction(weather.z);
    if (!(hc < T(1))) return T(0);
    const T t = saturate(cloud_type + (weather.y - T(0.5)) * type_spread);
    // hc below 0 (under the layer, where the gradient is 0) rounds nothing: hc^2 overflowed for
    // h around -1e20 in float, and 0 coverage times -Inf gave NaN (found by the fuzz test).
    const T hr = hc > T(0) ? hc : T(0);
    const T c = saturate(weather.x - T(0.5) + coverage) * (T(1) - top_rounding * hr * hr);
    return apply_coverage(nubis_base_cloud(base) * height_gradient_for_type(hc, t), c);
}

}  // namespace cloudmath

#endif  // CLOUDMATH_DENSITY_HPP
