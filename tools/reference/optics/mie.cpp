// tools/reference/optics/mie.cpp: Lorenz-Mie series for a homogeneous sphere. See mie.hpp for the
// conventions and the sources (Bohren & Huffman 1983 ch. 4 / BHMIE; Wiscombe 1979, 1980).
#include "mie.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cloudmath::reference {

namespace {

constexpr double pi = 3.14159265358979323846;
using complex = std::complex<double>;

// psi_1(x) = sin x / x - cos x loses about -log10(x^2) digits to cancellation for small x;
// its Taylor series x^2/3 - x^4/30 + x^6/840 - x^8/45360 is exact to rounding for x < 0.1.
double riccati_psi1(double x) {
    if (x < 0.1) {
        const double x2 = x * x;
        return x2 * (1.0 / 3.0 - x2 * (1.0 / 30.0 - x2 * (1.0 / 840.0 - x2 / 45360.0)));
    }
    return std::sin(x) / x - std::cos(x);
}

// D_n(z) for n = 0 .. n_stop by downward recurrence from D = 0 at n_start (Wiscombe 1979,
// eq. 4.1 ff.): every downward step damps the error of the start value, and
// 15 |z|^(1/3) + 16 steps above max(n_stop, |z|) bring it below double precision.
std::vector<complex> log_derivative(complex z, std::size_t n_stop) {
    const double az = std::abs(z);
    const double start = std::max(static_cast<double>(n_stop), az) + 15.0 * std::cbrt(az) + 16.0;
    const auto n_start = static_cast<std::size_t>(std::ceil(start));
    std::vector<complex> d(n_stop + 1);
    complex dn(0.0, 0.0);
    for (std::size_t n = n_start; n > 0; --n) {
        const complex n_over_z = static_cast<double>(n) / z;
        dn = n_over_z - 1.0 / (dn + n_over_z);  // now D_(n-1)
        if (n - 1 <= n_stop) d[n - 1] = dn;
    }
    return d;
}

// Angular blocks small enough that the recurrence state and the four partial sums stay in
// the L1 cache; a fixed trip count lets the compiler vectorise the loop over angles.
constexpr std::size_t angle_block = 128;

// Per-term factors (2n+1)/(n(n+1)) a_n and (2n+1)/(n(n+1)) b_n split into real and imaginary
// arrays for the kernel below.
struct weighted_terms {
    std::vector<double> ar, ai, br, bi;
};

weighted_terms weight_terms(const mie_coefficients& c) {
    weighted_terms w;
    const std::size_t n_terms = c.a.size();
    w.ar.resize(n_terms);
    w.ai.resize(n_terms);
    w.br.resize(n_terms);
    w.bi.resize(n_terms);
    for (std::size_t i = 0; i < n_terms; ++i) {
        const auto n = static_cast<double>(i + 1);
        const double f = (2.0 * n + 1.0) / (n * (n + 1.0));
        w.ar[i] = f * c.a[i].real();
        w.ai[i] = f * c.a[i].imag();
        w.br[i] = f * c.b[i].real();
        w.bi[i] = f * c.b[i].imag();
    }
    return w;
}

// The state of the amplitude sums on one block of angles.
struct angle_block_state {
    double mu[angle_block];
    double pi_prev[angle_block];  // pi_(n-1)
    double pi_cur[angle_block];   // pi_n
    double s1r[angle_block], s1i[angle_block], s2r[angle_block], s2i[angle_block];
};

// Adds term n to S1 and S2 on a block and advances pi by the upward recurrence
//   pi_(n+1) = (2n+1)/n mu pi_n - (n+1)/n pi_(n-1),  tau_n = n mu pi_n - (n+1) pi_(n-1)
// (Bohren & Huffman eqs. 4.47). Kept out of line on purpose: inlined into the loop over n,
// GCC 12 at -O3 applies unroll-and-jam to the pair of loops and the whole computation runs
// about 1.8 times slower (measured); the call costs nothing next to 128 angles of work.
[[gnu::noinline]] void add_term(angle_block_state& s, double n, double ar, double ai, double br,
                                double bi) {
    const double up = (2.0 * n + 1.0) / n, down = (n + 1.0) / n;
    for (std::size_t j = 0; j < angle_block; ++j) {
        const double p = s.pi_cur[j];
        const double t = n * s.mu[j] * p - (n + 1.0) * s.pi_prev[j];
        s.s1r[j] += ar * p + br * t;
        s.s1i[j] += ai * p + bi * t;
        s.s2r[j] += ar * t + br * p;
        s.s2i[j] += ai * t + bi * p;
        s.pi_cur[j] = up * s.mu[j] * p - down * s.pi_prev[j];
        s.pi_prev[j] = p;
    }
}

// Computes S1, S2 at every cosine, block by block, and hands them to
// sink(j, s1r, s1i, s2r, s2i). The recurrence starts from pi_0 = 0, pi_1 = 1.
template <class Sink>
void amplitude_blocks(const weighted_terms& w, const std::vector<double>& mu_in, Sink&& sink) {
    const std::size_t n_terms = w.ar.size();
    angle_block_state s;
    for (std::size_t j0 = 0; j0 < mu_in.size(); j0 += angle_block) {
        const std::size_t count = std::min(angle_block, mu_in.size() - j0);
        for (std::size_t j = 0; j < angle_block; ++j) {
            s.mu[j] = j < count ? std::clamp(mu_in[j0 + j], -1.0, 1.0) : 0.0;
            s.pi_prev[j] = 0.0;
            s.pi_cur[j] = 1.0;
            s.s1r[j] = s.s1i[j] = s.s2r[j] = s.s2i[j] = 0.0;
        }
        for (std::size_t i = 0; i < n_terms; ++i)
            add_term(s, static_cast<double>(i + 1), w.ar[i], w.ai[i], w.br[i], w.bi[i]);
        for (std::size_t j = 0; j < count; ++j)
            sink(j0 + j, s.s1r[j], s.s1i[j], s.s2r[j], s.s2i[j]);
    }
}

}  // namespace

