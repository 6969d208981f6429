// Tests of density.hpp: height gradients and their presets, type blending, the exponential
// height distribution, coverage (monotonic, the fixed GPU Pro 7 inversion), erosion, and
// exponential height fog with its analytic optical depth against quadrature.
#include <cloudmath/density.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {
ld smoothstep_ref(ld e0, ld e1, ld x) {
    const ld t = std::fmin(std::fmax((x - e0) / (e1 - e0), 0.0L), 1.0L);
    return t * t * (3 - 2 * t);
}
}  // namespace

TEST_CASE_TEMPLATE("height_gradient: difference of two smoothsteps, presets in [0, 1]", T, float, double) {
    const glm::vec<4, T> p(T(0.1), T(0.3), T(0.6), T(0.9));
    for (int i = 0; i <= 100; ++i) {
        const T h = T(i) / T(100);
        const ld ref = smoothstep_ref(0.1L, 0.3L, h) - smoothstep_ref(0.6L, 0.9L, h);
        CHECK(std::fabs(ld(height_gradient(h, p)) - ref) <= 16 * cm_test::eps<T>());
    }
    CHECK(height_gradient(T(0.45), p) == T(1));
    CHECK(height_gradient(T(0), p) == T(0));
    CHECK(height_gradient(T(1), p) == T(0));
    // Degenerate edges: a box, defined (GLSL smoothstep would be undefined).
    const glm::vec<4, T> box(T(0.2), T(0.2), T(0.7), T(0.7));
    CHECK(height_gradient(T(0.1), box) == T(0));
    CHECK(height_gradient(T(0.5), box) == T(1));
    CHECK(height_gradient(T(0.8), box) == T(0));
    // Presets (REFERENCES.md values).
    CHECK(height_profile_stratus<T>() == glm::vec<4, T>(T(0.02), T(0.05), T(0.09), T(0.11)));
    CHECK(height_profile_stratocumulus<T>() == glm::vec<4, T>(T(0.02), T(0.2), T(0.48), T(0.625)));
    CHECK(height_profile_cumulus<T>() == glm::vec<4, T>(T(0.01), T(0.0625), T(0.78), T(1.0)));
    for (int i = 0; i <= 200; ++i) {
        const T h = T(i) / T(200);
        for (const glm::vec<4, T>& q : {height_profile_stratus<T>(), height_profile_stratocumulus<T>(), height_profile_cumulus<T>()}) {
            CHECK(height_gradient(h, q) >= T(0));
            CHECK(height_gradient(h, q) <= T(1));
        }
    }
    CHECK(height_gradient(T(0.07), height_profile_stratus<T>()) == T(1));
    CHECK(height_gradient(T(0.3), height_profile_stratus<T>()) == T(0));   // stratus is thin
    CHECK(height_gradient(T(0.5), height_profile_cumulus<T>()) == T(1));  // cumulus is tall
}

TEST_CASE_TEMPLATE("height_gradient_for_type: presets at 0, 0.5, 1, blended profiles between", T, float, double) {
    for (int i = 0; i <= 50; ++i) {
        const T h = T(i) / T(50);
        CHECK(cm_test::same_value(height_gradient_for_type(h, T(0)), height_gradient(h, height_profile_stratus<T>())));
        CHECK(cm_test::same_value(height_gradient_for_type(h, T(0.5)), height_gradient(h, height_profile_stratocumulus<T>())));
        CHECK(cm_test::same_value(height_gradient_for_type(h, T(1)), height_gradient(h, height_profile_cumulus<T>())));
        CHECK(height_gradient_for_type(h, T(-3)) == height_gradient_for_type(h, T(0)));  // type clamped
        CHECK(height_gradient_for_type(h, T(7)) == height_gradient_for_type(h, T(1)));
    }
    // Type 0.25: the profile halfway between stratus and stratocumulus.
    const glm::vec<4, T> mid = height_profile_for_type(T(0.25));
    const glm::vec<4, T> want = (height_profile_stratus<T>() + height_profile_stratocumulus<T>()) * T(0.5);
    for (int c = 0; c < 4; ++c) CHECK(mid[c] == doctest::Approx(want[c]));
    // Weights sum to one everywhere, so the blended edges stay ordered.
    for (int i = 0; i <= 100; ++i) {
        const glm::vec<4, T> q = height_profile_for_type(T(i) / T(100));
        CHECK(q.x <= q.y);
        CHECK(q.y <= q.z);
        CHECK(q.z <= q.w);
    }
}

