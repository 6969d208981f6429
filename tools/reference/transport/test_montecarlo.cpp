// tools/reference/transport/test_montecarlo.cpp: validation of the Monte Carlo reference
// (montecarlo.hpp) against published values and closed forms that do not come from it:
//   - van de Hulst 1980 slab values (via the DISORT test suite, see REFERENCES.md);
//   - exact energy bookkeeping of the analog forward tracer;
//   - single scattering against closed forms (slab, Chandrasekhar 1960 / Liou 2002 ch. 6) and
//     against an independent quadrature along the ray (sphere);
//   - energy of the sphere: the power scattered out equals the power removed from the beam;
//   - phase sampling: mean cosines against the published closed forms.
// Every Monte Carlo check requires |MC - reference| < 4 standard errors AND a standard error
// below a stated bound, so that the check has teeth.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <cloudmath/phase.hpp>

#include "montecarlo.hpp"

namespace mc = cloudmath::reference::mc;

namespace {

constexpr double pi = 3.14159265358979323846;

// |estimate - reference| < 4 standard errors, and the standard error below max_se.
void check_mc(const char* what, double mean, double se, double reference, double max_se) {
    const double z = se > 0.0 ? (mean - reference) / se : 0.0;
    MESSAGE(std::string(what) << ": MC " << mean << " +- " << se << ", reference "
                              << reference << " (" << z << " sigma)");
    CHECK(std::abs(mean - reference) < 4.0 * se);
    CHECK(se < max_se);
    CHECK(se > 0.0);
}
void check_mc(const char* what, const mc::estimate& e, double reference, double max_se) {
    check_mc(what, e.mean, e.std_error, reference, max_se);
}

mc::run_options options(unsigned threads = 2, std::uint64_t seed = 1, unsigned max_order = 0) {
    mc::run_options o;
    o.threads = threads;
    o.seed = seed;
    o.max_order = max_order;
    return o;
}

// Single-scattering radiance L/F0 of a slab (closed forms; the source omega p F0 exp(-t/mu0)
// integrated along the view ray, optical depth t from the top).
// Reflected: omega p mu0/(mu0 + mu) (1 - exp(-tau (1/mu0 + 1/mu))).
double single_reflected(double omega, double p, double tau, double mu0, double mu) {
    return omega * p * mu0 / (mu0 + mu) * -std::expm1(-tau * (1.0 / mu0 + 1.0 / mu));
}
// Transmitted: omega p mu0/(mu - mu0) (exp(-tau/mu) - exp(-tau/mu0)), written with
// x = tau (1/mu0 - 1/mu) as omega p (tau/mu) exp(-tau/mu) (1 - exp(-x))/x for x >= 0 and
// omega p (tau/mu) exp(-tau/mu0) (exp(x) - 1)/x for x < 0: no overflow nor cancellation, and
// right at mu = mu0 (the fraction tends to 1).
double single_transmitted(double omega, double p, double tau, double mu0, double mu) {
    const double x = tau * (1.0 / mu0 - 1.0 / mu);
    const double e = x >= 0.0 ? std::exp(-tau / mu) : std::exp(-tau / mu0);
    const double f = x == 0.0 ? 1.0 : (x > 0.0 ? -std::expm1(-x) : std::expm1(x)) / x;
    return omega * p * (tau / mu) * e * f;
}

// Cosine of the single-scattering angle for an exit cosine mu and relative azimuth phi
// (DISORT's convention, restated here rather than taken from the code under test).
double scattering_cosine(bool transmitted, double mu, double mu0, double phi) {
    const double s = std::sqrt(1.0 - mu * mu), s0 = std::sqrt(1.0 - mu0 * mu0);
    return (transmitted ? mu * mu0 : -mu * mu0) + s * s0 * std::cos(phi);
}

// Distance from x (inside the unit sphere) along unit d to the surface.
double chord(const mc::vec3& x, const mc::vec3& d) {
    const double b = x.x * d.x + x.y * d.y + x.z * d.z;
    const double c = x.x * x.x + x.y * x.y + x.z * x.z - 1.0;
    return -b + std::sqrt(b * b - c);
}

// Single-scattering radiance of the sphere along a ray by composite Simpson quadrature:
// integral over the in-sphere segment of sigma_t omega p(mu) exp(-sigma_t (t - t_in))
// exp(-sigma_t chord(x(t), sun)) dt.
double sphere_single_quadrature(const mc::ray& r, double tau_d, double omega, double g,
                                const mc::vec3& sun) {
    const double len = std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y +
                                 r.direction.z * r.direction.z);
    const mc::vec3 d{r.direction.x / len, r.direction.y / len, r.direction.z / len};
    const mc::vec3& o = r.origin;
    const double b = o.x * d.x + o.y * d.y + o.z * d.z;
    const double c = o.x * o.x + o.y * o.y + o.z * o.z - 1.0;
    const double disc = b * b - c;
    if (disc <= 0.0) return 0.0;
    const double t_in = std::max(0.0, -b - std::sqrt(disc));
    const double t_out = -b + std::sqrt(disc);
    if (t_out <= t_in) return 0.0;
    const double sigma = 0.5 * tau_d;
    const double p = cloudmath::phase_hg(d.x * sun.x + d.y * sun.y + d.z * sun.z, g);
    const int n = 4000;  // even
    const double h = (t_out - t_in) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double t = t_in + h * i;
        const mc::vec3 x{o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
        const double f = std::exp(-sigma * (t - t_in)) * std::exp(-sigma * chord(x, sun));
        sum += f * (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
    }
    return sigma * omega * p * sum * h / 3.0;
}

// A file name in the temporary directory, unique to this run (tests may run concurrently).
std::string temp_path(const std::string& name) {
    static const unsigned long long tag = std::random_device{}();
    return (std::filesystem::temp_directory_path() /
            ("cloudmath_" + std::to_string(tag) + "_" + name))
        .string();
}

}  // namespace

