// Tests of noise.hpp: hash quality, tiling on every axis (also through negative
// coordinates), ranges and statistics over many samples, Perlin's closed-form properties at
// lattice points, analytic derivatives against finite differences, Worley's 27-cell search
// against a brute-force search, fBm and the Nubis compositions against their definitions,
// and curl noise's zero divergence.
#include <cloudmath/noise.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <set>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;
using cm_test::ld;

namespace {
template <class T>
glm::vec<3, T> random_point(cm_test::rng& r, T extent) {
    return glm::vec<3, T>(static_cast<T>(r.uniform()) * extent, static_cast<T>(r.uniform()) * extent,
                          static_cast<T>(r.uniform()) * extent);
}
}  // namespace

TEST_CASE("noise_hash: avalanche, uniform low bits, distinct cells") {
    static_assert(noise_hash(0U) == 0U, "constexpr (0 is the mixer's fixed point)");
    cm_test::rng r(7);
    double flipped = 0;
    int samples = 0;
    for (int i = 0; i < 2000; ++i) {
        const std::uint32_t x = static_cast<std::uint32_t>(r.next_u64());
        for (int b = 0; b < 32; ++b) {
            flipped += double(std::bitset<32>(noise_hash(x) ^ noise_hash(x ^ (1U << b))).count());
            ++samples;
        }
    }
    const double mean = flipped / samples;
    MESSAGE("avalanche: one input bit flips " << mean << " of 32 output bits on average");
    CHECK(mean > 15.5);
    CHECK(mean < 16.5);
    // Low byte of consecutive inputs: chi-square over 256 bins.
    std::vector<int> bins(256, 0);
    const int n = 256 * 400;
    for (int i = 0; i < n; ++i) ++bins[noise_hash(static_cast<std::uint32_t>(i)) & 255U];
    double chi2 = 0;
    for (int c : bins) chi2 += (c - 400.0) * (c - 400.0) / 400.0;
    CHECK(chi2 < 340);  // 255 degrees of freedom, p ~ 3e-4
    // Every cell of a 32^3 tile and 4 seeds hashes differently.
    std::set<std::uint32_t> seen;
    for (std::uint32_t s = 0; s < 4; ++s)
        for (std::uint32_t z = 0; z < 32; ++z)
            for (std::uint32_t y = 0; y < 32; ++y)
                for (std::uint32_t x = 0; x < 32; ++x) seen.insert(noise_hash(x, y, z, s));
    CHECK(seen.size() == 4U * 32U * 32U * 32U);
}

TEST_CASE_TEMPLATE("every noise tiles with its period on each axis, negative coordinates included", T, float, double) {
    cm_test::rng r(11);
    const T tol = std::is_same_v<T, float> ? T(2e-5) : T(1e-12);
    for (int period : {1, 3, 4, 7}) {
        ld worst = 0;
        for (int i = 0; i < 200; ++i) {
            const glm::vec<3, T> p = random_point<T>(r, T(period));
            for (int axis = 0; axis < 3; ++axis) {
                for (int k : {1, -1, -2}) {
                    glm::vec<3, T> q = p;
                    q[axis] += T(k * period);
                    auto diff = [&](T a, T b) { worst = std::max(worst, ld(std::fabs(a - b))); };
                    diff(perlin_noise(p, period, 5U), perlin_noise(q, period, 5U));
                    diff(worley_noise(p, period, 5U), worley_noise(q, period, 5U));
                    diff(perlin_fbm(p, period, 4, 2, T(0.5), 5U), perlin_fbm(q, period, 4, 2, T(0.5), 5U));
                    diff(perlin_fbm(p, period, 3, 3, T(0.5), 5U), perlin_fbm(q, period, 3, 3, T(0.5), 5U));
                    diff(worley_fbm(p, period, 3, 2, T(0.5), 5U), worley_fbm(q, period, 3, 2, T(0.5), 5U));
                    diff(worley_fbm_nubis(p, period, 5U), worley_fbm_nubis(q, period, 5U));
                    diff(perlin_worley(p, period, 5U), perlin_worley(q, period, 5U));
                    const glm::vec<3, T> c = curl_noise(p, period, 5U) - curl_noise(q, period, 5U);
                    diff(T(0), std::max(std::fabs(c.x), std::max(std::fabs(c.y), std::fabs(c.z))));
                    if (axis < 2) {
                        const glm::vec<2, T> p2(p.x, p.y), q2(q.x, q.y);
                        diff(perlin_noise(p2, period, 5U), perlin_noise(q2, period, 5U));
                        diff(perlin_fbm(p2, period, 4, 2, T(0.5), 5U), perlin_fbm(q2, period, 4, 2, T(0.5), 5U));
                        const glm::vec<2, T> c2 = curl_noise(p2, period, 5U) - curl_noise(q2, period, 5U);
                        diff(T(0), std::max(std::fabs(c2.x), std::fabs(c2.y)));
                    }
                }
            }
        }
        INFO("period " << period);
        CHECK(worst <= tol * T(period) * T(8));  // only the rounding of p + k period differs
    }
    // Period < 1 is treated as 1.
    const glm::vec<3, T> p(T(0.3), T(1.7), T(-2.2));
    CHECK(perlin_noise(p, 0) == perlin_noise(p, 1));
    CHECK(worley_noise(p, -4) == worley_noise(p, 1));
}

