// Tests of transmittance.hpp: Beer-Lambert, powder, Beer-Powder and the Nubis 2017
// attenuation against closed forms, their published peaks and crossings, ranges and hard
// cases (tau = 0, tiny, huge, negative, Inf, NaN), scalar and RGB.
#include <cloudmath/transmittance.hpp>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>
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

TEST_CASE_TEMPLATE("diffuse_transmittance: the two-stream form, limits, and the slab Monte Carlo", T, float, double) {
    // Closed form and limits.
    for (T g : {T(-1), T(0), T(0.5), T(0.85), T(1)})
        for (T tau : taus<T>()) {
            const ld want = 1.0L / (1.0L + 0.75L * (1.0L - ld(g)) * ld(tau));
            CHECK(cm_test::rel_err(diffuse_transmittance(tau, g), want) <= 4 * cm_test::eps<T>());
        }
    CHECK(diffuse_transmittance(T(0), T(0.8)) == T(1));
    CHECK(diffuse_transmittance(T(-3), T(0.8)) == T(1));          // negative depth: none
    CHECK(diffuse_transmittance(T(1e30), T(1)) == T(1));          // g = 1: all light forward
    CHECK(diffuse_transmittance(T(5), T(2)) == T(1));             // g clamped to 1
    CHECK(diffuse_transmittance(T(4), T(-3)) == diffuse_transmittance(T(4), T(-1)));
    CHECK(diffuse_transmittance(std::numeric_limits<T>::infinity(), T(0.8)) == T(0));
    // Similarity: the same transport depth (1 - g) tau gives the same value.
    CHECK(double(diffuse_transmittance(T(2), T(0.8))) == doctest::Approx(double(diffuse_transmittance(T(4), T(0.9)))).epsilon(1e-6));
    // Thick layers: the diffusion asymptote (4/3) / ((1 - g) tau + 2 z0), z0 = 0.7104
    // (REFERENCES.md, van de Hulst 1980), to 1% beyond a transport depth of 10.
    for (T tau : {T(100), T(400), T(1e4)}) {
        const ld tp = 0.2L * ld(tau);
        CHECK(cm_test::rel_err(diffuse_transmittance(tau, T(0.8)), (4.0L / 3.0L) / (tp + 1.4208L)) <= 0.01);
    }
    const glm::vec<3, T> v = diffuse_transmittance(glm::vec<3, T>(T(0), T(1), T(10)), T(0.8));
    CHECK(v.x == T(1));
    CHECK(v.z == diffuse_transmittance(T(10), T(0.8)));

    // Against the slab Monte Carlo (scripts/diffuse-transmittance.sh): HG phase, conservative,
    // isotropic illumination. The documented bounds: at most 0.037 too high, and within
    // 4.9% relative, never too low by more than 3 standard errors.
    std::ifstream in(std::string(CLOUDMATH_DATA_DIR) + "/diffuse_transmittance.csv");
    REQUIRE(in.good());
    std::string line;
    int rows = 0;
    double worst_abs = 0.0, worst_rel = 0.0;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#' || line[0] == 'g') continue;
        std::istringstream fields(line);
        double g = 0, tau = 0, t = 0, err = 0;
        char comma = 0;
        fields >> g >> comma >> tau >> comma >> t >> comma >> err;
        REQUIRE(fields);
        const double model = double(diffuse_transmittance(T(tau), T(g)));
        CAPTURE(g);
        CAPTURE(tau);
        CHECK(model - t <= 0.037 + 3.0 * err);
        CHECK(model - t >= -3.0 * err);
        CHECK(std::fabs(model - t) / t <= 0.049 + 3.0 * err / t);
        worst_abs = std::fmax(worst_abs, model - t);
        worst_rel = std::fmax(worst_rel, std::fabs(model - t) / t);
        ++rows;
    }
    CHECK(rows == 27);
    MESSAGE(std::string(sizeof(T) == sizeof(float) ? "float" : "double")
            << ": diffuse_transmittance against the slab Monte Carlo (27 cases): worst " << worst_abs << " too high, "
            << worst_rel << " relative");
}
