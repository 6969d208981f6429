// tools/reference/truths/atmosphere_variants.hpp: the multiple-scattering model's variants that were
// measured against the sky's path-traced truth while the library's model was chosen (issue
// 26; docs/atmosphere.md, "Multiple scattering: what was tried"). Each variant is a whole
// float model, written out here apart from the library: a 32-row multiple-scattering LUT over
// (altitude, mu_s) with 64 rays of 20 steps per texel and the sky marched from sea level in 32
// steps, with the options below. `cloudmath_atmosphere_truth variants` prints their errors.
#ifndef CLOUDMATH_TOOLS_ATMOSPHERE_VARIANTS_HPP
#define CLOUDMATH_TOOLS_ATMOSPHERE_VARIANTS_HPP

#include <array>
#include <vector>

#include "atmosphere_truth.hpp"

namespace cloudmath::reference::atmo {

struct ms_variant {
    const char* name;
    bool rayleigh_phase;  // the second order turned by Rayleigh's phase (else isotropic)
    bool mie_phase;       // the second order turned by Cornette-Shanks (else isotropic)
    int passes;           // passes that gather the orders from the air around (0: Hillaire's series)
    bool sky_lit_ground;  // the ground also reflects the sky's irradiance (else the sun's only)
    bool sqrt_u;          // LUT columns by sign(mu_s) sqrt(|mu_s|) (else linear in mu_s)
    bool moment;          // Rayleigh scatters the field by its vertical second moment (else isotropic)
    int width;            // LUT columns
};

// The variants in the order they were tried.
std::vector<ms_variant> ms_variants();

// The sky's radiance (per unit sun illuminance, 1/sr) for each row under a variant.
std::vector<std::array<double, 3>> variant_radiance(const ms_variant& v, const std::vector<truth_row>& rows);

}  // namespace cloudmath::reference::atmo

#endif  // CLOUDMATH_TOOLS_ATMOSPHERE_VARIANTS_HPP