TEST_CASE("Perlin noise: zero at lattice points, lattice gradient is a scaled cube-edge direction") {
    const double s = 0.96592582628906829;  // cos 15 deg, the documented scale
    for (int x = -3; x <= 5; ++x)
        for (int y = -2; y <= 4; ++y)
            for (int z = 0; z <= 3; ++z) {
                const glm::dvec3 p(x, y, z);
                const glm::dvec4 d = perlin_noise_derivatives(p, 4, 9U);
                CHECK(d.x == 0.0);
                CHECK(perlin_noise(glm::vec3(p), 4, 9U) == 0.0f);
                // The gradient has two components +-s and one 0 (one of the 12 edges).
                int nonzero = 0;
                for (int c = 1; c <= 3; ++c) {
                    if (d[c] != 0.0) {
                        ++nonzero;
                        CHECK(std::fabs(std::fabs(d[c]) - s) < 1e-15);
                    }
                }
                CHECK(nonzero == 2);
                CHECK(perlin_noise(glm::dvec2(x, y), 4, 9U) == 0.0);
            }
}

TEST_CASE("Perlin analytic derivatives match central finite differences") {
    cm_test::rng r(3);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 p = random_point<double>(r, 8.0);
        const glm::dvec4 d = perlin_noise_derivatives(p, 8, 2U);
        const double h = 1e-6;
        for (int c = 0; c < 3; ++c) {
            glm::dvec3 a = p, b = p;
            a[c] += h;
            b[c] -= h;
            const double fd = (perlin_noise_derivatives(a, 8, 2U).x - perlin_noise_derivatives(b, 8, 2U).x) / (2 * h);
            worst = std::max(worst, std::fabs(fd - d[c + 1]));
        }
    }
    MESSAGE("max |analytic - finite difference| = " << worst);
    CHECK(worst < 1e-7);
}

