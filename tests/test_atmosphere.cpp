// Tests of atmosphere.hpp: Earth's parameters as published, the extinction profile, the
// optical depth of a vertical ray against its closed form, the transmittance against an
// independent long double quadrature at every altitude and zenith angle (the 1e-3 target),
// the LUT mapping's round trip and the LUT's lookup, and EV100's closed forms.
#include <cloudmath/atmosphere.hpp>
#include <cloudmath/density.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {

// The reference: the straight ray's geometry and the extinction written out again in long
// double, midpoint rule over `steps` steps; transmittance 0 for a ray into the ground.
glm::vec<3, ld> reference_transmittance(const atmosphere_parameters<float>& a, ld h, ld mu, int steps) {
    const ld R = a.bottom_radius, top = a.top_radius, r = R + h;
    if (mu < 0 && r * r * (mu * mu - 1) + R * R >= 0) return glm::vec<3, ld>(0);
    const ld d = -r * mu + std::sqrt(r * r * (mu * mu - 1) + top * top);
    const ld ds = d / steps;
    glm::vec<3, ld> tau(0);
    for (int i = 0; i < steps; ++i) {
        const ld t = (i + 0.5L) * ds;
        const ld alt = std::sqrt(r * r + 2 * r * mu * t + t * t) - R;
        const ld tent = std::fmax(1 - std::fabs(alt - ld(a.ozone_center)) / ld(a.ozone_half_width), 0.0L);
        for (int c = 0; c < 3; ++c)
            tau[c] += ld(a.rayleigh_scattering[c]) * std::exp(-alt / ld(a.rayleigh_scale_height)) +
                      ld(a.mie_extinction) * std::exp(-alt / ld(a.mie_scale_height)) + ld(a.ozone_absorption[c]) * tent;
    }
    return glm::vec<3, ld>(std::exp(-tau.x * ds), std::exp(-tau.y * ds), std::exp(-tau.z * ds));
}

}  // namespace

TEST_CASE_TEMPLATE("earth_atmosphere: Bruneton 2017's constants (REFERENCES.md)", T, float, double) {
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    CHECK(a.bottom_radius == T(6360e3));
    CHECK(a.top_radius == T(6420e3));
    CHECK(a.rayleigh_scattering == glm::vec<3, T>(T(5.802e-6), T(13.558e-6), T(33.1e-6)));
    CHECK(a.rayleigh_scale_height == T(8000));
    CHECK(a.mie_scattering == T(3.996e-6));
    CHECK(a.mie_extinction == T(4.40e-6));
    CHECK(a.mie_scale_height == T(1200));
    CHECK(a.mie_g == T(0.8));
    CHECK(a.ozone_absorption == glm::vec<3, T>(T(0.650e-6), T(1.881e-6), T(0.085e-6)));
    CHECK(a.ozone_center == T(25e3));
    CHECK(a.ozone_half_width == T(15e3));
    CHECK(a.ground_albedo == T(0.1));
}

TEST_CASE_TEMPLATE("atmosphere_extinction: the three profiles, and the vertical optical depth in closed form", T, float, double) {
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    // At the ground: Rayleigh + Mie extinction (no ozone below 10 km).
    const glm::vec<3, T> ground = atmosphere_extinction(a, T(0));
    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(ground[c]), double(a.rayleigh_scattering[c]) + 4.40e-6) < 1e-6);
    CHECK(atmosphere_extinction(a, T(-500)) == ground);  // below 0 taken as 0
    // At the ozone peak the tent adds its full absorption.
    const glm::vec<3, T> peak = atmosphere_extinction(a, T(25e3));
    CHECK(cm_test::rel_err(double(peak.y), 13.558e-6 * std::exp(-25e3 / 8000.0) + 4.40e-6 * std::exp(-25e3 / 1200.0) + 1.881e-6) < 1e-5);
    // Straight up from h, the optical depth to the top in closed form:
    //   beta_R H_R (e^(-h/H_R) - e^(-(top-R)/H_R)) + the same for Mie + ozone's tent area above h.
    for (T h : {T(0), T(1500), T(12000), T(30000), T(55000)}) {
        CAPTURE(h);
        const ld top = 60000.0L, hh = ld(h);
        const auto tent_area = [](ld from) {  // area of the tent 10-40 km above `from`
            const auto F = [](ld x) {          // integral of the tent from 10 km to x
                x = std::fmin(std::fmax(x, 10e3L), 40e3L);
                return x <= 25e3L ? (x - 10e3L) * (x - 10e3L) / (2 * 15e3L) : 7.5e3L + (x - 25e3L) - (x - 25e3L) * (x - 25e3L) / (2 * 15e3L);
            };
            return F(60e3L) - F(from);
        };
        const glm::vec<3, T> tau = atmosphere_optical_depth(a, h, T(1), a.top_radius - a.bottom_radius - h, 4096);
        for (int c = 0; c < 3; ++c) {
            const ld want = ld(a.rayleigh_scattering[c]) * 8000.0L * (std::exp(-hh / 8000.0L) - std::exp(-top / 8000.0L)) +
                            4.40e-6L * 1200.0L * (std::exp(-hh / 1200.0L) - std::exp(-top / 1200.0L)) +
                            ld(a.ozone_absorption[c]) * tent_area(hh);
            CHECK(cm_test::rel_err(double(tau[c]), double(want)) < 1e-4);
        }
    }
}

