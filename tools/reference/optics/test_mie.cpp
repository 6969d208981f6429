// tools/reference/optics/test_mie.cpp: tests of the Lorenz-Mie reference (mie.hpp) and the droplet
// distributions (size_distribution.hpp). Reference values: the "Lorenz-Mie validation
// values" of REFERENCES.md (Wiscombe 1979 MIEV0 test cases, also used by miepython), the
// Rayleigh limit (Bohren & Huffman 1983 sec. 5.2), the optical theorem, Deirmendjian's C.1
// claims of REFERENCES.md, and independent quadratures written here.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <stdexcept>
#include <vector>

#include "mie.hpp"
#include "size_distribution.hpp"

using namespace cloudmath::reference;
using complex = std::complex<double>;

namespace {

constexpr double pi = 3.14159265358979323846;

double relative_error(double value, double reference) {
    return std::abs(value - reference) / std::abs(reference);
}

// Composite Simpson rule on [a, b] with an even number of intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int intervals) {
    const double h = (b - a) / intervals;
    double s = f(a) + f(b);
    for (int i = 1; i < intervals; ++i) s += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
    return s * h / 3.0;
}

// Henyey-Greenstein, closed form (Henyey & Greenstein 1941), mu = 1 forward.
double henyey_greenstein(double mu, double g) {
    return (1.0 - g * g) / (4.0 * pi * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
}

struct validation_case {
    double n, k, x;
    double q_ext;  // 0 where REFERENCES.md gives none (then Q_ext = Q_sca: no absorption)
    double q_sca, g;
};

}  // namespace

TEST_CASE("Mie matches every validation value of REFERENCES.md to 1e-5") {
    const validation_case cases[] = {
        {1.55, 0.0, 2.0 * pi * 0.525 / 0.6328, 3.10543, 3.10543, 0.63314},
        {0.75, 0.0, 10.0, 0.0, 2.232265, 0.896473},
        {0.75, 0.0, 1000.0, 0.0, 1.997908, 0.844944},
        {1.33, -1e-5, 100.0, 2.101321, 2.096594, 0.868959},
        {1.33, -1e-5, 10000.0, 2.004089, 1.723857, 0.907840},
        {1.5, -1.0, 1.0, 2.336321, 0.663454, 0.192136},
    };
    for (const auto& c : cases) {
        CAPTURE(c.n);
        CAPTURE(c.k);
        CAPTURE(c.x);
        const mie_efficiencies e = compute_efficiencies(compute_mie_coefficients({c.n, c.k}, c.x));
        CHECK(relative_error(e.q_ext, c.q_ext > 0.0 ? c.q_ext : c.q_sca) < 1e-5);
        CHECK(relative_error(e.q_sca, c.q_sca) < 1e-5);
        CHECK(relative_error(e.g, c.g) < 1e-5);
        CHECK(std::abs(e.q_abs - (e.q_ext - e.q_sca)) < 1e-15);
    }
}

TEST_CASE("S1 of m = 1.5 - i, x = 1 at 0, 90 and 180 deg matches REFERENCES.md to 1e-5") {
    const complex expected[] = {{0.584080, 0.190515}, {0.456340, 0.167167}, {0.348844, 0.146829}};
    const mie_result r = solve_mie({1.5, -1.0}, 1.0, {1.0, 0.0, -1.0});
    for (int i = 0; i < 3; ++i) {
        CAPTURE(i);
        CHECK(std::abs(r.s1[static_cast<std::size_t>(i)] - expected[i]) / std::abs(expected[i]) <
              1e-5);
    }
    // The sign of Im(m) does not matter: +i gives the same sphere and the same amplitudes.
    const mie_result plus = solve_mie({1.5, 1.0}, 1.0, {1.0, 0.0, -1.0});
    for (std::size_t i = 0; i < 3; ++i) CHECK(plus.s1[i] == r.s1[i]);
    CHECK(plus.efficiencies.q_ext == r.efficiencies.q_ext);
}