TEST_CASE_TEMPLATE("height_range_for_type: the gradient is exactly 0 outside the range, positive just inside", T, float, double) {
    // The presets' own edges (closed form: the profile's first and last edge).
    CHECK(height_range_for_type(T(0)) == glm::vec<2, T>(T(0.02), T(0.11)));
    CHECK(height_range_for_type(T(0.5)) == glm::vec<2, T>(T(0.02), T(0.625)));
    CHECK(height_range_for_type(T(1)) == glm::vec<2, T>(T(0.01), T(1)));
    CHECK(height_range_for_type(T(-2)) == height_range_for_type(T(0)));  // type clamped
    for (int i = 0; i <= 40; ++i) {
        const T type = T(i) / T(40);
        const glm::vec<2, T> r = height_range_for_type(type);
        REQUIRE(r.x < r.y);
        // Outside: exactly zero, so a march clamped to the range loses nothing. (Under
        // -ffast-math the profile's edge may round differently in the two call sites, so
        // the edges themselves are checked in strict builds only.)
#ifdef __FAST_MATH__
        const int last = 49;
#else
        const int last = 50;
#endif
        for (int j = 0; j <= last; ++j) {
            const T below = r.x * T(j) / T(50);
            const T above = r.y + (T(1) - r.y) * T(50 - j) / T(50);
            CHECK(height_gradient_for_type(below, type) == T(0));
            CHECK(height_gradient_for_type(above, type) == T(0));
        }
        // Tight: density a hair inside either end (the range is not padded).
        const T eps = (r.y - r.x) * T(1e-3);
        CHECK(height_gradient_for_type(r.x + eps, type) > T(0));
        CHECK(height_gradient_for_type(r.y - eps, type) > T(0));
    }
    CHECK(std::isnan(height_range_for_type(std::numeric_limits<T>::quiet_NaN()).x));
}

TEST_CASE_TEMPLATE("height_gradient_exponential: Olajos (1 - exp(-a h)) exp(-b h)", T, float, double) {
    for (int i = 0; i <= 100; ++i) {
        const T h = T(i) / T(100);
        const ld ref = -std::expm1(-50 * ld(h)) * std::exp(-4 * ld(h));
        CHECK(cm_test::close_ulps(height_gradient_exponential(h, T(50), T(4)), ref, 8));
    }
    // Tiny h keeps relative precision (1 - exp(-a h) would round to 0 in float).
    CHECK(cm_test::rel_err(height_gradient_exponential(T(1e-12), T(50), T(4)), 50e-12L) <= 1e-6L);
    // Peak of (1 - e^-50h) e^-4h at h = ln(54/4)/50.
    const T peak = static_cast<T>(std::log(54.0L / 4) / 50);
    CHECK(height_gradient_exponential(peak, T(50), T(4)) >= height_gradient_exponential(peak * T(0.95), T(50), T(4)));
    CHECK(height_gradient_exponential(peak, T(50), T(4)) >= height_gradient_exponential(peak * T(1.05), T(50), T(4)));
    CHECK(height_gradient_exponential(T(-0.1), T(50), T(4)) == T(0));
}

TEST_CASE_TEMPLATE("apply_coverage: max(0, base + coverage - 1), monotonic in coverage (not inverted)", T, float, double) {
    for (int b = 0; b <= 20; ++b)
        for (int c = 0; c <= 20; ++c) {
            const T base = T(b) / T(20), cov = T(c) / T(20);
            const ld ref = std::fmax(0.0L, ld(base) + ld(cov) - 1);
            CHECK(std::fabs(ld(apply_coverage(base, cov)) - ref) <= 8 * cm_test::eps<T>());
        }
    // More coverage never gives less cloud (GPU Pro 7's text has it the other way round).
    for (int b = 0; b <= 50; ++b) {
        T prev = T(0);
        for (int c = 0; c <= 200; ++c) {
            const T v = apply_coverage(T(b) / T(50), T(c) / T(200));
            CHECK(v >= prev);
            prev = v;
        }
    }
    CHECK(apply_coverage(T(0.8), T(0)) == T(0));
    CHECK(apply_coverage(T(0.8), T(1)) == T(0.8));
    CHECK(apply_coverage(T(1), T(0)) == T(0));        // degenerate remap range, finite
    CHECK(apply_coverage(T(0.8), T(2)) == T(0.8));     // coverage clamped
    CHECK(apply_coverage(T(0.8), T(-1)) == T(0));
}