TEST_CASE("atmosphere_transmittance: within 1e-3 of a long double quadrature at every altitude and zenith angle, in float") {
    const atmosphere_parameters<float> a = earth_atmosphere<float>();
    double worst = 0.0;
    int hit_ground_mismatch = 0;
    for (float h : {0.0f, 10.0f, 500.0f, 2000.0f, 8000.0f, 20000.0f, 40000.0f, 59000.0f, 60000.0f})
        for (int k = 0; k <= 80; ++k) {
            const float mu = -1.0f + 2.0f * float(k) / 80.0f;
            const glm::vec<3, ld> want = reference_transmittance(a, h, mu, 20000);
            const glm::vec3 got = atmosphere_transmittance(a, h, mu);
            if ((want.x == 0) != (got.x == 0.0f) && std::fabs(double(want.x) - double(got.x)) > 1e-3) ++hit_ground_mismatch;
            for (int c = 0; c < 3; ++c) worst = std::fmax(worst, std::fabs(double(got[c]) - double(want[c])));
        }
    MESSAGE("atmosphere_transmittance (64 steps, float): worst absolute error " << worst);
    CHECK(worst <= 1e-3);
    CHECK(hit_ground_mismatch == 0);
    // Near the horizon, where it changes fastest: rays just above and below it from 2 km.
    const float h = 2000.0f, r = a.bottom_radius + h;
    const float mu_horizon = -std::sqrt(1.0f - (a.bottom_radius / r) * (a.bottom_radius / r));
    for (float dmu : {1e-2f, 1e-3f, 1e-4f}) {
        CHECK(atmosphere_transmittance(a, h, mu_horizon - dmu) == glm::vec3(0.0f));  // into the ground
        const glm::vec<3, ld> want = reference_transmittance(a, h, mu_horizon + dmu, 20000);
        const glm::vec3 got = atmosphere_transmittance(a, h, mu_horizon + dmu);
        for (int c = 0; c < 3; ++c) CHECK(std::fabs(double(got[c]) - double(want[c])) <= 1e-3);
    }
    // Outside the air looking up: nothing to cross.
    CHECK(atmosphere_transmittance(a, 60000.0f, 0.5f) == glm::vec3(1.0f));
    // The sun at zenith seen from the ground: 0.94, 0.87, 0.76 (red, green, blue). With the
    // channels weighted as luminance (Rec. 709) and 128 klux above the air, the direct normal
    // illuminance is 112 klux, inside the 100-115 klux measured on clear days (REFERENCES.md:
    // about 100-110).
    const glm::vec3 zenith = atmosphere_transmittance(a, 0.0f, 1.0f);
    const double lux = 128.0 * (0.2126 * zenith.x + 0.7152 * zenith.y + 0.0722 * zenith.z);
    MESSAGE("direct normal illuminance at sea level, sun at zenith: " << lux << " klux");
    CHECK(lux >= 100.0);
    CHECK(lux <= 115.0);
    CHECK(zenith.x > zenith.y);
    CHECK(zenith.y > zenith.z);  // blue is scattered most: the sun is yellowed
}

TEST_CASE_TEMPLATE("transmittance LUT: the mapping's round trip, its edges, and the lookup", T, float, double) {
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    const glm::vec<2, T> size(T(256), T(64));
    // The round trip at texel centres: (altitude, mu) -> uv -> (altitude, mu).
    for (int j = 0; j < 64; j += 9)
        for (int i = 0; i < 256; i += 17) {
            const glm::vec<2, T> uv((T(i) + T(0.5)) / size.x, (T(j) + T(0.5)) / size.y);
            const glm::vec<2, T> am = atmosphere_transmittance_lut_altitude_mu(a, uv, size);
            CHECK(am.x >= T(0));
            CHECK(am.x <= a.top_radius - a.bottom_radius);
            CHECK(am.y >= T(-1));
            CHECK(am.y <= T(1));
            const glm::vec<2, T> back = atmosphere_transmittance_lut_uv(a, am.x, am.y, size);
            CHECK(std::fabs(double(back.x - uv.x)) <= (std::is_same_v<T, float> ? 2e-3 : 1e-9));
            CHECK(std::fabs(double(back.y - uv.y)) <= (std::is_same_v<T, float> ? 1e-4 : 1e-9));
        }
    // The edges: the ground at v's first texel centre, the top at its last; straight up at
    // u's first texel centre (d = d_min), the horizon at its last (d = d_max).
    CHECK(cm_test::rel_err(double(atmosphere_transmittance_lut_uv(a, T(0), T(1), size).y), 0.5 / 64.0) < 1e-5);
    CHECK(cm_test::rel_err(double(atmosphere_transmittance_lut_uv(a, T(60000), T(1), size).y), 1.0 - 0.5 / 64.0) < 1e-5);
    CHECK(cm_test::rel_err(double(atmosphere_transmittance_lut_uv(a, T(3000), T(1), size).x), 0.5 / 256.0) < 1e-5);
    const T r = a.bottom_radius + T(3000);
    const T horizon = -std::sqrt(T(1) - (a.bottom_radius / r) * (a.bottom_radius / r));
    CHECK(cm_test::rel_err(double(atmosphere_transmittance_lut_uv(a, T(3000), horizon, size).x), 1.0 - 0.5 / 256.0) < 1e-3);
}

// The LUT's error is the bilinear interpolation's across its rows: worst at 40 km, the top of
// the ozone tent, whose kink falls between rows (256 x 128 halves it: 1.0e-3, measured).
TEST_CASE("transmittance LUT 256 x 64: within 2.5e-3 of the quadrature away from the horizon, 0 into the ground") {
    const atmosphere_parameters<float> a = earth_atmosphere<float>();
    const std::vector<glm::vec3> lut = atmosphere_transmittance_lut(a, 256, 64);
    REQUIRE(lut.size() == 256u * 64u);
    double worst = 0.0, worst_near_horizon = 0.0;
    for (float h : {0.0f, 500.0f, 2000.0f, 8000.0f, 20000.0f, 40000.0f, 59000.0f})
        for (int k = 0; k <= 100; ++k) {
            const float mu = -1.0f + 2.0f * float(k) / 100.0f;
            const glm::vec3 got = atmosphere_transmittance_from_lut(a, lut, 256, 64, h, mu);
            const glm::vec3 want = atmosphere_transmittance(a, h, mu, 256);
            const float r = a.bottom_radius + h;
            const float horizon = -std::sqrt(std::fmax(1.0f - (a.bottom_radius / r) * (a.bottom_radius / r), 0.0f));
            const bool near_horizon = std::fabs(mu - horizon) < 0.06f;
            for (int c = 0; c < 3; ++c) {
                const double e = std::fabs(double(got[c]) - double(want[c]));
                (near_horizon ? worst_near_horizon : worst) = std::fmax(near_horizon ? worst_near_horizon : worst, e);
            }
        }
    MESSAGE("LUT 256 x 64: worst " << worst << " away from the horizon, " << worst_near_horizon << " within 0.06 of its cosine");
    CHECK(worst <= 2.5e-3);
    CHECK(worst_near_horizon <= 0.02);
    // A LUT too small for its stated size reads nothing.
    CHECK(atmosphere_transmittance_from_lut(a, std::vector<glm::vec3>(10), 256, 64, 0.0f, 1.0f) == glm::vec3(0.0f));
}

