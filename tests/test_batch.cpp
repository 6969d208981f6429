// Tests of batch.hpp: every batch function against the scalar functions element by element
// (exact policy within a few ulp, fast policy within the documented errors), over arrays that
// include the hard cases, with lengths that exercise the vector loops' remainders, and
// in-place use. Each check runs twice: with the run-time dispatch (AVX2 + FMA where the CPU
// has it) and restricted to the baseline code, so both compiled copies are tested.
#include <cloudmath/batch.hpp>
#include <cloudmath/integration.hpp>
#include <cloudmath/multiple_scattering.hpp>
#include <cloudmath/transmittance.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {
template <class T>
std::vector<T> mus(std::size_t n) {
    std::vector<T> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = T(-1) + T(2) * T(i) / T(n - 1);
    v[0] = T(-1.5);  // clamped
    v[n / 2] = T(1) - T(1e-6);
    return v;
}
template <class T>
std::vector<T> taus(std::size_t n) {
    std::vector<T> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<T>(std::pow(10.0L, -9 + 13.0L * i / (n - 1)));  // 1e-9 .. 1e4
    v[0] = T(0);
    v[1] = T(-3);  // clamped
    return v;
}
// Runs body once per instruction set the batch functions can use here, restoring dispatch.
template <class Body>
void for_each_isa(const Body& body) {
    for (bool baseline : {true, false}) {
        batch::restrict_to_baseline(baseline);
        const std::string isa = batch::isa_name(batch::active_isa());
        CAPTURE(isa);
        body();
    }
    batch::restrict_to_baseline(false);
}
// Max relative error of got against want (absolute below 1e-30).
template <class T>
ld worst(const std::vector<T>& got, const std::vector<T>& want) {
    ld w = 0;
    for (std::size_t i = 0; i < got.size(); ++i) w = std::max(w, cm_test::rel_err(ld(got[i]), std::fabs(ld(want[i])) < 1e-30L ? 0.0L : ld(want[i])));
    return w;
}
}  // namespace

TEST_CASE_TEMPLATE("batch phase functions match the scalar ones", T, float, double) {
    for_each_isa([&] {
        const T e = cm_test::eps<T>();
        for (std::size_t n : {std::size_t(1), std::size_t(7), std::size_t(1001)}) {
            const std::vector<T> mu = mus<T>(std::max<std::size_t>(n, 2));
            std::vector<T> out(mu.size()), want(mu.size());
            for (T g : {T(-0.9999), T(-0.5), T(0), T(0.8), T(0.999), T(1)}) {
                batch::phase_hg(mu.data(), mu.size(), g, out.data());
                for (std::size_t i = 0; i < mu.size(); ++i) want[i] = phase_hg(mu[i], g);
                CHECK(worst(out, want) <= 8 * e);  // documented: within 5.5 ulp of exact; scalar 3.7
                batch::phase_hg<fast_math>(mu.data(), mu.size(), g, out.data());
                CHECK(worst(out, want) <= 5.3e-3L);  // fast::phase_hg's documented error
                std::vector<T> scalar_fast(mu.size());
                for (std::size_t i = 0; i < mu.size(); ++i) scalar_fast[i] = fast::phase_hg(mu[i], g);
                // The same approximation as the scalar one: 4 ulp apart in the baseline code, up to
                // 6 where the AVX2 copy contracts the Newton step into FMAs.
                CHECK(worst(out, scalar_fast) <= (batch::active_isa() == batch::isa::baseline ? 4 : 8) * e);
                batch::phase_cornette_shanks(mu.data(), mu.size(), g, out.data());
                for (std::size_t i = 0; i < mu.size(); ++i) want[i] = phase_cornette_shanks(mu[i], g);
                CHECK(worst(out, want) <= 10 * e);
            }
            for (T d : {T(0.05), T(3), T(10), T(50)}) {
                const mie_approx_parameters<T> p = mie_approx_params(d);
                batch::phase_mie_approx(mu.data(), mu.size(), p, out.data());
                for (std::size_t i = 0; i < mu.size(); ++i) want[i] = phase_mie_approx(mu[i], p);
                CHECK(worst(out, want) <= 16 * e);
            }
        }
    });
}

