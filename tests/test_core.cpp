// Tests of core.hpp: saturate, remap, remap_clamped, smoothstep_safe and the stable
// exponential helpers, against closed forms and long double references.
#include <cloudmath/core.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

TEST_CASE_TEMPLATE("constants match long double values", T, float, double) {
    const ld pi = 3.141592653589793238462643383279502884L;
    CHECK(cm_test::rel_err(pi_v<T>, pi) <= cm_test::eps<T>() / 2);
    CHECK(cm_test::rel_err(two_pi_v<T>, 2 * pi) <= cm_test::eps<T>() / 2);
    CHECK(cm_test::rel_err(four_pi_v<T>, 4 * pi) <= cm_test::eps<T>() / 2);
    CHECK(cm_test::rel_err(inv_pi_v<T>, 1 / pi) <= cm_test::eps<T>() / 2);
    CHECK(cm_test::rel_err(inv_four_pi_v<T>, 1 / (4 * pi)) <= cm_test::eps<T>() / 2);
}

TEST_CASE_TEMPLATE("saturate clamps to [0, 1], scalars and vectors", T, float, double) {
    static_assert(saturate(T(1.5)) == T(1), "constexpr");
    CHECK(saturate(T(-0.25)) == T(0));
    CHECK(saturate(T(0.25)) == T(0.25));
    CHECK(saturate(T(7)) == T(1));
    CHECK(saturate(std::numeric_limits<T>::denorm_min()) == std::numeric_limits<T>::denorm_min());
    const glm::vec<3, T> v = saturate(glm::vec<3, T>(T(-1), T(0.5), T(2)));
    CHECK(v == glm::vec<3, T>(T(0), T(0.5), T(1)));
    if constexpr (cm_test::ieee_build) {
        CHECK(saturate(cm_test::make_inf<T>()) == T(1));
        CHECK(saturate(-cm_test::make_inf<T>()) == T(0));
        CHECK(cm_test::nan_bits(saturate(cm_test::make_nan<T>())));  // documented: NaN propagates
    }
}

TEST_CASE_TEMPLATE("remap is the unclamped linear map", T, float, double) {
    static_assert(remap(T(0.5), T(0), T(1), T(10), T(20)) == T(15), "constexpr");
    CHECK(remap(T(2), T(0), T(1), T(10), T(20)) == T(30));    // extrapolates
    CHECK(remap(T(-1), T(0), T(1), T(10), T(20)) == T(0));
    CHECK(remap(T(0.25), T(1), T(0), T(0), T(1)) == T(0.75));  // reversed old range
    // Nubis-style use: remap(x, lo, 1, 0, 1) against a long double reference on a grid.
    for (int i = 0; i <= 100; ++i) {
        const T x = T(i) / T(100);
        const T lo = T(0.3);
        const ld ref = (ld(x) - ld(lo)) / (1 - ld(lo));
        CHECK(cm_test::rel_err(remap(x, lo, T(1), T(0), T(1)), ref) <= 4 * cm_test::eps<T>() + 1e-30L);
    }
}

TEST_CASE_TEMPLATE("remap with a degenerate range is a finite step", T, float, double) {
    CHECK(remap(T(0.4), T(0.5), T(0.5), T(2), T(3)) == T(2));
    CHECK(remap(T(0.5), T(0.5), T(0.5), T(2), T(3)) == T(3));
    CHECK(remap(T(0.6), T(0.5), T(0.5), T(2), T(3)) == T(3));
    CHECK(remap_clamped(T(0.4), T(0.5), T(0.5), T(2), T(3)) == T(2));
    CHECK(remap_clamped(T(0.6), T(0.5), T(0.5), T(2), T(3)) == T(3));
    // A denormal-width range: unclamped may overflow (documented), clamped stays bounded.
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(remap_clamped(T(1), T(0), tiny, T(0), T(1)) == T(1));
    CHECK(remap_clamped(T(-1), T(0), tiny, T(0), T(1)) == T(0));
    CHECK(cm_test::finite_bits(remap_clamped(T(0.5), T(0), tiny, T(-5), T(5))));
}