TEST_CASE_TEMPLATE("EV100 and exposure: Lagarde and de Rousiers' closed forms", T, float, double) {
    // Sunny 16: f/16, 1/100 s, ISO 100: log2(25600).
    CHECK(cm_test::rel_err(double(ev100_from_camera(T(16), T(0.01), T(100))), std::log2(25600.0)) < 1e-6);
    CHECK(std::fabs(double(ev100_from_camera(T(1), T(1), T(100)))) < 1e-6);
    CHECK(cm_test::rel_err(double(ev100_from_camera(T(1), T(1), T(200))), -1.0) < 1e-6);  // twice the ISO: one stop less
    CHECK(std::fabs(double(ev100_from_luminance(T(0.125)))) < 1e-6);            // K = 12.5
    CHECK(cm_test::rel_err(double(exposure_from_ev100(T(0))), 1.0 / 1.2) < 1e-6);
    CHECK(cm_test::rel_err(double(exposure_from_ev100(T(10))), 1.0 / (1.2 * 1024.0)) < 1e-6);
    // Metering a luminance and exposing by it maps that luminance to the same value for any L:
    // L * exposure = L / (1.2 * 8 L) = 1 / 9.6.
    for (T L : {T(1e-3), T(1), T(5000)})
        CHECK(cm_test::rel_err(double(L * exposure_from_ev100(ev100_from_luminance(L))), 1.0 / 9.6) < 1e-5);
}

// ---------------------------------------------------------------------------------------
// Scattering, multiple scattering, in-scattering, sky radiance (part two).

TEST_CASE_TEMPLATE("atmosphere_scattering: the phase-weighted coefficient integrates to atmosphere_scattering_coefficient", T, float, double) {
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    for (const T h : {T(0), T(1200), T(25000), T(60000)}) {
        const glm::vec<3, T> s = atmosphere_scattering_coefficient(a, h);
        // Closed form at the altitude.
        for (int c = 0; c < 3; ++c)
            CHECK(cm_test::rel_err(double(s[c]), double(a.rayleigh_scattering[c]) * std::exp(-double(h) / 8000.0) +
                                                  3.996e-6 * std::exp(-double(h) / 1200.0)) < 1e-5);
        // 2 pi times the integral over cos_theta: midpoint rule, 20000 steps (Mie's g = 0.8 peak).
        glm::dvec3 sum(0.0);
        const int n = 20000;
        for (int i = 0; i < n; ++i) sum += glm::dvec3(atmosphere_scattering(a, h, T(-1) + T(2) * (T(i) + T(0.5)) / T(n)));
        sum *= 2.0 * 3.14159265358979323846 * 2.0 / n;
        for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(sum[c], double(s[c])) < 2e-4);
    }
    // Below the ground: the ground's values.
    CHECK(atmosphere_scattering_coefficient(a, T(-5)).x == atmosphere_scattering_coefficient(a, T(0)).x);
}

TEST_CASE_TEMPLATE("atmosphere_sun_illuminance: the sun above the air times the transmittance; 0 behind the ground", T, float, double) {
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    const glm::vec<3, T> e0(T(1), T(2), T(3));
    const glm::vec<3, T> e = atmosphere_sun_illuminance(a, T(0), T(1), e0);
    const glm::vec<3, T> t = atmosphere_transmittance(a, T(0), T(1), 64);
    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(e[c]), double(e0[c] * t[c])) < 1e-6);
    CHECK(atmosphere_sun_illuminance(a, T(0), T(-0.01), e0).y == T(0));
    // From 10 km the sun is still seen 0.01 below the horizontal (the horizon dips 3.2 degrees).
    CHECK(atmosphere_sun_illuminance(a, T(10000), T(-0.01), e0).x > T(0.1));
}

namespace {
// The vertical column's optical depths in closed form (the exponentials' integrals to the top,
// the ozone tent's area).
template <class T>
double vertical_tau(const atmosphere_parameters<T>& a, int c, bool scattering_only, bool rayleigh, bool mie) {
    const double Z = double(a.top_radius - a.bottom_radius);
    const double fr = double(a.rayleigh_scale_height) * -std::expm1(-Z / double(a.rayleigh_scale_height));
    const double fm = double(a.mie_scale_height) * -std::expm1(-Z / double(a.mie_scale_height));
    double tau = 0.0;
    if (rayleigh) tau += double(a.rayleigh_scattering[c]) * fr;
    if (mie) tau += (scattering_only ? double(a.mie_scattering) : double(a.mie_extinction)) * fm;
    if (!scattering_only && rayleigh && mie) tau += double(a.ozone_absorption[c]) * double(a.ozone_half_width);
    return tau;
}
}  // namespace

TEST_CASE_TEMPLATE("atmosphere_sky_radiance: single scattering up the column in closed form; transmittance along a segment", T, float, double) {
    // Sun and view at the zenith, no multiple scattering: every point of the column sends
    // P(1) sigma_s(z) of the sun's light and it crosses the whole column once, so
    // L = e^(-tau_ext) (tau_R P_R(1) + tau_M P_CS(1)) exactly (also the path tracer's test).
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    const atmosphere_multiple_scattering_table<T> none{};
    const glm::vec<3, T> up(T(0), T(1), T(0));
    const glm::vec<3, T> L = atmosphere_sky_radiance(a, none, T(0), up, up, 64, 64);
    for (int c = 0; c < 3; ++c) {
        const double expected = std::exp(-vertical_tau(a, c, false, true, true)) *
                                (vertical_tau(a, c, true, true, false) * double(phase_rayleigh(T(1))) +
                                 vertical_tau(a, c, true, false, true) * double(phase_cornette_shanks(T(1), a.mie_g)));
        INFO("channel " << c);
        CHECK(cm_test::rel_err(double(L[c]), expected) < 2e-3);
    }
    // The segment's transmittance is e^-(optical depth) of the same stretch.
    const T mu = T(0.2);
    const glm::vec<3, T> view(std::sqrt(T(1) - mu * mu), mu, T(0));
    const atmosphere_segment<T> seg = atmosphere_inscatter(a, none, T(500), view, up, T(30000), 64, 16);
    const glm::vec<3, T> tau = atmosphere_optical_depth(a, T(500), mu, T(30000), 4096);
    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(seg.transmittance[c]), std::exp(-double(tau[c]))) < 1e-3);
    // Nothing at distance 0; more light the farther the point; NaN in, NaN out.
    const atmosphere_segment<T> zero = atmosphere_inscatter(a, none, T(500), view, up, T(0), 16, 16);
    CHECK(zero.transmittance.x == T(1));
    CHECK(zero.radiance.z == T(0));
    CHECK(atmosphere_inscatter(a, none, T(500), view, up, T(1e4), 16, 16).radiance.z <
          atmosphere_inscatter(a, none, T(500), view, up, T(1e5), 16, 16).radiance.z);
    if (cm_test::ieee_build)  // -ffast-math assumes no NaN
        CHECK(std::isnan(atmosphere_inscatter(a, none, T(500), view, up, std::numeric_limits<T>::quiet_NaN(), 4, 4).radiance.x));
}