TEST_CASE("Rayleigh limit at x = 1e-3") {
    const double x = 1e-3;
    for (const complex m : {complex(1.33, 0.0), complex(1.5, -1.0), complex(0.75, 0.0)}) {
        CAPTURE(m);
        const complex m2 = m * m;
        const complex polarizability = (m2 - 1.0) / (m2 + 2.0);
        const double k2 = std::norm(polarizability);
        std::vector<double> mu;
        for (int i = 0; i <= 20; ++i) mu.push_back(1.0 - i / 10.0);
        const mie_result r = solve_mie(m, x, mu);
        // Bohren & Huffman eqs. 5.8-5.9; corrections are O(x^2) = 1e-6 relative.
        CHECK(relative_error(r.efficiencies.q_sca, 8.0 / 3.0 * std::pow(x, 4) * k2) < 1e-5);
        CHECK(relative_error(r.efficiencies.q_back, 4.0 * std::pow(x, 4) * k2) < 1e-5);
        const double q_abs = 4.0 * x * std::abs(polarizability.imag());
        if (q_abs > 0.0)
            CHECK(relative_error(r.efficiencies.q_abs, q_abs) < 1e-5);
        else
            CHECK(std::abs(r.efficiencies.q_abs) < 1e-6 * r.efficiencies.q_sca);
        CHECK(std::abs(r.efficiencies.g) < 1e-5);
        for (std::size_t j = 0; j < mu.size(); ++j) {
            const double p = unpolarized_phase(r.s1[j], r.s2[j], x, r.efficiencies.q_sca);
            CHECK(relative_error(p, 3.0 * (1.0 + mu[j] * mu[j]) / (16.0 * pi)) < 1e-5);
        }
    }
}

TEST_CASE("tiny spheres: the Rayleigh limit to rounding down to x = 1e-30, below it an error") {
    // Bohren & Huffman eqs. 5.8-5.9, whose O(x^2) corrections vanish here. Before the
    // mie_min_size_parameter check, x = 1e-160 gave Q_ext = NaN and no error.
    for (const complex m : {complex(1.33, 0.0), complex(1.5, -1.0), complex(1.333, -1.96e-9)})
        for (const double x : {1e-10, 1e-20, mie_min_size_parameter}) {
            CAPTURE(m);
            CAPTURE(x);
            const complex m2 = m * m;
            const complex polarizability = (m2 - 1.0) / (m2 + 2.0);
            const mie_result r = solve_mie(m, x, {1.0, 0.0, -1.0});
            const double q_sca = 8.0 / 3.0 * std::pow(x, 4) * std::norm(polarizability);
            const double q_abs = 4.0 * x * std::abs(polarizability.imag());
            CHECK(relative_error(r.efficiencies.q_sca, q_sca) < 1e-12);
            CHECK(relative_error(r.efficiencies.q_ext, q_sca + q_abs) < 1e-12);
            CHECK(std::abs(r.efficiencies.g) < 1e-12);
            for (std::size_t j = 0; j < 3; ++j) {
                const double mu = r.mu[j];
                CHECK(relative_error(unpolarized_phase(r.s1[j], r.s2[j], x, r.efficiencies.q_sca),
                                     3.0 * (1.0 + mu * mu) / (16.0 * pi)) < 1e-12);
            }
        }
    for (const double x : {0.99 * mie_min_size_parameter, 1e-160, 0.0, -1.0})
        CHECK_THROWS_AS((void)compute_mie_coefficients({1.33, 0.0}, x), std::invalid_argument);
}