TEST_CASE_TEMPLATE("remap_clamped: clamped, exact end points, either orientation", T, float, double) {
    static_assert(remap_clamped(T(2), T(0), T(1), T(0), T(1)) == T(1), "constexpr");
    const T new_min = T(0.1), new_max = T(0.7);
    CHECK(remap_clamped(T(-3), T(0), T(1), new_min, new_max) == new_min);
    CHECK(remap_clamped(T(0), T(0), T(1), new_min, new_max) == new_min);
    CHECK(remap_clamped(T(1), T(0), T(1), new_min, new_max) == new_max);  // bit-exact
    CHECK(remap_clamped(T(9), T(0), T(1), new_min, new_max) == new_max);
    CHECK(remap_clamped(T(9), T(0), T(1), T(1), T(0)) == T(0));            // reversed new range
    CHECK(remap_clamped(T(0.25), T(0), T(1), T(1), T(0)) == T(0.75));
    // Sweep: always within the new range, monotonic in x.
    T prev = new_min;
    for (int i = -50; i <= 150; ++i) {
        const T v = remap_clamped(T(i) / T(100), T(0), T(1), new_min, new_max);
        CHECK(v >= new_min);
        CHECK(v <= new_max);
        CHECK(v >= prev);
        prev = v;
    }
    if constexpr (cm_test::ieee_build) {
        CHECK(remap_clamped(cm_test::make_inf<T>(), T(0), T(1), T(0), T(1)) == T(1));
        CHECK(remap_clamped(-cm_test::make_inf<T>(), T(0), T(1), T(0), T(1)) == T(0));
    }
}

TEST_CASE_TEMPLATE("smoothstep_safe matches GLSL smoothstep and is defined for equal edges", T, float, double) {
    for (int i = -10; i <= 110; ++i) {
        const T x = T(i) / T(100);
        const ld t = std::fmin(std::fmax((ld(x) - 0.2L) / 0.6L, 0.0L), 1.0L);
        const ld ref = t * t * (3 - 2 * t);
        CHECK(std::fabs(ld(smoothstep_safe(T(0.2), T(0.8), x)) - ref) <= 8 * cm_test::eps<T>());
    }
    CHECK(smoothstep_safe(T(0.5), T(0.5), T(0.49)) == T(0));
    CHECK(smoothstep_safe(T(0.5), T(0.5), T(0.5)) == T(1));
    CHECK(smoothstep_safe(T(0.8), T(0.2), T(0.1)) == T(1));  // reversed edges: decreasing
    CHECK(smoothstep_safe(T(0.8), T(0.2), T(0.9)) == T(0));
}

// (1 - exp(-x)) in long double: expm1l is accurate to the long double ulp.
static ld ref_one_minus_exp_neg(ld x) { return -std::expm1(-x); }
static ld ref_one_minus_exp_neg_over_x(ld x) { return x == 0 ? 1.0L : -std::expm1(-x) / x; }

TEST_CASE_TEMPLATE("one_minus_exp_neg: 1 ulp-level accuracy where 1 - exp(-x) collapses", T, float, double) {
    ld worst = 0;
    for (int e = -37; e <= 3; ++e)  // normal numbers: -ffast-math flushes denormals to 0
        for (int m = 1; m <= 9; m += 2) {
            const T x = static_cast<T>(m * std::pow(10.0L, e));
            worst = std::fmax(worst, cm_test::rel_err_eps(one_minus_exp_neg(x), ref_one_minus_exp_neg(x)));
        }
    CHECK(worst <= 2);
    if constexpr (cm_test::ieee_build) {  // denormals survive only without flush-to-zero
        const T tiny = std::numeric_limits<T>::denorm_min() * T(8);
        CHECK(one_minus_exp_neg(tiny) == tiny);
    }
    // The textbook form is what this replaces: it returns 0 in float at x = 1e-8.
    volatile T x = T(1e-8);
    if constexpr (std::is_same_v<T, float>) CHECK(T(1) - std::exp(-x) == T(0));
    CHECK(one_minus_exp_neg(x) > T(0));
    const glm::vec<2, T> v = one_minus_exp_neg(glm::vec<2, T>(T(0), T(1)));
    CHECK(v.x == T(0));
    CHECK(cm_test::rel_err(v.y, 1 - std::exp(-1.0L)) <= 2 * cm_test::eps<T>());
    if constexpr (cm_test::ieee_build) CHECK(one_minus_exp_neg(cm_test::make_inf<T>()) == T(1));
}

