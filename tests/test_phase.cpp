// Tests of phase.hpp: normalisation over the sphere, mean cosines against closed forms,
// pointwise accuracy in float against long double textbook formulas, the published
// Jendersie & d'Eon values, HG sampling statistics, and the hard cases |g| -> 1, mu = +-1.
#include <cloudmath/phase.hpp>

#include <cmath>
#include <initializer_list>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {

const ld PI = 3.141592653589793238462643383279502884L;

// Textbook forms (the references; independent of the code under test). The base
// 1 + g^2 - 2 g mu is evaluated in quad precision, where its cancellation near the peaks
// (8 digits at |g| = 0.9999) still leaves ~1e-26; the rest in long double.
ld pow15_ref(ld mu, ld g) {  // (1 + g^2 - 2 g mu)^(3/2)
    const cm_test::quad q_mu = mu, q_g = g;
    const cm_test::quad d = 1 + q_g * q_g - 2 * q_g * q_mu;
    return static_cast<ld>(d * cm_test::sqrt_q(d));
}
ld hg_ref(ld mu, ld g) { return (1 - g * g) / (4 * PI * pow15_ref(mu, g)); }
ld cs_ref(ld mu, ld g) {
    return 3 / (8 * PI) * (1 - g * g) / (2 + g * g) * (1 + mu * mu) / pow15_ref(mu, g);
}
ld draine_ref(ld mu, ld g, ld a) {
    return (1 - g * g) * (1 + a * mu * mu) / (4 * PI * (1 + a * (1 + 2 * g * g) / 3) * pow15_ref(mu, g));
}
ld schlick_ref(ld mu, ld k) { return (1 - k * k) / (4 * PI * (1 - k * mu) * (1 - k * mu)); }
ld draine_mean_cos(ld g, ld a) {
    return g * (1 + a * (3 + 2 * g * g) / 5) / (1 + a * (1 + 2 * g * g) / 3);
}

// Integral and mean cosine of a phase function given as p(mu) in double.
template <class F>
ld integral(F p) {
    return cm_test::integrate_sphere([&](ld mu) { return static_cast<ld>(p(static_cast<double>(mu))); });
}
template <class F>
ld mean_cosine(F p) {
    return cm_test::integrate_sphere(
        [&](ld mu) { return mu * static_cast<ld>(p(static_cast<double>(mu))); });
}

std::vector<double> g_grid() {  // -0.99 .. 0.99 in steps of 0.01
    std::vector<double> gs;
    for (int i = -99; i <= 99; ++i) gs.push_back(i / 100.0);
    return gs;
}

// mu grid dense near both ends: +-1, +-(1 - 10^-k), and a uniform interior.
template <class T>
std::vector<T> mu_grid() {
    std::vector<T> mus;
    for (int i = -100; i <= 100; ++i) mus.push_back(static_cast<T>(i / 100.0L));
    for (int k = 1; k <= 15; ++k) {
        const T d = static_cast<T>(std::pow(10.0L, -k));
        mus.push_back(T(1) - d);
        mus.push_back(T(-1) + d);
    }
    return mus;
}

}  // namespace

TEST_CASE_TEMPLATE("isotropic and Rayleigh: values and normalisation", T, float, double) {
    static_assert(phase_isotropic<T>() > T(0), "constexpr");
    CHECK(cm_test::rel_err(phase_isotropic<T>(), 1 / (4 * PI)) <= cm_test::eps<T>());
    for (T mu : mu_grid<T>())
        CHECK(cm_test::rel_err(phase_rayleigh(mu), 3 * (1 + ld(mu) * ld(mu)) / (16 * PI)) <= 4 * cm_test::eps<T>());
    CHECK(std::fabs(integral([](double mu) { return phase_rayleigh(mu); }) - 1) < 1e-12L);
    CHECK(std::fabs(mean_cosine([](double mu) { return phase_rayleigh(mu); })) < 1e-12L);
    CHECK(phase_rayleigh(T(2)) == phase_rayleigh(T(1)));  // mu clamped
}

