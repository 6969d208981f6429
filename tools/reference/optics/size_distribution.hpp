// tools/reference/optics/size_distribution.hpp: cloud droplet size distributions and their mean
// Lorenz-Mie phase function, the reference that cloudmath's analytic phase functions (HG,
// dual HG, Draine, HG + Draine) are measured against.
//
// Usage:
//   using namespace cloudmath::reference;
//   mean_phase_settings s;                       // 0.55 um, water 1.333 - 1.96e-9 i
//   s.threads = 2;
//   const mean_phase_result r = compute_mean_phase(deirmendjian_c1(), s);
//   write_phase_table("mie_c1.csv", r.table);    // r.asymmetry_g is about 0.85
//
// Distributions: the modified gamma distribution n(r) = a r^alpha exp(-b r^gamma)
// (Deirmendjian 1969, "Electromagnetic Scattering on Spherical Polydispersions", ch. 6),
// r in micrometres, n(r) dr = number of droplets with radius in [r, r + dr] (per unit volume).
// Deirmendjian's cloud model C.1 is a = 2.373, alpha = 6, b = 1.5, gamma = 1 (100 droplets
// per cm^3, mode radius 4 um, effective radius (alpha + 3) / b = 6 um).
//
// Mean phase function (Hansen & Travis 1974, Space Sci. Rev. 16, 527, sec. 2): with
// k = 2 pi / lambda,
//   p(theta) = int n(r) (|S1|^2 + |S2|^2)(r, theta) dr / (2 k^2 int n(r) C_sca(r) dr)   [1/sr]
// normalised analytically by the mean scattering cross section, so that it integrates to 1
// up to the angular discretisation; the asymmetry parameter is the C_sca-weighted mean of
// the single-sphere g (Hansen & Travis eq. 2.51).
//
// Radius quadrature, in size parameter x = k r from 0 up to the radius where r^2 n(r) (the
// cross-section weight) has fallen to weight_cutoff times its maximum:
//   - the range is cut into cells of width size_parameter_step (midpoint rule);
//   - each cell is refined adaptively (split in three, the middle third reusing the centre
//     value) while the one- and three-point estimates of ANY tabulated quantity (the
//     intensity at every angle, the cross sections, ...) differ by more than
//     relative_tolerance times that quantity's whole integral, spread uniformly over x.
//     The tolerances come from a first pass with 4 times the step.
// Why adaptive: for nearly non-absorbing water the Mie efficiencies carry resonance spikes
// far narrower than any affordable uniform step; a uniform sample that lands on one turns
// its height times the step into noise, and the glory region (170-180 deg) then changes by
// about 1% each time the step is halved (measured: 0.05 -> 0.025 -> 0.0125 for C.1 at
// 0.55 um). Refinement around every sampled spike removes that noise.
// Defaults chosen by convergence for C.1 at 0.55 um (largest relative change over the
// 1231 angles of default_angles_deg(), always at 180 deg): halving the step 0.1 -> 0.05
// changes the table by 3e-5 (4e-5 for the r_eff = 10 um gamma distribution); against a
// reference with step 0.05 and tolerance 1e-4 the
// defaults (0.1, 1e-2) differ by 1.4e-4, (0.1, 3e-2) by 4e-4, (0.2, 0.1) by 2.3e-3.
//
// Threads: radii are cut into fixed chunks of consecutive radii; threads take chunks in turn
// and every chunk sums into its own buffer; the buffers are added in chunk order at the end.
// The result is therefore bit-identical for any thread count.
#ifndef CLOUDMATH_TOOLS_SIZE_DISTRIBUTION_HPP
#define CLOUDMATH_TOOLS_SIZE_DISTRIBUTION_HPP

#include <complex>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "phase_table.hpp"

namespace cloudmath::reference {

// n(r) = scale r^alpha exp(-b r^gamma), r in micrometres.
struct modified_gamma {
    double scale = 1.0;  // a, droplets per um (per unit volume)
    double alpha = 6.0;
    double b = 1.5;  // um^-gamma
    double gamma = 1.0;