// ---------------------------------------------------------------------------------------
TEST_CASE("slab: van de Hulst reflection and transmission, HG g = 0.75, mu0 = 1, albedo 1") {
    const mc::phase_model hg = mc::make_phase("hg:0.75");
    SUBCASE("tau = 1") {
        const auto r = mc::trace_slab({1.0, 1.0, 1.0}, hg, 2000000, 20, options());
        check_mc("tau 1 R", r.reflected, 0.078742, 2.5e-4);
        check_mc("tau 1 T_diffuse", r.transmitted_diffuse, 0.553376, 5e-4);
        check_mc("tau 1 T_direct", r.transmitted_direct, std::exp(-1.0), 1e-3);
    }
    SUBCASE("tau = 8") {
        const auto r = mc::trace_slab({8.0, 1.0, 1.0}, hg, 1000000, 20, options());
        check_mc("tau 8 R", r.reflected, 0.506418, 6e-4);
        check_mc("tau 8 T_diffuse", r.transmitted_diffuse, 0.493247, 6e-4);
        check_mc("tau 8 T_direct", r.transmitted_direct, std::exp(-8.0), 1e-4);
    }
}

TEST_CASE("slab: the tabulated phase path reproduces van de Hulst") {
    SUBCASE("table:PATH made from HG g = 0.75 on the default angles") {
        cloudmath::reference::phase_table t = cloudmath::reference::tabulate_phase(
            cloudmath::reference::default_angles_deg(),
            [](double mu) { return cloudmath::phase_hg(mu, 0.75); });
        t.set_meta("source", "HG g = 0.75 (test_montecarlo)");
        const std::string path = temp_path("test_montecarlo_hg075.csv");
        cloudmath::reference::write_phase_table(path, t);
        const mc::phase_model table = mc::make_phase("table:" + path);
        std::remove(path.c_str());
        CHECK(table.exact_sampling());
        const auto r = mc::trace_slab({1.0, 1.0, 1.0}, table, 1000000, 20, options(2, 2));
        check_mc("table R", r.reflected, 0.078742, 5e-4);
        check_mc("table T_diffuse", r.transmitted_diffuse, 0.553376, 1e-3);
    }
    SUBCASE("draine:0.75,0 (equals HG 0.75) sampled from its tabulation with weights") {
        const mc::phase_model draine = mc::make_phase("draine:0.75,0");
        CHECK_FALSE(draine.exact_sampling());
        const auto r = mc::trace_slab({1.0, 1.0, 1.0}, draine, 1000000, 20, options(2, 3));
        check_mc("weighted R", r.reflected, 0.078742, 5e-4);
        check_mc("weighted T_diffuse", r.transmitted_diffuse, 0.553376, 1e-3);
        check_mc("weighted mean photon weight", r.photon_weight, 1.0, 1e-3);
    }
}