TEST_CASE("HG, Cornette-Shanks, Draine integrate to 1 and have the closed-form mean cosine, |g| <= 0.99") {
    ld worst_norm = 0, worst_mean = 0;
    for (double g : g_grid()) {
        const ld n_hg = integral([g](double mu) { return phase_hg(mu, g); });
        const ld m_hg = mean_cosine([g](double mu) { return phase_hg(mu, g); });
        const ld n_cs = integral([g](double mu) { return phase_cornette_shanks(mu, g); });
        const ld m_cs = mean_cosine([g](double mu) { return phase_cornette_shanks(mu, g); });
        const ld gl = g;
        const ld cs_mean = 3 * gl * (4 + gl * gl) / (5 * (2 + gl * gl));
        worst_norm = std::fmax(worst_norm, std::fmax(std::fabs(n_hg - 1), std::fabs(n_cs - 1)));
        worst_mean = std::fmax(worst_mean, std::fmax(std::fabs(m_hg - gl), std::fabs(m_cs - cs_mean)));
        for (double a : {0.0, 0.5, 1.0, 5.0, 250.0}) {
            const ld n_d = integral([g, a](double mu) { return phase_draine(mu, g, a); });
            const ld m_d = mean_cosine([g, a](double mu) { return phase_draine(mu, g, a); });
            worst_norm = std::fmax(worst_norm, std::fabs(n_d - 1));
            worst_mean = std::fmax(worst_mean, std::fabs(m_d - draine_mean_cos(gl, a)));
        }
    }
    MESSAGE("worst |integral - 1| = " << double(worst_norm) << ", worst mean-cosine error = " << double(worst_mean));
    CHECK(worst_norm < 1e-6L);
    CHECK(worst_mean < 1e-6L);
    // REFERENCES.md: Cornette-Shanks mean cosine 0.88466 at g = 0.85.
    CHECK(std::fabs(mean_cosine([](double mu) { return phase_cornette_shanks(mu, 0.85); }) - 0.88466L) < 5e-6L);
}

TEST_CASE("HG stays normalised at the clamp |g| = 0.9999 and for |g| >= 1 (clamped, finite)") {
    for (double g : {0.999, 0.9999, 1.0, 1.5, -0.999, -0.9999, -1.0}) {
        const ld n = integral([g](double mu) { return phase_hg(mu, g); });
        INFO("g = " << g);
        CHECK(std::fabs(n - 1) < 1e-6L);
    }
    CHECK(phase_hg(1.0f, 1.0f) == phase_hg(1.0f, phase_g_max<float>));
    CHECK(phase_hg(1.0f, -1.0f) == phase_hg(1.0f, -phase_g_max<float>));
    CHECK(cm_test::finite_bits(phase_hg(1.0f, 1.0f)));
    CHECK(cm_test::finite_bits(phase_cornette_shanks(1.0f, 1.0f)));
    CHECK(cm_test::finite_bits(phase_draine(-1.0f, -1.0f, 250.0f)));
    CHECK(phase_hg(-1.0f, 1.0f) >= 0.0f);
    // Peak value at the clamp, documented in the header: 1.59e7.
    CHECK(std::fabs(phase_hg(1.0, 1.0) - 1.5915e7) < 0.001e7);
}

TEST_CASE("known mistake: HG divided by 4 * 3.1415 or (4 + pi) is not normalised; ours is") {
    const double g = 0.6;
    const ld ours = integral([g](double mu) { return phase_hg(mu, g); });
    const ld gpu_pro = integral([g](double mu) { return phase_hg(mu, g) * 4.0 * 3.141592653589793 / (4.0 * 3.1415); });
    const ld lygia = integral([g](double mu) { return phase_hg(mu, g) * 4.0 * 3.141592653589793 / (4.0 + 3.141592653589793); });
    CHECK(std::fabs(ours - 1) < 1e-9L);
    CHECK(std::fabs(gpu_pro - 1) > 2e-5L);
    CHECK(std::fabs(lygia - 1) > 0.5L);
}

TEST_CASE("known mistake: Cornette-Shanks with mu^2 in the denominator integrates to 1.246 at g = 0.5") {
    // The seed-thesis variant: 3/2 (1-g^2)/(2+g^2) (1+mu^2) / (1 + g^2 - 2 g mu^2)^(3/2) / (4 pi).
    auto wrong = [](ld mu, ld g) {
        return 3 / (8 * PI) * (1 - g * g) / (2 + g * g) * (1 + mu * mu) / std::pow(1 + g * g - 2 * g * mu * mu, 1.5L);
    };
    const ld n_wrong_05 = cm_test::integrate_sphere([&](ld mu) { return wrong(mu, 0.5L); });
    const ld n_wrong_085 = cm_test::integrate_sphere([&](ld mu) { return wrong(mu, 0.85L); });
    CHECK(std::fabs(n_wrong_05 - 1.246L) < 1e-3L);   // REFERENCES.md
    CHECK(std::fabs(n_wrong_085 - 1.091L) < 1e-3L);
    CHECK(std::fabs(integral([](double mu) { return phase_cornette_shanks(mu, 0.5); }) - 1) < 1e-9L);
}

