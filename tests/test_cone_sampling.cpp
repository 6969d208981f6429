// Tests of cone_sampling.hpp: the Vogel kernel, sample distances and lengths, positions
// inside the cone, the far sample, and optical depth through constant and layered media.
#include <cloudmath/cone_sampling.hpp>

#include <cmath>

#include <glm/geometric.hpp>
#include <initializer_list>
#include <limits>
#include <set>
#include <type_traits>
#include <utility>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

TEST_CASE_TEMPLATE("cone_kernel_offset: deterministic points strictly inside the unit disc, evenly spread", T, float, double) {
    for (int n : {1, 5, 6, 16}) {
        std::set<std::pair<long, long>> seen;
        ld mean_x = 0, mean_y = 0;
        for (int i = 0; i < n; ++i) {
            const glm::vec<2, T> k = cone_kernel_offset<T>(i, n);
            const ld r = std::hypot(ld(k.x), ld(k.y));
            CHECK(r < 1);
            CHECK(cm_test::rel_err(r, std::sqrt((i + 0.5L) / n)) <= 8 * cm_test::eps<T>());
            seen.insert({std::lround(ld(k.x) * 1e4L), std::lround(ld(k.y) * 1e4L)});
            mean_x += k.x;
            mean_y += k.y;
            CHECK(cone_kernel_offset<T>(i, n) == k);           // deterministic
            CHECK(cone_kernel_offset<T>(i + n, n) == k);       // modulo n
            CHECK(cone_kernel_offset<T>(i - n, n) == k);
        }
        CHECK(int(seen.size()) == n);  // distinct points
        if (n >= 6) CHECK(std::hypot(mean_x / n, mean_y / n) < 0.2L);  // no strong bias to one side
    }
    CHECK(cone_kernel_offset<T>(3, 0) == cone_kernel_offset<T>(0, 1));  // n < 1 treated as 1
}

TEST_CASE_TEMPLATE("cone sample distances, lengths and the far sample", T, float, double) {
    const cone_light_config<T> cfg{6, T(50), T(0.4), T(800), T(100)};
    for (int i = 0; i < 5; ++i) {
        CHECK(cone_sample_distance(cfg, i) == (T(i) + T(0.5)) * T(50));
        CHECK(cone_sample_length(cfg, i) == T(50));
    }
    CHECK(cone_sample_distance(cfg, 5) == T(800));
    CHECK(cone_sample_length(cfg, 5) == T(100));
    CHECK(cone_sample_distance(cfg, -2) == T(25));   // clamped to the first
    CHECK(cone_sample_distance(cfg, 99) == T(800));  // past the end: the far sample
    const cone_light_config<T> no_far{4, T(10), T(0.5), T(0), T(0)};
    CHECK(cone_sample_distance(no_far, 3) == T(35));
    CHECK(cone_sample_distance(no_far, 9) == T(35));
    CHECK(cone_sample_length(no_far, 3) == T(10));
    static_assert(cone_sample_distance(cone_light_config<T>{6, T(50), T(0.4), T(800), T(100)}, 1) == T(75), "constexpr");
    // No samples at all: indices clamp to the first position, never a negative distance
    // (found by the GLSL parity review: the GLSL twin clamps the same way).
    const cone_light_config<T> empty{0, T(10), T(0.5), T(0), T(0)};
    CHECK(cone_sample_distance(empty, 0) == T(5));
    CHECK(cone_sample_distance(empty, 3) == T(5));
    CHECK(cone_sample_distance(empty, -1) == T(5));
}