TEST_CASE_TEMPLATE("one_minus_exp_neg_over_x: within 2 ulp for every x >= 0, exactly 1 at 0", T, float, double) {
    CHECK(one_minus_exp_neg_over_x(T(0)) == T(1));
    CHECK(one_minus_exp_neg_over_x(std::numeric_limits<T>::denorm_min()) == T(1));
    CHECK(one_minus_exp_neg_over_x(std::numeric_limits<T>::min()) == T(1));
    ld worst = 0;
    T worst_x = 0;
    // Log-spaced from 1e-38 (float) / 1e-300 (double) to 1e4, 20 points per decade, plus
    // the hard cases of the issue.
    const int lo = std::is_same_v<T, float> ? -37 : -300;
    for (int i = lo * 20; i <= 4 * 20; ++i) {
        const T x = static_cast<T>(std::pow(10.0L, i / 20.0L));
        const ld e = cm_test::rel_err_eps(one_minus_exp_neg_over_x(x), ref_one_minus_exp_neg_over_x(x));
        if (e > worst) { worst = e; worst_x = x; }
    }
    for (T x : {T(1e-30), T(6e-8), T(1e-7), T(1e-5), T(1e-8), T(0.25), T(1), T(88), T(1e4)}) {
        const ld e = cm_test::rel_err_eps(one_minus_exp_neg_over_x(x), ref_one_minus_exp_neg_over_x(x));
        if (e > worst) { worst = e; worst_x = x; }
    }
    INFO("worst x = " << worst_x);
    MESSAGE(cm_test::type_name<T>() << ": one_minus_exp_neg_over_x worst error " << double(worst) << " eps (at x = " << worst_x << ")");
    CHECK(worst <= 2);
    // Negative x (growing exponential) stays accurate until exp overflows.
    CHECK(cm_test::rel_err(one_minus_exp_neg_over_x(T(-10)), ref_one_minus_exp_neg_over_x(-10.0L)) <= 3 * cm_test::eps<T>());
    if constexpr (cm_test::ieee_build) CHECK(one_minus_exp_neg_over_x(cm_test::make_inf<T>()) == T(0));
}

TEST_CASE("one_minus_exp_neg_over_x against the textbook quotient in float (the known mistake)") {
    // REFERENCES.md: naive (1 - exp(-x))/x is 20% off at 1e-7 and 3e-3 at 1e-5 in float.
    // It is 0 below 2^-25 = 2.98e-8, where exp(-x) rounds to 1 (measured here with glibc's
    // correctly rounded expf; REFERENCES.md quotes 6e-8, one float ulp below 1 further).
    auto naive = [](float x) { volatile float e = std::exp(-x); return (1.0f - e) / x; };
    CHECK(naive(2.9e-8f) == 0.0f);
    CHECK(cm_test::rel_err(one_minus_exp_neg_over_x(2.9e-8f), ref_one_minus_exp_neg_over_x(ld(2.9e-8f))) <= 2 * cm_test::eps<float>());
    CHECK(cm_test::rel_err(naive(1e-7f), 1.0L) > 0.1L);
    CHECK(cm_test::rel_err(naive(1e-5f), ref_one_minus_exp_neg_over_x(1e-5L)) > 1e-3L);
    CHECK(cm_test::rel_err(one_minus_exp_neg_over_x(5e-8f), ref_one_minus_exp_neg_over_x(ld(5e-8f))) <= 2 * cm_test::eps<float>());
    CHECK(cm_test::rel_err(one_minus_exp_neg_over_x(1e-7f), ref_one_minus_exp_neg_over_x(ld(1e-7f))) <= 2 * cm_test::eps<float>());
    CHECK(cm_test::rel_err(one_minus_exp_neg_over_x(1e-5f), ref_one_minus_exp_neg_over_x(ld(1e-5f))) <= 2 * cm_test::eps<float>());
}