TEST_CASE_TEMPLATE("ranges and statistics over many samples", T, float, double) {
    cm_test::rng r(17);
    const int n = 200000;
    double p_sum = 0, p_sq = 0, p_max = 0, p2_max = 0, w_sum = 0, w_sq = 0, pw_sum = 0, wf_sum = 0;
    bool in_range = true;
    for (int i = 0; i < n; ++i) {
        const glm::vec<3, T> p = random_point<T>(r, T(16));
        const T pn = perlin_noise(p, 16);
        const T p2 = perlin_noise(glm::vec<2, T>(p.x, p.y), 16);
        const T wn = worley_noise(p, 16);
        const T f1 = worley_f1(p, 16);
        const T pw = perlin_worley(p, 16);
        const T wf = worley_fbm_nubis(p, 16);
        const T pf = perlin_fbm(p, 16, 5);
        in_range = in_range && pn >= T(-1) && pn <= T(1) && p2 >= T(-1) && p2 <= T(1) && wn >= T(0) && wn <= T(1) &&
                   f1 >= T(0) && f1 <= T(1.7320509) && pw >= T(0) && pw <= T(1) && wf >= T(0) && wf <= T(1) &&
                   pf >= T(-1) && pf <= T(1);
        p_sum += double(pn);
        p_sq += double(pn) * double(pn);
        p_max = std::max(p_max, std::fabs(double(pn)));
        p2_max = std::max(p2_max, std::fabs(double(p2)));
        w_sum += double(wn);
        w_sq += double(wn) * double(wn);
        pw_sum += double(pw);
        wf_sum += double(wf);
    }
    CHECK(in_range);
    const double p_mean = p_sum / n, p_std = std::sqrt(p_sq / n - p_mean * p_mean);
    const double w_mean = w_sum / n, w_std = std::sqrt(w_sq / n - w_mean * w_mean);
    MESSAGE(cm_test::type_name<T>() << ": Perlin mean " << p_mean << " std " << p_std << " max |n| " << p_max << " (2D " << p2_max
                                    << "); Worley mean " << w_mean << " std " << w_std << "; Perlin-Worley mean " << pw_sum / n
                                    << "; Nubis Worley fBm mean " << wf_sum / n);
    // Expectations (measured over 200 000 samples, stated in docs/noise.md): Perlin is
    // symmetric about 0 with std ~0.2; random samples come within 10% of the bound 1.
    CHECK(std::fabs(p_mean) < 0.005);
    CHECK(p_std > 0.15);
    CHECK(p_std < 0.30);
    CHECK(p_max > 0.85);
    CHECK(p2_max > 0.85);
    CHECK(w_mean > 0.55);
    CHECK(w_mean < 0.80);
    CHECK(w_std > 0.05);
    CHECK(w_std < 0.25);
    // Measured 0.614 and 0.700: Perlin-Worley sits above Perlin's 0.5 (the remap dilates it),
    // the Nubis Worley fBm keeps Worley's mean (its weights sum to 1).
    CHECK(pw_sum / n > 0.55);
    CHECK(pw_sum / n < 0.68);
    CHECK(std::fabs(wf_sum / n - w_mean) < 0.02);
}

// The 27-cell search is not exact everywhere (documented in noise.hpp: 29 of 20 million
// points differ from a 125-cell search); on these 3000 points it must agree exactly.
TEST_CASE("Worley: the 27-cell search matches a brute-force 125-cell search on 3000 points; 1 at feature points") {
    cm_test::rng r(23);
    auto feature = [](int cx, int cy, int cz, int period, std::uint32_t seed) {
        auto wrap = [period](int i) { return ((i % period) + period) % period; };
        const std::uint32_t h = noise_hash(std::uint32_t(wrap(cx)), std::uint32_t(wrap(cy)), std::uint32_t(wrap(cz)), seed);
        const std::uint32_t h2 = noise_hash(h), h3 = noise_hash(h2);
        return glm::dvec3(cx + double(h >> 8) / 16777216.0, cy + double(h2 >> 8) / 16777216.0, cz + double(h3 >> 8) / 16777216.0);
    };
    for (int i = 0; i < 3000; ++i) {
        const glm::dvec3 p = random_point<double>(r, 10.0) - glm::dvec3(5.0);
        double best = 1e9;
        const int cx = int(std::floor(p.x)), cy = int(std::floor(p.y)), cz = int(std::floor(p.z));
        for (int dz = -2; dz <= 2; ++dz)
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) best = std::min(best, glm::length(feature(cx + dx, cy + dy, cz + dz, 5, 4U) - p));
        CHECK(std::fabs(worley_f1(p, 5, 4U) - best) < 1e-12);
    }
    for (int c = 0; c < 20; ++c) {
        const glm::dvec3 f = feature(c % 5, (c * 3) % 5, (c * 7) % 5, 5, 4U);
        CHECK(worley_noise(f, 5, 4U) == doctest::Approx(1.0).epsilon(1e-12));
    }
}

