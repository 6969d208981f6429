// Tests of integration.hpp: integrate_scattering against the exact integral in long double
// for sigma_t ds from 0 to 1e4 (and the hard cases 0, 1e-30, 1e-8, 1e4), the biased clamp
// it replaces, and march_accumulator's step-size independence in homogeneous media.
#include <cloudmath/integration.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {
// Exact step integral S (1 - exp(-s ds)) / s in long double, S ds at s = 0.
ld exact_step(ld S, ld sigma, ld ds) {
    const ld x = sigma * ds;
    return x == 0 ? S * ds : S * ds * (-std::expm1(-x) / x);
}
}  // namespace

TEST_CASE_TEMPLATE("integrate_scattering within a few ulp for sigma_t ds in [0, 1e4], no clamp constant", T, float, double) {
    CHECK(integrate_scattering(T(2), T(0), T(3)) == T(6));  // exactly S ds
    ld worst = 0;
    for (T sigma : {T(0), T(1e-30), T(1e-20), T(1e-8), T(1e-6), T(1e-3), T(0.05), T(1), T(10), T(100), T(1e4)})
        for (T ds : {T(0.01), T(0.5), T(1), T(7.3)}) {
            const T S = T(0.37);
            worst = std::fmax(worst, cm_test::rel_err_eps(integrate_scattering(S, sigma, ds), exact_step(S, sigma, ds)));
        }
    for (int i = -30 * 10; i <= 4 * 10; ++i) {  // x = sigma * 1 log-spaced, 10 per decade
        const T sigma = static_cast<T>(std::pow(10.0L, i / 10.0L));
        worst = std::fmax(worst, cm_test::rel_err_eps(integrate_scattering(T(1), sigma, T(1)), exact_step(1, sigma, 1)));
    }
    MESSAGE(cm_test::type_name<T>() << ": integrate_scattering worst relative error: " << double(worst) << " eps");
    CHECK(worst <= 4);
    CHECK(integrate_scattering(T(1), T(-2), T(1)) == T(1));  // negative extinction: no attenuation
    if constexpr (cm_test::ieee_build) CHECK(integrate_scattering(T(1), cm_test::make_inf<T>(), T(1)) == T(0));
}

TEST_CASE("known mistake: max(sigma_t, 1e-6) clamping and the naive quotient are biased for thin media") {
    auto clamped = [](float S, float s, float ds) { return (S - S * std::exp(-s * ds)) / std::fmax(s, 1e-6f); };
    auto naive = [](float S, float s, float ds) { volatile float e = std::exp(-s * ds); return S * (1.0f - e) / s; };
    // Thin fog: sigma_t = 1e-8 1/m over a 10 m step. The exact answer is S ds (1 - 5e-8).
    const ld exact = exact_step(1, ld(1e-8f), 10);
    const ld e_clamped = cm_test::rel_err(clamped(1.0f, 1e-8f, 10.0f), exact);
    const ld e_naive = cm_test::rel_err(naive(1.0f, 1e-8f, 10.0f), exact);
    const ld e_ours = cm_test::rel_err(integrate_scattering(1.0f, 1e-8f, 10.0f), exact);
    MESSAGE("sigma_t = 1e-8, ds = 10: clamp " << double(e_clamped) << ", naive " << double(e_naive) << ", ours " << double(e_ours));
    CHECK(e_clamped > 0.5L);   // the clamp loses the whole step
    CHECK(e_naive > 1e-3L);
    CHECK(e_ours <= 2 * cm_test::eps<float>());
    CHECK(clamped(1.0f, 0.0f, 10.0f) == 0.0f);  // and returns nothing at all at sigma_t = 0
}

TEST_CASE_TEMPLATE("integrate_scattering: RGB extinction and grey extinction overloads", T, float, double) {
    using v3 = glm::vec<3, T>;
    const v3 S(T(1), T(2), T(3));
    const v3 sig(T(0), T(0.5), T(1e4));
    const v3 r = integrate_scattering(S, sig, T(2));
    for (int c = 0; c < 3; ++c) CHECK(r[c] == integrate_scattering(S[c], sig[c], T(2)));
    const v3 g = integrate_scattering(S, T(0.5), T(2));
    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(g[c], exact_step(S[c], 0.5L, 2)) <= 4 * cm_test::eps<T>());
}

