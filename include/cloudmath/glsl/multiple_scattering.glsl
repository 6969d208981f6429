// cloudmath/glsl/multiple_scattering.glsl: GLSL twin of cloudmath/multiple_scattering.hpp,
// Wrenninge's octaves: sum_{i<N} b^i phase(mu, c^i g) exp(-a^i tau).
// Letters: a scales extinction, b the contribution, c the eccentricity (b <= a conserves
// energy); Frostbite's notes swap a and b.
//
// Configuration (#define before the include):
//   CM_MS_OCTAVES   octave count of the overloads without an `octaves` argument (default 3),
//                   a compile-time constant, so drivers unroll the loop.
//   CM_MS_PHASE     name of a user function `float f(float mu, float scale)` returning the
//                   phase function with eccentricities scaled by `scale` = c^i. When defined,
//                   cm_multiple_scattering_with(...) is available (the C++ generic form).
#ifndef CM_MULTIPLE_SCATTERING_GLSL
#define CM_MULTIPLE_SCATTERING_GLSL

#include "core.glsl"
#include "phase.glsl"
#include "transmittance.glsl"

#ifndef CM_MS_OCTAVES
#define CM_MS_OCTAVES 3
#endif

float cm_multiple_scattering(float optical_depth, float mu, float g, float a, float b, float c,
                             int octaves) {
    float sum = 0.0;
    float ai = 1.0, bi = 1.0, ci = 1.0;
    for (int i = 0; i < octaves; ++i) {
        sum += bi * cm_phase_hg(mu, ci * g) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}

// CM_MS_OCTAVES octaves (the C++ multiple_scattering<N>).
float cm_multiple_scattering(float optical_depth, float mu, float g, float a, float b, float c) {
    return cm_multiple_scattering(optical_depth, mu, g, a, b, c, CM_MS_OCTAVES);
}

#ifdef CM_MS_PHASE
float cm_multiple_scattering_with(float optical_depth, float mu, float a, float b, float c,
                                  int octaves) {
    float sum = 0.0;
    float ai = 1.0, bi = 1.0, ci = 1.0;
    for (int i = 0; i < octaves; ++i) {
        sum += bi * CM_MS_PHASE(mu, ci) * cm_beer_lambert(ai * optical_depth);
        ai *= a;
        bi *= b;
        ci *= c;
    }
    return sum;
}
float cm_multiple_scattering_with(float optical_depth, float mu, float a, float b, float c) {
    return cm_multiple_scattering_with(optical_depth, mu, a, b, c, CM_MS_OCTAVES);
}
#endif

#endif  // CM_MULTIPLE_SCATTERING_GLSL
