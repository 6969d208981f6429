// Tests of tools/reference/phase_error: metrics against closed forms (isotropic table against
// Rayleigh, HG and a scaled copy), self-comparison, parameter recovery of the fits from
// tables made from each model, the Cornette-Shanks moment inversion, the Nelder-Mead
// minimiser, well-formed SVG output and an end-to-end run of the cloudmath_phase_error CLI.
// References: closed forms derived in the comments, and an independent Simpson quadrature.
#include <doctest/doctest.h>

#include <cloudmath/phase.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "phase_error.hpp"

namespace ref = cloudmath::reference;
using cloudmath::phase_cornette_shanks;
using cloudmath::phase_draine;
using cloudmath::phase_hg;
using cloudmath::phase_hg_dual;
using cloudmath::phase_mie_approx;
using cloudmath::phase_rayleigh;

namespace {

constexpr double pi = 3.14159265358979323846;

double iso(double) { return 1.0 / (4.0 * pi); }

template <class F>
ref::phase_table table_of(F&& f) {
    return ref::tabulate_phase(ref::default_angles_deg(), f);
}

// Simpson's rule over mu in [a, b] with n (even) intervals: independent of compare()'s nodes.
template <class F>
double simpson(F&& f, double a, double b, int n) {
    const double h = (b - a) / n;
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
    return s * h / 3.0;
}

// Tags balanced and properly nested; counts the elements named `count_name`.
bool balanced_xml(const std::string& text, const std::string& count_name, int& count) {
    std::vector<std::string> open;
    count = 0;
    std::size_t i = 0;
    while ((i = text.find('<', i)) != std::string::npos) {
        const std::size_t end = text.find('>', i);
        if (end == std::string::npos) return false;
        const std::string tag = text.substr(i + 1, end - i - 1);
        i = end + 1;
        if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) return false;
            open.pop_back();
            continue;
        }
        const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
        if (name == count_name) ++count;
        if (tag.back() != '/') open.push_back(name);
    }
    return open.empty();
}