TEST_CASE("single-sphere phase function integrates to 1 and its mean cosine is g") {
    // Simpson in theta, 2 pi int p sin(theta) dtheta, fine enough for the forward peak
    // (angular width about 1/x).
    struct sphere {
        complex m;
        double x;
        int intervals;
    };
    for (const sphere s : {sphere{{1.55, 0.0}, 5.2128, 4000}, sphere{{1.33, -1e-5}, 100.0, 40000},
                           sphere{{1.5, -1.0}, 30.0, 20000}, sphere{{0.75, 0.0}, 300.0, 100000}}) {
        CAPTURE(s.x);
        std::vector<double> theta, mu;
        const double h = pi / s.intervals;
        for (int i = 0; i <= s.intervals; ++i) {
            theta.push_back(i * h);
            mu.push_back(std::cos(i * h));
        }
        const mie_result r = solve_mie(s.m, s.x, mu);
        double norm = 0.0, mean_cos = 0.0;
        for (int i = 0; i <= s.intervals; ++i) {
            const auto j = static_cast<std::size_t>(i);
            const double w = (i == 0 || i == s.intervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
            const double p = unpolarized_phase(r.s1[j], r.s2[j], s.x, r.efficiencies.q_sca);
            norm += w * p * std::sin(theta[j]);
            mean_cos += w * p * std::sin(theta[j]) * mu[j];
        }
        norm *= 2.0 * pi * h / 3.0;
        mean_cos *= 2.0 * pi * h / 3.0;
        CHECK(std::abs(norm - 1.0) < 1e-7);
        CHECK(std::abs(mean_cos - r.efficiencies.g) < 1e-7);
    }
}

TEST_CASE("optical theorem: Q_ext = 4 / x^2 Re S(0)") {
    for (const complex m :
         {complex(1.33, -1e-5), complex(1.5, -1.0), complex(0.75, 0.0), complex(2.0, -0.1)})
        for (const double x : {0.01, 0.5, 3.0, 50.0, 2000.0}) {
            CAPTURE(m);
            CAPTURE(x);
            const mie_result r = solve_mie(m, x, {1.0});
            CHECK(std::abs(r.s1[0] - r.s2[0]) <= 1e-12 * std::abs(r.s1[0]));
            CHECK(relative_error(4.0 / (x * x) * r.s1[0].real(), r.efficiencies.q_ext) < 1e-10);
        }
}

TEST_CASE("x from 1e-3 to 1e4: finite, Q_sca <= Q_ext, |g| <= 1; x = 1e4 amplitudes finite") {
    for (const complex m : {complex(1.33, 0.0), complex(1.333, -1.96e-9), complex(1.5, -1.0),
                            complex(0.75, 0.0), complex(1.33, -0.5)}) {
        for (double x = 1e-3; x <= 1.0001e4; x *= 1.6) {
            CAPTURE(m);
            CAPTURE(x);
            const mie_efficiencies e = compute_efficiencies(compute_mie_coefficients(m, x));
            REQUIRE(std::isfinite(e.q_ext));
            REQUIRE(std::isfinite(e.q_sca));
            REQUIRE(std::isfinite(e.q_back));
            REQUIRE(std::isfinite(e.g));
            CHECK(e.q_sca > 0.0);
            CHECK(e.q_sca <= e.q_ext * (1.0 + 1e-9));
            CHECK(std::abs(e.g) <= 1.0);
        }
        const mie_result r = solve_mie(m, 1e4, {1.0, 0.9999, 0.5, 0.0, -0.5, -1.0});
        CHECK(r.efficiencies.q_ext > 1.99);
        CHECK(r.efficiencies.q_ext < 2.02);  // extinction paradox: Q_ext -> 2
        for (std::size_t j = 0; j < r.s1.size(); ++j) {
            CHECK(std::isfinite(r.s1[j].real()));
            CHECK(std::isfinite(r.s1[j].imag()));
            CHECK(std::isfinite(r.s2[j].real()));
            CHECK(std::isfinite(r.s2[j].imag()));
        }
    }
}

TEST_CASE("bad sphere input throws") {
    // Hardening round 2, B1: a huge |m| overflowed the recurrence's start index (undefined
    // behaviour, a wrong Q_ext) or ran for minutes.
    CHECK_THROWS_AS((void)compute_mie_coefficients({1.33, 1e19}, 10.0), std::invalid_argument);
    CHECK_THROWS_AS((void)compute_mie_coefficients({1.33, 1e9}, 10.0), std::invalid_argument);
    CHECK_THROWS_AS((void)compute_mie_coefficients({1001.0, 0.0}, 1.0), std::invalid_argument);
    CHECK_THROWS_AS((void)compute_mie_coefficients({900.0, 0.0}, 2000.0), std::invalid_argument);
    CHECK_NOTHROW((void)compute_mie_coefficients({999.0, 0.0}, 1000.0));  // |m| x = 999000: accepted
    CHECK_THROWS_AS((void)compute_mie_coefficients({1.33, 0.0}, 0.0), std::invalid_argument);
    CHECK_THROWS_AS((void)compute_mie_coefficients({0.0, 0.0}, 1.0), std::invalid_argument);
    CHECK_THROWS_AS((void)compute_mie_coefficients({1.33, 0.0}, std::nan("")),
                    std::invalid_argument);
}

TEST_CASE("modified gamma: effective radius solve and normalisation by independent quadrature") {
    struct shape {
        double r_eff, alpha, gamma;
    };
    for (const shape s : {shape{6.0, 6.0, 1.0}, shape{5.0, 6.0, 1.0}, shape{20.0, 6.0, 1.0},
                          shape{8.0, 2.0, 0.5}, shape{12.0, 1.0, 3.0}}) {
        CAPTURE(s.r_eff);
        CAPTURE(s.alpha);
        CAPTURE(s.gamma);
        const modified_gamma d = modified_gamma_from_effective_radius(s.r_eff, s.alpha, s.gamma);
        const double r_top = 60.0 * s.r_eff * (s.gamma < 1.0 ? 10.0 : 1.0);
        const auto moment = [&](int power) {
            return simpson([&](double r) { return std::pow(r, power) * d.density(r); }, 0.0, r_top,
                           400000);
        };
        CHECK(relative_error(moment(3) / moment(2), s.r_eff) < 1e-8);
        CHECK(relative_error(moment(0), 1.0) < 1e-6);
        CHECK(relative_error(d.effective_radius_um(), s.r_eff) < 1e-12);
    }
    // C.1 is the r_eff = 6 um member of the alpha = 6, gamma = 1 family; 2.373 r^6 e^-1.5r
    // holds 2.373 * 6! / 1.5^7 = 99.998 droplets.
    const modified_gamma c1 = deirmendjian_c1();
    CHECK(std::abs(modified_gamma_from_effective_radius(6.0).b - 1.5) < 1e-12);
    CHECK(relative_error(c1.effective_radius_um(), 6.0) < 1e-12);
    CHECK(relative_error(c1.total_number(), 2.373 * 720.0 / std::pow(1.5, 7)) < 1e-12);
    CHECK(relative_error(c1.density(4.0), 2.373 * 4096.0 * std::exp(-6.0)) < 1e-14);
    CHECK_THROWS_AS((void)modified_gamma_from_effective_radius(-1.0), std::invalid_argument);
    CHECK_THROWS_AS((void)modified_gamma_from_effective_radius(5.0, -2.0), std::invalid_argument);
}

TEST_CASE("default water indices") {
    CHECK(default_water_index(0.55) == complex(1.333, -1.96e-9));
    CHECK(default_water_index(0.70) == complex(1.33, 0.0));
    CHECK_FALSE(default_water_index(1.6).has_value());
}

TEST_CASE("distribution result does not depend on the thread count") {
    // Small droplets at a long wavelength: cheap, yet many cells and refinements.
    mean_phase_settings s;
    s.wavelength_um = 2.0;
    s.refractive_index = {1.33, 0.0};
    s.size_parameter_step = 0.2;
    s.angles_deg = {0.0, 10.0, 45.0, 90.0, 135.0, 170.0, 180.0};
    const modified_gamma d = modified_gamma_from_effective_radius(3.0);
    s.threads = 1;
    const mean_phase_result one = compute_mean_phase(d, s);
    for (unsigned threads : {2u, 3u}) {
        s.threads = threads;
        const mean_phase_result many = compute_mean_phase(d, s);
        CHECK(many.table.phase == one.table.phase);
        CHECK(many.asymmetry_g == one.asymmetry_g);
        CHECK(many.mean_c_sca_um2 == one.mean_c_sca_um2);
    }
    CHECK(one.evaluation_count > one.cell_count);
    CHECK(relative_error(one.effective_radius_um, 3.0) < 1e-3);
}

TEST_CASE("Deirmendjian C.1 at 0.55 um: g, normalisation and the HG claims of REFERENCES.md") {
    // Coarser than the tool's defaults (step 0.2, tolerance 0.1) to keep the test short; at
    // this resolution the table is within 2.3e-3 of the converged one at every angle
    // (measured against step 0.05, tolerance 1e-4), and g within 2e-5.
    mean_phase_settings s;  // 0.55 um, 1.333 - 1.96e-9 i, default_angles_deg()
    s.size_parameter_step = 0.2;
    s.relative_tolerance = 0.1;
    s.threads = 1;
    double last_progress = -1.0;
    bool progress_monotonic = true;
    s.progress = [&](double f) {
        progress_monotonic = progress_monotonic && f >= last_progress && f <= 1.0;
        last_progress = f;
    };
    const mean_phase_result r = compute_mean_phase(deirmendjian_c1(), s);
    CHECK(progress_monotonic);
    CHECK(last_progress == 1.0);

    // REFERENCES.md: "g is about 0.853" (three digits).
    CHECK(std::abs(r.asymmetry_g - 0.853) < 1.5e-3);
    // The table, analytically normalised by the mean C_sca, integrates to 1 up to the
    // angular grid; its own mean cosine agrees with the Mie efficiencies' g.
    CHECK(std::abs(r.integral_before_normalisation - 1.0) < 1e-3);
    CHECK(std::abs(r.table.integral() - 1.0) < 1e-12);
    CHECK(std::abs(r.table.mean_cosine() - r.asymmetry_g) < 1e-3);
    // The quadrature reproduces the distribution's closed-form moments.
    CHECK(relative_error(r.effective_radius_um, 6.0) < 1e-4);
    CHECK(relative_error(r.number_integral, deirmendjian_c1().total_number()) < 1e-4);
    // Nearly non-absorbing water, droplets of 2 .. 28 um: Q_ext close to 2.
    CHECK(r.single_scattering_albedo > 0.999999);
    CHECK(r.single_scattering_albedo < 1.0);
    const double geometric =
        pi * 2.373 * 40320.0 / std::pow(1.5, 9) / deirmendjian_c1().total_number();
    CHECK(r.mean_c_ext_um2 / geometric > 2.0);
    CHECK(r.mean_c_ext_um2 / geometric < 2.2);

    // "HG with that g is 32x too low at 0 deg, 3.3x too high at 90 deg and 15x too low at
    // 180 deg". The claims carry two significant digits and depend on the source's g, grid
    // and index; 20% separates them from any plausible error (e.g. a wrong normalisation by
    // 2 or 4 pi, or theta measured from the backward direction) while accepting rounding.
    const double g = r.asymmetry_g;
    const double forward = r.table.evaluate(1.0) / henyey_greenstein(1.0, g);
    const double side = henyey_greenstein(0.0, g) / r.table.evaluate(0.0);
    const double backward = r.table.evaluate(-1.0) / henyey_greenstein(-1.0, g);
    MESSAGE("C.1 at 0.55 um against HG with g = " << g << ": table/HG " << forward
            << " at 0 deg, HG/table " << side << " at 90 deg, table/HG " << backward
            << " at 180 deg");
    CHECK(std::abs(forward / 32.0 - 1.0) < 0.2);
    CHECK(std::abs(side / 3.3 - 1.0) < 0.2);
    CHECK(std::abs(backward / 15.0 - 1.0) < 0.2);
}

TEST_CASE("bad distribution settings throw") {
    mean_phase_settings s;
    s.size_parameter_step = 0.0;
    CHECK_THROWS_AS((void)compute_mean_phase(deirmendjian_c1(), s), std::invalid_argument);
    s.size_parameter_step = 0.1;
    s.wavelength_um = -1.0;
    CHECK_THROWS_AS((void)compute_mean_phase(deirmendjian_c1(), s), std::invalid_argument);
    s.wavelength_um = 0.55;
    CHECK_THROWS_AS((void)compute_mean_phase(modified_gamma{1.0, 6.0, -1.0, 1.0}, s),
                    std::invalid_argument);
}