    [[nodiscard]] double density(double r_um) const;
    // int r^3 n dr / int r^2 n dr = Gamma((alpha+4)/gamma) / Gamma((alpha+3)/gamma) b^(-1/gamma).
    [[nodiscard]] double effective_radius_um() const;
    // int n dr = scale Gamma((alpha+1)/gamma) / (gamma b^((alpha+1)/gamma)).
    [[nodiscard]] double total_number() const;
    // Radius of the maximum of r^2 n(r): ((alpha+2) / (b gamma))^(1/gamma).
    [[nodiscard]] double cross_section_mode_um() const;
    // Throws std::invalid_argument unless scale > 0, alpha > -1, b > 0, gamma > 0, all finite.
    void validate() const;
};

// Deirmendjian's cloud model C.1: 2.373 r^6 exp(-1.5 r).
[[nodiscard]] modified_gamma deirmendjian_c1();

// The modified gamma distribution with the given shape (alpha, gamma) and effective radius,
// normalised to one droplet in total: b = (Gamma((alpha+4)/gamma) / Gamma((alpha+3)/gamma) /
// r_eff)^gamma in closed form. alpha = 6, gamma = 1, r_eff = 6 reproduces C.1's shape.
[[nodiscard]] modified_gamma modified_gamma_from_effective_radius(double r_eff_um,
                                                                  double alpha = 6.0,
                                                                  double gamma = 1.0);

// Refractive index of liquid water at the wavelengths the tools use by default: 0.55 um
// -> 1.333 - 1.96e-9 i, 0.70 um -> 1.33 (Deirmendjian's value for C.1); other wavelengths
// have no default (std::nullopt): give the index explicitly.
[[nodiscard]] std::optional<std::complex<double>> default_water_index(double wavelength_um);

struct mean_phase_settings {
    double wavelength_um = 0.55;
    std::complex<double> refractive_index{1.333, -1.96e-9};  // sign of Im ignored (mie.hpp)
    double size_parameter_step = 0.1;
    double weight_cutoff = 1e-9;       // of r^2 n(r) relative to its maximum
    double relative_tolerance = 1e-2;  // adaptive refinement target per component
    int max_refinement_depth = 12;     // cells shrink to step / 3^depth at most
    std::vector<double> angles_deg;    // ascending 0 .. 180; empty: default_angles_deg()
    unsigned threads = 0;              // 0: std::thread::hardware_concurrency()
    bool normalize = true;             // divide the table by its integral (recorded in the result)
    // Called on the calling thread with the fraction of the work done (0 .. 1), a few times
    // per second and once with 1 at the end.
    std::function<void(double)> progress;
};

struct mean_phase_result {
    phase_table table;                           // no metadata; finalized
    double integral_before_normalisation = 0.0;  // the table's piecewise-linear integral
    double asymmetry_g = 0.0;                    // C_sca-weighted Mie g
    double mean_c_ext_um2 = 0.0;                 // per droplet: int n C_ext dr / int n dr
    double mean_c_sca_um2 = 0.0;
    double single_scattering_albedo = 0.0;  // mean C_sca / mean C_ext
    double number_integral = 0.0;           // int n dr by the radius quadrature
    double effective_radius_um = 0.0;       // by the radius quadrature
    double r_min_um = 0.0, r_max_um = 0.0;  // centres of the first and last base cell
    std::size_t cell_count = 0;             // base cells of width size_parameter_step
    std::size_t evaluation_count = 0;       // Mie evaluations, both passes
    double size_parameter_step = 0.0;
};

// Throws std::invalid_argument on bad settings or distribution.
[[nodiscard]] mean_phase_result compute_mean_phase(const modified_gamma& distribution,
                                                   const mean_phase_settings& settings);

}  // namespace cloudmath::reference

#endif  // CLOUDMATH_TOOLS_SIZE_DISTRIBUTION_HPP