std::string read_all(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("regions cover 0 to 180 degrees without gaps") {
    const auto& r = ref::phase_error_regions();
    REQUIRE(r.size() == 3);
    CHECK(r.front().theta_min_deg == 0.0);
    CHECK(r.back().theta_max_deg == 180.0);
    for (std::size_t i = 1; i < r.size(); ++i) CHECK(r[i].theta_min_deg == r[i - 1].theta_max_deg);
    CHECK(r[0].theta_max_deg == 5.0);
    CHECK(r[1].theta_max_deg == 160.0);
}

TEST_CASE("a model compared with its own table has no error but the table's interpolation") {
    // The table is linear in mu between rows, the model is not: the only error left is the
    // table's interpolation error, O(h^2) in the row spacing, so halving every row interval
    // must divide it by about 4.
    const std::vector<ref::phase_function> models = {
        [](double mu) { return phase_hg(mu, 0.7); },
        [](double mu) { return phase_hg_dual(mu, 0.8, -0.5, 0.5); },
        [](double mu) { return phase_draine(mu, 0.6, 5.0); },
        [](double mu) { return phase_mie_approx(mu, 8.0); },
    };
    std::vector<double> fine;
    const auto angles = ref::default_angles_deg();
    for (std::size_t i = 0; i + 1 < angles.size(); ++i) {
        fine.push_back(angles[i]);
        fine.push_back(0.5 * (angles[i] + angles[i + 1]));
    }
    fine.push_back(180.0);
    for (const auto& model : models) {
        const auto c = ref::compare(table_of(model), model);
        for (const auto& e : c.regions) {
            CHECK(e.rms_factor < 5e-4);
            CHECK(e.max_rel_error < 2e-3);
        }
        CHECK(c.misdirected_energy < 1e-4);
        CHECK(c.model_integral == doctest::Approx(c.table_integral).epsilon(2e-4));
        CHECK(c.model_mean_cosine == doctest::Approx(c.table_mean_cosine).epsilon(1e-4));
        const auto c_fine = ref::compare(ref::tabulate_phase(fine, model), model);
        const double ratio = c.misdirected_energy / c_fine.misdirected_energy;
        CHECK(ratio > 3.0);
        CHECK(ratio < 5.0);
    }
}

TEST_CASE("isotropic table against Rayleigh: closed forms") {
    const auto table = table_of(iso);
    const auto c = ref::compare(table, [](double mu) { return phase_rayleigh(mu); });
    // p_R - p_iso = (3 mu^2 - 1) / (16 pi), zero at mu = 1/sqrt(3). Misdirected energy
    // = 0.5 * 2 pi * (1/16 pi) * integral_{-1}^{1} |3 mu^2 - 1| dmu
    // = (1/8) * integral_0^1 |3 mu^2 - 1| dmu = (1/8) (2/(3 sqrt 3) + 2/(3 sqrt 3)) = 1/(6 sqrt 3).
    CHECK(c.misdirected_energy == doctest::Approx(1.0 / (6.0 * std::sqrt(3.0))).epsilon(1e-7));
    CHECK(c.model_integral == doctest::Approx(1.0).epsilon(1e-7));
    CHECK(std::abs(c.model_mean_cosine) < 1e-12);
    CHECK(c.table_integral == doctest::Approx(1.0).epsilon(1e-13));
    // Ratio 3 (1 + mu^2) / 4: 1.5 at 0 and 180 deg, 0.75 (1 + cos^2 5 deg) at the side edge.
    const double c5 = std::cos(5.0 * pi / 180.0), c160 = std::cos(160.0 * pi / 180.0);
    CHECK(c.regions[0].max_rel_error == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(c.regions[0].max_at_deg == 0.0);
    CHECK(c.regions[1].max_rel_error == doctest::Approx(0.75 * (1 + c5 * c5) - 1).epsilon(1e-12));
    CHECK(c.regions[1].max_at_deg == 5.0);
    CHECK(c.regions[2].max_rel_error == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(c.regions[2].max_at_deg == 180.0);
    // RMS of ln ratio over each region's solid angle, by Simpson in mu.
    auto sq = [](double mu) {
        const double l = std::log(0.75 * (1.0 + mu * mu));
        return l * l;
    };
    const double bounds[4] = {1.0, c5, c160, -1.0};
    for (int r = 0; r < 3; ++r) {
        const double a = bounds[r + 1], b = bounds[r];
        const double rms = std::sqrt(simpson(sq, a, b, 2000) / (b - a));
        CHECK(c.regions[static_cast<std::size_t>(r)].rms_factor ==
              doctest::Approx(std::expm1(rms)).epsilon(1e-6));
        // Share of isotropic light in the region: (b - a) / 2.
        CHECK(c.regions[static_cast<std::size_t>(r)].table_energy ==
              doctest::Approx((b - a) / 2.0).epsilon(1e-12));
    }
}

TEST_CASE("isotropic table against twice itself: factor 2 everywhere") {
    const auto c = ref::compare(table_of(iso), [](double) { return 2.0 / (4.0 * pi); });
    for (const auto& e : c.regions) {
        CHECK(e.rms_factor == doctest::Approx(1.0).epsilon(1e-12));
        CHECK(e.max_rel_error == doctest::Approx(1.0).epsilon(1e-12));
    }
    CHECK(c.misdirected_energy == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(c.model_integral == doctest::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("isotropic table against HG: misdirected energy in closed form") {
    // HG exceeds 1/(4 pi) for mu > mu* where (1 + g^2 - 2 g mu*)^(3/2) = 1 - g^2; the HG
    // energy there is (1 - g^2)/(2g) (1/(1 - g) - 1/sqrt(1 + g^2 - 2 g mu*)), the isotropic
    // energy (1 - mu*)/2; misdirected energy is their difference.
    for (double g : {0.3, 0.5, 0.85}) {
        const double mu_star = (1.0 + g * g - std::pow(1.0 - g * g, 2.0 / 3.0)) / (2.0 * g);
        const double hg_part = (1.0 - g * g) / (2.0 * g) *
                               (1.0 / (1.0 - g) - 1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu_star));
        const double expected = hg_part - (1.0 - mu_star) / 2.0;
        const auto c = ref::compare(table_of(iso), [g](double mu) { return phase_hg(mu, g); });
        CHECK(c.misdirected_energy == doctest::Approx(expected).epsilon(1e-6));
        CHECK(c.model_mean_cosine == doctest::Approx(g).epsilon(1e-6));
    }
}

TEST_CASE("Nelder-Mead finds the Rosenbrock minimum") {
    int calls = 0;
    const auto r = ref::nelder_mead(
        [&](const std::vector<double>& x) {
            ++calls;
            return 100.0 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1.0 - x[0], 2);
        },
        {-1.2, 1.0});
    CHECK(r.x[0] == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(r.x[1] == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(r.value < 1e-12);
    CHECK(r.evaluations == calls);
}

TEST_CASE("fits recover the parameters of tables made from each model") {
    SUBCASE("HG g = 0.7") {
        const auto t = ref::make_fit_target(table_of([](double mu) { return phase_hg(mu, 0.7); }));
        const auto r = ref::fit_hg(t);
        CHECK(r.parameters[0] == doctest::Approx(0.7).epsilon(1e-6));
        CHECK(r.residual < 1e-6);
    }
    SUBCASE("dual-lobe HG (0.85, -0.3, 0.3), lobes given in the other order") {
        const auto t = ref::make_fit_target(
            table_of([](double mu) { return phase_hg_dual(mu, -0.3, 0.85, 0.7); }));
        const auto r = ref::fit_hg_dual(t);
        CHECK(r.parameters[0] == doctest::Approx(0.85).epsilon(1e-4));
        CHECK(r.parameters[1] == doctest::Approx(-0.3).epsilon(1e-4));
        CHECK(r.parameters[2] == doctest::Approx(0.3).epsilon(1e-4));
        CHECK(r.residual < 1e-5);
    }
    SUBCASE("Cornette-Shanks g = 0.8") {
        const auto t = ref::make_fit_target(
            table_of([](double mu) { return phase_cornette_shanks(mu, 0.8); }));
        CHECK(ref::fit_cornette_shanks(t).parameters[0] == doctest::Approx(0.8).epsilon(1e-6));
    }
    SUBCASE("Draine g = 0.6, alpha = 5") {
        const auto t =
            ref::make_fit_target(table_of([](double mu) { return phase_draine(mu, 0.6, 5.0); }));
        const auto r = ref::fit_draine(t);
        CHECK(r.parameters[0] == doctest::Approx(0.6).epsilon(1e-4));
        CHECK(r.parameters[1] == doctest::Approx(5.0).epsilon(1e-3));
        CHECK(r.residual < 1e-5);
    }
    SUBCASE("Jendersie-d'Eon at d = 8 um: size and the four parameters") {
        const auto t =
            ref::make_fit_target(table_of([](double mu) { return phase_mie_approx(mu, 8.0); }));
        const auto d = ref::fit_mie_approx_diameter(t);
        CHECK(d.parameters[0] == doctest::Approx(8.0).epsilon(1e-4));
        const auto p = cloudmath::mie_approx_params(8.0);
        const auto r = ref::fit_mie_approx_parameters(t);
        CHECK(r.parameters[0] == doctest::Approx(p.g_hg).epsilon(1e-4));
        CHECK(r.parameters[1] == doctest::Approx(p.g_draine).epsilon(1e-3));
        CHECK(r.parameters[2] == doctest::Approx(p.alpha).epsilon(1e-2));
        CHECK(r.parameters[3] == doctest::Approx(p.w_draine).epsilon(1e-3));
        CHECK(r.residual < 1e-4);
    }
    SUBCASE("four parameters off the published curve") {
        const cloudmath::mie_approx_parameters<double> p{0.95, 0.45, 12.0, 0.35};
        const auto t =
            ref::make_fit_target(table_of([&](double mu) { return phase_mie_approx(mu, p); }));
        const auto r = ref::fit_mie_approx_parameters(t);
        CHECK(r.parameters[0] == doctest::Approx(0.95).epsilon(1e-4));
        CHECK(r.parameters[1] == doctest::Approx(0.45).epsilon(1e-3));
        CHECK(r.parameters[2] == doctest::Approx(12.0).epsilon(1e-2));
        CHECK(r.parameters[3] == doctest::Approx(0.35).epsilon(1e-3));
    }
}

TEST_CASE("moment-matched Cornette-Shanks g solves the closed form") {
    // REFERENCES.md: CS mean cosine 0.88466 at g = 0.85.
    CHECK(ref::cornette_shanks_mean_cosine(0.85) == doctest::Approx(0.88466).epsilon(1e-5));
    CHECK(ref::cornette_shanks_g_for_mean_cosine(0.88466) == doctest::Approx(0.85).epsilon(2e-5));
    for (double G : {-0.6, 0.0, 0.3, 0.853, 0.95}) {
        const double g = ref::cornette_shanks_g_for_mean_cosine(G);
        // Root of 3 g^3 - 5 G g^2 + 12 g - 10 G.
        CHECK(std::abs(3 * g * g * g - 5 * G * g * g + 12 * g - 10 * G) < 1e-12);
        // The tabulated CS function has that mean cosine (independent trapezoid moments).
        const auto t = table_of([g](double mu) { return phase_cornette_shanks(mu, g); });
        CHECK(t.mean_cosine() / t.integral() == doctest::Approx(G).epsilon(1e-4));
    }
}

TEST_CASE("report variants: order, the exact size variant, fits no worse than moments") {
    // Mie approximation at d = 8 um = 2 r_eff with r_eff = 4: that variant matches exactly.
    const auto table = table_of([](double mu) { return phase_mie_approx(mu, 8.0); });
    double last = -1.0;
    int calls = 0;
    const auto v = ref::phase_variants(table, 4.0, [&](double f) {
        CHECK(f >= last);
        last = f;
        ++calls;
    });
    const char* ids[] = {"hg_moment",  "hg_fit",          "dual_frostbite",   "dual_fit",
                         "schlick_moment", "cs_moment", "cs_fit", "draine_fit", "mie_approx_d2reff",
                         "mie_approx_dfit", "mie_approx_fit"};
    REQUIRE(v.size() == 11);
    for (std::size_t i = 0; i < v.size(); ++i) CHECK(v[i].id == ids[i]);
    CHECK(last == 1.0);
    CHECK(calls > 1);
    CHECK(v[8].residual < 1e-12);
    CHECK(ref::compare(table, v[8].model).misdirected_energy < 1e-4);  // interpolation only
    CHECK(v[1].residual <= v[0].residual);  // fit started from the moment-matched g
    CHECK(v[6].residual <= v[5].residual + 1e-3);
    CHECK(v[0].parameters[0].second ==
          doctest::Approx(table.mean_cosine() / table.integral()).epsilon(1e-12));
    // Without r_eff the size variant is left out.
    CHECK(ref::phase_variants(table, 0.0).size() == 10);
}

TEST_CASE("SVG plots are well formed, one polyline per curve, small") {
    std::vector<ref::plot_curve> curves(3);
    const auto angles = ref::default_angles_deg();
    const double gs[3] = {0.0, 0.7, 0.95};
    for (int k = 0; k < 3; ++k) {
        auto& c = curves[static_cast<std::size_t>(k)];
        c.label = "curve <" + std::to_string(k) + "> & co";
        c.colour = "#123456";
        c.dash = k == 1 ? "6,4" : "";
        c.theta_deg = angles;
        for (double th : angles) c.phase.push_back(phase_hg(std::cos(th * pi / 180.0), gs[k]));
    }
    for (const std::string& svg :
         {ref::svg_phase_cartesian(curves, "title & <test>"),
          ref::svg_phase_cartesian(curves, "zoom", 10.0), ref::svg_phase_polar(curves, "polar")}) {
        CHECK(svg.rfind("<svg", 0) == 0);
        CHECK(svg.find("</svg>") == svg.size() - 7);
        int polylines = 0;
        CHECK(balanced_xml(svg, "polyline", polylines));
        CHECK(polylines == 3);
        CHECK(svg.find("<test>") == std::string::npos);  // escaped
        CHECK(svg.find("curve &lt;1&gt; &amp; co") != std::string::npos);
        // Every polyline within the point budget.
        std::size_t at = 0;
        while ((at = svg.find("points=\"", at)) != std::string::npos) {
            const std::size_t end = svg.find('"', at + 8);
            const std::string pts = svg.substr(at + 8, end - at - 8);
            std::size_t n = 1;
            for (char ch : pts) n += ch == ' ';
            CHECK(n <= ref::svg_max_points_per_curve);
            CHECK(n >= 2);
            at = end;
        }
        CHECK(svg.size() < 60000);
    }
}

#ifdef CLOUDMATH_PHASE_ERROR_EXE
TEST_CASE("the CLI writes the report, the CSV and three SVGs per table") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::absolute("phase_error_test_cli");
    fs::remove_all(dir);
    fs::create_directories(dir / "data");
    auto table = table_of([](double mu) { return phase_mie_approx(mu, 8.0); });
    table.metadata = {{"distribution", "test, made from phase_mie_approx"},
                      {"wavelength_um", "0.55"},
                      {"r_eff_um", "4"}};
    ref::write_phase_table((dir / "data" / "small.csv").string(), table);
    const std::string command = std::string("\"") + CLOUDMATH_PHASE_ERROR_EXE + "\" --docs \"" +
                                (dir / "docs").string() + "\" \"" +
                                (dir / "data" / "small.csv").string() + "\" > \"" +
                                (dir / "stdout.txt").string() + "\" 2>&1";
    REQUIRE(std::system(command.c_str()) == 0);
    const std::string md = read_all((dir / "docs" / "phase_error.md").string());
    CHECK(md.find("Generated by `cloudmath_phase_error") != std::string::npos);
    CHECK(md.find("do not edit by hand") != std::string::npos);
    CHECK(md.find("(images/phase_error_small.svg)") != std::string::npos);
    CHECK(md.find("(images/phase_polar_small.svg)") != std::string::npos);
    CHECK(md.find("(images/phase_forward_small.svg)") != std::string::npos);
    const std::string csv = read_all((dir / "docs" / "phase_error.csv").string());
    int lines = 0;
    for (char ch : csv) lines += ch == '\n';
    CHECK(lines == 12);  // header + 11 variants
    CHECK(csv.find("small,\"test, made from phase_mie_approx\",0.55,4,") != std::string::npos);
    for (const char* svg :
         {"phase_error_small.svg", "phase_polar_small.svg", "phase_forward_small.svg"}) {
        const std::string text = read_all((dir / "docs" / "images" / svg).string());
        int polylines = 0;
        CHECK(balanced_xml(text, "polyline", polylines));
        CHECK(polylines == 12);  // the table and 11 variants
    }
    CHECK(read_all((dir / "stdout.txt").string()).find(" s\n") != std::string::npos);
}
#endif
