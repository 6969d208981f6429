// cloudmath/integration.hpp: energy-conserving integration of in-scattered light over a
// ray-march step, and a front-to-back march accumulator.
//
// Use:      #include <cloudmath/integration.hpp>
//           cloudmath::march_accumulator<glm::vec3, float> acc;
//           for (each step) { acc.add_segment(S, sigma_t, ds); if (acc.is_opaque(0.01f)) break; }
//           color = background * acc.transmittance + acc.luminance;
// Units:    S is the source term per unit length (radiance / m), for single scattering
//           S = sigma_s * phase * L_light * T_light; sigma_t in 1/m; ds in m.
// Source:   Hillaire, "Physically based and unified volumetric rendering in Frostbite",
//           SIGGRAPH 2015 Advances: within a step of length ds with constant S and sigma_t,
//           integral_0^ds S exp(-sigma_t t) dt = S (1 - exp(-sigma_t ds)) / sigma_t.
// Accuracy: written as S ds (1 - exp(-x))/x with x = sigma_t ds and the -expm1 form of
//           core.hpp: exactly S ds at sigma_t = 0 and within a few ulp for every x in
//           [0, 1e4] and beyond, with no clamp constant. The common
//           max(sigma_t, 1e-6) clamp is biased for thin media, and the naive quotient
//           returns 0 in float for x < 6e-8.
// GLSL twin: cloudmath/glsl/integration.glsl.
#ifndef CLOUDMATH_INTEGRATION_HPP
#define CLOUDMATH_INTEGRATION_HPP

#include "core.hpp"
#include "transmittance.hpp"

namespace cloudmath {

// integrate_scattering(S, sigma_t, ds) = S (1 - exp(-sigma_t ds)) / sigma_t, which is S ds
// at sigma_t = 0. Domain: sigma_t >= 0 and ds >= 0; negative sigma_t * ds is clamped to 0
// (a non-attenuating step). sigma_t * ds = +Inf gives 0.
template <class T, std::enable_if_t<detail::is_real_v<T>, int> = 0>
[[nodiscard]] inline T integrate_scattering(T S, T sigma_t, T ds) noexcept {
    return S * ds * one_minus_exp_neg_over_x(detail::max(sigma_t * ds, T(0)));
}

// RGB (or any N) source with per-channel extinction.
template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> integrate_scattering(const glm::vec<L, T, Q>& S,
                                                            const glm::vec<L, T, Q>& sigma_t,
                                                            T ds) noexcept {
    return detail::map(S, sigma_t, [ds](T s, T e) { return integrate_scattering(s, e, ds); });
}

// RGB source with grey (scalar) extinction: one exponential for all channels.
template <glm::length_t L, class T, glm::qualifier Q>
[[nodiscard]] inline glm::vec<L, T, Q> integrate_scattering(const glm::vec<L, T, Q>& S,
                                                            T sigma_t, T ds) noexcept {
    return S * integrate_scattering(T(1), sigma_t, ds);
}

// Front-to-back accumulation along a view ray.
//   Radiance:   T, or glm::vec<N, T> for colour.
//   Extinction: T (grey media) or the same vector type as Radiance (chromatic extinction).
// luminance starts at 0 and transmittance at 1; after the march the pixel is
// background * transmittance + luminance. Each add_segment is exact for a step with
// constant S and sigma_t, so the result does not depend on the step size for a
// homogeneous medium.
template <class Radiance, class Extinction = Radiance>
struct march_accumulator {
    Radiance luminance = Radiance(0);
    Extinction transmittance = Extinction(1);

    // Adds a step of length ds with source S (radiance per metre) and extinction sigma_t.
    // Works with scalar or vector S and sigma_t as integrate_scattering does.
    template <class Source, class Sigma, class Length>
    void add_segment(const Source& S, const Sigma& sigma_t, Length ds) noexcept {
        luminance += transmittance * integrate_scattering(S, sigma_t, ds);
        transmittance *= beer_lambert(sigma_t * ds);
    }

    // True once every channel's transmittance is below min_transmittance: the rest of the
    // ray can change the pixel by at most min_transmittance * (remaining radiance), so the
    // march may stop (the usual early-out).
    template <class Threshold>
    [[nodiscard]] constexpr bool is_opaque(Threshold min_transmittance) const noexcept {
        if constexpr (detail::is_real_v<Extinction>) {
            return transmittance < min_transmittance;
        } else {
            for (glm::length_t i = 0; i < Extinction::length(); ++i)
                if (!(transmittance[i] < min_transmittance)) return false;
            return true;
        }
    }

    // 1 - transmittance: the accumulated opacity (alpha) per channel.
    [[nodiscard]] constexpr Extinction opacity() const noexcept {
        return Extinction(1) - transmittance;
    }
};

}  // namespace cloudmath

#endif  // CLOUDMATH_INTEGRATION_HPP
