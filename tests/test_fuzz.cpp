// Fuzz test: the public functions on random finite inputs, inside and far outside their
// documented domains (each header states its domain), in float and double. Built, like the
// other unit tests, plain, with -ffast-math and with AddressSanitizer + UBSan, so that
// undefined behaviour (signed overflow, out-of-range int conversions, out-of-bounds reads)
// on any of these inputs fails the sanitized run. Checked here: what each header promises for
// any finite input (no NaN, results in the stated range), and inside the domain the stated
// range of the result. The GLSL twins get the same treatment on the GPU driver (ctest
// glsl.fuzz). Fixed seeds: the run is deterministic and takes about a second.
#include <cloudmath/batch.hpp>
#include <cloudmath/cloudmath.hpp>
#include <cloudmath/noise_bake.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "test_support.hpp"

namespace cm = cloudmath;

namespace {

// Random numbers for one type: `any()` mixes moderate values, magnitudes over the whole
// exponent range (both signs) and the special finite values; `in(lo, hi)` is uniform.
template <class T>
struct inputs {
    std::mt19937_64 rng;
    explicit inputs(std::uint64_t seed) : rng(seed) {}
    T unit() { return std::uniform_real_distribution<T>(T(0), T(1))(rng); }
    T in(T lo, T hi) { return lo + (hi - lo) * unit(); }
    T any() {
        const T r = unit();
        const T sign = unit() < T(0.5) ? T(-1) : T(1);
        if (r < T(0.1)) {
            const T specials[] = {T(0), T(1), std::numeric_limits<T>::min(), std::numeric_limits<T>::denorm_min(),
                                  std::numeric_limits<T>::max(), std::numeric_limits<T>::epsilon(), T(0.5)};
            return sign * specials[std::size_t(unit() * T(6.999))];
        }
        if (r < T(0.5)) return sign * in(T(0), T(4));
        const T top = T(std::numeric_limits<T>::max_exponent10 - 1), bottom = T(std::numeric_limits<T>::min_exponent10);
        return sign * std::pow(T(10), in(bottom, top));
    }
    int any_int() {
        std::uniform_int_distribution<int> wide(std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
        std::uniform_int_distribution<int> small(-70, 70);
        return unit() < T(0.5) ? small(rng) : wide(rng);
    }
};

constexpr int rounds = 4000;

// A finite result (only meaningful in IEEE builds: -ffast-math may assume it anyway).
template <class T>
bool ok(T x) {
    return !cm_test::ieee_build || std::isfinite(x);
}

template <class T>
bool in_range(T x, T lo, T hi) {
    return x >= lo && x <= hi;
}

}  // namespace

TEST_CASE_TEMPLATE("fuzz core: saturate, remap_clamped, smoothstep_safe, 1 - e^-x stay finite and in range", T, float, double) {
    inputs<T> r(1);
    for (int k = 0; k < rounds; ++k) {
        const T x = r.any(), a = r.any(), b = r.any(), c = r.any(), d = r.any();
        CHECK(in_range(cm::saturate(x), T(0), T(1)));
        const T m = cm::remap_clamped(x, a, b, c, d);
        CHECK(ok(m));
        if (c <= d) CHECK(in_range(m, c, d));
        else CHECK(in_range(m, d, c));
        CHECK(in_range(cm::smoothstep_safe(a, b, x), T(0), T(1)));
        const T y = std::fabs(x);
        CHECK(in_range(cm::one_minus_exp_neg(y), T(0), T(1)));
        CHECK(in_range(cm::one_minus_exp_neg_over_x(y), T(0), T(1)));
    }
}

TEST_CASE_TEMPLATE("fuzz transmittance: Beer-Lambert, powder, Beer-Powder, diffuse transmittance, and the batch forms agree", T, float, double) {
    inputs<T> r(2);
    std::vector<T> tau(256), exact(256), quick(256);
    for (int k = 0; k < rounds / 256 + 1; ++k) {
        for (T& t : tau) t = r.any();
        cm::batch::beer_powder(tau.data(), tau.size(), exact.data());
        cm::batch::beer_powder<cm::fast_math>(tau.data(), tau.size(), quick.data());
        for (std::size_t i = 0; i < tau.size(); ++i) {
            const T t = tau[i];
            CHECK(in_range(cm::beer_lambert(t), T(0), T(1)));
            CHECK(in_range(cm::powder(std::fabs(t), T(2)), T(0), T(1)));
            const T bp = cm::beer_powder(t);
            CHECK(ok(bp));
            CHECK(bp >= T(0));
            CAPTURE(t);
            CHECK(ok(exact[i]));
            CHECK(ok(quick[i]));
            CHECK(std::fabs(exact[i] - bp) <= T(1e-5) * (T(1) + bp));
            CHECK(in_range(cm::diffuse_transmittance(t, r.in(T(-1), T(1))), T(0), T(1)));
        }
    }
}

TEST_CASE_TEMPLATE("fuzz phase functions: finite and non-negative for any mu and g; sampling stays in [-1, 1]", T, float, double) {
    inputs<T> r(3);
    for (int k = 0; k < rounds; ++k) {
        const T mu = r.any(), g = r.any(), g2 = r.any(), w = r.any();
        for (const T p : {cm::phase_hg(mu, g), cm::phase_hg_dual(mu, g, g2, w), cm::phase_cornette_shanks(mu, g),
                          cm::phase_draine(mu, g, std::fabs(w)), cm::phase_mie_approx(mu, cm::mie_approx_params(std::fabs(g2)))}) {
            CAPTURE(mu);
            CAPTURE(g);
            CHECK(ok(p));
            CHECK(p >= T(0));
        }
        const T s = cm::sample_phase_hg(g, r.unit());
        CHECK(in_range(s, T(-1), T(1)));
    }
}

TEST_CASE_TEMPLATE("fuzz lighting: octaves and the diffusion model inside their domains, finite and non-negative", T, float, double) {
    inputs<T> r(4);
    for (int k = 0; k < rounds; ++k) {
        const T tau = std::fabs(r.any()), mu = r.in(T(-1), T(1)), g = r.in(T(-0.95), T(0.95));
        const T m = cm::multiple_scattering(tau, mu, g, r.unit(), r.unit(), r.unit(), 1 + int(r.unit() * T(7)));
        CHECK(ok(m));
        CHECK(m >= T(0));
        // The homogeneous-media fit and the whole-cloud fit (the example renderer's default).
        const T tb = std::fabs(r.any()), tv = std::fabs(r.any()), albedo = r.unit();
        for (const cm::diffusion_model* model : {&cm::diffusion_models::fitted, &cm::diffusion_models::clouds}) {
            const T d = cm::diffusion_scattering(tau, tb, tv, mu, g, albedo, *model);
            CAPTURE(tau);
            CHECK(ok(d));
            CHECK(d >= T(0));
        }
    }
}

TEST_CASE_TEMPLATE("fuzz density and geometry: finite inputs give finite densities, altitudes and segments", T, float, double) {
    inputs<T> r(5);
    for (int k = 0; k < rounds; ++k) {
        const T h = r.any(), a = std::fabs(r.any()), b = std::fabs(r.any());
        const T e = cm::height_gradient_exponential(h, a, b);
        CAPTURE(h);
        CHECK(ok(e));
        CHECK(in_range(e, T(0), T(1)));
        CHECK(in_range(cm::apply_coverage(r.any(), r.any()), T(0), T(1)));
        // Planet geometry inside its domain: altitudes from 0 to 1000 km, any direction.
        const T alt = r.in(T(0), T(1e6)), muz = r.in(T(-1), T(1)), R = T(6371e3);
        const glm::vec<2, T> seg = cm::cloud_layer_segment(alt, muz, R, r.in(T(0), T(2e4)), r.in(T(0), T(2e4)));
        if (seg.y > seg.x) {
            CHECK(ok(seg.x));
            CHECK(ok(seg.y));
            CHECK(seg.x >= T(0));
        }
        CHECK(ok(cm::altitude_along_ray(alt, muz, R, r.in(T(0), T(1e6)))));
        const glm::vec<3, T> p(r.in(T(-1e5), T(1e5)), r.in(T(-1e5), T(1e5)), r.in(T(-1e5), T(1e5)));
        CHECK(ok(cm::point_altitude(p, alt, R)));
        // Any finite ray and sphere: the roots are finite or the (-1, -1) miss.
        // Any ray and sphere whose squared sizes are finite (the domain: |o - c|^2 and r^2 must
        // not overflow): the roots are finite or the (-1, -1) miss.
        const glm::vec<3, T> o(r.any(), r.any(), r.any());
        const T radius = std::fabs(r.any());
        const glm::vec<2, T> t = cm::ray_sphere_intersect(o, glm::vec<3, T>(T(0), T(0), T(1)), glm::vec<3, T>(T(0)), radius);
        if (cm_test::ieee_build && std::isfinite(T(4) * glm::dot(o, o)) && std::isfinite(T(4) * radius * radius)) {
            CAPTURE(o.x);
            CAPTURE(radius);
            CHECK((std::isfinite(t.x) || t.x == T(-1)));
        }
    }
}

TEST_CASE("fuzz integer arguments: cone offsets, noise periods and bake cells never overflow") {
    inputs<float> r(6);
    for (int k = 0; k < rounds; ++k) {
        const int i = r.any_int(), n = r.any_int();
        const glm::vec2 o = cm::cone_kernel_offset<float>(i, n);
        CHECK(ok(o.x));
        CHECK(ok(o.y));
        CHECK(glm::length(o) <= 1.0001f);
        // Coordinates up to 1e30: the fBm's last octave (p 2^7 at 8 octaves) must stay finite
        // (noise.hpp states the limit, about 127 - log2|p| octaves at lacunarity 2).
        glm::vec3 p(r.any(), r.any(), r.any());
        p = glm::clamp(p, glm::vec3(-1e30f), glm::vec3(1e30f));
        const int period = r.any_int();
        const float perlin = cm::perlin_noise(p, period, std::uint32_t(k));
        CHECK(in_range(perlin, -1.0f, 1.0f));
        CHECK(in_range(cm::worley_noise(p, period, std::uint32_t(k)), 0.0f, 1.0f));
        const float fbm = cm::perlin_fbm(p, period, 1 + (k % 8), 2, 0.5f, std::uint32_t(k));
        CHECK(ok(fbm));
        // Bake texels for any cell count (the volumes themselves reject cells > 1024).
        const glm::vec4 texel = cm::bake_base_texel(glm::vec3(r.in(0.0f, 8.0f)), n, std::uint32_t(k));
        CHECK(ok(texel.x));
        const glm::vec3 detail = cm::bake_detail_texel(glm::vec3(r.in(0.0f, 8.0f)), n, std::uint32_t(k));
        CHECK(ok(detail.x));
    }
}

TEST_CASE("fuzz sequences, steps and sampling: in range for any input") {
    inputs<float> r(7);
    for (int k = 0; k < rounds; ++k) {
        const std::uint32_t h = std::uint32_t(r.rng()), f = std::uint32_t(r.rng()), index = std::uint32_t(r.rng());
        CHECK(in_range(cm::frame_jitter(h, f), 0.0f, 0.99999995f));
        CHECK(in_range(cm::sample_jitter(h, f, index), 0.0f, 0.99999995f));
        CHECK(in_range(cm::hash_to_unit<float>(h), 0.0f, 0.99999995f));
        const int most = r.any_int();
        const int sub = cm::refine_substeps(r.any(), most);
        CHECK(sub >= 1);
        CHECK(sub <= (most > 1 ? most : 1));
        const float length = std::fabs(r.any());
        CHECK(in_range(cm::light_march_distance(r.any(), length), 0.0f, length));
        const float t0 = r.in(0.0f, 1e6f), t1 = t0 + r.in(0.0f, 1e6f);
        const float s = cm::march_schedule_distance(r.any(), t0, t1, r.in(1e-3f, 1e6f));
        CHECK(in_range(s, t0 * (1.0f - 1e-6f), t1 * (1.0f + 1e-6f)));
        CHECK(in_range(cm::temporal_blend_weight(std::fabs(r.any()), std::fabs(r.any())), 0.0f, 1.0f));
        // The CPU texture sampler reads inside the texture for any coordinate.
        const glm::ivec3 size(1 + k % 5, 1 + k % 3, 2);
        const float v = cm::texture_trilinear_repeat(glm::vec3(r.any(), r.any(), r.any()), size, [&](int x, int y, int z) {
            CHECK(in_range(x, 0, size.x - 1));
            CHECK(in_range(y, 0, size.y - 1));
            CHECK(in_range(z, 0, size.z - 1));
            return 1.0f;
        });
        // A constant texture reads as itself (NaN for NaN weights: IEEE builds only can tell).
        if (cm_test::ieee_build) CHECK((v == 1.0f || !std::isfinite(v) || std::fabs(v - 1.0f) < 1e-5f));
    }
}