TEST_CASE_TEMPLATE("batch transmittance, integration and octaves match the scalar ones", T, float, double) {
    for_each_isa([&] {
        // Under -ffast-math exp_vectorizable may lose its two-step range reduction (documented in
        // batch.hpp: 1.6e-5 float, 2.6e-13 double); the budgets grow accordingly.
        const T e = cm_test::ieee_build ? cm_test::eps<T>() : T(std::is_same_v<T, float> ? 1.6e-5 / 4 : 2.6e-13 / 4);
        const std::vector<T> tau = taus<T>(1003);
        const std::vector<T> mu = mus<T>(1003);
        std::vector<T> out(tau.size()), want(tau.size());
        batch::beer_lambert(tau.data(), tau.size(), out.data());
        for (std::size_t i = 0; i < tau.size(); ++i) want[i] = beer_lambert(tau[i]);
        CHECK(worst(out, want) <= 4 * e);
        batch::beer_lambert<fast_math>(tau.data(), tau.size(), out.data());
        CHECK(worst(out, want) <= 6.0e-5L);
        batch::beer_powder(tau.data(), tau.size(), out.data());
        for (std::size_t i = 0; i < tau.size(); ++i) want[i] = beer_powder(tau[i]);
        CHECK(worst(out, want) <= 8 * e);  // keeps relative precision for tiny tau, unlike the fast form
        batch::nubis_attenuation(tau.data(), tau.size(), out.data());
        for (std::size_t i = 0; i < tau.size(); ++i) want[i] = nubis_attenuation(tau[i]);
        CHECK(worst(out, want) <= 4 * e);
        std::vector<T> S(tau.size(), T(0.37));
        batch::integrate_scattering(S.data(), tau.data(), tau.size(), T(2), out.data());
        for (std::size_t i = 0; i < tau.size(); ++i) want[i] = integrate_scattering(S[i], tau[i], T(2));
        CHECK(worst(out, want) <= 8 * e);
        for (int octaves : {0, 1, 3, 8}) {
            batch::multiple_scattering(tau.data(), mu.data(), tau.size(), T(0.8), T(0.5), T(0.5), T(0.5), octaves, out.data());
            for (std::size_t i = 0; i < tau.size(); ++i) want[i] = multiple_scattering(tau[i], mu[i], T(0.8), T(0.5), T(0.5), T(0.5), octaves);
            CHECK(worst(out, want) <= 16 * e);
            batch::multiple_scattering<fast_math>(tau.data(), mu.data(), tau.size(), T(0.8), T(0.5), T(0.5), T(0.5), octaves, out.data());
            CHECK(worst(out, want) <= 5.3e-3L);  // fast::multiple_scattering's documented error
        }
        // In place: out may be the input.
        std::vector<T> inplace = tau;
        batch::beer_lambert(inplace.data(), inplace.size(), inplace.data());
        batch::beer_lambert(tau.data(), tau.size(), out.data());
        CHECK(inplace == out);
        batch::beer_lambert(tau.data(), 0, out.data());  // n = 0: nothing to do
    });
}

TEST_CASE("batch dispatch: the instruction set follows the CPU and restrict_to_baseline") {
    // What the dispatch should pick, from the compiler's own CPU test.
#if CLOUDMATH_BATCH_DISPATCH
    const bool wide = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    const bool wide = false;
#endif
    CHECK(batch::active_isa() == (wide ? batch::isa::avx2_fma : batch::isa::baseline));
    batch::restrict_to_baseline(true);
    CHECK(batch::active_isa() == batch::isa::baseline);
    batch::restrict_to_baseline(false);
    CHECK(batch::active_isa() == (wide ? batch::isa::avx2_fma : batch::isa::baseline));
    CHECK(std::string(batch::isa_name(batch::isa::baseline)) == "baseline");
    CHECK(std::string(batch::isa_name(batch::isa::avx2_fma)) == "avx2+fma");
    MESSAGE("batch functions run with " << std::string(batch::isa_name(batch::active_isa())));
}