TEST_CASE("slab: energy bookkeeping of the forward tracer") {
    const mc::phase_model hg = mc::make_phase("hg:0.85");
    SUBCASE("albedo 1 and 0.9: R + T_d + T_dir + A = 1 exactly") {
        for (double albedo : {1.0, 0.9}) {
            CAPTURE(albedo);
            const auto r = mc::trace_slab({2.0, 0.6, albedo}, hg, 100000, 10, options());
            const double sum = r.reflected.mean + r.transmitted_diffuse.mean +
                               r.transmitted_direct.mean + r.absorbed.mean +
                               r.beyond_max_order.mean;
            // Every photon ends in exactly one bucket with weight 1: the fractions add to 1
            // to rounding of the sums, and the photon weight has no variance.
            CHECK(std::abs(sum - 1.0) < 1e-12);
            CHECK(r.photon_weight.mean == 1.0);
            CHECK(r.photon_weight.std_error == 0.0);
            CHECK(r.beyond_max_order.mean == 0.0);
            if (albedo == 1.0) {
                CHECK(r.absorbed.mean == 0.0);
            } else {
                CHECK(r.absorbed.mean > 0.05);
            }
            check_mc("T_direct tau 2 mu0 0.6", r.transmitted_direct, std::exp(-2.0 / 0.6), 1e-3);
        }
    }
    SUBCASE("max order: the photons stopped are counted, the sum stays 1") {
        const auto r = mc::trace_slab({2.0, 0.6, 0.9}, hg, 100000, 10, options(2, 1, 2));
        const double sum = r.reflected.mean + r.transmitted_diffuse.mean +
                           r.transmitted_direct.mean + r.absorbed.mean +
                           r.beyond_max_order.mean;
        CHECK(std::abs(sum - 1.0) < 1e-12);
        CHECK(r.beyond_max_order.mean > 0.1);
    }
    SUBCASE("weighted sampling: fractions add to the mean photon weight") {
        const auto r =
            mc::trace_slab({2.0, 0.6, 0.9}, mc::make_phase("cs:0.8"), 100000, 10, options());
        const double sum = r.reflected.mean + r.transmitted_diffuse.mean +
                           r.transmitted_direct.mean + r.absorbed.mean;
        CHECK(std::abs(sum - r.photon_weight.mean) < 1e-12);
        check_mc("cs:0.8 mean photon weight", r.photon_weight, 1.0, 1e-3);
    }
}