TEST_CASE_TEMPLATE("fBm, Nubis Worley fBm and Perlin-Worley follow their definitions", T, float, double) {
    cm_test::rng r(29);
    for (int i = 0; i < 300; ++i) {
        const glm::vec<3, T> p = random_point<T>(r, T(4));
        // perlin_fbm: sum of gain^i noise(p L^i, period L^i, seed + i) / sum of gain^i.
        ld sum = 0, norm = 0, amp = 1;
        for (int o = 0; o < 4; ++o) {
            const T f = T(std::pow(3.0, o));
            sum += amp * ld(perlin_noise(p * f, 4 * int(std::pow(3, o)), 8U + std::uint32_t(o)));
            norm += amp;
            amp *= 0.6L;
        }
        // 32 eps: four octaves summed and normalised; -ffast-math may re-associate the sum.
        CHECK(std::fabs(ld(perlin_fbm(p, 4, 4, 3, T(0.6), 8U)) - sum / norm) < 32 * cm_test::eps<T>());
        const T nubis = T(0.625) * worley_noise(p, 4, 8U) + T(0.25) * worley_noise(p * T(2), 8, 9U) +
                        T(0.125) * worley_noise(p * T(4), 16, 10U);
        CHECK(std::fabs(worley_fbm_nubis(p, 4, 8U) - nubis) < 4 * cm_test::eps<T>());
        const T perlin01 = perlin_fbm(p, 4, 3, 2, T(0.5), 8U) * T(0.5) + T(0.5);
        CHECK(std::fabs(perlin_worley(p, 4, 8U) - remap_clamped(perlin01, worley_fbm_nubis(p, 4, 109U) - T(1), T(1), T(0), T(1))) <
              4 * cm_test::eps<T>());
        CHECK(perlin_fbm(p, 4, 0, 2, T(0.5), 8U) == perlin_noise(p, 4, 8U));  // octaves < 1 -> 1
        CHECK(worley_fbm(p, 4, 1, 2, T(0.5), 8U) == worley_noise(p, 4, 8U));
        CHECK(std::fabs(perlin_fbm(glm::vec<2, T>(p.x, p.y), 4, 1, 2, T(0.5), 8U) - perlin_noise(glm::vec<2, T>(p.x, p.y), 4, 8U)) <
              2 * cm_test::eps<T>());
    }
}

TEST_CASE("curl noise is divergence-free and equals the curl of its potential") {
    cm_test::rng r(31);
    double worst_div = 0, worst_curl = 0, scale = 0, worst_div2 = 0;
    const double h = 1e-5;
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 p = random_point<double>(r, 8.0);
        double div = 0;
        for (int c = 0; c < 3; ++c) {
            glm::dvec3 a = p, b = p;
            a[c] += h;
            b[c] -= h;
            div += (curl_noise(a, 8, 3U)[c] - curl_noise(b, 8, 3U)[c]) / (2 * h);
        }
        worst_div = std::max(worst_div, std::fabs(div));
        // Finite-difference curl of the potential (psi_x, psi_y, psi_z) = Perlin seeds 3, 4, 5.
        auto psi = [](const glm::dvec3& q, int k) { return perlin_noise_derivatives(q, 8, 3U + std::uint32_t(k)).x; };
        auto d = [&](int k, int axis) {
            glm::dvec3 a = p, b = p;
            a[axis] += h;
            b[axis] -= h;
            return (psi(a, k) - psi(b, k)) / (2 * h);
        };
        const glm::dvec3 fd(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
        const glm::dvec3 c = curl_noise(p, 8, 3U);
        worst_curl = std::max(worst_curl, glm::length(fd - c));
        scale = std::max(scale, glm::length(c));
        const glm::dvec2 p2(p.x, p.y);
        const double div2 = (curl_noise(p2 + glm::dvec2(h, 0), 8, 3U).x - curl_noise(p2 - glm::dvec2(h, 0), 8, 3U).x) / (2 * h) +
                            (curl_noise(p2 + glm::dvec2(0, h), 8, 3U).y - curl_noise(p2 - glm::dvec2(0, h), 8, 3U).y) / (2 * h);
        worst_div2 = std::max(worst_div2, std::fabs(div2));
    }
    MESSAGE("curl: max |div| " << worst_div << " (2D " << worst_div2 << "), max |curl - FD curl| " << worst_curl << ", max |curl| " << scale);
    CHECK(worst_div < 1e-5 * scale);
    CHECK(worst_div2 < 1e-5 * scale);
    CHECK(worst_curl < 1e-6 * scale);
    CHECK(scale > 1.0);  // a real field, not zero
}