TEST_CASE_TEMPLATE("cone_sample_position: inside the cone toward the light, far sample on the axis", T, float, double) {
    using v3 = glm::vec<3, T>;
    const cone_light_config<T> cfg{6, T(50), T(0.4), T(800), T(100)};
    for (const v3& dir_raw : {v3(T(0), T(1), T(0)), v3(T(0), T(0), T(-1)), v3(T(1), T(2), T(3)), v3(T(-0.3), T(0.1), T(-0.9))}) {
        const v3 dir = glm::normalize(dir_raw);
        const v3 origin(T(10), T(-4), T(7));
        ld lateral_max = 0;
        for (int i = 0; i < cfg.sample_count; ++i) {
            const v3 p = cone_sample_position(origin, dir, cfg, i);
            const v3 d = p - origin;
            // Along and across the axis in long double (|d x dir| has no cancellation).
            const ld dx = d.x, dy = d.y, dz = d.z, ux = dir.x, uy = dir.y, uz = dir.z;
            const ld along = dx * ux + dy * uy + dz * uz;
            const ld cx = dy * uz - dz * uy, cy = dz * ux - dx * uz, cz = dx * uy - dy * ux;
            const ld lateral = std::sqrt(cx * cx + cy * cy + cz * cz);
            CHECK(std::fabs(along - ld(cone_sample_distance(cfg, i))) <= 1e3L * cm_test::eps<T>() * 800);
            if (i < 5) {
                // Radius sqrt((i + 1/2) / 5) of the cone radius at that distance.
                const ld want = 0.4L * ld(cone_sample_distance(cfg, i)) * std::sqrt((i + 0.5L) / 5);
                CHECK(std::fabs(lateral - want) <= 1e3L * cm_test::eps<T>() * 800);
                CHECK(lateral <= 0.4L * along * (1 + 1e-4L));
                lateral_max = std::fmax(lateral_max, lateral);
            } else {
                CHECK(lateral <= 1e3L * cm_test::eps<T>() * 800);  // far sample on the axis
            }
        }
        CHECK(lateral_max > 10);  // the cone really spreads
    }
    // Zero spread: every sample on the ray.
    const cone_light_config<T> line{5, T(10), T(0), T(0), T(0)};
    for (int i = 0; i < 5; ++i)
        CHECK(cone_sample_position(v3(T(0)), v3(T(0), T(0), T(1)), line, i) == v3(T(0), T(0), (T(i) + T(0.5)) * T(10)));
}

TEST_CASE_TEMPLATE("cone_optical_depth: constant medium exact, half-space, callable with the sample index", T, float, double) {
    using v3 = glm::vec<3, T>;
    const cone_light_config<T> cfg{6, T(50), T(0.4), T(800), T(100)};
    const v3 up(T(0), T(1), T(0));
    const T tau = cone_optical_depth(v3(T(0)), up, cfg, [](const v3&) { return T(0.01); });
    CHECK(cm_test::rel_err(tau, 0.01L * (5 * 50 + 100)) <= 16 * cm_test::eps<T>());
    // A cloud slab 100 < y < 200: samples at 125 and 175 fall in it (lateral offsets are
    // perpendicular to the light, so heights are exact), the far one at 800 does not.
    const T slab = cone_optical_depth(v3(T(0)), up, cfg, [](const v3& p) { return (p.y > T(100) && p.y < T(200)) ? T(0.02) : T(0); });
    CHECK(cm_test::rel_err(slab, 0.02L * 2 * 50) <= 16 * cm_test::eps<T>());
    // The (p, i) form: cheap density after the second sample.
    int calls = 0;
    const T indexed = cone_optical_depth(v3(T(0)), up, cfg, [&](const v3&, int i) { ++calls; return i < 2 ? T(0.01) : T(0); });
    CHECK(calls == 6);
    CHECK(cm_test::rel_err(indexed, 0.01L * 2 * 50) <= 16 * cm_test::eps<T>());
    const cone_light_config<T> none{0, T(50), T(0.4), T(800), T(100)};
    CHECK(cone_optical_depth(v3(T(0)), up, none, [](const v3&) { return T(1); }) == T(0));
}

