// tools/reference/optics/mie.hpp: Lorenz-Mie scattering by a homogeneous sphere, in double precision.
// The ground truth for cloud droplet phase functions (see size_distribution.hpp).
//
// Usage:
//   const auto r = cloudmath::reference::solve_mie({1.33, -1e-5}, 100.0, {1.0, 0.0, -1.0});
//   r.efficiencies.q_ext, r.efficiencies.g, r.s1[0], unpolarized_phase(r.s1[1], r.s2[1], ...)
//
// Algorithm: Bohren & Huffman (1983), "Absorption and Scattering of Light by Small
// Particles", ch. 4 and appendix A (BHMIE), with the choices of Wiscombe (1979, NCAR/TN-140,
// "Mie scattering calculations: advances in technique and fast, vector-speed computer codes";
// 1980, Appl. Opt. 19, 1505, MIEV0):
//   - number of terms n_stop = x + 4 x^(1/3) + 2;
//   - logarithmic derivative D_n(m x) = psi_n'(m x) / psi_n(m x) by DOWNWARD recurrence
//     D_(n-1) = n/z - 1/(D_n + n/z), started at D = 0 about 15 |m x|^(1/3) + 16 terms above
//     max(n_stop, |m x|), where the starting error has died out (it shrinks every step);
//   - Riccati-Bessel psi_n(x), chi_n(x) by upward recurrence (stable up to n_stop),
//     xi = psi - i chi;
//   - angular functions pi_n(mu), tau_n(mu) by upward recurrence.
// Valid and tested for size parameters 1e-3 .. 1e4 and any absorption; accepted from
// mie_min_size_parameter = 1e-30 (see there) upward.
//
// Conventions:
//   - x = 2 pi r / lambda (size parameter), m = relative refractive index (droplet / medium).
//   - Absorption: m = n - i k with k >= 0 (Wiscombe's and REFERENCES.md's sign, time factor
//     exp(+i omega t)). Both signs of Im(m) are accepted and mean the same absorbing sphere:
//     only |Im m| is used.
//   - The amplitudes S1, S2 and the coefficients a_n, b_n are returned in that same
//     exp(+i omega t) convention (the complex conjugates of Bohren & Huffman's values):
//     Wiscombe's test case m = 1.5 - i, x = 1 gives S1(0) = 0.584080 + 0.190515 i.
//   - theta is the scattering angle, theta = 0 is forward; the amplitudes are indexed by
//     mu = cos(theta) (mu = 1 forward, as in cloudmath).
//   - Efficiencies are cross sections over the geometric cross section pi r^2. q_back is
//     Bohren & Huffman's backscattering efficiency |S(180 deg)|^2 4 / x^2 (equal to 4 pi
//     times the differential cross section at 180 deg over pi r^2).
//   - Unpolarized incident light: the differential scattering cross section is
//     (|S1|^2 + |S2|^2) / (2 k^2), so the phase function normalised to 1 over the sphere is
//     p(mu) = (|S1|^2 + |S2|^2) / (2 k^2 C_sca) = (|S1|^2 + |S2|^2) / (2 pi x^2 Q_sca)  [1/sr]
//     using k^2 C_sca = k^2 pi r^2 Q_sca = pi x^2 Q_sca.
#ifndef CLOUDMATH_TOOLS_MIE_HPP
#define CLOUDMATH_TOOLS_MIE_HPP

#include <complex>
#include <cstddef>
#include <vector>

namespace cloudmath::reference {

// The smallest size parameter accepted. Small spheres are the Rayleigh limit (Bohren &
// Huffman sec. 5.2: Q_sca = 8/3 x^4 |K|^2, Q_abs = 4 x Im K, K = (m^2 - 1)/(m^2 + 2)), which
// the series reproduces to rounding down to about x = 1e-50 (tested at 1e-30). Below that
// the coefficients' squares (|a_1|^2 ~ x^6) underflow: Q_sca and the phase function became
// 0 and NaN near x = 1e-54, every efficiency NaN (2 / x^2 overflows) below 1e-154, with no
// error. 1e-30 keeps 20 orders of margin; no droplet distribution comes near it (their
// smallest size parameter is about 1e-6 times the quadrature step).
inline constexpr double mie_min_size_parameter = 1e-30;

// The largest refractive index modulus and |m| x accepted. The log-derivative recurrence runs
// down from above |m| x, one step each: 1e6 steps take milliseconds; |m| = 1e9 at x = 10 ran
// for minutes, and |m| = 1e19 overflowed the start index's conversion to size_t (undefined
// behaviour) and printed a wrong Q_ext. Water, ice and absorbing aerosols have |m| < 3;
// metals in the visible reach tens.
inline constexpr double mie_max_index_modulus = 1000.0;
inline constexpr double mie_max_index_size_parameter = 1e6;

// Wiscombe's number of series terms: floor(x + 4 x^(1/3) + 2), at least 1.
[[nodiscard]] std::size_t mie_term_count(double size_parameter);

// The Mie series coefficients a_n, b_n (n = 1 .. n_stop, stored at index n - 1), in the
// exp(+i omega t) convention described above.
struct mie_coefficients {
    double size_parameter = 0.0;
    std::complex<double> refractive_index;  // as given by the caller
    std::vector<std::complex<double>> a;
    std::vector<std::complex<double>> b;
};

// Throws std::invalid_argument for x < mie_min_size_parameter (so for x <= 0), non-finite
// input, Re(m) <= 0, |m| > mie_max_index_modulus or |m| x > mie_max_index_size_parameter.
[[nodiscard]] mie_coefficients compute_mie_coefficients(std::complex<double> m,
                                                        double size_parameter);

struct mie_efficiencies {
    double q_ext = 0.0;   // extinction efficiency
    double q_sca = 0.0;   // scattering efficiency
    double q_abs = 0.0;   // q_ext - q_sca
    double q_back = 0.0;  // backscattering efficiency (see the conventions above)
    double g = 0.0;       // asymmetry parameter <cos theta>
};

[[nodiscard]] mie_efficiencies compute_efficiencies(const mie_coefficients& c);

// S1(mu) and S2(mu) for every cosine in mu (any order, each clamped to [-1, 1]).
void compute_amplitudes(const mie_coefficients& c, const std::vector<double>& mu,
                        std::vector<std::complex<double>>& s1,
                        std::vector<std::complex<double>>& s2);

// Adds weight * (|S1(mu_j)|^2 + |S2(mu_j)|^2) to sum[j] for every j (sum is resized to
// mu.size() if it is smaller). The kernel of the size-distribution averages: no allocation
// of amplitude arrays, angles processed in cache-sized blocks.
void accumulate_intensity(const mie_coefficients& c, const std::vector<double>& mu, double weight,
                          std::vector<double>& sum);

// Everything for one sphere: efficiencies and the amplitudes at the given cosines.
struct mie_result {
    mie_efficiencies efficiencies;
    std::size_t terms = 0;
    std::vector<double> mu;
    std::vector<std::complex<double>> s1;
    std::vector<std::complex<double>> s2;
};

[[nodiscard]] mie_result solve_mie(std::complex<double> m, double size_parameter,
                                   const std::vector<double>& mu = {});

// Phase function of one sphere for unpolarized light [1/sr], normalised over the sphere:
// (|S1|^2 + |S2|^2) / (2 pi x^2 Q_sca).
[[nodiscard]] double unpolarized_phase(std::complex<double> s1, std::complex<double> s2,
                                       double size_parameter, double q_sca);

}  // namespace cloudmath::reference

#endif  // CLOUDMATH_TOOLS_MIE_HPP