TEST_CASE_TEMPLATE("erode: remap_clamped(base, erosion, 1, 0, 1)", T, float, double) {
    CHECK(erode(T(0.5), T(0)) == T(0.5));
    CHECK(erode(T(0.2), T(0.3)) == T(0));
    CHECK(erode(T(0.65), T(0.3)) == doctest::Approx(T(0.5)));
    CHECK(erode(T(1), T(0.3)) == T(1));
    CHECK(erode(T(0.999), T(1)) == T(0));   // degenerate: a step, finite
    CHECK(erode(T(1), T(1)) == T(1));
    for (int i = 0; i <= 100; ++i) {
        const T v = erode(T(i) / T(100), T(0.4));
        CHECK(v >= T(0));
        CHECK(v <= T(1));
    }
}

TEST_CASE_TEMPLATE("height fog: density and the analytic optical depth against quadrature", T, float, double) {
    CHECK(cm_test::rel_err(height_fog_density(T(100), T(0.02), T(0.001)), 0.02L * std::exp(-0.1L)) <= 4 * cm_test::eps<T>());
    static const cm_test::gauss16 gl;
    ld worst = 0;
    for (T h : {T(0), T(10), T(500)})
        for (T mu : {T(-0.5), T(-1e-6), T(0), T(1e-9), T(0.01), T(0.3), T(1)})
            for (T L : {T(1), T(100), T(5000)}) {
                const T rho0 = T(0.02), k = T(0.002);
                // Reference: the integral by composite Gauss-Legendre in long double.
                ld ref = 0;
                for (int p = 0; p < 16; ++p)
                    ref += gl.integrate([&](ld t) { return ld(rho0) * std::exp(-ld(k) * (ld(h) + t * ld(mu))); }, ld(L) * p / 16, ld(L) * (p + 1) / 16);
                worst = std::fmax(worst, cm_test::rel_err(height_fog_optical_depth(h, mu, L, rho0, k), ref));
            }
    MESSAGE(cm_test::type_name<T>() << ": height_fog_optical_depth worst relative error " << double(worst));
    CHECK(worst <= 16 * cm_test::eps<T>());
    // Horizontal rays and zero falloff are exact: rho0 L exp(-k h).
    CHECK(cm_test::rel_err(height_fog_optical_depth(T(10), T(0), T(100), T(0.02), T(0.002)), 0.02L * 100 * std::exp(-ld(T(0.002)) * 10)) <= 4 * cm_test::eps<T>());
    CHECK(height_fog_optical_depth(T(10), T(0.5), T(100), T(0.02), T(0)) == doctest::Approx(T(2)));
    // Looking steeply down from high up over a long distance: no overflow (written from the low end).
    const T deep = height_fog_optical_depth(T(3000), T(-1), T(3000), T(0.02), T(0.05));
    CHECK(cm_test::finite_bits(deep));
    CHECK(cm_test::rel_err(deep, 0.02L / 0.05L * -std::expm1(-ld(T(0.05)) * 3000)) <= 8 * cm_test::eps<T>());
    CHECK(height_fog_optical_depth(T(10), T(-3), T(5), T(0.02), T(0.002)) == height_fog_optical_depth(T(10), T(-1), T(5), T(0.02), T(0.002)));
}

TEST_CASE_TEMPLATE("density functions: denormal and NaN inputs (documented: NaN propagates)", T, float, double) {
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(height_gradient(tiny, height_profile_cumulus<T>()) == T(0));
    CHECK(height_gradient_exponential(tiny, T(50), T(4)) >= T(0));
    CHECK(apply_coverage(tiny, T(1)) == tiny);
    CHECK(height_fog_optical_depth(T(0), tiny, T(10), T(0.1), T(0.01)) == doctest::Approx(T(1)));
    if constexpr (cm_test::ieee_build) {
        const T nan = cm_test::make_nan<T>();
        CHECK(cm_test::nan_bits(height_gradient(nan, height_profile_cumulus<T>())));
        CHECK(cm_test::nan_bits(height_gradient_for_type(T(0.5), nan)));
        CHECK(cm_test::nan_bits(apply_coverage(nan, T(0.5))));
        CHECK(cm_test::nan_bits(erode(nan, T(0.5))));
        CHECK(cm_test::nan_bits(height_fog_optical_depth(nan, T(0.5), T(10), T(0.1), T(0.01))));
        CHECK(height_fog_density(cm_test::make_inf<T>(), T(0.1), T(0.01)) == T(0));
    }
}

