// Tests of texture_lod.hpp: the footprint against the pinhole's geometry (the angle one
// pixel subtends, in long double), and the level against log2 and OpenGL's rule (level k
// where a texel of level k is as wide as the footprint), with the hard cases.
#include <cloudmath/texture_lod.hpp>

#include <cmath>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

TEST_CASE_TEMPLATE("pixel_footprint: one pixel's width at a distance", T, float, double) {
    // 60-degree vertical view over 270 rows: the centre pixel subtends 2 atan(tan30 / 270).
    const T tan_half = T(0.5773502691896258), rows = T(270);
    for (T d : {T(1), T(1000), T(35000), T(1e6)}) {
        const ld angle = 2.0L * std::atan(0.5773502691896258L / 270.0L);
        const ld chord = 2.0L * ld(d) * std::tan(angle / 2.0L);  // the pixel's width at the centre
        CHECK(cm_test::rel_err(pixel_footprint(d, tan_half, rows), chord) <= 8 * cm_test::eps<T>());
    }
    CHECK(pixel_footprint(T(0), tan_half, rows) == T(0));
    CHECK(pixel_footprint(T(-5), tan_half, rows) < T(0));
    // Twice the rows, half the footprint.
    CHECK(double(pixel_footprint(T(1000), tan_half, T(540))) == doctest::Approx(double(pixel_footprint(T(1000), tan_half, rows)) / 2.0));
}

TEST_CASE_TEMPLATE("texture_lod: log2 of footprint over texel, 0 for magnification and bad input", T, float, double) {
    const T texel = T(46.875);  // a 32^3 volume over 1500 m
    for (int k = 0; k <= 6; ++k) {
        // A footprint of 2^k texels is level k exactly.
        CHECK(double(texture_lod(texel * std::ldexp(T(1), k), texel)) == doctest::Approx(double(k)).epsilon(1e-6));
    }
    // Between levels: log2.
    CHECK(double(texture_lod(T(3) * texel, texel)) == doctest::Approx(std::log2(3.0)).epsilon(1e-6));
    // Magnification, zero, negative: level 0.
    CHECK(texture_lod(T(0.5) * texel, texel) == T(0));
    CHECK(texture_lod(texel, texel) == T(0));
    CHECK(texture_lod(T(0), texel) == T(0));
    CHECK(texture_lod(T(-100), texel) == T(0));
    if constexpr (cm_test::ieee_build) {
        CHECK(texture_lod(std::numeric_limits<T>::quiet_NaN(), texel) == T(0));
        CHECK(texture_lod(std::numeric_limits<T>::infinity(), texel) == std::numeric_limits<T>::infinity());
    }
    // The renderer's case: the detail volume 35 km away at 480 x 270 with a 60-degree view.
    const T w = pixel_footprint(T(35000), T(0.5773502691896258), T(270));
    CHECK(double(w) == doctest::Approx(149.67).epsilon(1e-3));
    CHECK(double(texture_lod(w, texel)) == doctest::Approx(std::log2(149.67 / 46.875)).epsilon(1e-3));
}
