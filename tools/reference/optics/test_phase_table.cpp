// Tests of tools/reference/phase_table: exact integrals of the piecewise-linear table,
// sampling that reproduces the table's own CDF and mean cosine, the CSV round trip and the
// errors on malformed files. References are closed forms of linear functions.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "phase_table.hpp"

using cloudmath::reference::default_angles_deg;
using cloudmath::reference::phase_table;
using cloudmath::reference::read_phase_table;
using cloudmath::reference::tabulate_phase;
using cloudmath::reference::write_phase_table;

namespace {
constexpr double pi = 3.14159265358979323846;
std::string scratch(const char* name) { return std::string("phase_table_test_") + name; }
}  // namespace

TEST_CASE("default angles: 0 to 180, ascending, fine at both ends") {
    const auto a = default_angles_deg();
    CHECK(a.size() == 1231);
    CHECK(a.front() == 0.0);
    CHECK(a.back() == 180.0);
    for (std::size_t i = 1; i < a.size(); ++i) REQUIRE(a[i] > a[i - 1]);
    CHECK(a[1] == doctest::Approx(0.01).epsilon(1e-12));
    CHECK(a[a.size() - 2] == doctest::Approx(179.98).epsilon(1e-12));
}

TEST_CASE("integral and mean cosine are exact for functions linear in mu") {
    // p(mu) = (1 + 0.6 mu) / (4 pi): integral 1, mean cosine 0.6 / 3 = 0.2.
    const auto t = tabulate_phase(default_angles_deg(),
                                  [](double mu) { return (1.0 + 0.6 * mu) / (4.0 * pi); });
    CHECK(t.integral() == doctest::Approx(1.0).epsilon(1e-13));
    CHECK(t.mean_cosine() == doctest::Approx(0.2).epsilon(1e-12));
    CHECK(t.evaluate(0.3) == doctest::Approx(1.18 / (4.0 * pi)).epsilon(1e-12));
    CHECK(t.evaluate(2.0) == doctest::Approx(1.6 / (4.0 * pi)).epsilon(1e-12));  // clamped
}

TEST_CASE("normalize divides by the integral") {
    auto t = tabulate_phase(default_angles_deg(), [](double mu) { return 3.0 + mu * mu; });
    // 2 pi * integral of (3 + mu^2) over [-1, 1] = 2 pi (6 + 2/3); the table's trapezoids
    // overestimate a convex function slightly.
    const double old = t.normalize();
    CHECK(old == doctest::Approx(2.0 * pi * (6.0 + 2.0 / 3.0)).epsilon(1e-5));
    CHECK(t.integral() == doctest::Approx(1.0).epsilon(1e-14));
}

TEST_CASE("sample_mu inverts the table's CDF exactly") {
    // Strongly peaked: sampling must follow the piecewise-linear table, whose CDF at any row
    // is the trapezoid sum computed here independently.
    const auto t = tabulate_phase(default_angles_deg(), [](double mu) {
        const double g = 0.9;
        return (1 - g * g) / (4 * pi * std::pow(1 + g * g - 2 * g * mu, 1.5));
    });
    double area = 0.0;
    const std::size_t n = t.mu_ascending.size();
    for (std::size_t i = 1; i < n; ++i) {
        area += 0.5 * (t.phase_ascending[i] + t.phase_ascending[i - 1]) *
                (t.mu_ascending[i] - t.mu_ascending[i - 1]);
        const double u = 2.0 * pi * area / t.integral();
        if (i % 97 == 0 || i == n - 1)
            CHECK(t.sample_mu(u) == doctest::Approx(t.mu_ascending[i]).epsilon(1e-9));
    }
    CHECK(t.sample_mu(0.0) == -1.0);
    CHECK(t.sample_mu(1.0) == doctest::Approx(1.0));
    // Sampled mean cosine (stratified, 2^16 samples) against the exact table moment.
    const int m = 1 << 16;
    double s = 0.0;
    for (int k = 0; k < m; ++k) s += t.sample_mu((k + 0.5) / m);
    CHECK(s / m == doctest::Approx(t.mean_cosine() / t.integral()).epsilon(1e-4));
}

TEST_CASE("CSV round trip keeps metadata and values to the last bit") {
    auto t = tabulate_phase(default_angles_deg(),
                            [](double mu) { return std::exp(3.0 * mu) / 10.0 + 1e-300; });
    t.set_meta("distribution", "test");
    t.set_meta("wavelength_um", "0.55");
    t.set_meta("distribution", "test, replaced");
    const std::string path = scratch("roundtrip.csv");
    write_phase_table(path, t);
    const auto r = read_phase_table(path);
    REQUIRE(r.theta_deg.size() == t.theta_deg.size());
    for (std::size_t i = 0; i < r.phase.size(); ++i) {
        REQUIRE(r.theta_deg[i] == t.theta_deg[i]);
        REQUIRE(r.phase[i] == t.phase[i]);
    }
    CHECK(r.meta("distribution") == "test, replaced");
    CHECK(r.meta("wavelength_um") == "0.55");
    CHECK(r.meta("missing") == "");
    CHECK(r.metadata.size() == 2);
    std::remove(path.c_str());
}

TEST_CASE("malformed tables are rejected with the path and line") {
    const std::string path = scratch("bad.csv");
    auto write = [&](const char* text) {
        std::ofstream(path) << text;
    };
    auto message_of = [&]() -> std::string {
        try {
            (void)read_phase_table(path);
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    };
    write("theta_deg,mu,phase\n0,1,1\n90,0,x\n180,-1,1\n");
    CHECK(message_of().find(path + ":3") != std::string::npos);
    write("theta,mu,p\n");
    CHECK(message_of().find("header") != std::string::npos);
    write("theta_deg,mu,phase\n0,1,1\n90,0,1\n");
    CHECK(message_of().find("0 to 180") != std::string::npos);
    write("theta_deg,mu,phase\n0,1,1\n90,0,-1\n180,-1,1\n");
    CHECK(message_of().find(">= 0") != std::string::npos);
    write("theta_deg,mu,phase\n0,1,1\n90,0,1\n90,0,1\n180,-1,1\n");
    CHECK(message_of().find("ascending") != std::string::npos);
    write("theta_deg,mu,phase\n0,1,0\n180,-1,0\n");
    CHECK(message_of().find("integrates to 0") != std::string::npos);
    std::remove(path.c_str());
    CHECK_THROWS_AS((void)read_phase_table("/nonexistent/dir/table.csv"), std::runtime_error);
    phase_table t;
    t.theta_deg = {0.0, 180.0};
    t.phase = {1.0};
    CHECK_THROWS_AS(t.finalize(), std::invalid_argument);
}
