// cloudmath minimal example: prints phase-function values at a few scattering angles and a
// Beer-Lambert / Beer-Powder / Nubis attenuation curve, then lights one ray through a
// homogeneous cloud with the energy-conserving march accumulator.
//
// Build and run: bash scripts/main.sh (README's first command).
#include <cloudmath/cloudmath.hpp>

#include <cmath>
#include <cstdio>
#include <initializer_list>

int main() {
    namespace cm = cloudmath;

    std::printf("Phase functions (1/sr) against scattering angle; mu = cos(angle), forward = 0 deg\n");
    std::printf("%6s %10s %10s %12s %12s %12s %14s\n", "angle", "isotropic", "Rayleigh", "HG g=0.8",
                "dual HG", "Cornette-S.", "Mie d=10um");
    const cm::mie_approx_parameters<double> droplet = cm::mie_approx_params(10.0);  // once per medium
    for (double deg : {0.0, 1.0, 5.0, 30.0, 90.0, 150.0, 180.0}) {
        const double mu = std::cos(deg * cm::pi_v<double> / 180.0);
        std::printf("%6.0f %10.5f %10.5f %12.5f %12.5f %12.5f %14.5f\n", deg, cm::phase_isotropic<double>(),
                    cm::phase_rayleigh(mu), cm::phase_hg(mu, 0.8), cm::phase_hg_dual(mu, 0.8, -0.5, 0.5),
                    cm::phase_cornette_shanks(mu, 0.8), cm::phase_mie_approx(mu, droplet));
    }

    std::printf("\nTransmittance against optical depth tau\n");
    std::printf("%6s %12s %12s %12s %16s\n", "tau", "Beer", "Beer-Powder", "Nubis 2017", "3 octaves, 1/sr");
    for (double tau : {0.0, 0.25, 0.5493, 1.0, 2.0, 4.0, 8.0}) {
        std::printf("%6.4f %12.6f %12.6f %12.6f %16.6f\n", tau, cm::beer_lambert(tau), cm::beer_powder(tau),
                    cm::nubis_attenuation(tau), cm::multiple_scattering(tau, 0.5, 0.8, 0.5, 0.5, 0.5, 3));
    }
    std::printf("(Beer-Powder peaks at tau = ln(3)/2 = 0.5493 with 4/(3 sqrt 3) = 0.7698; octaves: mu = 0.5,\n"
                " g = 0.8, a = b = c = 0.5, the sum of phase times transmittance over 3 octaves)\n");

    // One view ray through 1 km of cloud (sigma_t = 0.05 1/m, albedo 1), sun at 60 degrees
    // from the view direction, light reaching each sample through 20 m of the same cloud.
    const float sigma_t = 0.05f, sun = 1.0f, mu = 0.5f;
    cm::march_accumulator<float> acc;
    int steps = 0;
    for (; steps < 64 && !acc.is_opaque(0.001f); ++steps) {
        const float light = sun * cm::beer_lambert(sigma_t * 20.0f);
        const float S = sigma_t * light * cm::phase_hg(mu, 0.8f);  // source per metre
        acc.add_segment(S, sigma_t, 1000.0f / 64.0f);
    }
    std::printf("\nMarch: %d of 64 steps before the early-out, luminance %.6g, transmittance %.3g\n", steps,
                static_cast<double>(acc.luminance), static_cast<double>(acc.transmittance));
    return 0;
}