TEST_CASE("seeds give independent fields") {
    cm_test::rng r(37);
    double sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 p = random_point<double>(r, 8.0);
        const double a = perlin_noise(p, 8, 1U), b = perlin_noise(p, 8, 2U);
        sab += a * b;
        saa += a * a;
        sbb += b * b;
    }
    const double corr = sab / std::sqrt(saa * sbb);
    MESSAGE("correlation between seeds 1 and 2: " << corr);
    CHECK(std::fabs(corr) < 0.05);
}

TEST_CASE_TEMPLATE("far coordinates and absurd octave counts: finite, no overflow (UBSan build checks)", T, float, double) {
    const glm::vec<3, T> far(T(3e9), T(-5e12), T(1e20));
    CHECK(cm_test::finite_bits(perlin_noise(far, 4)));
    CHECK(cm_test::finite_bits(worley_noise(far, 4)));
    CHECK(cm_test::finite_bits(perlin_noise(glm::vec<2, T>(far.x, far.y), 4)));
    // 40 octaves of lacunarity 3: the octave period saturates instead of overflowing int.
    const glm::vec<3, T> p(T(0.3), T(0.6), T(0.9));
    CHECK(cm_test::finite_bits(perlin_fbm(p, 8, 40, 3, T(0.5))));
    CHECK(cm_test::finite_bits(worley_fbm(p, 1 << 29, 3, 2, T(0.5))));
    CHECK(cm_test::finite_bits(worley_fbm_nubis(p, 1 << 29)));
    CHECK(perlin_fbm(p, 8, 40, 3, T(0.5)) >= T(-1));
    CHECK(perlin_fbm(p, 8, 40, 3, T(0.5)) <= T(1));
}

// Hardening round 2, A7: a NaN coordinate was converted to int (undefined behaviour; the
// UBSan build caught INT_MIN - 1 in worley_f1). Now the lattice cell is defined in every build
// and, with IEEE semantics, the NaN reaches the result.
TEST_CASE_TEMPLATE("NaN and infinite coordinates: no int conversion of them, NaN results (UBSan build checks)", T, float, double) {
    const T nan = cm_test::make_nan<T>(), inf = cm_test::make_inf<T>();
    for (int axis = 0; axis < 3; ++axis)
        for (T bad : {nan, inf, -inf}) {
            glm::vec<3, T> p(T(0.3), T(0.6), T(0.9));
            p[axis] = bad;
            const T values[] = {perlin_noise(p, 8), worley_noise(p, 8), worley_f1(p, 8), perlin_fbm(p, 8, 4),
                                worley_fbm(p, 8, 3), worley_fbm_nubis(p, 8), perlin_worley(p, 8),
                                perlin_noise(glm::vec<2, T>(p[axis], T(0.4)), 8)};
            if (cm_test::ieee_build)
                for (T v : values) CHECK(cm_test::nan_bits(v));
        }
}

