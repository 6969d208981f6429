// Tests of diffusion_lighting.hpp: the chord's diffusion solution against its differential
// equation, boundary conditions and the diffusion law of transmission; the whole model
// against a long double evaluation of its formula; the table's interpolation; its limits
// (no table and no peak: exact single scattering) and the hard cases (zero and huge optical
// depths, +Inf, mu = +-1, g at and past +-1, denormals) in float and double, with and
// without -ffast-math. The fitted numbers' documented errors are checked against the
// stored Monte Carlo data by tools/reference/truths/test_lighting_diffusion.cpp.
#include <cloudmath/diffusion_lighting.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {

namespace L = diffusion_layout;
const ld PI = 3.141592653589793238462643383279502884L;

ld hg_ref(ld mu, ld g) {
    g = std::fmax(std::fmin(g, 0.9999L), -0.9999L);
    return (1 - g * g) / (4 * PI * std::pow(1 + g * g - 2 * g * mu, 1.5L));
}

// The chord's fluence and flux with absorption kappa, from the sinh/cosh form directly.
ld fluence_ref(ld x, ld y, ld kappa, ld& flux) {
    const ld z = L::extrapolation, Lc = x + y, W = Lc + 2 * z;
    const ld e_far = std::exp(-(Lc + z)), ez = std::exp(z);
    if (kappa == 0) {
        const ld slope = (ez - e_far) / W;
        flux = slope - std::exp(-x);
        return std::fmax(3 * (ez - std::exp(-x) - slope * (x + z)), 0.0L);
    }
    // sinh(k a) / sinh(k W) and cosh(k a) / sinh(k W); past k W = 100 (where sinh overflows
    // long double for the largest chords) as e^(k (a - W)) (1 -+ e^(-2 k a)) / (1 - e^(-2 k W)).
    const auto R = [&](ld a) {
        return kappa * W < 100 ? std::sinh(kappa * a) / std::sinh(kappa * W)
                               : std::exp(kappa * (a - W)) * (1 - std::exp(-2 * kappa * a)) / (1 - std::exp(-2 * kappa * W));
    };
    const auto Q = [&](ld a) {
        return kappa * W < 100 ? std::cosh(kappa * a) / std::sinh(kappa * W)
                               : std::exp(kappa * (a - W)) * (1 + std::exp(-2 * kappa * a)) / (1 - std::exp(-2 * kappa * W));
    };
    const ld scale = 1 / (1 - kappa * kappa);
    flux = scale * (kappa * (ez * Q(y + z) - e_far * Q(x + z)) - std::exp(-x));
    return std::fmax(3 * scale * (e_far * R(x + z) + ez * R(y + z) - std::exp(-x)), 0.0L);
}

// The model's formula (header comment) in long double, table by explicit multilinear sum.
ld model_ref(ld ts, ld tb, ld tv, ld mu, ld g, ld albedo, const diffusion_model& m) {
    ts = std::fmin(std::fmax(ts, 0.0L), 1e6L);
    tb = std::fmin(std::fmax(tb, 0.0L), 1e6L);
    tv = std::fmin(std::fmax(tv, 0.0L), 1e6L);
    mu = std::fmin(std::fmax(mu, -1.0L), 1.0L);
    const ld gc = std::fmin(std::fmax(g, -0.999L), 0.999L);
    const ld w = std::fmin(std::fmax(albedo, 0.0L), 1.0L);
    const ld s = std::fmax(1 - w * gc, 0.001L);
    const ld kappa = std::fmin(std::sqrt(3 * (1 - w) / s), 0.9L);
    const ld x = s * ts, y = s * tb, z = L::extrapolation;
    const ld direct = std::exp(-ts);
    ld peak = 0;
    for (int ia = 0; ia < L::peak_a_count; ++ia)
        for (int ic = 0; ic < L::peak_c_count; ++ic)
            peak += ld(m.peak[ia * L::peak_c_count + ic]) * hg_ref(mu, ld(L::peak_c[ic]) * g) *
                    std::fmax(std::exp(-ld(L::peak_a[ia]) * x) - direct, 0.0L);
    ld flux = 0;
    const ld U = fluence_ref(x, y, kappa, flux);
    const ld D = w * (1 - gc) / s * std::fmax(U + 3 * gc * flux * mu, 0.0L) / (4 * PI);
    const ld t = (x + z) * (y + z) / (x + y + 2 * z), d = s * tv + z;
    const ld u[4] = {x / (1 + x), y / (1 + y), (mu + 1) / 2, d / (d + t)};
    const int n[4] = {L::size_x, L::size_y, L::size_mu, L::size_d};
    ld C = 0;
    for (int ix = 0; ix < n[0]; ++ix)
        for (int iy = 0; iy < n[1]; ++iy)
            for (int im = 0; im < n[2]; ++im)
                for (int id = 0; id < n[3]; ++id) {
                    const int at[4] = {ix, iy, im, id};
                    ld wt = 1;
                    for (int k = 0; k < 4; ++k) wt *= std::fmax(0.0L, 1 - std::fabs(u[k] * (n[k] - 1) - at[k]));
                    C += wt * ld(m.table[L::table_index(ix, iy, im, id)]);
                }
    return std::fmax(hg_ref(mu, g) * direct + peak + D * std::fmax(C, 0.0L), 0.0L);
}

}  // namespace