TEST_CASE_TEMPLATE("cone_optical_depth equals the sum over cone_sample_position (rotated Vogel angles)", T, float, double) {
    using v3 = glm::vec<3, T>;
    // A density that varies across the cone, so lateral positions matter.
    auto sigma = [](const v3& p) { return T(0.01) * (T(1) + T(0.5) * std::sin(T(0.02) * p.x) * std::cos(T(0.017) * p.z)); };
    for (int count : {1, 6, 16}) {
        for (T far : {T(0), T(900)}) {
            const cone_light_config<T> cfg{count, T(40), T(0.6), far, T(120)};
            const v3 origin(T(3), T(-1), T(2));
            const v3 dir = glm::normalize(v3(T(0.3), T(1), T(-0.2)));
            ld sum = 0;
            for (int i = 0; i < count; ++i) sum += ld(sigma(cone_sample_position(origin, dir, cfg, i))) * ld(cone_sample_length(cfg, i));
            INFO("count " << count << ", far " << far);
            CHECK(cm_test::rel_err(cone_optical_depth(origin, dir, cfg, sigma), sum) <= (std::is_same_v<T, float> ? 2e-6L : 1e-13L));
        }
    }
}


// Regression (fuzzing, UBSan): the wrap ((i % n) + n) % n overflowed int, undefined
// behaviour, for n > INT_MAX / 2 and 0 < i % n (the sanitize build aborts on it). The
// reference is the closed form: k = i mod n, radius sqrt((k + 1/2) / n), angle k times the
// golden angle, in long double.
TEST_CASE_TEMPLATE("cone_kernel_offset: every int index and count, no overflow; strictly inside up to the documented n", T, float, double) {
    const int int_max = std::numeric_limits<int>::max(), int_min = std::numeric_limits<int>::min();
    const ld golden = 2.399963229728653322231555506633613853L;
    for (int n : {int_max, int_max - 1, (1 << 30) + 1, 1 << 30, 1 << 23, 3})
        for (int i : {0, 1, 5, 7, -1, -2, int_max, int_max - 1, int_min, int_min + 1}) {
            INFO("i = " << i << ", n = " << n);
            const long long kk = ((static_cast<long long>(i) % n) + n) % n;  // wide: no overflow
            const glm::vec<2, T> k = cone_kernel_offset<T>(i, n);
            REQUIRE(cm_test::finite_bits(k.x));
            REQUIRE(cm_test::finite_bits(k.y));
            const ld r = std::hypot(ld(k.x), ld(k.y));
            CHECK(r <= 1 + 4 * ld(cm_test::eps<T>()));  // radius <= 1; cos and sin round
            // Strictly inside: documented for n <= 2^23 in float and every n in double.
            if (std::is_same_v<T, double> || n <= (1 << 23)) CHECK(r < 1);
            CHECK(cm_test::rel_err(r, std::sqrt((ld(kk) + 0.5L) / ld(n))) <= 8 * cm_test::eps<T>());
            // The angle of a small index is exact to rounding (a large one carries the rounding
            // of T(k) * golden angle, up to half an ulp of the angle).
            if (kk < 8) {
                CHECK(std::fabs(ld(k.x) - std::sqrt((ld(kk) + 0.5L) / ld(n)) * std::cos(ld(kk) * golden)) <= 32 * cm_test::eps<T>());
                CHECK(std::fabs(ld(k.y) - std::sqrt((ld(kk) + 0.5L) / ld(n)) * std::sin(ld(kk) * golden)) <= 32 * cm_test::eps<T>());
            }
        }
    // Through the sample positions: a config with the largest sample count.
    const cone_light_config<T> cfg{int_max, T(50), T(0.4), T(800), T(100)};
    const glm::vec<3, T> origin(T(1), T(2), T(3)), up(T(0), T(1), T(0));
    for (int i : {0, 3, int_max - 2, int_max - 1}) {
        const glm::vec<3, T> p = cone_sample_position(origin, up, cfg, i);
        CHECK(cm_test::finite_bits(p.x));
        CHECK(cm_test::finite_bits(p.y));
        CHECK(cm_test::finite_bits(p.z));
    }
}