TEST_CASE("low-discrepancy sequences: Roberts' closed form, even coverage, bit-exact in float and double") {
    const long double phi1 = 0.61803398874989484820L;                                    // golden ratio - 1
    const long double plastic = 1.32471795724474602596L, a1 = 1 / plastic, a2 = 1 / (plastic * plastic);
    const auto circular = [](long double a, long double b) {
        const long double d = std::fabs(a - b);
        return std::min(d, 1 - d);
    };
    for (std::uint32_t n = 0; n < 4096; ++n) {
        // fract(1/2 + n alpha): alpha rounded to 2^-32 (n 2^-33 at most) and the value to 2^-24.
        const long double tol = std::ldexp(1.0L, -24) + n * std::ldexp(1.0L, -33);
        const auto fract = [](long double x) { return x - std::floor(x); };
        CHECK(circular(low_discrepancy_r1<double>(n), fract(0.5L + n * phi1)) <= tol);
        const glm::dvec2 r2 = low_discrepancy_r2<double>(n);
        CHECK(circular(r2.x, fract(0.5L + n * a1)) <= tol);
        CHECK(circular(r2.y, fract(0.5L + n * a2)) <= tol);
        // 24 bits: exact in float, identical in double.
        CHECK(double(low_discrepancy_r1<float>(n)) == low_discrepancy_r1<double>(n));
        CHECK(glm::dvec2(low_discrepancy_r2<float>(n)) == r2);
        CHECK(low_discrepancy_r1<float>(n) < 1.0f);
    }
    // R1 and the per-pixel frame jitter: the first N frames of any pixel leave no gap wider
    // than 2/N (white noise leaves gaps near ln(N)/N), for every N up to 256.
    for (std::uint32_t pixel_hash : {0U, 12345U, 0xdeadbeefU, 0xffffffffU, noise_hash(7U)}) {
        CHECK(frame_jitter(pixel_hash, 0U) == float(pixel_hash >> 8) / 16777216.0f);  // frame 0: the hash itself
        std::vector<double> xs;
        for (std::uint32_t frame = 0; frame < 256; ++frame) {
            xs.push_back(frame_jitter<double>(pixel_hash, frame));
            std::vector<double> sorted = xs;
            std::sort(sorted.begin(), sorted.end());
            double widest = 1.0 - sorted.back() + sorted.front();
            for (std::size_t i = 1; i < sorted.size(); ++i) widest = std::max(widest, sorted[i] - sorted[i - 1]);
            CHECK(widest * double(sorted.size()) < 2.0);
        }
    }
    // R2: N = k^2 points put at most 2 in any cell of a k x k grid.
    for (int k : {4, 8, 16}) {
        std::vector<int> count(static_cast<std::size_t>(k * k), 0);
        for (std::uint32_t n = 0; n < std::uint32_t(k * k); ++n) {
            const glm::vec2 p = low_discrepancy_r2(n);
            ++count[static_cast<std::size_t>(int(p.y * float(k)) * k + int(p.x * float(k)))];
        }
        CHECK(*std::max_element(count.begin(), count.end()) <= 2);
    }
}

// Hardening round 2, A9: the exact R1 sequence has at most 3 gap sizes (three-distance
// theorem); its 24-bit outputs, each truncated, at most 6, in at most 3 groups of sizes one
// unit (2^-24) apart, as noise.hpp now says.
TEST_CASE("low_discrepancy_r1: the 24-bit outputs' gaps: at most 6 sizes, in at most 3 groups one unit apart") {
    int worst_sizes = 0;
    for (int count : {2, 3, 5, 8, 13, 50, 100, 233, 377, 1000, 1597, 4096}) {
        std::vector<std::uint32_t> units;
        for (int n = 0; n < count; ++n)
            units.push_back(static_cast<std::uint32_t>(low_discrepancy_r1<double>(static_cast<std::uint32_t>(n)) * 16777216.0));
        std::sort(units.begin(), units.end());
        std::vector<std::uint32_t> gaps;
        for (std::size_t i = 0; i < units.size(); ++i)
            gaps.push_back(i + 1 < units.size() ? units[i + 1] - units[i] : units[0] + 16777216u - units[i]);
        std::sort(gaps.begin(), gaps.end());
        gaps.erase(std::unique(gaps.begin(), gaps.end()), gaps.end());
        int groups = 1;
        for (std::size_t i = 1; i < gaps.size(); ++i)
            if (gaps[i] - gaps[i - 1] > 1u) ++groups;
        CAPTURE(count);
        CHECK(gaps.size() <= 6);
        CHECK(groups <= 3);
        worst_sizes = std::max(worst_sizes, static_cast<int>(gaps.size()));
    }
    CHECK(worst_sizes > 3);  // the quantisation does show: the exact sequence's bound of 3 is not the outputs'
}