TEST_CASE("atmosphere_sky_radiance in thin air: the step integral keeps its digits (float)") {
    // Every coefficient a billionth of Earth's: each step's optical depth is 1e-13 to 1e-10,
    // where the textbook (1 - e^(-x)) / x is 0 in float (core.hpp). Single scattering up the
    // column, as above: e^(-tau) (tau_R P_R(1) + tau_M P_CS(1)).
    atmosphere_parameters<float> a = earth_atmosphere<float>();
    a.rayleigh_scattering *= 1e-9f;
    a.mie_scattering *= 1e-9f;
    a.mie_extinction *= 1e-9f;
    a.ozone_absorption *= 1e-9f;
    const atmosphere_multiple_scattering_table<float> none{};
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 L = atmosphere_sky_radiance(a, none, 0.0f, up, up, 64, 64);
    for (int c = 0; c < 3; ++c) {
        const double expected = std::exp(-vertical_tau(a, c, false, true, true)) *
                                (vertical_tau(a, c, true, true, false) * double(phase_rayleigh(1.0f)) +
                                 vertical_tau(a, c, true, false, true) * double(phase_cornette_shanks(1.0f, a.mie_g)));
        INFO("channel " << c);
        CHECK(cm_test::rel_err(double(L[c]), expected) < 2e-3);
    }
}

TEST_CASE("atmosphere_multiple_scattering: none without scattering, the LUT's texels, and more than single scattering adds") {
    atmosphere_parameters<float> dark = earth_atmosphere<float>();
    dark.rayleigh_scattering = glm::vec3(0.0f);
    dark.mie_scattering = 0.0f;
    dark.ground_albedo = 0.0f;
    CHECK(atmosphere_multiple_scattering(dark, 1000.0f, 0.5f, 16, 8, 8).z == 0.0f);
    const auto a = earth_atmosphere<float>();
    const std::vector<glm::vec3> lut = atmosphere_multiple_scattering_lut(a, 8, 8, 16, 8, 8);
    float largest = 0.0f;
    for (const glm::vec3& texel : lut) largest = std::max(largest, texel.y);
    const glm::vec2 size(8.0f);
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const glm::vec2 uv((float(i) + 0.5f) / 8.0f, (float(j) + 0.5f) / 8.0f);
            const glm::vec2 am = atmosphere_multiple_scattering_lut_altitude_mu(a, uv, size);
            const glm::vec2 back = atmosphere_multiple_scattering_lut_uv(a, am.x, am.y, size);
            CHECK(cm_test::rel_err(back.x, uv.x) < 1e-5);
            CHECK(cm_test::rel_err(back.y, uv.y) < 1e-5);
            // The lookup at a texel's centre is the texel: to 1e-4 relative, or for texels in
            // the Earth's shadow, thousands of times below their neighbours, to 1e-4 of a
            // thousandth of the LUT's largest (-ffast-math moves the centre by an ulp, which
            // weighs in a neighbour by that much).
            const glm::vec3 at = atmosphere_multiple_scattering_from_lut(a, lut, 8, 8, am.x, am.y);
            const float texel = lut[std::size_t(j * 8 + i)].y;
            CHECK(std::fabs(at.y - texel) <= 1e-4f * std::max(texel, 1e-3f * largest));
        }
    // Sun above the horizon: positive, bluer than red (Rayleigh), less at the top of the air.
    const glm::vec3 ground = atmosphere_multiple_scattering(a, 0.0f, 0.5f, 64, 20, 32);
    const glm::vec3 high = atmosphere_multiple_scattering(a, 50000.0f, 0.5f, 64, 20, 32);
    CHECK(ground.z > ground.x);
    CHECK(ground.x > 0.0f);
    CHECK(high.z < ground.z);
    // The sun far below the horizon lights nothing.
    CHECK(atmosphere_multiple_scattering(a, 0.0f, -1.0f, 16, 8, 8).y == 0.0f);
}

TEST_CASE("atmosphere_ground_irradiance: the sky's cosine-weighted radiance over the upper hemisphere") {
    const auto a = earth_atmosphere<float>();
    const std::vector<glm::vec3> lut = atmosphere_multiple_scattering_lut(a, 16, 16, 16, 10, 16);
    const atmosphere_multiple_scattering_table<float> ms{&lut, 16, 16};
    // Against an independent quadrature: 48 azimuths x 48 cosines (midpoint), double sums.
    for (const double elevation : {90.0, 10.0, 1.0}) {
        const double e = elevation * 3.14159265358979323846 / 180.0;
        const glm::vec3 sun(float(std::cos(e)), float(std::sin(e)), 0.0f);
        glm::dvec3 want(0.0);
        const int na = 48, nc = 48;
        for (int i = 0; i < na; ++i)
            for (int j = 0; j < nc; ++j) {
                const double c = (j + 0.5) / nc, sn = std::sqrt(1.0 - c * c), phi = 2.0 * 3.14159265358979323846 * (i + 0.5) / na;
                const glm::vec3 d(float(sn * std::cos(phi)), float(c), float(sn * std::sin(phi)));
                want += glm::dvec3(atmosphere_sky_radiance(a, ms, 0.0f, d, sun)) * c;
            }
        want *= 2.0 * 3.14159265358979323846 / (na * nc);
        const glm::vec3 got = atmosphere_ground_irradiance(a, ms, sun.y);
        for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(got[c]), want[c]) < 0.01);
    }
    // No scattering, no sky; the sun far below lights no sky.
    atmosphere_parameters<float> dark = a;
    dark.rayleigh_scattering = glm::vec3(0.0f);
    dark.mie_scattering = 0.0f;
    CHECK(atmosphere_ground_irradiance(dark, atmosphere_multiple_scattering_table<float>{}, 0.5f).z == 0.0f);
    CHECK(atmosphere_ground_irradiance(a, ms, -1.0f).z == 0.0f);
    if (cm_test::ieee_build) CHECK(std::isnan(atmosphere_ground_irradiance(a, ms, std::numeric_limits<float>::quiet_NaN()).x));
}