TEST_CASE_TEMPLATE("Nubis density model: each step against its formula, limits and ranges", T, float, double) {
    using v3 = glm::vec<3, T>;
    using v4 = glm::vec<4, T>;
    // Low-frequency fBm: G 0.625 + B 0.25 + A 0.125 (weights sum to 1).
    CHECK(nubis_low_frequency_fbm(v4(T(0.9), T(1), T(1), T(1))) == T(1));
    CHECK(nubis_low_frequency_fbm(v4(T(0.9), T(0.4), T(0.8), T(0.2))) == doctest::Approx(T(0.4 * 0.625 + 0.8 * 0.25 + 0.2 * 0.125)));
    // Base cloud: remap(R, lf - 1, 1, 0, 1): (R + 1) / 2 when lf = 0, R when lf = 1.
    CHECK(nubis_base_cloud(v4(T(0.5), T(0), T(0), T(0))) == doctest::Approx(T(0.75)));
    CHECK(nubis_base_cloud(v4(T(0.3), T(1), T(1), T(1))) == doctest::Approx(T(0.3)));
    CHECK(nubis_high_frequency_fbm(v3(T(1), T(0), T(0))) == T(0.625));
    // Erosion threshold: 0.2 hf at the bottom (wispy), 0.2 (1 - hf) from a tenth up (billowy).
    const v3 detail(T(0.8), T(0.4), T(0.0));
    const T hf = T(0.8 * 0.625 + 0.4 * 0.25);
    CHECK(nubis_detail_erosion(detail, T(0)) == doctest::Approx(T(0.2) * hf));
    CHECK(nubis_detail_erosion(detail, T(0.1)) == doctest::Approx(T(0.2) * (T(1) - hf)));
    CHECK(nubis_detail_erosion(detail, T(0.7)) == doctest::Approx(T(0.2) * (T(1) - hf)));
    CHECK(nubis_detail_erosion(detail, T(0.05)) == doctest::Approx(T(0.2) * T(0.5)));
    // Composition: zero coverage gives no cloud; without erosion (hf = 0 at h = 0 ... use a
    // detail of 0 at the bottom) the density is the shaped base with coverage applied.
    const v4 base(T(0.8), T(0.5), T(0.5), T(0.5));
    CHECK(nubis_density(base, detail, T(0), T(1), T(0.5)) == T(0));
    const T h = T(0.05);  // inside the cumulus profile's ramp, erosion threshold 0.2 * mix(0, 1, 0.5)
    const T shaped = nubis_base_cloud(base) * height_gradient_for_type(h, T(1));
    CHECK(nubis_density(base, v3(T(0)), T(0.9), T(1), h) == doctest::Approx(erode(apply_coverage(shaped, T(0.9)), T(0.1))));
    // Range and monotonic in coverage over a grid of samples.
    cm_test::rng r(5);
    bool ok = true;
    for (int i = 0; i < 2000; ++i) {
        const v4 b(T(r.uniform()), T(r.uniform()), T(r.uniform()), T(r.uniform()));
        const v3 d(T(r.uniform()), T(r.uniform()), T(r.uniform()));
        const T type = T(r.uniform()), hh = T(r.uniform());
        T prev = T(0);
        for (int c = 0; c <= 10; ++c) {
            const T v = nubis_density(b, d, T(c) / T(10), type, hh);
            ok = ok && v >= T(0) && v <= T(1) && v >= prev && cm_test::finite_bits(v);
            prev = v;
        }
        const T base_cloud = nubis_base_cloud(b);
        ok = ok && base_cloud >= T(0) && base_cloud <= T(1);
    }
    CHECK(ok);
}