TEST_CASE_TEMPLATE("diffusion_chord_fluence solves the chord's diffusion equation", T, float, double) {
    const T z = T(L::extrapolation);
    ld worst_U = 0, worst_F = 0;
    for (T kappa : {T(0), T(1e-7), T(1e-3), T(0.05), T(0.27), T(0.9)})
        for (T Lc : {T(0.05), T(1), T(10), T(300), T(1e5)}) {
            T flux = T(0);
            // U vanishes at the extrapolated ends (the formula holds on [-z, L + z]).
            CHECK(std::abs(diffusion_chord_fluence(-z, Lc + z, std::exp(z), kappa, flux)) < T(64) * cm_test::eps<T>());
            for (T f : {T(0.001), T(0.1), T(0.5), T(0.9), T(0.999)}) {
                const T x = f * Lc;
                ld flux_ref = 0;
                const ld U_ref = fluence_ref(x, Lc - x, kappa, flux_ref);
                const T U = diffusion_chord_fluence(x, Lc - x, std::exp(-x), kappa, flux);
                // On the fluence's scale 3 e^z (the formula cancels toward the chord's ends).
                worst_U = std::fmax(worst_U, std::fabs(ld(U) - U_ref) / (3 * std::exp(ld(z))));
                worst_F = std::fmax(worst_F, std::fabs(ld(flux) - flux_ref) / std::exp(ld(z)));
            }
        }
    MESSAGE(cm_test::type_name<T>() << ": chord fluence worst error " << double(worst_U) << ", flux " << double(worst_F));
    CHECK(worst_U <= 256 * cm_test::eps<T>());
    CHECK(worst_F <= 256 * cm_test::eps<T>());
    // The equation itself, by central differences in long double on the reference:
    // -U''/3 + kappa^2 U / 3 = e^-x, and Fick's law F = -U'/3.
    for (ld kappa : {0.0L, 0.3L})
        for (ld x : {0.2L, 1.0L, 5.0L}) {
            const ld h = 1e-4L, Lc = 8;
            ld f0, fm, fp;
            const ld u0 = fluence_ref(x, Lc - x, kappa, f0), um = fluence_ref(x - h, Lc - x + h, kappa, fm),
                     up = fluence_ref(x + h, Lc - x - h, kappa, fp);
            CHECK(double(-(up - 2 * u0 + um) / (h * h) / 3 + kappa * kappa * u0 / 3) ==
                  doctest::Approx(double(std::exp(-x))).epsilon(1e-5));
            CHECK(double(f0) == doctest::Approx(double(-(up - um) / (2 * h) / 3)).epsilon(1e-7));
        }
    // Deep in a thick conservative chord the net flux is e^z / (L + 2 z): diffuse
    // transmission; with absorption it falls exponentially instead.
    T flux = T(0);
    (void)diffusion_chord_fluence(T(90), T(10), std::exp(T(-90)), T(0), flux);
    CHECK(double(flux) == doctest::Approx(std::exp(L::extrapolation) / (100 + 2 * L::extrapolation)).epsilon(1e-5));
    T absorbed = T(0);
    (void)diffusion_chord_fluence(T(90), T(10), std::exp(T(-90)), T(0.1), absorbed);
    CHECK(absorbed < flux * T(0.01));
    // The conservative limit is continuous across the small-kappa switch.
    T f_small = T(0), f_zero = T(0);
    const T U_small = diffusion_chord_fluence(T(2), T(3), std::exp(T(-2)), T(1.1e-5), f_small);
    const T U_zero = diffusion_chord_fluence(T(2), T(3), std::exp(T(-2)), T(0), f_zero);
    CHECK(U_small == doctest::Approx(U_zero).epsilon(1e-5));
    CHECK(f_small == doctest::Approx(f_zero).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("diffusion_similarity: van de Hulst's relations, clamped", T, float, double) {
    const auto m = diffusion_similarity(T(0.85), T(0.99));
    CHECK(m.s == doctest::Approx(1 - 0.99 * 0.85));
    CHECK(m.kappa == doctest::Approx(std::sqrt(3 * 0.01 / (1 - 0.99 * 0.85))));
    CHECK(diffusion_similarity(T(0.85), T(1)).kappa == T(0));
    CHECK(diffusion_similarity(T(0.85), T(1)).s == doctest::Approx(0.15));
    CHECK(diffusion_similarity(T(0.85), T(0)).kappa == doctest::Approx(0.9));  // clamped
    CHECK(diffusion_similarity(T(1), T(1)).s == doctest::Approx(0.001));     // g clamped to 0.999
    CHECK(diffusion_similarity(T(0.5), T(2)).kappa == T(0));                  // albedo clamped to 1
}

// Every shipped model: those of homogeneous media (diffusion_models::all) and the
// whole-cloud fit (diffusion_models::clouds, not in all[]).
const diffusion_model every_model[] = {diffusion_models::fitted, diffusion_models::physical, diffusion_models::clouds};

TEST_CASE_TEMPLATE("diffusion_scattering matches its formula in long double", T, float, double) {
    ld worst = 0;
    for (const diffusion_model& m : every_model)
        for (T ts : {T(0), T(0.2), T(2), T(15), T(80)})
            for (T tb : {T(0), T(1), T(30)})
                for (T tv : {T(0), T(0.7), T(12)})
                    for (T mu : {T(-1), T(-0.4), T(0.3), T(0.95), T(1)})
                        for (T g : {T(0), T(0.75), T(0.85), T(0.9)})
                          for (T albedo : {T(1), T(0.99), T(0.8)}) {
                            const T got = diffusion_scattering(ts, tb, tv, mu, g, albedo, m);
                            const ld ref = model_ref(ts, tb, tv, mu, g, albedo, m);
                            // Relative to the sum's terms' scale (the single-scattering phase
                            // and the diffusion's 3 e^z / 4 pi), not to a result that can cancel.
                            const ld scale = hg_ref(mu, g) + 0.5L;
                            worst = std::fmax(worst, std::fabs(ld(got) - ref) / scale);
                        }
    MESSAGE(cm_test::type_name<T>() << ": diffusion_scattering worst error " << double(worst));
    CHECK(worst <= 4096 * cm_test::eps<T>());
}

TEST_CASE_TEMPLATE("diffusion_scattering limits", T, float, double) {
    // No table, no peak: exact single scattering.
    diffusion_model none{};
    none.name = "none";
    const T mu = T(0.3), g = T(0.85);
    for (T ts : {T(0), T(1), T(7)})
        CHECK(diffusion_scattering(ts, T(2), T(1), mu, g, T(0.99), none) == doctest::Approx(phase_hg(mu, g) * std::exp(-ts)));
    // The generic form with the HG phase equals the HG form (to rounding: -ffast-math may
    // reassociate the two inlined copies differently).
    const auto hg = [g](T m, T scale) { return phase_hg(m, scale * g); };
    for (const diffusion_model& m : every_model)
        CHECK(diffusion_scattering_with(T(3), T(4), T(0.5), mu, g, T(0.99), m, hg) ==
              doctest::Approx(diffusion_scattering(T(3), T(4), T(0.5), mu, g, T(0.99), m)).epsilon(64 * cm_test::eps<T>()));
    // Negative depths count as 0, depths past 1e6 as 1e6, mu and g are clamped.
    const diffusion_model& f = diffusion_models::fitted;
    CHECK(diffusion_scattering(T(-5), T(-1), T(-2), mu, g, T(1), f) == diffusion_scattering(T(0), T(0), T(0), mu, g, T(1), f));
    CHECK(diffusion_scattering(T(2e6), T(1e7), T(1e9), mu, g, T(1), f) ==
          diffusion_scattering(T(1e6), T(1e6), T(1e6), mu, g, T(1), f));
    CHECK(diffusion_scattering(T(1), T(1), T(1), T(3), g, T(1), f) == diffusion_scattering(T(1), T(1), T(1), T(1), g, T(1), f));
    CHECK(diffusion_scattering(T(1), T(1), T(1), mu, g, T(1.5), f) == diffusion_scattering(T(1), T(1), T(1), mu, g, T(1), f));
    // Thick clouds: the single scattering is gone, the diffusion stays; absorption dims it.
    const T conservative = diffusion_scattering(T(50), T(10), T(1), mu, g, T(1), diffusion_models::physical);
    CHECK(conservative > T(0));
    CHECK(diffusion_scattering(T(50), T(10), T(1), mu, g, T(0.99), diffusion_models::physical) < conservative);
    // No scattering, no diffusion: albedo 0 leaves the single-scattering and peak terms.
    diffusion_model only_table = diffusion_models::physical;
    for (float& p : only_table.peak) p = 0.0f;
    CHECK(diffusion_scattering(T(3), T(3), T(1), mu, g, T(0), only_table) == doctest::Approx(phase_hg(mu, g) * std::exp(T(-3))));
}

TEST_CASE("diffusion table: exact at the nodes, multilinear between them") {
    const diffusion_model& m = diffusion_models::fitted;
    for (int ix = 0; ix < L::size_x; ++ix)
        for (int iy = 0; iy < L::size_y; ++iy)
            for (int im = 0; im < L::size_mu; ++im)
                for (int id = 0; id < L::size_d; ++id) {
                    const diffusion_coordinates<double> u{double(ix) / (L::size_x - 1), double(iy) / (L::size_y - 1),
                                                          double(im) / (L::size_mu - 1), double(id) / (L::size_d - 1)};
                    CHECK(diffusion_table_lookup(m, u) == doctest::Approx(m.table[L::table_index(ix, iy, im, id)]).epsilon(1e-12));
                }
    // Half way between two nodes along mu: their mean.
    const diffusion_coordinates<double> mid{0.0, 0.0, 0.5 / (L::size_mu - 1), 0.0};
    CHECK(diffusion_table_lookup(m, mid) ==
          doctest::Approx(0.5 * (double(m.table[L::table_index(0, 0, 0, 0)]) + double(m.table[L::table_index(0, 0, 1, 0)]))));
    // Coordinates: each in [0, 1], with the documented limits.
    const auto u0 = diffusion_table_coordinates(0.0, 0.0, 0.0, -1.0, 0.85, 1.0);
    CHECK(u0.u_sun == 0.0);
    CHECK(u0.u_behind == 0.0);
    CHECK(u0.u_mu == 0.0);
    CHECK(u0.u_surface == doctest::Approx(2.0 / 3.0));  // d = z, t = z / 2 on both surfaces
    const auto u1 = diffusion_table_coordinates(1e6, 1e6, 1e6, 1.0, 0.85, 0.99);
    CHECK(u1.u_sun == doctest::Approx(1.0).epsilon(1e-4));
    CHECK(u1.u_mu == 1.0);
    CHECK(u1.u_surface > 0.0);
    CHECK(u1.u_surface < 1.0);
}

TEST_CASE_TEMPLATE("diffusion_scattering: finite and >= 0 on the hard cases", T, float, double) {
    std::vector<T> depths{T(0), std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::min(), T(1e-30), T(0.5), T(40), T(1e6), T(1e30), std::numeric_limits<T>::max()};
    if (cm_test::ieee_build) depths.push_back(cm_test::make_inf<T>());
    int bad = 0;
    for (const diffusion_model& m : every_model)
        for (T ts : depths)
            for (T tb : depths)
                for (T tv : {T(0), T(3), std::numeric_limits<T>::max()})
                    for (T mu : {T(-1), T(0), T(1)})
                        for (T g : {T(-1), T(-0.999), T(0), T(0.85), T(0.999), T(1), T(5)})
                          for (T albedo : {T(0), T(0.5), T(0.99), T(1), T(3)}) {
                            const T v = diffusion_scattering(ts, tb, tv, mu, g, albedo, m);
                            if (!cm_test::finite_bits(v) || v < T(0)) ++bad;
                        }
    CHECK(bad == 0);
}

TEST_CASE("diffusion models: documented fit ranges and errors are consistent") {
    for (const diffusion_model& m : every_model) {
        CHECK(m.tau_min > 0.0f);
        CHECK(m.tau_max > m.tau_min);
        CHECK(m.g_max >= m.g_min);
        CHECK(m.rms_error > 0.0f);
        CHECK(m.max_error >= m.rms_error);
        CHECK(m.holdout_rms_error > 0.0f);
    }
    // The fitted model is the default and beats plain diffusion on its own data.
    CHECK(std::string(diffusion_models::all[0].name) == "fitted");
    // all[] lists the models of homogeneous media only: the whole-cloud fit is not one of them,
    // and it is worse than the homogeneous fit on the homogeneous reference (its data are
    // whole clouds: docs/lighting_research.md).
    CHECK(std::size(diffusion_models::all) == 2);
    for (const diffusion_model& m : diffusion_models::all) CHECK(std::string(m.name) != "clouds");
    CHECK(std::string(diffusion_models::clouds.name) == "clouds");
    CHECK(diffusion_models::clouds.rms_error > diffusion_models::fitted.rms_error);
    CHECK(diffusion_models::fitted.rms_error < diffusion_models::physical.rms_error);
}

// Hardening round 2, A1: a NaN argument was converted to int by diffusion_hat, and the table
// was read about 2^31 entries away (a segfault at -O2). Now the nodes stay in the table and
// the NaN reaches the result.
TEST_CASE_TEMPLATE("diffusion model: a NaN argument gives NaN, never an index outside the table", T, float, double) {
    const T nan = cm_test::make_nan<T>();
    const T args[6] = {T(1), T(1), T(1), T(0.3), T(0.85), T(1)};
    for (const diffusion_model& m : every_model)
        for (int k = 0; k < 6; ++k) {
            T a[6];
            for (int i = 0; i < 6; ++i) a[i] = i == k ? nan : args[i];
            const T v = diffusion_scattering(a[0], a[1], a[2], a[3], a[4], a[5], m);
            const diffusion_coordinates<T> u = diffusion_table_coordinates(a[0], a[1], a[2], a[3], a[4], a[5]);
            const T c = diffusion_table_lookup(m, u);
            if (cm_test::ieee_build) {
                CHECK_MESSAGE(cm_test::nan_bits(v), "argument " << k);
                CHECK_MESSAGE(cm_test::nan_bits(c), "argument " << k);
            }
        }
    // Each coordinate NaN alone, in every build: the lookup reads the table only (ASan and
    // UBSan builds catch any other read or conversion).
    for (int k = 0; k < 4; ++k) {
        T w[4] = {T(0.2), T(0.5), T(0.7), T(0.9)};
        w[k] = nan;
        const T c = diffusion_table_lookup(diffusion_models::clouds, diffusion_coordinates<T>{w[0], w[1], w[2], w[3]});
        if (cm_test::ieee_build) CHECK(cm_test::nan_bits(c));
    }
}
