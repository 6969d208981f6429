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

}  // namespace cloudmath

#endif  // CLOUDMATH_MULTIPLE_SCATTERING_HPP