std::size_t mie_term_count(double size_parameter) {
    const double n = size_parameter + 4.0 * std::cbrt(size_parameter) + 2.0;
    return std::max<std::size_t>(1, static_cast<std::size_t>(n));
}

mie_coefficients compute_mie_coefficients(complex m, double x) {
    if (!(x >= mie_min_size_parameter) || !std::isfinite(x) || !std::isfinite(m.real()) ||
        !std::isfinite(m.imag()) || !(m.real() > 0.0))
        throw std::invalid_argument(
            "Mie: need a finite size parameter >= 1e-30 (mie_min_size_parameter) and Re(m) > 0");
    if (!(std::abs(m) <= mie_max_index_modulus) || !(std::abs(m) * x <= mie_max_index_size_parameter))
        throw std::invalid_argument("Mie: need |m| <= 1000 and |m| x <= 1e6 (mie_max_index_modulus, "
                                    "mie_max_index_size_parameter): the series' recurrence runs |m| x steps");
    // Bohren & Huffman's formulas assume exp(-i omega t), absorption as +i k: work with that
    // and conjugate the coefficients at the end (the efficiencies do not change).
    const complex m_bh(m.real(), std::abs(m.imag()));
    const std::size_t n_stop = mie_term_count(x);
    const std::vector<complex> d = log_derivative(m_bh * x, n_stop);

    mie_coefficients c;
    c.size_parameter = x;
    c.refractive_index = m;
    c.a.resize(n_stop);
    c.b.resize(n_stop);
    // psi_(n-1), psi_n and chi_(n-1), chi_n, starting at n = 1 from psi_0 = sin x,
    // chi_0 = cos x (Bohren & Huffman eqs. 4.88-4.89; xi = psi - i chi).
    double psi_prev = std::sin(x), psi = riccati_psi1(x);
    double chi_prev = std::cos(x), chi = std::cos(x) / x + std::sin(x);
    for (std::size_t i = 0; i < n_stop; ++i) {
        const auto n = static_cast<double>(i + 1);
        if (i > 0) {
            const double f = (2.0 * n - 1.0) / x;
            const double psi_next = f * psi - psi_prev;
            const double chi_next = f * chi - chi_prev;
            psi_prev = psi;
            psi = psi_next;
            chi_prev = chi;
            chi = chi_next;
        }
        const complex xi(psi, -chi), xi_prev(psi_prev, -chi_prev);
        const complex da = d[i + 1] / m_bh + n / x;
        const complex db = m_bh * d[i + 1] + n / x;
        const complex a = (da * psi - psi_prev) / (da * xi - xi_prev);
        const complex b = (db * psi - psi_prev) / (db * xi - xi_prev);
        c.a[i] = std::conj(a);
        c.b[i] = std::conj(b);
    }
    return c;
}