TEST_CASE("atmosphere_ground_irradiance_lut: the sky-lit ground below the horizon") {
    const auto a = earth_atmosphere<float>();
    const std::vector<glm::vec3> lut = atmosphere_multiple_scattering_lut(a, 16, 16, 16, 10, 16);
    const atmosphere_multiple_scattering_table<float> sun_only{&lut, 16, 16};
    const std::vector<glm::vec3> E = atmosphere_ground_irradiance_lut(a, sun_only, 9, 32);
    REQUIRE(E.size() == 9);
    const atmosphere_multiple_scattering_table<float> sky_lit{&lut, 16, 16, nullptr, &E};
    // The values sit at the sun cosines of the LUT's column spacing: u = 0.5 + 0.5 sign sqrt|mu_s|
    // at i / 8, so mu_s = -1, -0.5625, -0.25, -0.0625, 0, 0.0625, 0.25, 0.5625, 1.
    const float nodes[9] = {-1.0f, -0.5625f, -0.25f, -0.0625f, 0.0f, 0.0625f, 0.25f, 0.5625f, 1.0f};
    for (int i = 0; i < 9; ++i) {
        const glm::vec3 want = atmosphere_ground_irradiance(a, sun_only, nodes[i], 32);
        for (int c = 0; c < 3; ++c) CHECK(E[static_cast<std::size_t>(i)][c] == doctest::Approx(want[c]).epsilon(2e-4));  // the node's mu_s, rounded in float
    }
    CHECK(E[0].z == 0.0f);  // the sun at the nadir lights no sky
    CHECK(E[8].z > E[6].z);
    // Looking straight down from the ground: no air between, so the radiance is the Lambertian
    // ground's, albedo / pi (T_sun mu_s + E_sky(mu_s)) at a node, and without the values the
    // sun's term alone.
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    for (const int i : {5, 6, 7}) {
        const float mu_s = nodes[i];
        const glm::vec3 sun(std::sqrt(1.0f - mu_s * mu_s), mu_s, 0.0f);
        const glm::vec3 direct = atmosphere_transmittance(a, 0.0f, mu_s) * mu_s;
        const glm::vec3 with_sky = atmosphere_sky_radiance(a, sky_lit, 0.0f, down, sun);
        const glm::vec3 without = atmosphere_sky_radiance(a, sun_only, 0.0f, down, sun);
        for (int c = 0; c < 3; ++c) {
            CHECK(with_sky[c] == doctest::Approx(a.ground_albedo / 3.14159265f * (direct[c] + E[static_cast<std::size_t>(i)][c])).epsilon(1e-4));
            CHECK(without[c] == doctest::Approx(a.ground_albedo / 3.14159265f * direct[c]).epsilon(1e-4));
        }
    }
    // Between two values the lookup is linear in u: halfway between the nodes 0.0625 and 0.25
    // (u = 0.5 + 0.5 * 0.375) it reads their mean.
    {
        const float mu_s = 0.375f * 0.375f;
        const glm::vec3 sun(std::sqrt(1.0f - mu_s * mu_s), mu_s, 0.0f);
        const glm::vec3 ground = (atmosphere_sky_radiance(a, sky_lit, 0.0f, down, sun) -
                                  atmosphere_sky_radiance(a, sun_only, 0.0f, down, sun)) * (3.14159265f / a.ground_albedo);
        for (int c = 0; c < 3; ++c) CHECK(ground[c] == doctest::Approx(0.5f * (E[5][c] + E[6][c])).epsilon(1e-4));
    }
    // Views that reach the sky, not the ground, are unchanged.
    const glm::vec3 up = glm::normalize(glm::vec3(0.3f, 0.2f, 0.1f)), sun(0.8f, 0.6f, 0.0f);
    CHECK(atmosphere_sky_radiance(a, sky_lit, 0.0f, up, sun) == atmosphere_sky_radiance(a, sun_only, 0.0f, up, sun));
    // The sun below the horizon: the sky alone lights the ground.
    {
        const glm::vec3 set(0.999f, -0.0447f, 0.0f);
        CHECK(atmosphere_sky_radiance(a, sun_only, 0.0f, down, glm::normalize(set)).z == 0.0f);
        CHECK(atmosphere_sky_radiance(a, sky_lit, 0.0f, down, glm::normalize(set)).z > 0.0f);
    }
    // Without multiple scattering the sky still has its single scattering: the values are its
    // irradiance (less than with the LUT). Sizes below 2 give 2.
    const std::vector<glm::vec3> single = atmosphere_ground_irradiance_lut(a, atmosphere_multiple_scattering_table<float>{}, 9, 32);
    REQUIRE(single.size() == 9);
    CHECK(single[6].z > 0.0f);
    CHECK(single[6].z < E[6].z);
    CHECK(single[6].z == doctest::Approx(atmosphere_ground_irradiance(a, atmosphere_multiple_scattering_table<float>{}, nodes[6], 32).z).epsilon(2e-4));
    CHECK(atmosphere_ground_irradiance_lut(a, sun_only, 0, 4).size() == 2);
    // The lookup: clamped at the ends; a NaN sun cosine reads a defined column (floor_to_int,
    // never an undefined conversion) with a NaN weight: NaN out.
    CHECK(detail::atmosphere_ground_irradiance_at(a, E, -2.0f) == E[0]);
    CHECK(detail::atmosphere_ground_irradiance_at(a, E, 2.0f) == E[8]);
    CHECK(detail::atmosphere_ground_irradiance_at(a, std::vector<glm::vec3>{glm::vec3(0.5f)}, 0.3f) == glm::vec3(0.5f));
    CHECK(detail::atmosphere_ground_irradiance_at(a, std::vector<glm::vec3>{}, 0.3f) == glm::vec3(0.0f));
    if (cm_test::ieee_build) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        CHECK(std::isnan(detail::atmosphere_ground_irradiance_at(a, E, nan).z));
        CHECK(std::isnan(atmosphere_sky_radiance(a, sky_lit, 0.0f, down, glm::vec3(nan, nan, nan)).x));
    }
}