TEST_CASE_TEMPLATE("pointwise accuracy against long double, forward and backward peaks", T, float, double) {
    // Inputs are taken as the exact float/double values, so only the algorithm's rounding
    // is measured. Budgets in units of the type's epsilon.
    ld worst_hg = 0, worst_cs = 0, worst_d = 0, worst_s = 0;
    for (T g : {T(-0.9999), T(-0.999), T(-0.99), T(-0.8), T(-0.3), T(0), T(1e-4), T(0.3), T(0.8), T(0.85), T(0.99), T(0.995), T(0.999), T(0.9999)}) {
        for (T mu : mu_grid<T>()) {
            worst_hg = std::fmax(worst_hg, cm_test::rel_err_eps(phase_hg(mu, g), hg_ref(mu, g)));
            worst_cs = std::fmax(worst_cs, cm_test::rel_err_eps(phase_cornette_shanks(mu, g), cs_ref(mu, g)));
            worst_d = std::fmax(worst_d, cm_test::rel_err_eps(phase_draine(mu, g, T(21.996)), draine_ref(mu, g, ld(T(21.996)))));
            worst_s = std::fmax(worst_s, cm_test::rel_err_eps(phase_schlick(mu, g), schlick_ref(mu, g)));
        }
    }
    MESSAGE(cm_test::type_name<T>() << ": worst error in eps: HG " << double(worst_hg) << ", CS " << double(worst_cs)
                                     << ", Draine " << double(worst_d) << ", Schlick " << double(worst_s));
    CHECK(worst_hg <= 8);
    CHECK(worst_cs <= 10);
    CHECK(worst_d <= 12);
    // Schlick's (1 - k) + k (1 - mu) is folded back into 1 - k mu by -ffast-math's
    // re-association (HG's squared form is not); its peak accuracy is then ~1e-4 relative,
    // far inside the approximation's own 9-90% error (documented in phase.hpp).
    CHECK(worst_s <= (cm_test::ieee_build ? 8 : 4096));
}

TEST_CASE("known mistake: the textbook HG denominator in float loses 10% at g = 0.999") {
    auto naive = [](float mu, float g) {
        volatile float d = 1.0f + g * g - 2.0f * g * mu;
        return (1.0f - g * g) / (4.0f * 3.14159265f * d * std::sqrt(d));
    };
    struct row { float g; ld naive_at_least; };
    for (row r : {row{0.99f, 1e-4L}, row{0.995f, 5e-4L}, row{0.999f, 2e-2L}}) {
        const ld ref = hg_ref(1.0L, r.g);
        const ld e_naive = cm_test::rel_err(naive(1.0f, r.g), ref);
        const ld e_ours = cm_test::rel_err(phase_hg(1.0f, r.g), ref);
        MESSAGE("g = " << r.g << ": naive float error " << double(e_naive) << ", ours " << double(e_ours));
        CHECK(e_naive > r.naive_at_least);
        CHECK(e_ours < 1e-6L);
    }
}

TEST_CASE_TEMPLATE("dual-lobe HG is the documented mix, normalised, w clamped", T, float, double) {
    for (T mu : mu_grid<T>()) {
        const ld ref = 0.5L * hg_ref(mu, ld(T(0.8))) + 0.5L * hg_ref(mu, ld(T(-0.5)));
        CHECK(cm_test::rel_err_eps(phase_hg_dual(mu, T(0.8), T(-0.5), T(0.5)), ref) <= 10);
    }
    CHECK(phase_hg_dual(T(0.3), T(0.8), T(-0.5), T(2)) == phase_hg(T(0.3), T(-0.5)));
    CHECK(phase_hg_dual(T(0.3), T(0.8), T(-0.5), T(-1)) == phase_hg(T(0.3), T(0.8)));
    const ld n = integral([](double mu) { return phase_hg_dual(mu, 0.8, 0.5, 0.9); });
    const ld m = mean_cosine([](double mu) { return phase_hg_dual(mu, 0.8, 0.5, 0.9); });
    CHECK(std::fabs(n - 1) < 1e-9L);
    CHECK(std::fabs(m - (0.1L * 0.8L + 0.9L * 0.5L)) < 1e-9L);
}