TEST_CASE_TEMPLATE("march_accumulator: step-size independent for homogeneous media, early out, opacity", T, float, double) {
    // Homogeneous slab of length 10, sigma_t = 0.3, source S = 2: exact L = S/sigma (1 - e^-3),
    // T = e^-3, whatever the number of steps.
    const ld L_exact = 2 / 0.3L * -std::expm1(-0.3L * 10);
    for (int steps : {1, 3, 64, 1000}) {
        march_accumulator<T> acc;
        const T ds = T(10) / T(steps);
        for (int i = 0; i < steps; ++i) acc.add_segment(T(2), T(0.3), ds);
        INFO("steps = " << steps);
        CHECK(cm_test::rel_err(acc.luminance, L_exact) <= 8 * ld(steps) * cm_test::eps<T>());
        CHECK(cm_test::rel_err(acc.transmittance, std::exp(-ld(T(0.3)) * 10)) <= 4 * ld(steps) * cm_test::eps<T>());
        CHECK(acc.opacity() == T(1) - acc.transmittance);
    }
    // Colour with grey extinction, and colour with chromatic extinction.
    march_accumulator<glm::vec<3, T>, T> grey;
    march_accumulator<glm::vec<3, T>> chroma;
    CHECK(grey.transmittance == T(1));
    CHECK(chroma.luminance == glm::vec<3, T>(T(0)));
    for (int i = 0; i < 20; ++i) {
        grey.add_segment(glm::vec<3, T>(T(1), T(2), T(3)), T(0.5), T(1));
        chroma.add_segment(glm::vec<3, T>(T(1)), glm::vec<3, T>(T(0.1), T(0.5), T(2)), T(1));
    }
    CHECK(cm_test::rel_err(grey.luminance.z, 3 / 0.5L * -std::expm1(-10.0L)) <= 64 * cm_test::eps<T>());
    CHECK(cm_test::rel_err(chroma.transmittance.x, std::exp(-ld(T(0.1)) * 20)) <= 64 * cm_test::eps<T>());
    CHECK(grey.is_opaque(T(0.01)));            // e^-10 < 0.01
    CHECK_FALSE(chroma.is_opaque(T(0.01)));    // the red channel is still e^-2 = 0.135
    CHECK(chroma.is_opaque(T(0.2)));
    CHECK(chroma.opacity().z == T(1) - chroma.transmittance.z);
    // A thin medium (sigma_t = 1e-9) accumulates S * length, no bias.
    march_accumulator<T> thin;
    for (int i = 0; i < 100; ++i) thin.add_segment(T(1), T(1e-9), T(1));
    CHECK(cm_test::rel_err(thin.luminance, 100 * (1 - 50e-9L)) <= 64 * cm_test::eps<T>());
}

TEST_CASE_TEMPLATE("integrate_scattering: denormal extinction and NaN inputs", T, float, double) {
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(integrate_scattering(T(3), tiny, T(2)) == T(6));
    CHECK(integrate_scattering(T(3), T(1), tiny) >= T(0));
    if constexpr (cm_test::ieee_build) {
        CHECK(cm_test::nan_bits(integrate_scattering(cm_test::make_nan<T>(), T(1), T(1))));
        CHECK(cm_test::nan_bits(integrate_scattering(T(1), cm_test::make_nan<T>(), T(1))));  // documented: NaN propagates
    }
}