TEST_CASE_TEMPLATE("atmosphere_multiple_scattering_source: Rayleigh's phase over a field symmetric about the vertical", T, float, double) {
    const atmosphere_parameters<T> a = earth_atmosphere<T>();
    const glm::vec<3, T> psi(T(0.02), T(0.03), T(0.05));
    for (const T h : {T(0), T(1500), T(20000)}) {
        const glm::vec<3, T> sigma_s = atmosphere_scattering_coefficient(a, h);
        const glm::vec<3, T> rayleigh = a.rayleigh_scattering * std::exp(-h / a.rayleigh_scale_height);
        for (const T mu : {T(-1), T(-0.3), T(0), T(0.5), T(1)}) {
            // An isotropic field (moment psi / 3): sigma_s psi, whatever the direction.
            const glm::vec<3, T> iso = atmosphere_multiple_scattering_source(a, h, psi, psi / T(3), mu);
            for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(iso[c]), double(sigma_s[c] * psi[c])) < 1e-5);
        }
        // A field all along the horizon (moment 0): Rayleigh's phase averaged over the horizon's
        // directions is 3/(16 pi) (1 + cos^2): a horizontal view sees 4 pi 3/(16 pi) (1 + 1/2) = 9/8
        // of isotropic, a vertical one 4 pi 3/(16 pi) = 3/4. The aerosols stay isotropic.
        const glm::vec<3, T> flat_h = atmosphere_multiple_scattering_source(a, h, psi, glm::vec<3, T>(T(0)), T(0));
        const glm::vec<3, T> flat_v = atmosphere_multiple_scattering_source(a, h, psi, glm::vec<3, T>(T(0)), T(1));
        // A field all from straight up and down (moment psi): a vertical view sees 4 pi 3/(16 pi) 2 = 3/2.
        const glm::vec<3, T> column = atmosphere_multiple_scattering_source(a, h, psi, psi, T(-1));
        for (int c = 0; c < 3; ++c) {
            const double mie = double(sigma_s[c] - rayleigh[c]) * double(psi[c]);
            CHECK(cm_test::rel_err(double(flat_h[c]), 1.125 * double(rayleigh[c] * psi[c]) + mie) < 1e-5);
            CHECK(cm_test::rel_err(double(flat_v[c]), 0.75 * double(rayleigh[c] * psi[c]) + mie) < 1e-5);
            CHECK(cm_test::rel_err(double(column[c]), 1.5 * double(rayleigh[c] * psi[c]) + mie) < 1e-5);
        }
    }
}

TEST_CASE("atmosphere_multiple_scattering_refined_lut: Hillaire's with no pass, converged in three, brighter where his series falls short") {
    const auto a = earth_atmosphere<float>();
    // No pass: Hillaire's LUT, texel for texel, and an isotropic field's moment.
    const std::vector<glm::vec3> hillaire = atmosphere_multiple_scattering_lut(a, 8, 8, 16, 8, 8);
    std::vector<glm::vec3> none_moments;
    const std::vector<glm::vec3> none = atmosphere_multiple_scattering_refined_lut(a, 8, 8, 0, 16, 8, 8, &none_moments);
    REQUIRE(none.size() == hillaire.size());
    REQUIRE(none_moments.size() == hillaire.size());
    for (std::size_t k = 0; k < none.size(); ++k) {
        CHECK(none[k] == hillaire[k]);
        CHECK(none_moments[k] == hillaire[k] / 3.0f);
    }
    // No scattering and a black ground, no multiple scattering.
    atmosphere_parameters<float> dark = a;
    dark.rayleigh_scattering = glm::vec3(0.0f);
    dark.mie_scattering = 0.0f;
    dark.ground_albedo = 0.0f;
    for (const glm::vec3& t : atmosphere_multiple_scattering_refined_lut(dark, 4, 4, 2, 8, 4, 4)) CHECK(t.z == 0.0f);
    // The passes converge: the third and the fifth agree within 0.5% wherever the sun is up.
    std::vector<glm::vec3> moments;
    const std::vector<glm::vec3> three = atmosphere_multiple_scattering_refined_lut(a, 16, 8, 3, 32, 12, 16, &moments);
    const std::vector<glm::vec3> five = atmosphere_multiple_scattering_refined_lut(a, 16, 8, 5, 32, 12, 16);
    const std::vector<glm::vec3> zero = atmosphere_multiple_scattering_refined_lut(a, 16, 8, 0, 32, 12, 16);
    for (int j = 0; j < 8; ++j)
        for (int i = 8; i < 16; ++i) {  // columns with the sun above the horizon
            const std::size_t k = std::size_t(j * 16 + i);
            for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(three[k][c]), double(five[k][c])) < 0.005);
        }
    // At the ground with the sun 10 degrees up, blue: Hillaire's series (the point's own
    // transfer for all the air around) falls short of the gathered orders, which see the
    // brighter air above.
    const float mu_s = float(std::sin(10.0 * 3.14159265358979323846 / 180.0));
    const glm::vec3 refined = atmosphere_multiple_scattering_from_lut(a, three, 16, 8, 0.0f, mu_s);
    const glm::vec3 series = atmosphere_multiple_scattering_from_lut(a, zero, 16, 8, 0.0f, mu_s);
    MESSAGE("ground, sun at 10 degrees, blue: Hillaire " << series.z << ", refined " << refined.z);
    CHECK(refined.z > 1.05f * series.z);
    // Near the ground the field comes mostly from near the horizon (long, bright paths): its
    // vertical moment is below an isotropic field's third; high up, with the air below
    // brighter than the black space above, it is not far from it.
    const glm::vec3 moment_ground = atmosphere_multiple_scattering_from_lut(a, moments, 16, 8, 0.0f, mu_s);
    MESSAGE("ground, sun at 10 degrees, blue: vertical moment / mean " << moment_ground.z / refined.z);
    CHECK(moment_ground.z < 0.3f * refined.z);
    CHECK(moment_ground.z > 0.1f * refined.z);
}

TEST_CASE("atmosphere_stacked_table: each part's block at the rows the GLSL reads (part * height), the ground's zero") {
    const auto a = earth_atmosphere<float>();
    const atmosphere_sky_luts<float> luts = atmosphere_make_sky_luts(a, 5, 3, 2, 16, 6, 8);
    const std::vector<glm::vec3> stacked = atmosphere_stacked_table(luts);
    REQUIRE(atmosphere_stacked_table_parts == 4 + atmosphere_aerosol_field_nodes);
    REQUIRE(stacked.size() == std::size_t(5 * 3 * atmosphere_stacked_table_parts));
    // Texel (x, y) of part p where atmosphere.glsl's example reads it: texelFetch(u_table,
    // ivec2(x, y + p * height)) of a width-wide image, row-major.
    const auto at = [&](int part, int x, int y) { return stacked[std::size_t((y + part * 3) * 5 + x)]; };
    REQUIRE(luts.texels.size() == 15);
    REQUIRE(luts.vertical_moments.size() == 15);
    REQUIRE(luts.sun_azimuth_moments.size() == 15);
    REQUIRE(luts.aerosol_field.size() == std::size_t(15 * atmosphere_aerosol_field_nodes));
    // Every part compared holds light somewhere (a part mapped to the wrong rows would differ).
    std::vector<int> lit(std::size_t(atmosphere_stacked_table_parts), 0);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            const std::size_t i = std::size_t(y * 5 + x);
            CHECK(at(0, x, y) == luts.texels[i]);              // CM_ATMOSPHERE_TABLE_PSI
            CHECK(at(1, x, y) == luts.vertical_moments[i]);    // _VERTICAL
            CHECK(at(2, x, y) == luts.sun_azimuth_moments[i]); // _ALONG
            CHECK(at(3, x, y) == glm::vec3(0.0f));             // _GROUND: a texture of its own
            for (int j = 0; j < atmosphere_aerosol_field_nodes; ++j)
                CHECK(at(4 + j, x, y) == luts.aerosol_field[std::size_t(j) * 15 + i]);  // _AEROSOL + j
            for (int p = 0; p < atmosphere_stacked_table_parts; ++p) lit[std::size_t(p)] += at(p, x, y).z > 0.0f ? 1 : 0;
        }
    for (int p = 0; p < atmosphere_stacked_table_parts; ++p)
        if (p != 3) CHECK_MESSAGE(lit[std::size_t(p)] > 0, "part " << p << " is zero everywhere");
}

