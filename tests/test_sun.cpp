// Tests of sun.hpp: the solid angle of a cone against 2 pi (1 - cos r) in long double, and the
// sun disc's radiance: zero outside, limb-darkened inside, and integrating to the irradiance
// over the sphere (the energy test of a light source, as pbrt tests its phase functions).
#include <cloudmath/sun.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

TEST_CASE_TEMPLATE("cone_solid_angle: 2 pi (1 - cos r) without cancellation", T, float, double) {
    for (T r : {T(1e-6), T(1e-4), sun_angular_radius<T>(), T(0.1), T(1), T(1.5707963267948966), T(3.141592653589793)}) {
        const ld want = 4 * 3.14159265358979323846L * std::sin(ld(r) / 2) * std::sin(ld(r) / 2);
        CHECK(cm_test::rel_err(cone_solid_angle(r), want) <= 8 * cm_test::eps<T>());
    }
    CHECK(cone_solid_angle(T(0)) == T(0));
    // The hemisphere and the whole sphere.
    CHECK(double(cone_solid_angle(T(1.5707963267948966))) == doctest::Approx(2.0 * 3.14159265358979).epsilon(1e-6));
    CHECK(double(cone_solid_angle(T(3.141592653589793))) == doctest::Approx(4.0 * 3.14159265358979).epsilon(1e-6));
    // The real Sun: 6.80e-5 sr (its disc is 14,700 times brighter than its irradiance).
    CHECK(double(cone_solid_angle(sun_angular_radius<T>())) == doctest::Approx(6.7999e-5).epsilon(1e-3));
}

TEST_CASE_TEMPLATE("sun_disc_radiance: zero outside, limb darkening, integrates to the irradiance", T, float, double) {
    // Up to 0.91 rad, where the documented 0.06 r^2 still holds (hardening round 2, A9).
    for (T r : {sun_angular_radius<T>(), T(0.0349), T(0.3), T(0.91)})
        for (T u : {T(0), T(0.6), T(1)}) {
            CAPTURE(r);
            CAPTURE(u);
            const T E = T(2.5);
            const ld omega = ld(cone_solid_angle(r));
            const ld peak = ld(E) / (omega * (1 - ld(u) / 3));
            // Centre and limb: I0 and I0 (1 - u).
            CHECK(cm_test::rel_err(sun_disc_radiance(E, T(1), r, u), peak) <= 16 * cm_test::eps<T>());
            // Inside, at half and 0.9 of the radius. (cos_angle itself limits the limb: in float
            // it resolves the real Sun's radius in about 180 steps of 6e-8.)
            for (ld f : {0.5L, 0.9L}) {
                const T c = T(std::cos(ld(r) * f));
                const ld x = std::sin(std::acos(ld(c))) / std::sin(ld(r));  // of the rounded input
                CHECK(double(sun_disc_radiance(E, c, r, u)) ==
                      doctest::Approx(double(peak * (1 - ld(u) + ld(u) * std::sqrt(1 - x * x))))
                          .epsilon(cm_test::ieee_build ? 1e-3 : 5e-3));  // -ffast-math reassociates
            }
            // Outside the disc and behind the viewer: 0.
            CHECK(sun_disc_radiance(E, std::cos(r * T(1.01)), r, u) == T(0));
            CHECK(sun_disc_radiance(E, T(-1), r, u) == T(0));
            CHECK(sun_disc_radiance(E, T(0), r, u) == T(0));
            // Energy: the integral over the disc's solid angle in long double (midpoint in
            // theta) is the irradiance, to 0.06 r^2 plus the quadrature's error.
            const int n = 4000;
            ld sum = 0;
            for (int i = 0; i < n; ++i) {
                const ld theta = ld(r) * (i + 0.5L) / n;
                const ld x = std::sin(theta) / std::sin(ld(r));
                sum += peak * (1 - ld(u) + ld(u) * std::sqrt(std::fmax(0.0L, 1 - x * x))) * std::sin(theta);
            }
            const ld integral = 2 * 3.14159265358979323846L * sum * ld(r) / n;
            CHECK(std::fabs(integral / ld(E) - 1) <= 0.06L * ld(r) * ld(r) + 1e-4L);
            // Monotonic darkening from the centre to the limb (u > 0), flat for u = 0.
            T previous = sun_disc_radiance(E, T(1), r, u);
            for (int k = 1; k < 20; ++k) {
                const T v = sun_disc_radiance(E, std::cos(r * T(k) / T(20)), r, u);
                if (u > T(0)) CHECK(v <= previous * T(1.000001));
                else CHECK(v == doctest::Approx(double(previous)).epsilon(1e-5));
                previous = v;
            }
        }
    // Limb darkening past [0, 1] is clamped; NaN inputs give NaN or 0, never Inf.
    CHECK(sun_disc_radiance(T(1), T(1), T(0.01), T(-2)) == sun_disc_radiance(T(1), T(1), T(0.01), T(0)));
    CHECK(sun_disc_radiance(T(1), T(1), T(0.01), T(5)) == sun_disc_radiance(T(1), T(1), T(0.01), T(1)));
    if (cm_test::ieee_build) {
        CHECK(sun_disc_radiance(T(1), cm_test::make_nan<T>(), T(0.01), T(0.6)) == T(0));
        CHECK(cm_test::nan_bits(sun_disc_radiance(cm_test::make_nan<T>(), T(1), T(0.01), T(0.6))));
    }
}
