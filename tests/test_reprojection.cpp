// Tests of reprojection.hpp: the Bayer update order against the matrix written out, the
// projection as the exact inverse of the pinhole ray (in long double), the bilinear
// footprint against GL_LINEAR's definition, and the blend weight as a running mean.
#include <cloudmath/reprojection.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

TEST_CASE("bayer_index_4x4: the 4 x 4 Bayer matrix, repeating every 4 pixels") {
    // Bayer 1973 ordered-dither matrix, row y = 0 first.
    const std::uint32_t want[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
    for (std::uint32_t y = 0; y < 4; ++y)
        for (std::uint32_t x = 0; x < 4; ++x) {
            CHECK(bayer_index_4x4(x, y) == want[y][x]);
            CHECK(bayer_index_4x4(x + 4, y + 8) == want[y][x]);
            CHECK(bayer_index_4x4(x + 0xfffffff0U, y + 0x7ffffffcU) == want[y][x]);
        }
}

TEST_CASE("temporal_update_offset: 16 frames render every pixel of a block once, spread out") {
    std::set<std::uint32_t> seen;
    for (std::uint32_t f = 0; f < 16; ++f) {
        const glm::uvec2 o = temporal_update_offset(f);
        REQUIRE(o.x < 4U);
        REQUIRE(o.y < 4U);
        CHECK(bayer_index_4x4(o.x, o.y) == f);
        seen.insert(o.y * 4U + o.x);
        CHECK(temporal_update_offset(f + 16U * 12345U) == o);  // period 16, also past 2^16 frames
        // Any 4 consecutive frames visit each 2 x 2 quarter of the block once.
        std::set<std::uint32_t> quarters;
        for (std::uint32_t k = 0; k < 4; ++k) {
            const glm::uvec2 q = temporal_update_offset(f + k);
            quarters.insert((q.y / 2U) * 2U + q.x / 2U);
        }
        CHECK(quarters.size() == 4U);
        // Consecutive frames are never neighbours within the block (city-block distance >= 2):
        // the new samples of two frames do not clump.
        const glm::uvec2 n = temporal_update_offset(f + 1U);
        const auto dist = [](std::uint32_t a, std::uint32_t b) { return a > b ? a - b : b - a; };
        CHECK(dist(o.x, n.x) + dist(o.y, n.y) >= 2U);
    }
    CHECK(seen.size() == 16U);
}

// The pinhole ray through normalised screen point (u, v), as the renderer builds it.
template <class T>
glm::vec<3, T> ray_through(T u, T v, const glm::vec<3, T>& f, const glm::vec<3, T>& r, const glm::vec<3, T>& up, T tan_half,
                           T aspect) {
    return f + r * ((T(2) * u - T(1)) * aspect * tan_half) + up * ((T(2) * v - T(1)) * tan_half);
}

TEST_CASE_TEMPLATE("camera_project: inverse of the pinhole ray, depth along forward", T, float, double) {
    // A tilted orthonormal basis (yaw 30 deg, pitch 10 deg), as the renderer's camera.
    const T yaw = T(0.5235987755982988), pitch = T(0.17453292519943295);
    const glm::vec<3, T> f(std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
    const glm::vec<3, T> r = glm::normalize(glm::cross(f, glm::vec<3, T>(0, 1, 0)));
    const glm::vec<3, T> up = glm::cross(r, f);
    const T tan_half = T(0.5773502691896258), aspect = T(16) / T(9);
    for (T u : {T(0), T(0.001), T(0.25), T(0.5), T(0.999), T(1)})
        for (T v : {T(0), T(0.3), T(0.5), T(1)})
            for (T dist : {T(1), T(1000), T(35000), T(1e7)}) {
                CAPTURE(u);
                CAPTURE(v);
                CAPTURE(dist);
                const glm::vec<3, T> d = ray_through(u, v, f, r, up, tan_half, aspect);
                const glm::vec<3, T> p = d * (dist / glm::length(d));
                const glm::vec<3, T> uvz = camera_project(p, f, r, up, tan_half, aspect);
                // A few roundings of the basis and of the ray: 64 ulp of the coordinates.
                CHECK(std::fabs(double(uvz.x - u)) <= 64.0 * double(std::numeric_limits<T>::epsilon()));
                CHECK(std::fabs(double(uvz.y - v)) <= 64.0 * double(std::numeric_limits<T>::epsilon()));
                const ld want_z = ld(dist) / std::sqrt(ld(glm::dot(d, d)));  // |d . f| = 1 up to rounding
                CHECK(cm_test::rel_err(uvz.z, want_z) <= 16 * cm_test::eps<T>());
            }
    // Off screen but in front: u, v outside [0, 1], depth positive.
    const glm::vec<3, T> side = camera_project(f + r * T(5), f, r, up, tan_half, aspect);
    CHECK(side.x > T(1));
    CHECK(side.z > T(0));
    // Behind, on the camera plane and NaN: (-1, -1, z), never a mirrored point on screen.
    const glm::vec<3, T> behind = camera_project(-f * T(10) + r * T(0.1), f, r, up, tan_half, aspect);
    CHECK(behind.x == T(-1));
    CHECK(behind.y == T(-1));
    CHECK(double(behind.z) == doctest::Approx(-10.0).epsilon(1e-5));
    const glm::vec<3, T> plane = camera_project(r * T(3), f, r, up, tan_half, aspect);
    CHECK(plane.x == T(-1));
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(camera_project(glm::vec<3, T>(nan, T(0), T(1)), f, r, up, tan_half, aspect).x == T(-1));
    // The camera itself (z = 0): no division by zero.
    CHECK(camera_project(glm::vec<3, T>(0), f, r, up, tan_half, aspect).x == T(-1));
}

TEST_CASE_TEMPLATE("texel_bilinear: GL_LINEAR's footprint, exact at texel centres", T, float, double) {
    const glm::vec<2, T> size(T(320), T(180));
    // Texel centres: the texel itself with zero weight on its neighbours.
    for (int i : {0, 1, 17, 318, 319})
        for (int j : {0, 90, 179}) {
            const glm::vec<2, T> uv((T(i) + T(0.5)) / size.x, (T(j) + T(0.5)) / size.y);
            const glm::vec<4, T> fp = texel_bilinear(uv, size);
            // Either (i, 0) or (i - 1, ~1) within one rounding of uv * size.
            const T x = fp.x + fp.z, y = fp.y + fp.w;
            CHECK(std::fabs(double(x - T(i))) <= 1e3 * double(std::numeric_limits<T>::epsilon()));
            CHECK(std::fabs(double(y - T(j))) <= 1e3 * double(std::numeric_limits<T>::epsilon()));
            CHECK(fp.z >= T(0));
            CHECK(fp.z < T(1));
        }
    // Half way between texel centres 3 and 4 in x, a quarter of the way from 10 to 11 in y.
    const glm::vec<4, T> mid = texel_bilinear(glm::vec<2, T>(T(4) / size.x, T(10.75) / size.y), size);
    CHECK(mid.x == T(3));
    CHECK(double(mid.z) == doctest::Approx(0.5).epsilon(1e-5));
    CHECK(mid.y == T(10));
    CHECK(double(mid.w) == doctest::Approx(0.25).epsilon(1e-4));
    // Left of the first centre: x0 = -1 (the caller sees a missing texel), fraction still in [0, 1).
    const glm::vec<4, T> edge = texel_bilinear(glm::vec<2, T>(T(0.1) / size.x, T(0.5)), size);
    CHECK(edge.x == T(-1));
    CHECK(double(edge.z) == doctest::Approx(0.6).epsilon(1e-4));
    // Bilinear weights reproduce a linear function exactly: f(x) = 3x + 2 sampled at centres.
    for (T uvx : {T(0.01), T(0.3), T(0.77)}) {
        const glm::vec<4, T> fp = texel_bilinear(glm::vec<2, T>(uvx, T(0.5)), size);
        const T f0 = T(3) * fp.x + T(2), f1 = T(3) * (fp.x + T(1)) + T(2);
        const T got = f0 * (T(1) - fp.z) + f1 * fp.z;
        const T want = T(3) * (uvx * size.x - T(0.5)) + T(2);
        CHECK(std::fabs(double(got - want)) <= 1e-3 * double(std::fabs(want)) + 1e-9);
    }
}

// Hardening round 2, A8: at a texel centre uv = (i + 1/2) / width, uv * width - 1/2 landed
// below i in about 4% of (i, width) pairs: x0 = i - 1, fx = 1, and column 0's own centre then
// failed the caller's 0 <= x0 test.
TEST_CASE_TEMPLATE("texel_bilinear: every texel centre of every width up to 600 is (i, 0) exactly", T, float, double) {
    int wrong = 0, checked = 0;
    for (int width = 1; width <= 600; ++width)
        for (int i = 0; i < width; ++i) {
            const T u = (T(i) + T(0.5)) / T(width);
            const glm::vec<4, T> fp = texel_bilinear(glm::vec<2, T>(u, u), glm::vec<2, T>(T(width), T(width)));
            if (fp.x != T(i) || fp.z != T(0) || fp.y != T(i) || fp.w != T(0)) ++wrong;
            ++checked;
        }
    CHECK(checked == 180300);
    CHECK(wrong == 0);
    CHECK(texel_bilinear(glm::vec<2, T>(T(0.5) / T(214), T(0.5)), glm::vec<2, T>(T(214), T(1))) ==
          glm::vec<4, T>(T(0), T(0), T(0), T(0)));
    // Off the centres the footprint is GL_LINEAR's: a point a thousandth of a texel past a
    // centre keeps its fraction (the snap is within 4 ulp of uv * size only).
    const glm::vec<4, T> near_centre = texel_bilinear(glm::vec<2, T>((T(7.501)) / T(300), T(0.5)), glm::vec<2, T>(T(300), T(1)));
    CHECK(near_centre.x == T(7));
    CHECK(double(near_centre.z) == doctest::Approx(0.001).epsilon(std::is_same_v<T, float> ? 2e-3 : 1e-9));
}

TEST_CASE_TEMPLATE("temporal_blend_weight: running mean up to max_samples, then exponential", T, float, double) {
    // A running mean: blending samples x_1..x_n with weights 1 / n gives their plain mean.
    const T xs[] = {T(3), T(-1), T(7), T(2), T(5)};
    T mean = T(0), samples = T(0);
    for (T x : xs) {
        const T w = temporal_blend_weight(samples, T(8));
        mean = mean + (x - mean) * w;
        samples += T(1);
    }
    CHECK(double(mean) == doctest::Approx(3.2).epsilon(1e-6));
    CHECK(temporal_blend_weight(T(0), T(8)) == T(1));
    CHECK(temporal_blend_weight(T(3), T(8)) == T(0.25));
    // At and past the cap: 1 / max_samples.
    CHECK(temporal_blend_weight(T(7), T(8)) == T(0.125));
    CHECK(temporal_blend_weight(T(1000), T(8)) == T(0.125));
    CHECK(temporal_blend_weight(std::numeric_limits<T>::infinity(), T(8)) == T(0.125));
    // No history: negative or NaN counts, and max_samples <= 1.
    CHECK(temporal_blend_weight(T(-2), T(8)) == T(1));
    CHECK(temporal_blend_weight(std::numeric_limits<T>::quiet_NaN(), T(8)) == T(1));
    CHECK(temporal_blend_weight(T(5), T(1)) == T(1));
    CHECK(temporal_blend_weight(T(5), T(0)) == T(1));
    CHECK(temporal_blend_weight(T(5), std::numeric_limits<T>::quiet_NaN()) == T(1));
}
