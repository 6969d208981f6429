// Tests of atmosphere.hpp: Earth's parameters as published, the extinction profile, the
// optical depth of a vertical ray against its closed form, the transmittance against an
// independent long double quadrature at every altitude and zenith angle (the 1e-3 target),
// the LUT mapping's round trip and the LUT's lookup, and EV100's closed forms.
#include <cloudmath/atmosphere.hpp>

#include <cmath>
#include <initializer_list>
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
    for (int c = 0; c < 3; ++c) CHECK(double(ground[c]) == doctest::Approx(double(a.rayleigh_scattering[c]) + 4.40e-6).epsilon(1e-6));
    CHECK(atmosphere_extinction(a, T(-500)) == ground);  // below 0 taken as 0
    // At the ozone peak the tent adds its full absorption.
    const glm::vec<3, T> peak = atmosphere_extinction(a, T(25e3));
    CHECK(double(peak.y) == doctest::Approx(13.558e-6 * std::exp(-25e3 / 8000.0) + 4.40e-6 * std::exp(-25e3 / 1200.0) + 1.881e-6).epsilon(1e-5));
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
            CHECK(double(tau[c]) == doctest::Approx(double(want)).epsilon(1e-4));
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
    CHECK(double(atmosphere_transmittance_lut_uv(a, T(0), T(1), size).y) == doctest::Approx(0.5 / 64.0));
    CHECK(double(atmosphere_transmittance_lut_uv(a, T(60000), T(1), size).y) == doctest::Approx(1.0 - 0.5 / 64.0));
    CHECK(double(atmosphere_transmittance_lut_uv(a, T(3000), T(1), size).x) == doctest::Approx(0.5 / 256.0));
    const T r = a.bottom_radius + T(3000);
    const T horizon = -std::sqrt(T(1) - (a.bottom_radius / r) * (a.bottom_radius / r));
    CHECK(double(atmosphere_transmittance_lut_uv(a, T(3000), horizon, size).x) == doctest::Approx(1.0 - 0.5 / 256.0).epsilon(1e-3));
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
    CHECK(double(ev100_from_camera(T(16), T(0.01), T(100))) == doctest::Approx(std::log2(25600.0)).epsilon(1e-6));
    CHECK(double(ev100_from_camera(T(1), T(1), T(100))) == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(double(ev100_from_camera(T(1), T(1), T(200))) == doctest::Approx(-1.0).epsilon(1e-6));  // twice the ISO: one stop less
    CHECK(double(ev100_from_luminance(T(0.125))) == doctest::Approx(0.0).epsilon(1e-6));            // K = 12.5
    CHECK(double(exposure_from_ev100(T(0))) == doctest::Approx(1.0 / 1.2).epsilon(1e-6));
    CHECK(double(exposure_from_ev100(T(10))) == doctest::Approx(1.0 / (1.2 * 1024.0)).epsilon(1e-6));
    // Metering a luminance and exposing by it maps that luminance to the same value for any L:
    // L * exposure = L / (1.2 * 8 L) = 1 / 9.6.
    for (T L : {T(1e-3), T(1), T(5000)})
        CHECK(double(L * exposure_from_ev100(ev100_from_luminance(L))) == doctest::Approx(1.0 / 9.6).epsilon(1e-5));
}