TEST_CASE_TEMPLATE("air_optical_depth: Rayleigh and aerosol constants, closed forms and a quadrature", T, float, double) {
    const ld rayleigh[3] = {5.802e-6L, 13.558e-6L, 33.1e-6L};
    const ld aerosol = 4.40e-6L;
    // A level ray at sea level: beta L.
    const glm::vec<3, T> level = air_optical_depth(T(0), T(0), T(10000));
    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(level[c], (rayleigh[c] + aerosol) * 10000) <= 8 * cm_test::eps<T>());
    // Straight up from the ground through the whole atmosphere: beta H.
    const glm::vec<3, T> up = air_optical_depth(T(0), T(1), T(1e6));
    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(up[c], rayleigh[c] * 8000 + aerosol * 1200) <= 8 * cm_test::eps<T>());
    // Slant rays from the ground, the clouds and above them, against a midpoint quadrature.
    for (T h : {T(2), T(2700), T(7000)})
        for (T mu : {T(-0.3), T(-0.01), T(0.02), T(0.5)})
            for (T L : {T(1000), T(35000)}) {
                if (ld(h) + ld(mu) * ld(L) < 0) continue;  // below the ground
                const int n = 20000;
                ld sum_r = 0, sum_a = 0;
                for (int i = 0; i < n; ++i) {
                    const ld alt = ld(h) + ld(mu) * ld(L) * (i + 0.5L) / n;
                    sum_r += std::exp(-alt / 8000);
                    sum_a += std::exp(-alt / 1200);
                }
                const glm::vec<3, T> tau = air_optical_depth(h, mu, L);
                for (int c = 0; c < 3; ++c)
                    CHECK(cm_test::rel_err(tau[c], (rayleigh[c] * sum_r + aerosol * sum_a) * ld(L) / n) <= 1e-5L);
            }
}

TEST_CASE_TEMPLATE("aerial_perspective: L e^-tau + L_air (1 - e^-tau), exact at both ends", T, float, double) {
    for (T tau : {T(0), T(1e-30), T(1e-8), T(1e-3), T(0.5), T(3), T(40), T(1e4)})
        for (T L : {T(0), T(0.3), T(2.5)}) {
            const ld want = ld(L) * std::exp(-ld(tau)) + ld(0.7) * -std::expm1(-ld(tau));
            CHECK(std::abs(ld(aerial_perspective(L, T(0.7), tau)) - want) <= 4 * cm_test::eps<T>() * (std::abs(want) + ld(L)));
        }
    CHECK(aerial_perspective(T(0.3), T(0.7), T(0)) == T(0.3));  // no air: the radiance itself
    const glm::vec<3, T> v = aerial_perspective(glm::vec<3, T>(1, 2, 3), glm::vec<3, T>(0.5), glm::vec<3, T>(0, 1, 100));
    CHECK(v.x == T(1));
    CHECK(v.y == doctest::Approx(0.5 + 1.5 * std::exp(-1.0)));
    CHECK(v.z == doctest::Approx(0.5).epsilon(1e-12));
    if (cm_test::ieee_build) {
        CHECK(aerial_perspective(T(0.3), T(0.7), cm_test::make_inf<T>()) == T(0.7));  // opaque air: only its light
        CHECK(cm_test::nan_bits(aerial_perspective(cm_test::make_nan<T>(), T(0.7), T(1))));
    }
}

// Hardening round 2, A3: L + (L_air - L)(1 - e^-tau) lost L_air when L >> L_air and could
// leave [L, L_air]; the two weighted terms keep it, within a few ulp of the long double value.
TEST_CASE_TEMPLATE("aerial_perspective: L >> L_air keeps L_air, and the result stays between L and L_air", T, float, double) {
    const auto want = [](T L, T L_air, T tau) { return ld(L) * std::exp(-ld(tau)) + ld(L_air) * -std::expm1(-ld(tau)); };
    CHECK(std::abs(ld(aerial_perspective(T(1.5e6), T(0.2), T(30))) - want(T(1.5e6), T(0.2), T(30))) <= 4 * cm_test::eps<T>() * 0.2L);
    if (cm_test::ieee_build) CHECK(aerial_perspective(T(1e13), T(3), cm_test::make_inf<T>()) == T(3));
    CHECK(aerial_perspective(T(1e13), T(3), T(1e6)) == T(3));
    int outside = 0, off = 0;
    for (T L : {T(0), T(1e-20), T(0.2), T(3), T(1e6), T(1e13), T(1e30)})
        for (T L_air : {T(0), T(1e-20), T(0.2), T(3), T(1e6), T(1e13)})
            for (T tau : {T(0), T(1e-30), T(1e-6), T(0.3), T(5), T(30), T(80), T(700), T(1e4)}) {
                const T v = aerial_perspective(L, L_air, tau);
                if (v < std::min(L, L_air) || v > std::max(L, L_air)) ++outside;
                const ld w = want(L, L_air, tau);
                if (std::abs(ld(v) - w) > 4 * cm_test::eps<T>() * w + ld(std::numeric_limits<T>::denorm_min())) ++off;
            }
    CHECK(outside == 0);
    CHECK(off == 0);
    CHECK(aerial_perspective(T(0.3), T(0.7), T(-2)) == T(0.3));  // tau < 0 taken as 0
}