TEST_CASE("Schlick: exactly normalised; phase_hg_schlick within its documented error of HG") {
    for (double k : {-0.9, -0.5, 0.0, 0.5, 0.9, 0.99})
        CHECK(std::fabs(integral([k](double mu) { return phase_schlick(mu, k); }) - 1) < 1e-9L);
    CHECK(schlick_k_from_hg_g(0.5) == doctest::Approx(1.55 * 0.5 - 0.55 * 0.125));
    static_assert(schlick_k_from_hg_g(0.0f) == 0.0f, "constexpr");
    // Documented maximum relative error against HG over mu in [-1, 1].
    struct bound { double g_max; double err; };
    for (bound b : {bound{0.3, 0.09}, bound{0.5, 0.23}, bound{0.8, 0.66}, bound{0.9, 0.90}}) {
        double worst = 0;
        for (int gi = -100; gi <= 100; ++gi) {
            const double g = b.g_max * gi / 100.0;
            for (double mu : mu_grid<double>())
                worst = std::fmax(worst, double(cm_test::rel_err(phase_hg_schlick(mu, g), hg_ref(mu, g))));
        }
        MESSAGE("|g| <= " << b.g_max << ": Schlick max relative error " << worst);
        CHECK(worst <= b.err);
        CHECK(worst > b.err * 0.8);  // the documented bound is tight, not a blanket
    }
}

TEST_CASE("Jendersie & d'Eon Mie approximation reproduces the published table") {
    struct row { double d, g_hg, g_d, alpha, w_d, p0, p180, mean; };
    for (row r : {row{5, 0.97068, 0.50834, 17.068, 0.44783, 101.1, 0.0148, 0.843},
                  row{10, 0.98818, 0.55567, 21.996, 0.48196, 586.9, 0.0127, 0.864},
                  row{20, 0.99461, 0.59379, 27.114, 0.49816, 2742, 0.0109, 0.879},
                  row{50, 0.99795, 0.62508, 32.315, 0.50762, 18673, 0.0095, 0.892}}) {
        INFO("d = " << r.d);
        const mie_approx_parameters<double> p = mie_approx_params(r.d);
        CHECK(std::fabs(p.g_hg - r.g_hg) < 6e-6);     // table printed to 5 decimals
        CHECK(std::fabs(p.g_draine - r.g_d) < 6e-6);
        CHECK(std::fabs(p.alpha - r.alpha) < 6e-4);
        CHECK(std::fabs(p.w_draine - r.w_d) < 6e-6);
        CHECK(cm_test::rel_err(phase_mie_approx(1.0, r.d), r.p0) < 1e-3L);   // 4 significant digits
        CHECK(cm_test::rel_err(phase_mie_approx(-1.0, r.d), r.p180) < 4e-3L);
        // Mean cosine: by quadrature against the mixture's closed form (HG mean g_HG, Draine
        // mean from REFERENCES.md), and against the table. The table's 0.892 at d = 50 is
        // not what its own parameters give (0.89119), so the table check allows 1e-3.
        const ld m = mean_cosine([&](double mu) { return phase_mie_approx(mu, p); });
        const ld closed = (1 - ld(p.w_draine)) * p.g_hg + ld(p.w_draine) * draine_mean_cos(p.g_draine, p.alpha);
        CHECK(std::fabs(m - closed) < 1e-9L);
        CHECK(std::fabs(m - r.mean) < 1e-3L);
        CHECK(phase_mie_approx(0.3, r.d) == phase_mie_approx(0.3, p));
        CHECK(phase_mie_approx(0.3f, float(r.d)) == doctest::Approx(phase_mie_approx(0.3, r.d)).epsilon(1e-5));
    }
}

