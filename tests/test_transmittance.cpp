// Tests of transmittance.hpp: Beer-Lambert, powder, Beer-Powder and the Nubis 2017
// attenuation against closed forms, their published peaks and crossings, ranges and hard
// cases (tau = 0, tiny, huge, negative, Inf, NaN), scalar and RGB.
#include <cloudmath/transmittance.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {
template <class T>
std::vector<T> taus() {  // 0, tiny, the Beer-Powder landmarks, the float exp limit, huge
    return {T(0), T(1e-30), T(1e-8), T(1e-3), T(0.1), T(0.3466), T(0.5493), T(1),
            T(2), T(10), T(50), T(87), T(700), T(1e4), T(1e30)};
}
}  // namespace

TEST_CASE_TEMPLATE("beer_lambert = exp(-tau), in [0, 1], negative tau clamped", T, float, double) {
    for (T tau : taus<T>()) {
        const T t = beer_lambert(tau);
        CHECK(cm_test::close_ulps(t, std::exp(-ld(tau)), 2));
        CHECK(t >= T(0));
        CHECK(t <= T(1));
    }
    CHECK(beer_lambert(T(0)) == T(1));
    CHECK(beer_lambert(T(-3)) == T(1));
    const glm::vec<3, T> rgb = beer_lambert(glm::vec<3, T>(T(0), T(1), T(2)));
    CHECK(rgb.x == T(1));
    CHECK(rgb.y == beer_lambert(T(1)));
    CHECK(rgb.z == beer_lambert(T(2)));
    if constexpr (cm_test::ieee_build) {
        CHECK(beer_lambert(cm_test::make_inf<T>()) == T(0));
        CHECK(cm_test::nan_bits(beer_lambert(cm_test::make_nan<T>())));
    }
}

TEST_CASE_TEMPLATE("powder = 1 - exp(-k tau) with full relative precision for tiny tau", T, float, double) {
    for (T k : {T(0.5), T(2), T(10)})
        for (T tau : taus<T>()) {
            const ld ref = -std::expm1(-ld(k * tau));  // k * tau rounded as the function sees it
            CHECK(cm_test::rel_err(powder(tau, k), ref) <= 2 * cm_test::eps<T>());
            CHECK(powder(tau, k) >= T(0));
            CHECK(powder(tau, k) <= T(1));
        }
    CHECK(powder(T(1e-30), T(2)) > T(0));  // 1 - exp(-2e-30) rounds to 0; powder does not
    CHECK(powder(T(-1), T(2)) == T(0));
    CHECK(powder(glm::vec<2, T>(T(0), T(1)), T(2)).y == powder(T(1), T(2)));
}

TEST_CASE_TEMPLATE("beer_powder: Schneider's 2 exp(-d)(1 - exp(-2d)), peak and crossing with Beer", T, float, double) {
    for (T tau : taus<T>()) {
        const ld d = tau;
        const ld ref = 2 * std::exp(-d) * -std::expm1(-2 * d);
        CHECK(cm_test::close_ulps(beer_powder(tau), ref, 4));
        CHECK(beer_powder(tau) >= T(0));
    }
    // Peak 4 / (3 sqrt 3) = 0.7698 at d = ln 3 / 2 (REFERENCES.md).
    const T peak_d = static_cast<T>(std::log(3.0L) / 2);
    CHECK(cm_test::rel_err(beer_powder(peak_d), 4 / (3 * std::sqrt(3.0L))) <= 4 * cm_test::eps<T>());
    CHECK(beer_powder(peak_d) >= beer_powder(peak_d * T(0.99)));
    CHECK(beer_powder(peak_d) >= beer_powder(peak_d * T(1.01)));
    for (int i = 0; i <= 1000; ++i) CHECK(beer_powder(T(i) / T(100)) <= T(0.7698004));
    // Exceeds Beer-Lambert beyond ln 2 / 2 = 0.3466: not energy-bounded (documented).
    CHECK(beer_powder(T(0.34)) < beer_lambert(T(0.34)));
    CHECK(beer_powder(T(0.36)) > beer_lambert(T(0.36)));
    CHECK(beer_powder(T(0)) == T(0));
    CHECK(beer_powder(T(-2)) == T(0));
    CHECK(beer_powder(glm::vec<3, T>(T(1))).z == beer_powder(T(1)));
    if constexpr (cm_test::ieee_build) CHECK(beer_powder(cm_test::make_inf<T>()) == T(0));
}

TEST_CASE_TEMPLATE("nubis_attenuation: max(exp(-d), 0.7 exp(-0.25 d)), crossing at 0.4757", T, float, double) {
    for (T tau : taus<T>()) {
        const ld d = tau;
        const ld ref = std::fmax(std::exp(-d), 0.7L * std::exp(-0.25L * d));
        CHECK(cm_test::close_ulps(nubis_attenuation(tau), ref, 4));
        CHECK(nubis_attenuation(tau) <= T(1));
        CHECK(nubis_attenuation(tau) >= T(0));
    }
    const T cross = static_cast<T>(-std::log(0.7L) / 0.75L);
    CHECK(cross == doctest::Approx(0.4757).epsilon(1e-4));
    CHECK(nubis_attenuation(cross * T(0.99)) == beer_lambert(cross * T(0.99)));
    CHECK(nubis_attenuation(cross * T(1.01)) > beer_lambert(cross * T(1.01)));
    CHECK(nubis_attenuation(T(0)) == T(1));
    CHECK(nubis_attenuation(T(-1)) == T(1));
    CHECK(nubis_attenuation(glm::vec<2, T>(T(3))).x == nubis_attenuation(T(3)));
}

TEST_CASE_TEMPLATE("transmittance sweep: finite and in range on a dense grid, denormal tau", T, float, double) {
    bool ok = true;
    for (int i = 0; i <= 20000; ++i) {
        const T tau = static_cast<T>(std::pow(10.0L, -30 + 35 * i / 20000.0L));  // 1e-30 .. 1e5
        const T b = beer_lambert(tau), bp = beer_powder(tau), na = nubis_attenuation(tau), pw = powder(tau, T(2));
        ok = ok && cm_test::finite_bits(b) && cm_test::finite_bits(bp) && cm_test::finite_bits(na) && cm_test::finite_bits(pw);
        ok = ok && b >= T(0) && b <= T(1) && na >= T(0) && na <= T(1) && pw >= T(0) && pw <= T(1);
        ok = ok && bp >= T(0) && bp <= T(0.7698004);
    }
    CHECK(ok);
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(beer_lambert(tiny) == T(1));
    CHECK(nubis_attenuation(tiny) == T(1));
    CHECK(beer_powder(tiny) >= T(0));
    CHECK(beer_powder(tiny) <= T(1e-30));
}