TEST_CASE("sample_jitter: index 0 is frame_jitter, R1 over frames for each index, no shared offsets within a frame") {
    for (std::uint32_t pixel_hash : {0U, 12345U, 0xdeadbeefU, 0xffffffffU, noise_hash(7U)}) {
        for (std::uint32_t frame : {0U, 1U, 77U, 0xfffffff0U})
            CHECK(sample_jitter(pixel_hash, frame, 0U) == frame_jitter(pixel_hash, frame));
        // The closed form: the top 24 bits of hash + index * 0xc13fa9a9 + frame * 0x9e3779b9
        // (mod 2^32), exact in float and identical in double.
        const std::uint32_t index = 41U, frame = 9U;
        const std::uint64_t sum = (std::uint64_t(pixel_hash) + std::uint64_t(index) * 0xc13fa9a9ULL +
                                   std::uint64_t(frame) * 0x9e3779b9ULL) & 0xffffffffULL;
        CHECK(sample_jitter(pixel_hash, frame, index) == float(sum >> 8) / 16777216.0f);
        CHECK(double(sample_jitter<float>(pixel_hash, frame, index)) == sample_jitter<double>(pixel_hash, frame, index));
        // For a fixed index the frames leave no gap wider than 2/N; within a frame the
        // indices do not either (an R-sequence, not one offset repeated).
        for (std::uint32_t fixed : {3U, 200U}) {
            std::vector<double> over_frames, over_indices;
            for (std::uint32_t k = 0; k < 64; ++k) {
                over_frames.push_back(sample_jitter<double>(pixel_hash, k, fixed));
                over_indices.push_back(sample_jitter<double>(pixel_hash, fixed, k));
            }
            for (std::vector<double>* xs : {&over_frames, &over_indices}) {
                std::sort(xs->begin(), xs->end());
                double widest = 1.0 - xs->back() + xs->front();
                for (std::size_t i = 1; i < xs->size(); ++i) widest = std::max(widest, (*xs)[i] - (*xs)[i - 1]);
                CHECK(widest * double(xs->size()) < 2.0);
                CHECK(xs->back() < 1.0);
                CHECK(xs->front() >= 0.0);
            }
        }
    }
}

TEST_CASE("triangular_dither: the closed form, triangular moments, quantisation without bias") {
    CHECK(triangular_dither(0U) == 0.0f);
    CHECK(triangular_dither(0x0000ffffU) == 65535.0f / 65536.0f);   // the extremes stay inside (-1, 1)
    CHECK(triangular_dither(0xffff0000U) == -65535.0f / 65536.0f);
    CHECK(triangular_dither(0x00030001U) == -2.0f / 65536.0f);
    CHECK(double(triangular_dither<float>(0x12345678U)) == triangular_dither<double>(0x12345678U));  // exact in float
    // Moments of the triangular distribution on (-1, 1): mean 0, variance 1/6, E|x| = 1/3.
    const int n = 1 << 18;
    double sum = 0, sum2 = 0, sum_abs = 0;
    for (int i = 0; i < n; ++i) {
        const double d = triangular_dither<double>(noise_hash(std::uint32_t(i)));
        REQUIRE(d > -1.0);
        REQUIRE(d < 1.0);
        sum += d;
        sum2 += d * d;
        sum_abs += std::fabs(d);
    }
    CHECK(std::fabs(sum / n) < 3e-3);
    CHECK(sum2 / n == doctest::Approx(1.0 / 6.0).epsilon(0.01));
    CHECK(sum_abs / n == doctest::Approx(1.0 / 3.0).epsilon(0.01));
    // Quantising v + d / 255 to 8 bits: the mean of the stored values is v (plain rounding
    // would store the nearest step, off by up to half a step), for values between steps.
    for (double frac : {0.1, 0.25, 0.5, 0.8}) {
        const double v = (100.0 + frac) / 255.0;
        double stored = 0;
        for (int i = 0; i < n; ++i) stored += std::floor((v + triangular_dither<double>(noise_hash(std::uint32_t(i) + 77U)) / 255.0) * 255.0 + 0.5);
        CHECK(stored / n / 255.0 == doctest::Approx(v).epsilon(1e-5));
        CHECK(std::floor(v * 255.0 + 0.5) / 255.0 != doctest::Approx(v).epsilon(1e-4));  // without dither: biased
    }
}