// Found by the fuzz test (hardening round 2): far below the layer hc^2 overflowed and zero
// coverage times -Inf gave NaN; below the layer the density is 0.
TEST_CASE_TEMPLATE("cloud_shape_density: 0 far below the layer, for any coverage", T, float, double) {
    const glm::vec<4, T> base(T(0.8), T(0.5), T(0.5), T(0.5));
    for (T h : {T(-1), T(-1e20), -std::numeric_limits<T>::max()})
        for (T coverage : {T(0), T(0.5), T(1)})
            for (T rounding : {T(0), T(0.6), T(1)})
                CHECK(cloud_shape_density(base, glm::vec<3, T>(T(0.5), T(0.5), T(0.5)), h, coverage, T(0.5), T(0.5), rounding) == T(0));
}

TEST_CASE_TEMPLATE("cloud_top_fraction and cloud_shape_density: per-cloud type, top and rounded tops", T, float, double) {
    CHECK(cloud_top_fraction(T(0)) == T(0.6));
    CHECK(double(cloud_top_fraction(T(1))) == doctest::Approx(1.0));
    CHECK(double(cloud_top_fraction(T(0.5))) == doctest::Approx(0.8));
    CHECK(cloud_top_fraction(T(-3)) == T(0.6));  // the channel is clamped
    CHECK(double(cloud_top_fraction(T(7))) == doctest::Approx(1.0));

    // A base texel whose base cloud is 1 (R = 1, G = B = A = 0: remap(1, -1, 1, 0, 1) = 1).
    const glm::vec<4, T> full(T(1), T(0), T(0), T(0));
    // Neutral weather (G = 0.5, B = 1, R = 0.5) and no rounding: exactly the classic shape,
    // apply_coverage(height_gradient_for_type(h, type), coverage), at every height.
    for (T h : {T(0.05), T(0.2), T(0.5), T(0.77), T(0.95)})
        for (T type : {T(0), T(0.5), T(0.8), T(1)}) {
            CAPTURE(h);
            CAPTURE(type);
            const T want = apply_coverage(height_gradient_for_type(h, type), T(0.4));
            CHECK(double(cloud_shape_density(full, glm::vec<3, T>(T(0.5), T(0.5), T(1)), h, T(0.4), type, T(0.5), T(0))) ==
                  doctest::Approx(double(want)).epsilon(1e-6));
        }
    // G shifts the type by (G - 0.5) type_spread: G = 1 with spread 0.5 on type 0.5 is type 0.75.
    for (T h : {T(0.3), T(0.7), T(0.9)})
        CHECK(double(cloud_shape_density(full, glm::vec<3, T>(T(0.5), T(1), T(1)), h, T(0.4), T(0.5), T(0.5), T(0))) ==
              doctest::Approx(double(apply_coverage(height_gradient_for_type(h, T(0.75)), T(0.4)))).epsilon(1e-6));
    // B lowers the top: B = 0 compresses the profile under 60% of the height; at and above
    // h = 0.6 the density is exactly 0, below it is the profile at h / 0.6.
    const glm::vec<3, T> low(T(0.5), T(0.5), T(0));
    CHECK(cloud_shape_density(full, low, T(0.6), T(0.4), T(1), T(0.5), T(0)) == T(0));
    CHECK(cloud_shape_density(full, low, T(0.9), T(0.4), T(1), T(0.5), T(0)) == T(0));
    CHECK(double(cloud_shape_density(full, low, T(0.3), T(0.4), T(1), T(0.5), T(0))) ==
          doctest::Approx(double(apply_coverage(height_gradient_for_type(T(0.5), T(1)), T(0.4)))).epsilon(1e-6));
    // Rounding: the coverage falls as 1 - r hc^2, so the density never grows with it and the
    // effect grows toward the top (the cloud narrows into a dome).
    const glm::vec<3, T> w(T(0.6), T(0.5), T(1));
    const glm::vec<4, T> half(T(0.8), T(0.4), T(0.4), T(0.4));
    T previous_loss = T(-1);
    for (T h : {T(0.2), T(0.4), T(0.6), T(0.75)}) {
        const T flat = cloud_shape_density(half, w, h, T(0.6), T(1), T(0.5), T(0));
        const T round = cloud_shape_density(half, w, h, T(0.6), T(1), T(0.5), T(0.6));
        CHECK(round <= flat);
        const T loss = flat - round;
        CHECK(loss >= previous_loss - T(1e-6));
        previous_loss = loss;
        // Against the closed form.
        const T c = saturate(T(0.6) - T(0.5) + T(0.6)) * (T(1) - T(0.6) * h * h);
        CHECK(double(round) == doctest::Approx(double(apply_coverage(nubis_base_cloud(half) * height_gradient_for_type(h, T(1)), c))).epsilon(1e-6));
    }
    // Range: [0, 1] for any inputs in range, and 0 for a NaN height (no cloud where the
    // height is unknown).
    CHECK(cloud_shape_density(full, glm::vec<3, T>(T(1)), T(0.5), T(1), T(1), T(2), T(1)) <= T(1));
    if constexpr (cm_test::ieee_build)
        CHECK(cloud_shape_density(full, w, cm_test::make_nan<T>(), T(0.5), T(1), T(0.5), T(0.6)) == T(0));
}