TEST_CASE_TEMPLATE("march_schedule_distance: the closed form, exact ends, geometric steps, uniform limit", T, float, double) {
    struct range {
        T t0, t1, near_distance;
    };
    for (const range r : {range{T(0), T(35000), T(1000)}, range{T(1500), T(4000), T(500)}, range{T(0), T(1e6), T(1)},
                          range{T(20), T(21), T(1e4)}}) {
        CAPTURE(r.t0);
        CAPTURE(r.t1);
        // Ends exact, u clamped.
        CHECK(march_schedule_distance(T(0), r.t0, r.t1, r.near_distance) == r.t0);
        CHECK(march_schedule_distance(T(1), r.t0, r.t1, r.near_distance) == r.t1);
        CHECK(march_schedule_distance(T(-3), r.t0, r.t1, r.near_distance) == r.t0);
        CHECK(march_schedule_distance(T(7), r.t0, r.t1, r.near_distance) == r.t1);
        // Against expm1(u L) / expm1(L) in long double, relative to the range.
        const ld L = std::log1p((ld(r.t1) - ld(r.t0)) / (ld(r.t0) + ld(r.near_distance)));
        T previous = r.t0;
        for (int i = 1; i <= 64; ++i) {
            const T u = T(i) / T(64);
            const T t = march_schedule_distance(u, r.t0, r.t1, r.near_distance);
            const ld want = ld(r.t0) + (ld(r.t1) - ld(r.t0)) * std::expm1(ld(u) * L) / std::expm1(L);
            // 8 ulp of the range, plus the rounding of t itself.
            const ld eps = ld(std::numeric_limits<T>::epsilon());
            CHECK(std::abs(ld(t) - want) <= 8 * eps * ld(r.t1 - r.t0) + eps * want);
            CHECK(t >= previous);  // monotonic
            previous = t;
        }
    }
    // Consecutive steps grow by the constant factor e^(L / n): the last of 64 steps over 0-35 km
    // with near_distance 1 km is 36^(63/64) times the first (56 m and 2 km).
    const T first = march_schedule_distance(T(1) / T(64), T(0), T(35000), T(1000));
    const T last = T(35000) - march_schedule_distance(T(63) / T(64), T(0), T(35000), T(1000));
    CHECK(double(last / first) == doctest::Approx(std::pow(36.0, 63.0 / 64.0)).epsilon(1e-4));
    CHECK(double(first) == doctest::Approx(1000.0 * std::expm1(std::log(36.0) / 64.0)).epsilon(1e-5));
    // near_distance -> +Inf: uniform steps.
    for (T near_distance : {T(1e30), cm_test::ieee_build ? cm_test::make_inf<T>() : T(1e30)})
        for (int i = 0; i <= 8; ++i)
            CHECK(march_schedule_distance(T(i) / T(8), T(100), T(900), near_distance) ==
                  doctest::Approx(double(100 + 100 * i)).epsilon(1e-6));
    // An empty range stays put; NaN propagates (IEEE builds).
    CHECK(march_schedule_distance(T(0.5), T(42), T(42), T(1)) == T(42));
    if (cm_test::ieee_build) {
        const T nan = cm_test::make_nan<T>();
        CHECK(cm_test::nan_bits(march_schedule_distance(T(0.5), T(0), nan, T(1))));
        CHECK(cm_test::nan_bits(march_schedule_distance(T(0.5), T(0), T(10), nan)));
    }
}

TEST_CASE_TEMPLATE("light_march_distance: t = length u^2, exact ends, steps of length (2i + 1) / n^2", T, float, double) {
    CHECK(light_march_distance(T(0), T(3000)) == T(0));
    CHECK(light_march_distance(T(1), T(3000)) == T(3000));
    CHECK(light_march_distance(T(-2), T(3000)) == T(0));  // u clamped to [0, 1]
    CHECK(light_march_distance(T(5), T(3000)) == T(3000));
    CHECK(light_march_distance(T(0.5), T(0)) == T(0));
    // Against the closed form in long double, and the step lengths (2 i + 1) L / n^2 that
    // sum to L: the first of 6 steps is 6 times shorter than a uniform step.
    const int n = 6;
    const T length = T(3300);
    T sum = 0;
    for (int i = 0; i < n; ++i) {
        const T a = light_march_distance(T(i) / T(n), length), b = light_march_distance(T(i + 1) / T(n), length);
        const ld want = ld(length) * ld(2 * i + 1) / ld(n * n);
        CHECK(std::abs(ld(b - a) - want) <= 4 * ld(std::numeric_limits<T>::epsilon()) * ld(length));
        sum += b - a;
    }
    CHECK(double(sum) == doctest::Approx(double(length)).epsilon(1e-6));
    const T first = light_march_distance(T(1) / T(n), length);
    CHECK(double(first) * n == doctest::Approx(double(length) / n).epsilon(1e-6));
    if (cm_test::ieee_build) CHECK(cm_test::nan_bits(light_march_distance(T(0.5), cm_test::make_nan<T>())));
}