// Regression (fuzzing): batch::beer_powder was NaN for tau > FLT_MAX / 2 (DBL_MAX / 2): 2 tau
// overflowed and Inf * 0 followed; under -ffast-math from tau = FLT_MAX / 2 itself. The
// scalar beer_powder returns 0 there. Every batch function over huge optical depths, with
// both policies and instruction sets, against the closed forms in long double (their limits:
// everything here is exp(-huge) = 0 to within the smallest normal number).
TEST_CASE_TEMPLATE("batch functions at huge optical depths: finite, at the closed forms' limits", T, float, double) {
    const T big = std::numeric_limits<T>::max();
    std::vector<T> tau = {big / 2, std::nextafter(big / 2, big), big * T(0.75), big, T(1e30), T(std::is_same_v<T, float> ? 1.7e38 : 1e300),
                          T(1e4), T(745), T(103), T(30)};
    if constexpr (cm_test::ieee_build) tau.push_back(cm_test::make_inf<T>());
    const std::size_t n = tau.size();
    const std::vector<T> mu(n, T(0.3)), S(n, T(0.37));
    const ld pi = 3.141592653589793238462643383279502884L;
    auto hg = [pi](ld m, ld g) { return (1 - g * g) / (4 * pi * std::pow(1 + g * g - 2 * g * m, 1.5L)); };
    auto e = [](ld t) { return std::exp(-t); };
    auto check = [&](const char* what, const std::vector<T>& got, auto ref, ld rel) {
        for (std::size_t i = 0; i < n; ++i) {
            INFO(what << " at tau = " << tau[i]);
            REQUIRE(cm_test::finite_bits(got[i]));
            const ld want = ref(ld(tau[i]));
            CHECK(std::fabs(ld(got[i]) - want) <= rel * want + ld(std::numeric_limits<T>::min()));
        }
    };
    for_each_isa([&] {
        // exact_math: a few ulp (IEEE) or the -ffast-math budget of batch.hpp; fast_math: 1e-4.
        const ld exact = cm_test::ieee_build ? 16 * ld(cm_test::eps<T>()) : 1e-4L, fast = 1e-4L;
        std::vector<T> out(n);
        batch::beer_powder(tau.data(), n, out.data());
        check("beer_powder", out, [&](ld t) { return 2 * e(t) * -std::expm1(-2 * t); }, exact);
        batch::beer_powder<fast_math>(tau.data(), n, out.data());
        check("beer_powder<fast_math>", out, [&](ld t) { return 2 * e(t) * -std::expm1(-2 * t); }, fast);
        batch::beer_lambert(tau.data(), n, out.data());
        check("beer_lambert", out, e, exact);
        batch::beer_lambert<fast_math>(tau.data(), n, out.data());
        check("beer_lambert<fast_math>", out, e, fast);
        batch::nubis_attenuation(tau.data(), n, out.data());
        check("nubis_attenuation", out, [&](ld t) { return std::fmax(e(t), 0.7L * e(0.25L * t)); }, exact);
        batch::nubis_attenuation<fast_math>(tau.data(), n, out.data());
        check("nubis_attenuation<fast_math>", out, [&](ld t) { return std::fmax(e(t), 0.7L * e(0.25L * t)); }, fast);
        // sigma_t = tau, ds = 2: S (1 - e^-2tau) / tau, at most 0.37 / FLT_MAX.
        batch::integrate_scattering(S.data(), tau.data(), n, T(2), out.data());
        check("integrate_scattering", out, [&](ld t) { return 0.37L * -std::expm1(-2 * t) / t; }, exact);
        auto ms = [&](ld t) {
            ld s = 0, ai = 1, bi = 1, ci = 1;
            for (int o = 0; o < 3; ++o, ai *= 0.5L, bi *= 0.5L, ci *= 0.5L) s += bi * hg(0.3L, ci * 0.8L) * e(ai * t);
            return s;
        };
        batch::multiple_scattering(tau.data(), mu.data(), n, T(0.8), T(0.5), T(0.5), T(0.5), 3, out.data());
        check("multiple_scattering", out, ms, exact);
        batch::multiple_scattering<fast_math>(tau.data(), mu.data(), n, T(0.8), T(0.5), T(0.5), T(0.5), 3, out.data());
        check("multiple_scattering<fast_math>", out, ms, 5.3e-3L);
    });
    // The scalar forms agree: 0 (exp(-tau) underflows from tau = 1e4 on), and powder 1.
    for (T t : tau) {
        if (t >= T(1e4)) CHECK(beer_powder(t) == T(0));
        CHECK(powder(t, T(1e10)) == T(1));
    }
}