mie_efficiencies compute_efficiencies(const mie_coefficients& c) {
    // Bohren & Huffman eqs. 4.61, 4.62, 4.74 and the backscatter series of BHMIE.
    const double x = c.size_parameter;
    const std::size_t n_terms = c.a.size();
    double ext = 0.0, sca = 0.0, gsum = 0.0;
    complex back(0.0, 0.0);
    for (std::size_t i = 0; i < n_terms; ++i) {
        const auto n = static_cast<double>(i + 1);
        const complex a = c.a[i], b = c.b[i];
        ext += (2.0 * n + 1.0) * (a.real() + b.real());
        sca += (2.0 * n + 1.0) * (std::norm(a) + std::norm(b));
        gsum += (2.0 * n + 1.0) / (n * (n + 1.0)) * (a * std::conj(b)).real();
        if (i + 1 < n_terms) {
            const complex a1 = c.a[i + 1], b1 = c.b[i + 1];
            gsum += n * (n + 2.0) / (n + 1.0) * (a * std::conj(a1) + b * std::conj(b1)).real();
        }
        back += (i % 2 == 0 ? -1.0 : 1.0) * (2.0 * n + 1.0) * (a - b);
    }
    mie_efficiencies e;
    e.q_ext = 2.0 / (x * x) * ext;
    e.q_sca = 2.0 / (x * x) * sca;
    e.q_abs = e.q_ext - e.q_sca;
    e.q_back = std::norm(back) / (x * x);
    e.g = e.q_sca > 0.0 ? 4.0 / (x * x) * gsum / e.q_sca : 0.0;
    return e;
}

void compute_amplitudes(const mie_coefficients& c, const std::vector<double>& mu,
                        std::vector<complex>& s1, std::vector<complex>& s2) {
    s1.assign(mu.size(), complex(0.0, 0.0));
    s2.assign(mu.size(), complex(0.0, 0.0));
    amplitude_blocks(weight_terms(c), mu,
                     [&](std::size_t j, double s1r, double s1i, double s2r, double s2i) {
                         s1[j] = complex(s1r, s1i);
                         s2[j] = complex(s2r, s2i);
                     });
}

void accumulate_intensity(const mie_coefficients& c, const std::vector<double>& mu, double weight,
                          std::vector<double>& sum) {
    if (sum.size() < mu.size()) sum.resize(mu.size(), 0.0);
    amplitude_blocks(weight_terms(c), mu,
                     [&](std::size_t j, double s1r, double s1i, double s2r, double s2i) {
                         sum[j] += weight * (s1r * s1r + s1i * s1i + s2r * s2r + s2i * s2i);
                     });
}

mie_result solve_mie(complex m, double size_parameter, const std::vector<double>& mu) {
    const mie_coefficients c = compute_mie_coefficients(m, size_parameter);
    mie_result r;
    r.efficiencies = compute_efficiencies(c);
    r.terms = c.a.size();
    r.mu = mu;
    compute_amplitudes(c, mu, r.s1, r.s2);
    return r;
}

double unpolarized_phase(complex s1, complex s2, double size_parameter, double q_sca) {
    return (std::norm(s1) + std::norm(s2)) / (2.0 * pi * size_parameter * size_parameter * q_sca);
}

}  // namespace cloudmath::reference