// ---------------------------------------------------------------------------------------
TEST_CASE("slab: single scattering, backward estimator against the closed forms") {
    const double tau = 1.0, mu0 = 0.6, omega = 0.9;
    const std::vector<mc::slab_view> views = mc::parse_slab_views(
        "r:1,0; r:0.6,180; r:0.4,60; r:0.25,0; t:0.8,0; t:0.6,0; t:0.3,120; t:1,0");
    for (const std::string spec : {"hg:0.75", "cs:0.8", "mie_approx:10"}) {
        CAPTURE(spec);
        const mc::phase_model phase = mc::make_phase(spec);
        const auto L = mc::slab_radiance({tau, mu0, omega}, phase, views, 20000,
                                         options(2, 4, 1));
        for (std::size_t i = 0; i < views.size(); ++i) {
            const auto& v = views[i];
            const double cos_theta =
                scattering_cosine(v.transmitted, v.mu, mu0, v.phi_deg * pi / 180.0);
            CHECK(std::abs(mc::slab_view_scattering_cosine({tau, mu0, omega}, v) - cos_theta) <
                  1e-12);
            CHECK(std::abs(mc::slab_view_scattering_angle_deg({tau, mu0, omega}, v) -
                           std::acos(cos_theta) * 180.0 / pi) < 1e-5);
            const double p = phase.evaluate(cos_theta);
            const double ref = v.transmitted ? single_transmitted(omega, p, tau, mu0, v.mu)
                                             : single_reflected(omega, p, tau, mu0, v.mu);
            CAPTURE(i);
            // Relative bound: a single-scattering path is a Bernoulli-weighted constant.
            check_mc(v.transmitted ? "transmitted" : "reflected", L[i], ref,
                     0.02 * ref + 1e-6);
        }
    }
}

TEST_CASE("slab: single scattering, forward histograms against the closed forms") {
    const double tau = 1.0, mu0 = 0.6, omega = 0.9, g = 0.75;
    const unsigned bins = 10;
    const auto r = mc::trace_slab({tau, mu0, omega}, mc::make_phase("hg:0.75"), 1000000, bins,
                                  options(2, 5, 1));
    // Reference: average of the closed form over azimuth and over the bin with weight mu dmu.
    for (int side = 0; side < 2; ++side) {
        const bool transmitted = side == 1;
        const auto& h = transmitted ? r.transmitted_radiance : r.reflected_radiance;
        for (unsigned b = 0; b < bins; ++b) {
            const double lo = static_cast<double>(b) / bins, hi = (b + 1.0) / bins;
            const int nmu = 200, nphi = 360;
            double sum = 0.0;
            for (int i = 0; i < nmu; ++i) {
                const double mu = lo + (hi - lo) * (i + 0.5) / nmu;
                double az = 0.0;
                for (int j = 0; j < nphi; ++j) {
                    const double phi = 2.0 * pi * (j + 0.5) / nphi;
                    const double p =
                        cloudmath::phase_hg(scattering_cosine(transmitted, mu, mu0, phi), g);
                    az += transmitted ? single_transmitted(omega, p, tau, mu0, mu)
                                      : single_reflected(omega, p, tau, mu0, mu);
                }
                sum += mu * az / nphi;
            }
            const double ref = sum / nmu / (0.5 * (lo + hi));
            CAPTURE(transmitted);
            CAPTURE(b);
            check_mc(transmitted ? "histogram transmitted" : "histogram reflected", h[b], ref,
                     0.05 * ref);
        }
    }
}

TEST_CASE("sphere: single scattering against a quadrature along the ray") {
    const double tau_d = 2.0, omega = 0.9, g = 0.5;
    const mc::sphere_camera cam = mc::make_sphere_camera_line(60.0, 5);
    std::vector<mc::ray> rays = cam.rays;
    rays.push_back({{0.2, 0.1, -0.3}, {0.3, -0.5, 0.8}});   // origin inside the sphere
    rays.push_back({{0.0, 1.5, -3.0}, {0.0, 0.0, 1.0}});    // misses: exactly 0
    const auto L = mc::sphere_radiance({tau_d, omega, cam.sun_direction},
                                       mc::make_phase("hg:0.5"), rays, 20000, options(2, 6, 1));
    for (std::size_t i = 0; i + 1 < rays.size(); ++i) {
        CAPTURE(i);
        const double ref = sphere_single_quadrature(rays[i], tau_d, omega, g, cam.sun_direction);
        check_mc("sphere single scattering", L[i], ref, 0.02 * ref);
    }
    CHECK(L.back().mean == 0.0);
    CHECK(L.back().std_error == 0.0);
}

