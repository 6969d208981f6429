// cloudmath/multiple_scattering.hpp: Wrenninge's multiple-scattering octave approximation.
//
// Use:      #include <cloudmath/multiple_scattering.hpp>
//           float w = cloudmath::multiple_scattering(tau_light, mu, 0.8f, 0.5f, 0.5f, 0.5f, 3);
//           S = sigma_s * L_light * w;     // source term of integration.hpp
// Source:   Wrenninge, Kulla & Lundqvist, "Oz: The Great and Volumetric", SIGGRAPH 2013
//           Talks; Wrenninge, "Art-directable multiple volumetric scattering", 2015:
//             L = sum_{i=0}^{N-1} sigma_s b^i L_light p(mu, c^i g) exp(-a^i tau).
// Letters:  a scales the extinction (attenuation), b the contribution (scattering), c the
//           eccentricity g. Energy is conserved only when b <= a (each octave contributes
//           no more than the light it lets through); this is documented, not enforced,
//           because art-directed values (for instance a = 0.3, b = 0.75) break it on purpose.
//           Hillaire's Frostbite notes (2016) name the attenuation factor b and the
//           contribution factor a: their (a, b, c) is our (b, a, c).
// Values:   a = b = c = 0.5 with 3 octaves is the usual production choice (Unreal's defaults).
//           ms_preset holds it and fitted sets, each with its error measured against a
//           Monte Carlo reference: cloudmath::multiple_scattering(tau, mu, g, ms_preset::thin).
// Returns:  the dimensionless sum of phase (1/sr) times transmittance weights, >= 0.
// GLSL twin: cloudmath/glsl/multiple_scattering.glsl (#define CM_MS_OCTAVES sets N).
#ifndef CLOUDMATH_MULTIPLE_SCATTERING_HPP
#define CLOUDMATH_MULTIPLE_SCATTERING_HPP

#include <cmath>

#include "core.hpp"
#include "phase.hpp"
#include "transmittance.hpp"

namespace cloudmath {

// Generic form: phase(mu, scale) must return the phase function for eccentricities scaled
// by `scale` = c^i (for example a dual lobe with g0 * scale, g1 * scale). octaves <= 0
// gives 0. The powers are running products, so a = 0 or b = 0 give the single-scattering
// term alone (0^0 = 1 for octave 0).
template <class T, class PhaseFn>
[[nodiscard]] inline T multiple_scattering_with(T optical_depth, T mu, T a, T b, T c,
                                                int octaves, PhaseFn&& phase) noexcept {
    T sum = T(0);
    T ai = T(1), bi = T(1), ci = T(1);
    for (int i = 0; i < octaves; ++i) {
        sum += bi * phase(mu, ci) * beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}

// Compile-time octave count: after inlining the loop above has a constant trip count, so
// compilers unroll it and a scene that uses one octave pays for one.
template <int Octaves, class T, class PhaseFn>
[[nodiscard]] inline T multiple_scattering_with(T optical_depth, T mu, T a, T b, T c,
                                                PhaseFn&& phase) noexcept {
    static_assert(Octaves >= 1, "at least one octave (the single-scattering term)");
    return multiple_scattering_with(optical_depth, mu, a, b, c, Octaves,
                                    static_cast<PhaseFn&&>(phase));
}

// sum over i < octaves of b^i HG(mu, c^i g) exp(-a^i tau) (DESIGN.md contract).
template <class T>
[[nodiscard]] inline T multiple_scattering(T optical_depth, T mu, T g, T a, T b, T c,
                                           int octaves) noexcept {
    return multiple_scattering_with(optical_depth, mu, a, b, c, octaves,
                                    [g](T m, T scale) { return phase_hg(m, scale * g); });
}

// Same with the octave count fixed at compile time.
template <int Octaves, class T>
[[nodiscard]] inline T multiple_scattering(T optical_depth, T mu, T g, T a, T b,
                                           T c) noexcept {
    return multiple_scattering_with<Octaves>(
        optical_depth, mu, a, b, c, [g](T m, T scale) { return phase_hg(m, scale * g); });
}

// A fitted parameter set with the error it was measured to have. The error is against a
// double-precision Monte Carlo path tracer (all orders of scattering) for a homogeneous
// sphere seen from 30 to 170 degrees around the sun and a slab under suns 0 to 80 degrees
// from the zenith, HG phase with g = 0.85, albedo 1, optical thickness tau_min to tau_max,
// with the sun term integrated exactly along each camera ray. Each ray's error is relative
// to the mean radiance of its image (one geometry, thickness and sun angle):
// rms_error = rms of (L_model - L_MC) / mean(L_MC), max_error = its largest magnitude
// (docs/lighting_error.md, measured by tools/reference/truths/lighting_report.cpp;
// tools/reference/truths/test_lighting_presets.cpp reproduces both from the reference data).
// Outside that range, or for a very different g, the error is not measured.
// What the numbers say: no choice of a, b, c and N brings the octaves below 50% rms over
// these ranges (they have no term for light diffusing around a shadowing core); the fitted
// presets cut the production values' error by a third to a half.
struct multiple_scattering_preset {
    const char* name;
    float a, b, c;  // Wrenninge's extinction, contribution and eccentricity factors
    int octaves;
    float tau_min, tau_max;  // optical thickness range the error holds for
    float rms_error, max_error;
};

namespace ms_preset {
// The common production values a = b = c = 0.5, 3 octaves, measured over 1-100.
inline constexpr multiple_scattering_preset production{"production", 0.5f, 0.5f, 0.5f, 3,
                                                       1.0f, 100.0f, 1.034f, 3.726f};
// Fitted over optical thickness 1-100 (5 octaves: more change the rms by < 0.2%).
inline constexpr multiple_scattering_preset fitted{"fitted", 0.197f, 0.409f, 0.800f, 5,
                                                   1.0f, 100.0f, 0.7096f, 3.649f};
// Fitted over optical thickness 1-100 with 2 octaves: within 10% (relative) of the lowest
// rms any octave model reaches there, at 2 exponentials per sample. The second octave is
// barely attenuated (a = 0.064): a broad, forward-leaning stand-in for the diffuse light.
inline constexpr multiple_scattering_preset cheap{"cheap", 0.0639f, 0.582f, 0.676f, 2,
                                                  1.0f, 100.0f, 0.7394f, 3.657f};
// Fitted over thin media, optical thickness 1-10 (3 octaves).
inline constexpr multiple_scattering_preset thin{"thin", 0.173f, 0.435f, 0.805f, 3,
                                                 1.0f, 10.0f, 0.5524f, 1.311f};
// Fitted over thick media, optical thickness 10-100 (6 octaves).
inline constexpr multiple_scattering_preset thick{"thick", 0.299f, 0.625f, 0.529f, 6,
                                                  10.0f, 100.0f, 0.5431f, 2.180f};
// Every preset, for tools and tests that go through them all.
inline constexpr multiple_scattering_preset all[] = {production, fitted, cheap, thin, thick};
}  // namespace ms_preset

// The octave sum with a preset's a, b, c and octave count.
template <class T>
[[nodiscard]] inline T multiple_scattering(T optical_depth, T mu, T g,
                                           const multiple_scattering_preset& preset) noexcept {
    return multiple_scattering(optical_depth, mu, g, T(preset.a), T(preset.b), T(preset.c),
                               preset.octaves);
}

}  // namespace cloudmath

#endif  // CLOUDMATH_MULTIPLE_SCATTERING_HPP
