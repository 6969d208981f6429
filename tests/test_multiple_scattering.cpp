// Tests of multiple_scattering.hpp: the octave sum against a long double evaluation of the
// formula, its limits (1 octave = single scattering, b = 0, tau -> Inf), energy behaviour
// for b <= a, the generic form with other phase functions, and the compile-time count.
#include <cloudmath/multiple_scattering.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {
const ld PI = 3.141592653589793238462643383279502884L;
ld hg_ref(ld mu, ld g) { return (1 - g * g) / (4 * PI * std::pow(1 + g * g - 2 * g * mu, 1.5L)); }
ld octaves_ref(ld tau, ld mu, ld g, ld a, ld b, ld c, int n) {
    ld sum = 0;
    for (int i = 0; i < n; ++i) sum += std::pow(b, ld(i)) * hg_ref(mu, std::pow(c, ld(i)) * g) * std::exp(-std::pow(a, ld(i)) * tau);
    return sum;
}
}  // namespace

TEST_CASE_TEMPLATE("multiple_scattering matches the octave formula", T, float, double) {
    ld worst = 0;
    for (T tau : {T(0), T(0.1), T(1), T(5), T(30)})
        for (T mu : {T(-1), T(-0.3), T(0), T(0.7), T(1)})
            for (int n : {1, 2, 3, 4, 8}) {
                const T got = multiple_scattering(tau, mu, T(0.8), T(0.5), T(0.5), T(0.5), n);
                // The reference uses the float/double-rounded c^i g the code sees, to within eps.
                worst = std::fmax(worst, cm_test::rel_err(got, octaves_ref(tau, mu, ld(T(0.8)), 0.5L, 0.5L, 0.5L, n)));
                const T aeth = multiple_scattering(tau, mu, T(0.8), T(0.3), T(0.75), T(0.5), n);
                worst = std::fmax(worst, cm_test::rel_err(aeth, octaves_ref(tau, mu, ld(T(0.8)), ld(T(0.3)), ld(T(0.75)), 0.5L, n)));
            }
    MESSAGE(cm_test::type_name<T>() << ": multiple_scattering worst relative error " << double(worst));
    CHECK(worst <= 64 * cm_test::eps<T>());
}

TEST_CASE_TEMPLATE("multiple_scattering limits: one octave, zero octaves, b = 0, huge tau", T, float, double) {
    const T tau = T(1.3), mu = T(0.4), g = T(0.6);
    CHECK(multiple_scattering(tau, mu, g, T(0.5), T(0.5), T(0.5), 1) == phase_hg(mu, g) * beer_lambert(tau));
    CHECK(multiple_scattering(tau, mu, g, T(0.5), T(0.5), T(0.5), 0) == T(0));
    CHECK(multiple_scattering(tau, mu, g, T(0.5), T(0.5), T(0.5), -3) == T(0));
    CHECK(cm_test::same_value(multiple_scattering(tau, mu, g, T(0.5), T(0), T(0.5), 6), multiple_scattering(tau, mu, g, T(0.5), T(0), T(0.5), 1)));
    CHECK(multiple_scattering(T(1e30), mu, g, T(0.5), T(0.5), T(0.5), 8) == T(0));
    // a = 0: octaves beyond the first are unattenuated.
    CHECK(multiple_scattering(T(1e30), mu, g, T(0), T(0.5), T(0.5), 2) == doctest::Approx(T(0.5) * phase_hg(mu, g * T(0.5))));
    // g at the clamp, mu at the peak: finite.
    CHECK(cm_test::finite_bits(multiple_scattering(T(0), T(1), T(1), T(0.5), T(0.5), T(0.5), 8)));
}

TEST_CASE("multiple_scattering: with b <= a the octaves add at most the light a slab lets through") {
    // Integrated over the sphere (phase normalised), octave i contributes b^i exp(-a^i tau);
    // with b <= a each term is at most a^i exp(-a^i tau) <= 1/(e tau) * ..., and the sum stays
    // below N. Check the sphere integral equals the closed form sum b^i exp(-a^i tau).
    for (double tau : {0.0, 0.5, 2.0, 10.0}) {
        const ld got = cm_test::integrate_sphere([tau](ld mu) {
            return ld(multiple_scattering(tau, double(mu), 0.8, 0.5, 0.5, 0.5, 4));
        });
        ld ref = 0;
        for (int i = 0; i < 4; ++i) ref += std::pow(0.5L, i) * std::exp(-std::pow(0.5L, i) * tau);
        CHECK(std::fabs(got - ref) < 1e-12L);
        CHECK(got <= 2.0L);  // geometric bound sum b^i = 1.875 < 2
    }
}