TEST_CASE("Mie approximation: normalised and finite over all four diameter ranges, 0.1 to 50 um") {
    std::vector<double> ds = {0.1, 0.1000001, 0.2, 0.5, 1.0, 1.4999999, 1.5, 2.0, 3.0, 4.0, 4.8104773809653517 /* tan pole */, 4.9999999, 5.0, 7.5, 12.0, 30.0, 50.0};
    for (int i = 0; i <= 60; ++i) ds.push_back(0.1 * std::pow(500.0, i / 60.0));
    ld worst = 0;
    for (double d : ds) {
        const ld n = integral([d](double mu) { return phase_mie_approx(mu, d); });
        worst = std::fmax(worst, std::fabs(n - 1));
        const mie_approx_parameters<double> p = mie_approx_params(d);
        INFO("d = " << d);
        CHECK(p.w_draine >= 0.0);
        CHECK(p.w_draine <= 1.0);
        CHECK(std::fabs(p.g_hg) < 1.0);
        CHECK(std::fabs(p.g_draine) < 1.0);
    }
    MESSAGE("worst |integral - 1| over d in [0.1, 50]: " << double(worst));
    CHECK(worst < 1e-6L);
    // d <= 0.1: w_D = 0.252977 - 312.983 d^4.3, not (312.983 d)^4.3.
    CHECK(mie_approx_params(0.05).w_draine == doctest::Approx(0.252977 - 312.983 * std::pow(0.05, 4.3)));
    CHECK(mie_approx_params(0.0).w_draine == doctest::Approx(0.252977));
    CHECK(std::fabs(integral([](double mu) { return phase_mie_approx(mu, 0.01); }) - 1) < 1e-6L);
    // Out of the fit's range: clamped.
    CHECK(phase_mie_approx(0.5, 80.0) == phase_mie_approx(0.5, 50.0));
    CHECK(phase_mie_approx(0.5, -3.0) == phase_mie_approx(0.5, 0.0));
    for (float d : {0.05f, 0.7f, 3.0f, 4.81047738f, 25.0f})
        for (float mu : mu_grid<float>()) CHECK(cm_test::finite_bits(phase_mie_approx(mu, d)));
}

TEST_CASE_TEMPLATE("all phase functions: non-negative and finite on dense grids, mu clamped", T, float, double) {
    bool ok = true;
    for (int gi = -100; gi <= 100; ++gi) {
        const T g = T(gi) / T(100);
        for (T mu : mu_grid<T>()) {
            for (T p : {phase_hg(mu, g), phase_cornette_shanks(mu, g), phase_draine(mu, g, T(3)),
                        phase_hg_dual(mu, g, -g, T(0.3)), phase_schlick(mu, g), phase_hg_schlick(mu, g)})
                ok = ok && cm_test::finite_bits(p) && p >= T(0);
        }
    }
    CHECK(ok);
    CHECK(phase_hg(T(1.0001), T(0.9)) == phase_hg(T(1), T(0.9)));
    CHECK(phase_hg(T(-7), T(0.9)) == phase_hg(T(-1), T(0.9)));
    CHECK(phase_draine(T(0.2), T(0.5), T(-4)) == phase_draine(T(0.2), T(0.5), T(0)));  // alpha clamped
    CHECK(phase_draine(T(0.2), T(0.5), T(0)) == doctest::Approx(phase_hg(T(0.2), T(0.5))));
    CHECK(phase_draine(T(0.2), T(0.5), T(1)) == doctest::Approx(phase_cornette_shanks(T(0.2), T(0.5))));
    if constexpr (cm_test::ieee_build) {
        CHECK(cm_test::nan_bits(phase_hg(cm_test::make_nan<T>(), T(0.5))));  // documented: NaN propagates
        CHECK(cm_test::finite_bits(phase_hg(T(0.5), cm_test::make_inf<T>())));  // g clamped
    }
}

// ---------------------------------------------------------------------------------------
// Sampling.

namespace {
// Textbook inverse CDF in long double (our convention): mu = (1 + g^2 - s^2) / (2g),
// s = (1 - g^2) / (1 - g + 2 g u).
ld hg_inverse_cdf_ref(ld g, ld u) {
    if (g == 0) return 2 * u - 1;
    const ld s = (1 - g * g) / (1 - g + 2 * g * u);
    return (1 + g * g - s * s) / (2 * g);
}
}  // namespace

TEST_CASE_TEMPLATE("sample_phase_hg is the inverse CDF: accurate 1 - mu in the peak, monotonic, exact ends", T, float, double) {
    for (T g : {T(-0.9999), T(-0.99), T(-0.5), T(-1e-4), T(0), T(1e-4), T(0.5), T(0.9), T(0.99), T(0.9999)}) {
        CHECK(sample_phase_hg(g, T(0)) == T(-1));
        CHECK(sample_phase_hg(g, T(1)) == T(1));
        T prev = T(-1);
        ld worst = 0;
        for (int i = 0; i <= 1000; ++i) {
            const T u = T(i) / T(1000);
            const T mu = sample_phase_hg(g, u);
            CHECK(mu >= prev);
            prev = mu;
            const ld ref = hg_inverse_cdf_ref(ld(g), ld(u));
            // Error of 1 - mu (g >= 0) or 1 + mu (g < 0), relative: the peak side.
            const ld e = g >= 0 ? cm_test::rel_err(1 - ld(mu), 1 - ref) : cm_test::rel_err(1 + ld(mu), 1 + ref);
            worst = std::fmax(worst, std::fmin(e, std::fabs(ld(mu) - ref)));
        }
        INFO("g = " << g);
        CHECK(worst <= 16 * cm_test::eps<T>());
    }
    for (int i = 0; i <= 100; ++i)  // g = 0 is uniform in mu, with no special case
        CHECK(std::fabs(ld(sample_phase_hg(T(0), T(i) / T(100))) - (2 * ld(T(i) / T(100)) - 1)) <= 2 * cm_test::eps<T>());
    CHECK(sample_phase_hg(T(0.5), T(2)) == T(1));    // u clamped
    CHECK(sample_phase_hg(T(5), T(0.5)) == sample_phase_hg(phase_g_max<T>, T(0.5)));
}