TEST_CASE_TEMPLATE("refine_substeps: ceil of the optical depth in [1, max], NaN, Inf and huge values", T, float, double) {
    CHECK(refine_substeps(T(0), 16) == 1);
    CHECK(refine_substeps(T(-5), 16) == 1);
    CHECK(refine_substeps(T(1), 16) == 1);                // a step of optical depth 1 stays whole
    CHECK(refine_substeps(std::nextafter(T(1), T(2)), 16) == 2);
    CHECK(refine_substeps(T(2.5), 16) == 3);
    CHECK(refine_substeps(T(16), 16) == 16);
    CHECK(refine_substeps(T(15.01), 16) == 16);
    CHECK(refine_substeps(T(1e30), 16) == 16);            // no overflow in the int conversion
    CHECK(refine_substeps(std::numeric_limits<T>::max(), 1 << 30) == 1 << 30);
    CHECK(refine_substeps(T(7), 0) == 1);                 // max_substeps < 1 is taken as 1
    CHECK(refine_substeps(T(7), -3) == 1);
    CHECK(refine_substeps(std::numeric_limits<T>::denorm_min(), 16) == 1);
    if (cm_test::ieee_build) {
        CHECK(refine_substeps(cm_test::make_nan<T>(), 16) == 1);
        CHECK(refine_substeps(cm_test::make_inf<T>(), 16) == 16);
        CHECK(refine_substeps(-cm_test::make_inf<T>(), 16) == 1);
    }
    // Every sub-step then has an optical depth of at most 1 (below the cap).
    for (T tau = T(0.25); tau < T(16); tau += T(0.37)) CHECK(tau / T(refine_substeps(tau, 16)) <= T(1));
    // Hardening round 2, A5: in every build, -ffast-math included (where the NaN test was
    // folded away and NaN reached the int conversion: INT_MIN), the count is in [1, max].
    for (T x : {cm_test::make_nan<T>(), -cm_test::make_nan<T>(), cm_test::make_inf<T>(), -cm_test::make_inf<T>()}) {
        const int n = refine_substeps(x, 8);
        CHECK(n >= 1);
        CHECK(n <= 8);
    }
}

// Hardening round 2, A6: the ends were not exact (t_start + (t_end - t_start) g rounds past
// t_end, and t_end - t_start itself rounds), u just below 1 overshot, and a near_distance
// tiny against the range overflowed the ends' ratio (NaN).
TEST_CASE_TEMPLATE("march_schedule_distance: exact ends and results within them for any range", T, float, double) {
    CHECK(march_schedule_distance(T(1), T(0.21875), T(841061.688), T(7.086)) == T(841061.688));
    CHECK(march_schedule_distance(T(1), T(1), T(16777218), T(1)) == T(16777218));
    CHECK(march_schedule_distance(T(0), T(1), T(16777218), T(1)) == T(1));
    int outside = 0;
    std::uint32_t state = 7u;
    const auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return T(state >> 8) / T(16777216);
    };
    for (int i = 0; i < 20000; ++i) {
        const T t0 = std::pow(T(10), next() * T(7)) * next();
        const T t1 = t0 + std::pow(T(10), next() * T(7)) * next();
        const T near_distance = std::pow(T(10), next() * T(12) - T(6));
        for (T u : {std::nextafter(T(1), T(0)), next(), T(1) - next() * T(1e-6)}) {
            const T t = march_schedule_distance(u, t0, t1, near_distance);
            if (!(t >= t0 && t <= t1)) ++outside;
        }
    }
    CHECK(outside == 0);
    // near_distance tiny inside the domain: finite, and the closed form (long double) there:
    // t(1/2) = t_end (e^(L/2) - 1) / (e^L - 1) with e^L = (t_end + near) / near.
    const T tiny = std::is_same_v<T, float> ? T(1e-33) : T(1e-300);
    const T t = march_schedule_distance(T(0.5), T(0), T(1e6), tiny);
    CHECK(cm_test::finite_bits(t));
    const ld eL = (ld(1e6) + ld(tiny)) / ld(tiny);
    const ld want = ld(1e6) * (std::sqrt(eL) - 1) / (eL - 1);
    CHECK(std::abs(ld(t) - want) <= 1e-3L * want);
}