TEST_CASE("sphere: scattered power equals the power removed from the sun beam (albedo 1)") {
    // P_scattered = integral over directions and over the projected disc of L. Views
    // uniform on the sphere, impact points uniform on the unit disc: P = 4 pi * pi * <L>.
    // Removed from the beam: pi F0 (1 - <exp(-chord)>), <exp(-chord)> over the disc =
    // 2 [1 - (1 + tau_d) exp(-tau_d)] / tau_d^2.
    const double tau_d = 4.0;
    std::mt19937_64 gen(12345);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    const std::size_t n_rays = 50000;
    std::vector<mc::ray> rays;
    for (std::size_t i = 0; i < n_rays; ++i) {
        const double z = 2.0 * uni(gen) - 1.0, a = 2.0 * pi * uni(gen);
        const double s = std::sqrt(1.0 - z * z);
        const mc::vec3 d{s * std::cos(a), s * std::sin(a), z};
        // Orthonormal pair perpendicular to d (Gram-Schmidt on a fixed axis).
        const mc::vec3 k = std::abs(d.x) < 0.9 ? mc::vec3{1, 0, 0} : mc::vec3{0, 1, 0};
        const double kd = k.x * d.x + k.y * d.y + k.z * d.z;
        mc::vec3 e1{k.x - kd * d.x, k.y - kd * d.y, k.z - kd * d.z};
        const double n1 = std::sqrt(e1.x * e1.x + e1.y * e1.y + e1.z * e1.z);
        e1 = {e1.x / n1, e1.y / n1, e1.z / n1};
        const mc::vec3 e2{d.y * e1.z - d.z * e1.y, d.z * e1.x - d.x * e1.z,
                          d.x * e1.y - d.y * e1.x};
        const double r = std::sqrt(uni(gen)), b = 2.0 * pi * uni(gen);
        const double u = r * std::cos(b), v = r * std::sin(b);
        rays.push_back({{u * e1.x + v * e2.x - 2.0 * d.x, u * e1.y + v * e2.y - 2.0 * d.y,
                         u * e1.z + v * e2.z - 2.0 * d.z},
                        d});
    }
    const auto L = mc::sphere_radiance({tau_d, 1.0, {0.3, -0.4, 0.866}},
                                       mc::make_phase("hg:0.5"), rays, 4, options(2, 7));
    double sum = 0.0, sum_sq = 0.0;
    for (const auto& e : L) {
        sum += e.mean;
        sum_sq += e.mean * e.mean;
    }
    const double n = static_cast<double>(n_rays);
    const double mean = sum / n;
    const double se = std::sqrt((sum_sq / n - mean * mean) / (n - 1.0));
    const double scale = 4.0 * pi * pi;
    const double mean_transmission =
        2.0 * (1.0 - (1.0 + tau_d) * std::exp(-tau_d)) / (tau_d * tau_d);
    const double removed = pi * (1.0 - mean_transmission);
    check_mc("sphere scattered power", scale * mean, scale * se, removed, 0.01 * removed);
}

// ---------------------------------------------------------------------------------------
TEST_CASE("slab: backward estimator with all orders integrates to van de Hulst's R and T") {
    // Views with mu drawn from the density 2 mu and phi uniform: R = (pi / mu0) <L_reflected>,
    // likewise T_diffuse from the transmitted views.
    std::mt19937_64 gen(777);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    const std::size_t n = 50000;
    std::vector<mc::slab_view> views;
    for (int side = 0; side < 2; ++side)
        for (std::size_t i = 0; i < n; ++i)
            views.push_back({side == 1, std::sqrt(1.0 - uni(gen)), 360.0 * uni(gen)});
    const auto L = mc::slab_radiance({1.0, 1.0, 1.0}, mc::make_phase("hg:0.75"), views, 4,
                                     options(2, 8));
    for (std::size_t side = 0; side < 2; ++side) {
        double sum = 0.0, sum_sq = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = pi * L[side * n + i].mean;
            sum += x;
            sum_sq += x * x;
        }
        const double mean = sum / static_cast<double>(n);
        const double se = std::sqrt((sum_sq / static_cast<double>(n) - mean * mean) /
                                    static_cast<double>(n - 1));
        if (side == 0)
            check_mc("backward R tau 1", mean, se, 0.078742, 1e-3);
        else
            check_mc("backward T_diffuse tau 1", mean, se, 0.553376, 4e-3);
    }
}