// Regression (fuzzing): the blend (1 - t) new_min + t new_max landed one ulp outside the new
// range (always possible when new_min == new_max), and huge finite inputs gave
// Inf / Inf = NaN. The reference is the same closed form in long double, clamped, which has
// the exponent range to hold every difference of two floats or doubles.
TEST_CASE_TEMPLATE("remap_clamped: never outside the new range, finite and right for huge finite inputs", T, float, double) {
    auto ref = [](T x, T a, T b, T c, T d) {
        const ld t = std::fmin(std::fmax((ld(x) - ld(a)) / (ld(b) - ld(a)), 0.0L), 1.0L);
        return std::fmin(std::fmax((1 - t) * ld(c) + t * ld(d), std::fmin(ld(c), ld(d))), std::fmax(ld(c), ld(d)));
    };
    // The first case the fuzzer reported (float: 0.920364916 for the range [0.920364857, same]).
    CHECK(remap_clamped(T(-0.125486612f), T(-0.0317127705f), T(-1.16267025f), T(0.920364857f), T(0.920364857f)) ==
          T(0.920364857f));
    // Dense random sweep: the result is inside the new range, bit for bit.
    cm_test::rng r(71);
    long outside = 0;
    for (int i = 0; i < 300000; ++i) {
        const T x = T(4 * r.uniform() - 2), a = T(4 * r.uniform() - 2), b = T(4 * r.uniform() - 2);
        const T c = T(4 * r.uniform() - 2), d = i % 3 == 0 ? c : T(4 * r.uniform() - 2);
        const T v = remap_clamped(x, a, b, c, d);
        if (v < std::min(c, d) || v > std::max(c, d)) ++outside;
    }
    CHECK(outside == 0);
    // Huge finite inputs: every difference would overflow in T.
    const T big = std::numeric_limits<T>::max();
    const T xs[] = {big, -big, big / 2, big * T(0.75), T(0.3) * big, -T(0.6) * big, T(1), T(0)};
    const T olds[][2] = {{-big, big}, {big, -big}, {-big / 2, big}, {T(0), big}, {-big, T(0)}, {T(-1), big}, {-big * T(0.9), big * T(0.8)}};
    const T news[][2] = {{T(0), T(1)}, {T(1), T(0)}, {-big, big}, {big, big}, {big / 2, big}, {-big, -big * T(0.3)}, {T(-5), T(5)}};
    for (T x : xs)
        for (const auto& o : olds)
            for (const auto& n : news) {
                const T v = remap_clamped(x, o[0], o[1], n[0], n[1]);
                INFO("x = " << x << ", old = (" << o[0] << ", " << o[1] << "), new = (" << n[0] << ", " << n[1] << ")");
                REQUIRE(cm_test::finite_bits(v));
                CHECK(v >= std::min(n[0], n[1]));
                CHECK(v <= std::max(n[0], n[1]));
                // 4 eps of the new range's magnitude: two roundings of t, two of the blend.
                CHECK(std::fabs(ld(v) - ref(x, o[0], o[1], n[0], n[1])) <=
                      4 * cm_test::eps<T>() * std::fmax(std::fabs(ld(n[0])), std::fabs(ld(n[1]))));
            }
    // The reported case in exact terms: the middle of (-3e38, 3e38) maps to the middle.
    CHECK(remap_clamped(T(0), -big, big, T(0), T(1)) == T(0.5));
    CHECK(remap_clamped(big, -big, big, T(0), T(1)) == T(1));
    CHECK(remap_clamped(-big, -big, big, T(0), T(1)) == T(0));
    // smoothstep_safe shares the clamped coordinate: finite across the whole range too.
    CHECK(smoothstep_safe(-big, big, T(0)) == T(0.5));
    CHECK(smoothstep_safe(big, -big, big) == T(0));
}