TEST_CASE("atmosphere_make_sky_luts: the aerosol field keeps the field's light, turns it forward, and is read only where the sun is up") {
    const auto a = earth_atmosphere<float>();
    const atmosphere_sky_luts<float> luts = atmosphere_make_sky_luts(a, 16, 8, 3, 64, 12, 16);
    const std::size_t texels = 16 * 8;
    constexpr int J = atmosphere_aerosol_field_nodes;
    REQUIRE(luts.texels.size() == texels);
    REQUIRE(luts.vertical_moments.size() == texels);
    REQUIRE(luts.sun_azimuth_moments.size() == texels);
    REQUIRE(luts.aerosol_field.size() == texels * J);
    // The nodes: view zenith cosines x|x| over x evenly spaced in [-1, 1], the horizon in the middle.
    CHECK(detail::atmosphere_aerosol_node<float>(0) == -1.0f);
    CHECK(detail::atmosphere_aerosol_node<float>(J / 2) == 0.0f);
    CHECK(detail::atmosphere_aerosol_node<float>(J - 1) == 1.0f);
    // The weights: Cornette-Shanks averaged over azimuth, normalised to a mean of 1 over the
    // rays per node (an isotropic field is carried as it is).
    const std::vector<float> w = detail::atmosphere_aerosol_weights<float>(64, a.mie_g);
    REQUIRE(w.size() == std::size_t(64 * J));
    for (int j = 0; j < J; ++j) {
        double mean = 0.0;
        for (int k = 0; k < 64; ++k) mean += double(w[std::size_t(k * J + j)]) / 64.0;
        CHECK(std::fabs(mean - 1.0) < 1e-5);
    }
    // A view up weighs the ray nearest the zenith (k = 0) far above the ray nearest the nadir.
    CHECK(w[std::size_t(0 * J + J - 1)] > 20.0f * w[std::size_t(63 * J + J - 1)]);
    // The field's light: the phase integrates to 1, so the turned field averaged over all views
    // (trapezoid over the nodes' cosines) is the field's mean, within the 17 nodes' quadrature.
    for (std::size_t t = 0; t < texels; ++t) {
        glm::dvec3 mean(0.0);
        for (int j = 0; j + 1 < J; ++j) {
            const double d = double(detail::atmosphere_aerosol_node<float>(j + 1) - detail::atmosphere_aerosol_node<float>(j));
            mean += 0.25 * d * (glm::dvec3(luts.aerosol_field[std::size_t(j) * texels + t]) +
                                glm::dvec3(luts.aerosol_field[std::size_t(j + 1) * texels + t]));
        }
        for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(mean[c], double(luts.texels[t][c])) < 0.03);
        // The horizontal moment towards the sun's azimuth: between none and all of the light
        // that is not vertical.
        for (int c = 0; c < 3; ++c) {
            CHECK(luts.sun_azimuth_moments[t][c] >= 0.0f);
            CHECK(luts.sun_azimuth_moments[t][c] <= (luts.texels[t][c] - luts.vertical_moments[t][c]) * 1.0001f);
        }
    }
    // At the ground with the sun 10 degrees up the field is brightest along the horizon, and
    // the aerosols' forward peak turns that into views along it: the horizon node above the
    // field's mean, the zenith node below.
    const float mu_s = float(std::sin(10.0 * 3.14159265358979323846 / 180.0));
    const glm::vec2 uv = atmosphere_multiple_scattering_lut_uv(a, 0.0f, mu_s, glm::vec2(16.0f, 8.0f));
    const int col = std::min(15, int(uv.x * 16.0f));  // row 0: the ground
    const std::size_t t = std::size_t(col);
    MESSAGE("ground, sun at 10 degrees, blue: field " << luts.texels[t].z << ", turned into the horizon "
                                                      << luts.aerosol_field[std::size_t(J / 2) * texels + t].z << ", the zenith "
                                                      << luts.aerosol_field[std::size_t(J - 1) * texels + t].z);
    CHECK(luts.aerosol_field[std::size_t(J / 2) * texels + t].z > 1.05f * luts.texels[t].z);
    CHECK(luts.aerosol_field[std::size_t(J - 1) * texels + t].z < luts.texels[t].z);
    // Read only where the sun is above a point's horizon: with the sun 30 degrees below the
    // horizon (below every point of the air along these rays) a field of zeros changes nothing,
    // with the sun 10 degrees up it darkens the sky.
    atmosphere_sky_luts<float> zeroed = luts;
    std::fill(zeroed.aerosol_field.begin(), zeroed.aerosol_field.end(), glm::vec3(0.0f));
    const atmosphere_multiple_scattering_table<float> with = luts.table(), without = zeroed.table();
    const glm::vec3 view = glm::normalize(glm::vec3(0.0f, 0.05f, 1.0f));
    const float down = float(std::sin(-30.0 * 3.14159265358979323846 / 180.0));
    const glm::vec3 set_sun(std::sqrt(1.0f - down * down), down, 0.0f), up_sun(std::sqrt(1.0f - mu_s * mu_s), mu_s, 0.0f);
    CHECK(atmosphere_sky_radiance(a, with, 0.0f, view, set_sun) == atmosphere_sky_radiance(a, without, 0.0f, view, set_sun));
    CHECK(atmosphere_sky_radiance(a, without, 0.0f, view, up_sun).z < 0.99f * atmosphere_sky_radiance(a, with, 0.0f, view, up_sun).z);
    // A black sky stays black; a NaN direction gives NaN, not a value from a clamped lookup.
    atmosphere_parameters<float> dark = a;
    dark.rayleigh_scattering = glm::vec3(0.0f);
    dark.mie_scattering = 0.0f;
    dark.ground_albedo = 0.0f;
    const atmosphere_sky_luts<float> black = atmosphere_make_sky_luts(dark, 4, 4, 2, 16, 4, 4);
    for (const glm::vec3& v : black.aerosol_field) CHECK(v == glm::vec3(0.0f));
    CHECK(atmosphere_sky_radiance(dark, black.table(), 0.0f, view, up_sun) == glm::vec3(0.0f));
    if (cm_test::ieee_build) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        CHECK(std::isnan(atmosphere_sky_radiance(a, with, 0.0f, glm::vec3(nan, nan, nan), up_sun).x));
    }
}