// ---------------------------------------------------------------------------------------
TEST_CASE("phase models: sampled mean cosine equals 2 pi integral of mu p") {
    // Draine's mean cosine (Draine 2003): g [1 + alpha (3 + 2 g^2)/5] / [1 + alpha (1 + 2g^2)/3].
    auto draine_g = [](double g, double a) {
        return g * (1.0 + a * (3.0 + 2.0 * g * g) / 5.0) / (1.0 + a * (1.0 + 2.0 * g * g) / 3.0);
    };
    // Jendersie & d'Eon parameters at d = 10 um from REFERENCES.md (5 digits).
    const double mie10 = (1.0 - 0.48196) * 0.98818 + 0.48196 * draine_g(0.55567, 21.996);
    // A table that is no analytic model: Rayleigh plus a forward HG lobe, mean cosine from the
    // table's exact piecewise-linear integral.
    cloudmath::reference::phase_table t = cloudmath::reference::tabulate_phase(
        cloudmath::reference::default_angles_deg(), [](double mu) {
            return 0.3 * cloudmath::phase_rayleigh(mu) + 0.7 * cloudmath::phase_hg(mu, 0.9);
        });
    const std::string path = temp_path("test_montecarlo_mix.csv");
    cloudmath::reference::write_phase_table(path, t);
    const double table_g = t.mean_cosine() / t.integral();

    struct model {
        std::string spec;
        double mean_cosine;
    };
    const std::vector<model> models = {
        {"isotropic", 0.0},
        {"rayleigh", 0.0},
        {"hg:0.75", 0.75},
        {"hg:-0.3", -0.3},
        {"hg:0.99", 0.99},
        {"dual_hg:0.8,-0.5,0.5", 0.5 * 0.8 + 0.5 * -0.5},
        {"cs:0.85", 3.0 * 0.85 * (4.0 + 0.85 * 0.85) / (5.0 * (2.0 + 0.85 * 0.85))},
        {"draine:0.6,5", draine_g(0.6, 5.0)},
        {"mie_approx:10", mie10},
        {"table:" + path, table_g},
    };
    std::mt19937_64 gen(99);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    const int n = 200000;
    for (const auto& m : models) {
        CAPTURE(m.spec);
        const mc::phase_model phase = mc::make_phase(m.spec);
        double s_mu = 0.0, s_mu2 = 0.0, s_w = 0.0, s_w2 = 0.0;
        bool weights_one = true, in_range = true;
        for (int i = 0; i < n; ++i) {
            const auto smp = phase.sample(uni(gen));
            if (!(smp.mu >= -1.0 && smp.mu <= 1.0)) in_range = false;
            const double x = smp.weight * smp.mu;
            s_mu += x;
            s_mu2 += x * x;
            s_w += smp.weight;
            s_w2 += smp.weight * smp.weight;
            if (smp.weight != 1.0) weights_one = false;
        }
        CHECK(in_range);
        const double mean = s_mu / n, se = std::sqrt((s_mu2 / n - mean * mean) / (n - 1));
        check_mc("mean cosine", mean, se, m.mean_cosine, 5e-3);
        const double w = s_w / n, w_se = std::sqrt(std::max(0.0, s_w2 / n - w * w) / (n - 1));
        if (phase.exact_sampling()) {
            CHECK(weights_one);
        } else {
            check_mc("mean weight", w, w_se, 1.0, 1e-3);
        }
    }
    std::remove(path.c_str());
}