TEST_CASE("hash_to_unit: k / 2^24 from the top 24 bits, in [0, 1), exact in float") {
    CHECK(hash_to_unit<float>(0U) == 0.0f);
    CHECK(hash_to_unit<float>(0xffU) == 0.0f);  // the low 8 bits do not count
    CHECK(hash_to_unit<float>(0x100U) == 1.0f / 16777216.0f);
    CHECK(hash_to_unit<float>(0xffffffffU) == 16777215.0f / 16777216.0f);
    CHECK(hash_to_unit<float>(0xffffffffU) < 1.0f);
    for (std::uint32_t h : {1U, 12345U, 0x80000000U, 0xdeadbeefU, noise_hash(9U)}) {
        CHECK(double(hash_to_unit<float>(h)) == hash_to_unit<double>(h));
        CHECK(hash_to_unit<double>(h) == double(h >> 8) / 16777216.0);
    }
}

// Regression (fuzzing): gain had no documented range; gain -1 with an even octave count made
// the sum of amplitudes 0 (sum / 0: Inf or NaN), and large gains overflowed the amplitudes.
// Documented now: gain is clamped to [0, 1]. References from the definition over the base
// noise functions in long double: gain <= 0 is the first octave alone, gain >= 1 the plain
// mean of the octaves.
TEST_CASE_TEMPLATE("fBm: gain clamped to [0, 1]; negative, zero and huge gains give defined values in range", T, float, double) {
    cm_test::rng r(31);
    const T huge = std::numeric_limits<T>::max();
    for (int i = 0; i < 50; ++i) {
        const glm::vec<3, T> p = random_point<T>(r, T(4));
        const glm::vec<2, T> p2(p.x, p.y);
        ld mean3 = 0, mean2 = 0, meanw = 0;
        for (int o = 0; o < 4; ++o) {
            const T f = T(1 << o);
            mean3 += ld(perlin_noise(p * f, 4 << o, 8U + std::uint32_t(o))) / 4;
            mean2 += ld(perlin_noise(p2 * f, 4 << o, 8U + std::uint32_t(o))) / 4;
            meanw += ld(worley_noise(p * f, 4 << o, 8U + std::uint32_t(o))) / 4;
        }
        for (T gain : {T(-1), T(-0.5), T(-1e30), -huge, T(0)}) {
            INFO("gain = " << gain);
            CHECK(perlin_fbm(p, 4, 4, 2, gain, 8U) == perlin_noise(p, 4, 8U));
            CHECK(perlin_fbm(p2, 4, 4, 2, gain, 8U) == perlin_noise(p2, 4, 8U));
            CHECK(worley_fbm(p, 4, 4, 2, gain, 8U) == worley_noise(p, 4, 8U));
        }
        for (T gain : {T(1), T(1.5), T(2), T(1e30), huge}) {
            INFO("gain = " << gain);
            CHECK(std::fabs(ld(perlin_fbm(p, 4, 4, 2, gain, 8U)) - mean3) < 8 * cm_test::eps<T>());
            CHECK(std::fabs(ld(perlin_fbm(p2, 4, 4, 2, gain, 8U)) - mean2) < 8 * cm_test::eps<T>());
            CHECK(std::fabs(ld(worley_fbm(p, 4, 4, 2, gain, 8U)) - meanw) < 8 * cm_test::eps<T>());
        }
    }
    // Many octaves at the clamp ends: finite and in range (amplitudes never grow). 100
    // octaves of lacunarity 2 keep the frequency 2^99 finite in float (documented limit).
    const glm::vec<3, T> p(T(0.3), T(0.6), T(0.9));
    for (T gain : {T(-1), T(0), T(1), T(3), huge}) {
        const T v = perlin_fbm(p, 8, 100, 2, gain);
        CHECK(cm_test::finite_bits(v));
        CHECK(v >= T(-1));
        CHECK(v <= T(1));
    }
}