TEST_CASE_TEMPLATE("multiple_scattering_with: any phase function, runtime and compile-time octaves", T, float, double) {
    const T tau = T(0.7), mu = T(0.2);
    auto dual = [](T m, T scale) { return phase_hg_dual(m, T(0.8) * scale, T(-0.5) * scale, T(0.5)); };
    ld ref = 0;
    for (int i = 0; i < 3; ++i) {
        const ld s = std::pow(0.5L, i);
        ref += s * (0.5L * hg_ref(mu, 0.8L * s) + 0.5L * hg_ref(mu, -0.5L * s)) * std::exp(-s * ld(tau));
    }
    CHECK(cm_test::rel_err(multiple_scattering_with(tau, mu, T(0.5), T(0.5), T(0.5), 3, dual), ref) <= 64 * cm_test::eps<T>());
    CHECK(multiple_scattering_with<3>(tau, mu, T(0.5), T(0.5), T(0.5), dual) ==
          multiple_scattering_with(tau, mu, T(0.5), T(0.5), T(0.5), 3, dual));
    CHECK(multiple_scattering<4>(tau, mu, T(0.8), T(0.5), T(0.5), T(0.5)) ==
          multiple_scattering(tau, mu, T(0.8), T(0.5), T(0.5), T(0.5), 4));
    auto mie = [](T m, T scale) { (void)scale; return phase_mie_approx(m, T(10)); };
    CHECK(multiple_scattering_with<1>(tau, mu, T(0.5), T(0.5), T(0.5), mie) == phase_mie_approx(mu, T(10)) * beer_lambert(tau));
}

TEST_CASE_TEMPLATE("multiple_scattering sweep: finite and non-negative over the documented domain", T, float, double) {
    bool ok = true;
    for (int ti = 0; ti <= 40; ++ti)
        for (int mi = -20; mi <= 20; ++mi)
            for (T g : {T(-0.9999), T(-0.5), T(0), T(0.8), T(0.9999)})
                for (T a : {T(0), T(0.3), T(0.5), T(1)})
                    for (int n : {1, 3, 8}) {
                        const T tau = static_cast<T>(std::pow(10.0L, -8 + 12 * ti / 40.0L));
                        const T v = multiple_scattering(tau, T(mi) / T(20), g, a, T(0.5), T(0.5), n);
                        ok = ok && cm_test::finite_bits(v) && v >= T(0);
                    }
    CHECK(ok);
    if constexpr (cm_test::ieee_build) {
        CHECK(cm_test::nan_bits(multiple_scattering(cm_test::make_nan<T>(), T(0.5), T(0.8), T(0.5), T(0.5), T(0.5), 3)));
        CHECK(multiple_scattering(cm_test::make_inf<T>(), T(0.5), T(0.8), T(0.5), T(0.5), T(0.5), 3) == T(0));
    }
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(cm_test::same_value(multiple_scattering(tiny, tiny, T(0.8), T(0.5), T(0.5), T(0.5), 1), phase_hg(T(0), T(0.8))));
}

TEST_CASE_TEMPLATE("multiple_scattering with a preset equals the explicit parameters", T, float, double) {
    // The presets' documented error is reproduced by tools/reference/truths/test_lighting_presets.cpp
    // from the Monte Carlo reference; here: the overload uses exactly the preset's numbers.
    for (const multiple_scattering_preset& p : ms_preset::all)
        for (T tau : {T(0), T(0.5), T(8), T(100)})
            for (T mu : {T(-1), T(0.2), T(1)}) {
                CAPTURE(p.name);
                CHECK(multiple_scattering(tau, mu, T(0.85), p) ==
                      multiple_scattering(tau, mu, T(0.85), T(p.a), T(p.b), T(p.c), p.octaves));
            }
    CHECK(multiple_scattering(T(2), T(0.3), T(0.85), ms_preset::production) ==
          multiple_scattering<3>(T(2), T(0.3), T(0.85), T(0.5), T(0.5), T(0.5)));
}

TEST_CASE("multiple_scattering presets: parameters in range, measured error documented") {
    for (const multiple_scattering_preset& p : ms_preset::all) {
        CAPTURE(p.name);
        CHECK(p.a > 0.0f);
        CHECK(p.a <= 1.0f);
        CHECK(p.b > 0.0f);
        CHECK(p.b < 1.0f);
        CHECK(p.c > 0.0f);
        CHECK(p.c <= 1.0f);
        CHECK(p.octaves >= 1);
        CHECK(p.octaves <= 8);
        CHECK(p.tau_min < p.tau_max);
        CHECK(p.rms_error > 0.0f);
        CHECK(p.max_error >= p.rms_error);
    }
    // The fitted presets are better than the production values over their ranges.
    CHECK(ms_preset::fitted.rms_error < ms_preset::production.rms_error);
    CHECK(ms_preset::thin.rms_error < ms_preset::production.rms_error);
    CHECK(ms_preset::thick.rms_error < ms_preset::production.rms_error);
    CHECK(ms_preset::cheap.rms_error < ms_preset::production.rms_error);
    CHECK(ms_preset::cheap.octaves < ms_preset::production.octaves);
}