// Regression (fuzzing): below the layer the rise was clamped to 0 but exp(-b h) overflowed,
// and 0 * Inf gave NaN: float from h = -22.2 (b = 4), double from h = -177.5. The documented
// density below the layer is 0; closed form (1 - e^-ah) e^-bh in long double above it.
TEST_CASE_TEMPLATE("height_gradient_exponential: exactly 0 below the layer, finite in [0, 1] for every finite input", T, float, double) {
    const T big = std::numeric_limits<T>::max();
    for (T h : {T(-23), T(-22.2), T(-177.5), T(-178), T(-1e4), T(-1e30), -big, T(-1), T(-1e-30), T(-0.0), T(0)}) {
        INFO("h = " << h);
        CHECK(height_gradient_exponential(h, T(50), T(4)) == T(0));
        CHECK(height_gradient_exponential(h, T(1e3), T(1e3)) == T(0));
    }
    // Above the layer bottom, far up: the decay wins (0), and nothing overflows.
    for (T h : {T(10), T(30), T(200), T(1e4), T(1e30), big}) {
        INFO("h = " << h);
        const T v = height_gradient_exponential(h, T(50), T(4));
        REQUIRE(cm_test::finite_bits(v));
        CHECK(cm_test::close_ulps(v, -std::expm1(-50 * ld(h)) * std::exp(-4 * ld(h)), 8));
    }
    // Huge a and b: a h overflows to Inf (rise 1), b h too (decay 0): 0, not NaN.
    CHECK(height_gradient_exponential(T(1e30), big, big) == T(0));
    CHECK(height_gradient_exponential(T(0.5), big, T(0)) == T(1));
    // Negative a or b act as 0: no rise (0 everywhere), or no decay (the rise alone).
    CHECK(height_gradient_exponential(T(0.5), T(-50), T(4)) == T(0));
    CHECK(height_gradient_exponential(T(-0.5), T(-50), T(-4)) == T(0));
    CHECK(cm_test::close_ulps(height_gradient_exponential(T(0.05), T(50), T(-4)), -std::expm1(-50 * ld(T(0.05))), 4));
    // A sweep across every scale of h, both signs: always in [0, 1].
    for (int e = -30; e <= 30; ++e)
        for (int s : {-1, 1}) {
            const T h = T(s) * static_cast<T>(std::pow(10.0L, e));
            const T v = height_gradient_exponential(h, T(50), T(4));
            INFO("h = " << h);
            REQUIRE(cm_test::finite_bits(v));
            CHECK(v >= T(0));
            CHECK(v <= T(1));
            if (s < 0) CHECK(v == T(0));
        }
}