TEST_CASE("sample_phase_hg: sampled mean cosine equals g and the histogram passes chi-square") {
    cm_test::rng rng(12345);
    const int n = 200000, bins = 40;
    for (double g : {-0.7, 0.0, 0.3, 0.8, 0.95}) {
        std::vector<int> hist(bins, 0);
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            const double mu = sample_phase_hg(g, rng.uniform());
            sum += mu;
            int b = static_cast<int>((mu + 1) / 2 * bins);
            b = b < 0 ? 0 : (b >= bins ? bins - 1 : b);
            ++hist[static_cast<std::size_t>(b)];
        }
        // Mean within 5 standard errors; the variance from the pdf by quadrature.
        const ld second = cm_test::integrate_sphere([g](ld mu) { return mu * mu * hg_ref(mu, g); });
        const double sigma = std::sqrt(double(second - ld(g) * ld(g)) / n);
        INFO("g = " << g);
        CHECK(std::fabs(sum / n - g) < 5 * sigma);
        // Chi-square against bin probabilities integrated from the pdf (not from the sampler).
        static const cm_test::gauss16 gl;
        double chi2 = 0;
        for (int b = 0; b < bins; ++b) {
            const ld lo = -1 + 2.0L * b / bins, hi = -1 + 2.0L * (b + 1) / bins;
            const ld prob = 2 * PI * gl.integrate([g](ld mu) { return hg_ref(mu, g); }, lo, hi);
            const double expected = double(prob) * n;
            const double diff = hist[static_cast<std::size_t>(b)] - expected;
            chi2 += diff * diff / expected;
        }
        MESSAGE("g = " << g << ": chi-square " << chi2 << " with " << bins - 1 << " degrees of freedom");
        CHECK(chi2 < 80.0);  // p ~ 1e-4 for 39 degrees of freedom
    }
}

// Regression (fuzzing): mu went backwards by an ulp as u grew (3884 times over 2^24 + 1
// evenly spaced u at g = 0.3 in float), against the documented monotonicity. Dense sweeps:
// 2^20 + 1 evenly spaced u, and every representable u in windows of 2^15 values at 0, 1/4,
// 1/2, 3/4, 1 - 1e-4 and 1, for g across the range and at the clamp |g| -> 1.
TEST_CASE_TEMPLATE("sample_phase_hg is monotonic in u bit for bit: dense sweeps, |g| up to the clamp", T, float, double) {
    const T gs[] = {T(0), T(1e-4), T(0.1), T(0.3), T(-0.3), T(0.5), T(0.8), T(-0.8), T(0.9), T(0.99), T(-0.99),
                    T(0.999), T(-0.999), T(0.9999), T(-0.9999), T(1), T(-1)};
    for (T g : gs) {
        long backwards = 0;
        T prev = T(-1);
        const long n = 1L << 20;
        for (long i = 0; i <= n; ++i) {
            const T mu = sample_phase_hg(g, T(i) / T(n));
            backwards += mu < prev;
            prev = mu;
        }
        for (T centre : {T(0), T(0.25), T(0.5), T(0.75), T(1) - T(1e-4), T(1)}) {
            T u = centre;
            for (int k = 0; k < (1 << 14) && u > T(0); ++k) u = std::nextafter(u, T(-1));
            prev = sample_phase_hg(g, u);
            for (int k = 0; k < (1 << 15) && u < T(1); ++k) {
                u = std::nextafter(u, T(2));
                const T mu = sample_phase_hg(g, u);
                backwards += mu < prev;
                prev = mu;
            }
        }
        INFO("g = " << g);
        CHECK(backwards == 0);
        CHECK(sample_phase_hg(g, T(0)) == T(-1));
        CHECK(sample_phase_hg(g, T(1)) == T(1));
    }
}
