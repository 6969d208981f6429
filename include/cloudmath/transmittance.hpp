// cloudmath/transmittance.hpp: Beer-Lambert transmittance, powder, Schneider's
// Beer-Powder and the Nubis 2017 attenuation.
//
// Use:      #include <cloudmath/transmittance.hpp>
//           float T = cloudmath::beer_lambert(sigma_t * distance);
// Input:    optical depth tau = integral of sigma_t ds (dimensionless), tau >= 0.
//           Negative tau is clamped to 0 so every transmittance stays in [0, 1];
//           tau = +Inf gives the limit (0 for Beer-Lambert).
// Types:    scalar T (float, double) or glm::vec<N, T> component-wise (RGB optical depth).
// Accuracy: powder terms use -expm1 (core.hpp), so they keep full relative precision for
//           tiny tau where 1 - exp(-x) rounds to 0 in float.
// GLSL twin: cloudmath/glsl/transmittance.glsl.
#ifndef CLOUDMATH_TRANSMITTANCE_HPP
#define CLOUDMATH_TRANSMITTANCE_HPP

#include <cmath>

#include "core.hpp"

namespace cloudmath {

// Beer-Lambert: T = exp(-tau). Result in [0, 1] for every tau (negative tau clamped to 0).
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T beer_lambert(T optical_depth) noexcept {
    return std::exp(-detail::max(optical_depth, T(0)));
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> beer_lambert(const glm::vec<L, T, Q>& tau) noexcept {
    return detail::map(tau, [](T v) { return beer_lambert(v); });
}

// Powder effect (Schneider 2015, GPU Pro 7 2016): 1 - exp(-k tau), the darkening of cloud
// edges seen with the sun behind the viewer. k > 0 sets how fast it saturates (Schneider
// uses 2). k * tau < 0 is clamped to 0. Result in [0, 1].
// Domain: every finite tau and k; a product k tau that overflows gives 1 (powder(1e30f,
// 1e10f) == 1, in the GLSL twin too).
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T powder(T optical_depth, T k) noexcept {
    return one_minus_exp_neg(detail::max(k * optical_depth, T(0)));
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> powder(const glm::vec<L, T, Q>& tau, T k) noexcept {
    return detail::map(tau, [k](T v) { return powder(v, k); });
}

// Beer-Powder (Schneider, "Real-time volumetric cloudscapes", GPU Pro 7, 2016):
//   E = 2 exp(-tau) (1 - exp(-2 tau)).
// Peak 4 / (3 sqrt 3) = 0.7698 at tau = ln(3)/2 = 0.5493; it exceeds plain Beer-Lambert for
// tau > ln(2)/2 = 0.3466, so it is an artistic term, not an energy-bounded transmittance.
// Result in [0, 0.7698]. Domain: every finite tau (negative acts as 0); 0 once exp(-tau)
// underflows, also where 2 tau overflows (tau > FLT_MAX / 2): -expm1(-Inf) is 1, not NaN.
// batch::beer_powder and the GLSL twin give the same 0 there.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T beer_powder(T optical_depth) noexcept {
    const T tau = detail::max(optical_depth, T(0));
    return T(2) * std::exp(-tau) * one_minus_exp_neg(T(2) * tau);
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> beer_powder(const glm::vec<L, T, Q>& tau) noexcept {
    return detail::map(tau, [](T v) { return beer_powder(v); });
}

// Nubis 2017 attenuation (Schneider, "Nubis: authoring real-time volumetric cloudscapes
// with the Decima engine", SIGGRAPH 2017 Advances): max(exp(-tau), 0.7 exp(-0.25 tau)).
// The second exponential keeps light reaching deep into thick clouds, a cheap stand-in for
// multiple scattering. The two curves cross at tau = -ln(0.7) / 0.75 = 0.4756.
// Result in (0, 1].
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T nubis_attenuation(T optical_depth) noexcept {
    const T tau = detail::max(optical_depth, T(0));
    return detail::max(std::exp(-tau), T(0.7) * std::exp(T(-0.25) * tau));
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> nubis_attenuation(const glm::vec<L, T, Q>& tau) noexcept {
    return detail::map(tau, [](T v) { return nubis_attenuation(v); });
}

// diffuse_transmittance(tau, g): the share of isotropic (sky) light that crosses a
// conservatively scattering layer of optical depth tau and phase asymmetry g, direct and
// scattered together: the two-stream (Eddington) result 1 / (1 + 3/4 (1 - g) tau), a function
// of the transport optical depth (1 - g) tau only (similarity). Use it to occlude ambient
// light inside a cloud: sky light times diffuse_transmittance(optical depth to the top, g).
// Accuracy against the slab Monte Carlo (docs/data/diffuse_transmittance.csv, HG g = 0.6,
// 0.8, 0.9, tau 0.25 to 64): never too low, at most 0.037 too high (4.9% relative) for
// (1 - g) tau near 0.2-0.8, 1.3% at 6.4, 0.7% at 12.8; exact limits 1 at tau = 0 and 4 / (3 (1 - g) tau) for
// thick layers (the diffusion asymptote (4/3) / ((1 - g) tau + 1.42) of van de Hulst 1980).
// Albedo 1 (absorption would lower it); tau < 0 acts as 0; g is clamped to [-1, 1].
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T diffuse_transmittance(T optical_depth, T g) noexcept {
    const T tau = detail::max(optical_depth, T(0));
    return T(1) / (T(1) + T(0.75) * (T(1) - detail::clamp(g, T(-1), T(1))) * tau);
}

template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> diffuse_transmittance(const glm::vec<L, T, Q>& tau, T g) noexcept {
    return detail::map(tau, [g](T v) { return diffuse_transmittance(v, g); });
}

}  // namespace cloudmath

#endif  // CLOUDMATH_TRANSMITTANCE_HPP