TEST_CASE("global illuminance at sea level for a zenith sun: 110-130 klux (REFERENCES.md)") {
    // Direct normal (the sun's transmittance) plus the sky's irradiance on a horizontal plane
    // (the radiance's cosine-weighted integral over the upper hemisphere: 64 azimuths x 32
    // cosines, midpoint), for 128 klux above the air in every channel; luminance by Rec. 709.
    const auto a = earth_atmosphere<float>();
    std::vector<glm::vec3> moments;
    const std::vector<glm::vec3> lut = atmosphere_multiple_scattering_refined_lut(a, 32, 32, 3, 64, 20, 32, &moments);
    const atmosphere_multiple_scattering_table<float> ms{&lut, 32, 32, &moments};
    const glm::vec3 sun(0.0f, 1.0f, 0.0f);
    glm::dvec3 sky(0.0);
    const int na = 64, nc = 32;
    for (int i = 0; i < na; ++i)
        for (int j = 0; j < nc; ++j) {
            const double c = (j + 0.5) / nc, s = std::sqrt(1.0 - c * c), phi = 2.0 * 3.14159265358979323846 * (i + 0.5) / na;
            const glm::vec3 d(float(s * std::cos(phi)), float(c), float(s * std::sin(phi)));
            sky += glm::dvec3(atmosphere_sky_radiance(a, ms, 0.0f, d, sun)) * c;
        }
    sky *= 2.0 * 3.14159265358979323846 / (na * nc);
    const glm::dvec3 direct(atmosphere_sun_illuminance(a, 0.0f, 1.0f, glm::vec3(1.0f)));
    const auto lum = [](const glm::dvec3& v) { return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z; };
    const double global = 128.0 * (lum(direct) + lum(sky));
    MESSAGE("sea level, sun at zenith: direct " << 128.0 * lum(direct) << " klux, sky " << 128.0 * lum(sky) << " klux, global "
                                                << global << " klux");
    CHECK(global > 110.0);
    CHECK(global < 130.0);
    CHECK(128.0 * lum(sky) > 5.0);  // the sky's share: a few klux (diffuse fraction about 6%)
    // The zenith's luminance as the sun sets (docs/atmosphere.md quotes these): it falls with
    // the sun, and stays lit just after sunset (sun at -2 degrees) by the air above the shadow.
    double last = 1e30;
    for (const double elevation : {30.0, 10.0, 2.0, -2.0}) {
        const double e = elevation * 3.14159265358979323846 / 180.0;
        const glm::vec3 s(float(std::cos(e)), float(std::sin(e)), 0.0f);
        const double zenith = 128000.0 * lum(glm::dvec3(atmosphere_sky_radiance(a, ms, 0.0f, glm::vec3(0.0f, 1.0f, 0.0f), s)));
        MESSAGE("zenith luminance, sun at " << elevation << " degrees: " << zenith << " cd/m^2");
        CHECK(zenith < last);
        CHECK(zenith > 10.0);
        last = zenith;
    }
}

TEST_CASE("the renderer's haze against atmosphere_inscatter: its transmittance agrees, its one-colour in-scattering does not") {
    // density.hpp's air_optical_depth (the example renderer's aerial perspective) against the
    // atmosphere's transmittance along the same rays, and the one-colour haze (the horizon's
    // mean radiance times 1 - T, as the renderer's physical sky draws it) against the
    // atmosphere's in-scattering. docs/atmosphere.md quotes the ratios.
    const auto a = earth_atmosphere<float>();
    const std::vector<glm::vec3> lut = atmosphere_multiple_scattering_lut(a, 32, 32);
    const atmosphere_multiple_scattering_table<float> ms{&lut, 32, 32};
    const float deg = 3.14159265f / 180.0f;
    const auto lum = [](const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; };
    for (const float sun_elevation : {30.0f, 2.0f, -2.0f}) {
        const glm::vec3 sun(std::cos(sun_elevation * deg), std::sin(sun_elevation * deg), 0.0f);
        glm::vec3 horizon(0.0f);
        for (int i = 0; i < 8; ++i) {
            const float az = float(i) * 45.0f * deg;
            horizon += atmosphere_sky_radiance(a, ms, 2.0f, glm::vec3(std::cos(az) * std::cos(2.0f * deg), std::sin(2.0f * deg),
                                                                      std::sin(az) * std::cos(2.0f * deg)), sun);
        }
        horizon /= 8.0f;
        float lo = 1e30f, hi = 0.0f;
        for (const float el : {2.0f, 10.0f})
            for (const float az : {0.0f, 180.0f})
                for (const float d : {10000.0f, 30000.0f, 60000.0f}) {
                    const glm::vec3 v(std::cos(el * deg) * std::cos(az * deg), std::sin(el * deg), std::cos(el * deg) * std::sin(az * deg));
                    const atmosphere_segment<float> seg = atmosphere_inscatter(a, ms, 2.0f, v, sun, d);
                    const glm::vec3 tau = air_optical_depth(2.0f, v.y, d);
                    const glm::vec3 T(std::exp(-tau.x), std::exp(-tau.y), std::exp(-tau.z));
                    for (int c = 0; c < 3; ++c) CHECK(cm_test::rel_err(double(T[c]), double(seg.transmittance[c])) < 0.03);
                    const float ratio = lum(horizon * (glm::vec3(1.0f) - T)) / lum(seg.radiance);
                    lo = std::min(lo, ratio);
                    hi = std::max(hi, ratio);
                }
        MESSAGE("sun at " << sun_elevation << " degrees: the one-colour haze's in-scattering is " << lo << " to " << hi
                          << " times the atmosphere's (elevations 2 and 10, towards and away from the sun, 10-60 km)");
        CHECK(hi / lo > 1.5f);  // direction matters: one colour cannot be right both ways
    }
}