TEST_CASE("phase models: bad specs are rejected with std::invalid_argument") {
    for (const char* bad : {"", "hg", "hg:", "hg:1", "hg:-1", "hg:abc", "hg:0.5,0.1",
                            "dual_hg:0.5,0.2", "dual_hg:0.5,0.2,1.5", "cs:2", "draine:0.5",
                            "draine:0.5,-1", "mie_approx:0", "mie_approx:60", "isotropic:1",
                            "table:", "foo:1"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS((void)mc::make_phase(bad), std::invalid_argument);
    }
    CHECK_THROWS_AS((void)mc::make_phase("table:/nonexistent/phase.csv"), std::runtime_error);
    for (const char* bad : {"", "x:1,0", "r:0,0", "r:1.5,0", "r:1", "t:0.5,abc"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS((void)mc::parse_slab_views(bad), std::invalid_argument);
    }
}

TEST_CASE("determinism: same seed, different thread counts, identical results") {
    const mc::phase_model phase = mc::make_phase("cs:0.8");
    const auto a = mc::trace_slab({2.0, 0.7, 0.95}, phase, 30000, 8, options(1, 11));
    const auto b = mc::trace_slab({2.0, 0.7, 0.95}, phase, 30000, 8, options(3, 11));
    const auto c = mc::trace_slab({2.0, 0.7, 0.95}, phase, 30000, 8, options(1, 12));
    CHECK(a.reflected.mean == b.reflected.mean);
    CHECK(a.reflected.std_error == b.reflected.std_error);
    CHECK(a.transmitted_diffuse.mean == b.transmitted_diffuse.mean);
    CHECK(a.absorbed.mean == b.absorbed.mean);
    for (std::size_t i = 0; i < a.reflected_radiance.size(); ++i) {
        CHECK(a.reflected_radiance[i].mean == b.reflected_radiance[i].mean);
        CHECK(a.transmitted_radiance[i].std_error == b.transmitted_radiance[i].std_error);
    }
    CHECK(a.reflected.mean != c.reflected.mean);

    const mc::sphere_camera cam = mc::make_sphere_camera_grid(120.0, 3);
    const auto s1 = mc::sphere_radiance({10.0, 0.99, cam.sun_direction}, phase, cam.rays, 5000,
                                        options(1, 13));
    const auto s2 = mc::sphere_radiance({10.0, 0.99, cam.sun_direction}, phase, cam.rays, 5000,
                                        options(2, 13));
    for (std::size_t i = 0; i < s1.size(); ++i) {
        CHECK(s1[i].mean == s2[i].mean);
        CHECK(s1[i].std_error == s2[i].std_error);
    }
    double last = -1.0;
    mc::run_options with_progress = options(2, 13);
    with_progress.progress = [&](double f) {
        CHECK(f > last);
        last = f;
    };
    (void)mc::slab_radiance({1.0, 1.0, 1.0}, phase, mc::parse_slab_views("r:1,0;t:1,0"), 10000,
                            with_progress);
    CHECK(last == 1.0);
}

TEST_CASE("sphere camera: geometry of the orthographic camera builders") {
    const mc::sphere_camera cam = mc::make_sphere_camera_line(90.0, 9);
    REQUIRE(cam.rays.size() == 9);
    CHECK(cam.u[4] == doctest::Approx(0.0));
    CHECK(cam.u[0] == doctest::Approx(-8.0 / 9.0));
    const mc::vec3& d = cam.view_direction;
    CHECK(d.x * cam.sun_direction.x + d.y * cam.sun_direction.y + d.z * cam.sun_direction.z ==
          doctest::Approx(0.0).epsilon(1e-12));
    // u > 0 is the sunward side.
    CHECK(cam.axis_u.z > 0.99);
    const mc::sphere_camera grid = mc::make_sphere_camera_grid(30.0, 4);
    CHECK(grid.rays.size() == 16);
    CHECK_THROWS_AS((void)mc::make_sphere_camera_line(181.0, 3), std::invalid_argument);
}
