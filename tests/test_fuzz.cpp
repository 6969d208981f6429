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
#include <cloudmath/fast_math.hpp>
#include <cloudmath/glsl.hpp>
#include <cloudmath/lighting_choice.hpp>
#include <cloudmath/noise_bake.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace cm = cloudmath;

namespace {

// The run's length and streams: 4000 rounds per case from fixed seeds in the suite (about a
// second, deterministic); scripts/fuzz.sh runs more rounds (CLOUDMATH_FUZZ_ROUNDS) on other
// streams (CLOUDMATH_FUZZ_SEED). A malformed value stops the run rather than being ignored.
int env_count(const char* name, int fallback) {
    const char* text = std::getenv(name);
    if (text == nullptr || *text == '\0') return fallback;
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (*end != '\0' || v < 0 || v > 1000000000L) {
        std::fprintf(stderr, "test_fuzz: %s must be a whole number from 0 to 1e9, not '%s'\n", name, text);
        std::exit(2);
    }
    return static_cast<int>(v);
}
int rounds_of_run() {
    static const int n = env_count("CLOUDMATH_FUZZ_ROUNDS", 4000);
    return n;
}
std::uint64_t seed_offset() {
    static const std::uint64_t n = static_cast<std::uint64_t>(env_count("CLOUDMATH_FUZZ_SEED", 0));
    return n;
}

// Random numbers for one type: `any()` mixes moderate values, magnitudes over the whole
// exponent range (both signs) and the special finite values; `in(lo, hi)` is uniform.
template <class T>
struct inputs {
    std::mt19937_64 rng;
    explicit inputs(std::uint64_t seed) : rng(seed + 1000003u * seed_offset()) {}
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
    for (int k = 0; k < rounds_of_run(); ++k) {
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
    for (int k = 0; k < rounds_of_run() / 256 + 1; ++k) {
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
    for (int k = 0; k < rounds_of_run(); ++k) {
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
    for (int k = 0; k < rounds_of_run(); ++k) {
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
    for (int k = 0; k < rounds_of_run(); ++k) {
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
    for (int k = 0; k < rounds_of_run(); ++k) {
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
    for (int k = 0; k < rounds_of_run(); ++k) {
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

// ---------------------------------------------------------------------------------------
// Hardening round 2: every public function has a fuzz entry (ctest coverage.fuzz_public_functions
// fails for a public function that is not called here). What each header promises for any
// input: no undefined behaviour (the sanitized build), finite results for finite inputs in
// the domain, results in their documented ranges.

TEST_CASE_TEMPLATE("fuzz integration, attenuation and the Beer shadow map", T, float, double) {
    inputs<T> r(11);
    for (int k = 0; k < rounds_of_run(); ++k) {
        const T S = std::fabs(r.any()), sigma = std::fabs(r.any()), ds = std::fabs(r.any());
        const T step = cm::integrate_scattering(S, sigma, ds);
        if (cm_test::ieee_build && std::isfinite(S * ds)) {
            CHECK(ok(step));
            CHECK(step >= T(0));
            CHECK(step <= S * ds * T(1.0001) + std::numeric_limits<T>::min());
        }
        cm::march_accumulator<glm::vec<3, T>, T> acc;
        acc.add_segment(glm::vec<3, T>(S), sigma, ds);
        CHECK(in_range(acc.opacity(), T(0), T(1)));
        CHECK(acc.is_opaque(T(1.5)));  // transmittance <= 1 < 1.5
        CHECK(in_range(cm::nubis_attenuation(r.any()), T(0), T(1)));
        // A march of random steps: the texel's optical depth is never negative nor above its total.
        cm::beer_shadow_accumulator<T> shadow;
        T t = r.in(T(0), T(1e6));
        for (int i = 0; i < 8; ++i) {
            const T d = r.in(T(0), T(500));
            shadow.add_step(t, d, r.unit() < T(0.5) ? T(0) : r.in(T(0), T(0.1)));
            t += d;
        }
        const glm::vec<3, T> texel = shadow.texel();
        const T depth = r.any();
        const T tau = cm::beer_shadow_optical_depth(texel, depth);
        CHECK(ok(tau));
        CHECK(in_range(tau, T(0), texel.z));
        CHECK(in_range(cm::beer_shadow_transmittance(texel, depth), T(0), T(1)));
        const glm::vec<3, T> uvd = cm::shadow_map_project(glm::vec<3, T>(r.in(T(-1e5), T(1e5)), r.in(T(-1e5), T(1e5)), r.in(T(-1e5), T(1e5))),
                                                          glm::vec<3, T>(T(0)), glm::vec<3, T>(T(1), T(0), T(0)),
                                                          glm::vec<3, T>(T(0), T(0), T(1)), glm::vec<3, T>(T(0), T(1), T(0)),
                                                          r.in(T(1), T(1e5)));
        CHECK(ok(uvd.x));
        CHECK(ok(uvd.z));
    }
}

TEST_CASE_TEMPLATE("fuzz the other phase functions: finite, non-negative, Schlick's k finite and within 1.002", T, float, double) {
    inputs<T> r(12);
    CHECK(cm::phase_isotropic<T>() > T(0));
    for (int k = 0; k < rounds_of_run(); ++k) {
        const T mu = r.any(), g = r.any();
        for (const T p : {cm::phase_rayleigh(mu), cm::phase_schlick(mu, g), cm::phase_hg_schlick(mu, g)}) {
            CAPTURE(mu);
            CAPTURE(g);
            CHECK(ok(p));
            CHECK(p >= T(0));
        }
        // 1.55 g - 0.55 g^3 peaks at 1.0016 near g = 0.97 (phase_schlick clamps its k).
        CHECK(in_range(cm::schlick_k_from_hg_g(r.in(T(-1), T(1))), T(-1.002), T(1.002)));
    }
}

TEST_CASE_TEMPLATE("fuzz the lighting models' parts and the model choice", T, float, double) {
    inputs<T> r(13);
    for (int k = 0; k < rounds_of_run(); ++k) {
        const T tau = std::fabs(r.any()), mu = r.in(T(-1), T(1)), g = r.in(T(-0.95), T(0.95));
        const T ms = cm::multiple_scattering_with(tau, mu, r.unit(), r.unit(), r.unit(), 1 + int(r.unit() * T(7)),
                                                  [&](T m, T scale) { return cm::phase_hg(m, scale * g); });
        CHECK(ok(ms));
        CHECK(ms >= T(0));
        const cm::diffusion_medium<T> medium = cm::diffusion_similarity(r.any(), r.any());
        CHECK(in_range(medium.s, T(0.001), T(2)));
        CHECK(in_range(medium.kappa, T(0), T(0.9)));
        const T x = std::fmin(std::fabs(r.any()), T(1e6)), y = std::fmin(std::fabs(r.any()), T(1e6));
        T flux = T(0);
        const T U = cm::diffusion_chord_fluence(x, y, std::exp(-x), medium.kappa, flux);
        CHECK(ok(U));
        CHECK(U >= T(0));
        CHECK(ok(flux));
        // Any finite arguments: coordinates in [0, 1] and a lookup inside the table's range.
        const cm::diffusion_coordinates<T> u = cm::diffusion_table_coordinates(r.any(), r.any(), r.any(), r.any(), r.any(), r.any());
        for (const T c : {u.u_sun, u.u_behind, u.u_mu, u.u_surface}) CHECK(in_range(c, T(0), T(1)));
        CHECK(ok(cm::diffusion_table_lookup(cm::diffusion_models::clouds, u)));
        const T d = cm::diffusion_scattering_with(tau, std::fabs(r.any()), std::fabs(r.any()), mu, g, r.unit(),
                                                  cm::diffusion_models::fitted, [&](T m, T scale) { return cm::phase_hg(m, scale * g); });
        CHECK(ok(d));
        CHECK(d >= T(0));
    }
    inputs<float> f(14);
    for (int k = 0; k < rounds_of_run(); ++k) {
        const float lo = f.any(), hi = f.any(), budget = f.any();
        bool extrapolated = false;
        const float e = cm::lighting_model_error(k % cm::lighting_choice_data::model_count, std::fmin(lo, hi), std::fmax(lo, hi), extrapolated);
        CHECK(ok(e));
        CHECK(e >= 0.0f);
        const cm::lighting_model_choice c = cm::choose_lighting_model(lo, hi, budget);
        CHECK(c.name != nullptr);
        if (lo <= hi) CHECK(c.kind != cm::lighting_model_kind::none);
    }
}

TEST_CASE_TEMPLATE("fuzz density: profiles, shapes, fog and air in range for any input", T, float, double) {
    inputs<T> r(15);
    for (int k = 0; k < rounds_of_run(); ++k) {
        const T h = r.any(), type = r.any(), cov = r.any();
        const glm::vec<4, T> base(r.unit(), r.unit(), r.unit(), r.unit());
        const glm::vec<3, T> det(r.unit(), r.unit(), r.unit()), weather(r.any(), r.any(), r.any());
        for (const glm::vec<4, T> profile : {cm::height_profile_stratus<T>(), cm::height_profile_stratocumulus<T>(),
                                             cm::height_profile_cumulus<T>(), cm::height_profile_for_type(type)})
            CHECK(in_range(cm::height_gradient(h, profile), T(0), T(1)));
        CHECK(in_range(cm::height_gradient_for_type(h, type), T(0), T(1)));
        const glm::vec<2, T> band = cm::height_range_for_type(type);
        CHECK(in_range(band.x, T(0), band.y));
        CHECK(in_range(cm::height_fraction(r.any(), r.any(), r.any()), T(0), T(1)));
        // -ffast-math rewrites 0.6 + 0.4 s <= 1 into s <= (1 - 0.6) / 0.4, which rounds below 1
        // in float: the bound holds to an ulp there, exactly in IEEE builds.
        CHECK(in_range(cm::cloud_top_fraction(r.any()), T(0.6), cm_test::ieee_build ? T(1) : T(1.000001)));
        CHECK(in_range(cm::erode(r.any(), r.any()), T(0), T(1)));
        CHECK(in_range(cm::nubis_low_frequency_fbm(base), T(0), T(1)));
        CHECK(in_range(cm::nubis_high_frequency_fbm(det), T(0), T(1)));
        CHECK(ok(cm::nubis_base_cloud(base)));
        CHECK(in_range(cm::nubis_detail_erosion(det, h), T(0), T(1)));
        CHECK(in_range(cm::nubis_density(base, det, cov, type, h), T(0), T(1)));
        CHECK(in_range(cm::cloud_shape_density(base, weather, h, cov, type, r.unit(), r.unit()), T(0), T(1)));
        const T a = r.any(), b = r.any();
        const T m = cm::remap(r.in(T(-4), T(4)), a, b, T(0), T(1));
        if (std::fabs(b - a) > T(1e-3)) CHECK(ok(m));
        // Fog and air inside their domain: altitudes 0..100 km, distances to 1000 km.
        // The ray's end stays above the ground (below it the optical depth is rightly huge).
        const T alt = r.in(T(0), T(1e5)), muz = r.in(T(-1), T(1));
        const T dist = muz < T(0) ? std::fmin(r.in(T(0), T(1e6)), alt / -muz) : r.in(T(0), T(1e6));
        const T fog = cm::height_fog_optical_depth(alt, muz, dist, r.in(T(0), T(1e-3)), r.in(T(1e-5), T(1e-2)));
        CHECK(ok(fog));
        CHECK(fog >= T(0));
        CHECK(in_range(cm::height_fog_density(alt, T(1e-3), T(1e-4)), T(0), T(1e-3)));
        const glm::vec<3, T> air = cm::air_optical_depth(alt, muz, dist);
        CHECK(ok(air.z));
        CHECK(air.x >= T(0));
        const T L = std::fabs(r.any()), Lair = std::fabs(r.any());
        const T seen = cm::aerial_perspective(L, Lair, std::fabs(r.any()));
        CHECK(in_range(seen, std::fmin(L, Lair), std::fmax(L, Lair)));
    }
}

TEST_CASE_TEMPLATE("fuzz geometry, cone, sun, texture LOD and reprojection", T, float, double) {
    inputs<T> r(16);
    for (int k = 0; k < rounds_of_run(); ++k) {
        const T alt = r.in(T(0), T(1e6)), muz = r.in(T(-1), T(1));
        const glm::vec<2, T> t = cm::ray_sphere_intersect_altitude(alt, muz, T(6371e3), r.in(T(0), T(2e4)));
        CHECK((t.x == T(-1) || ok(t.x)));
        CHECK((t.y == T(-1) || ok(t.y)));
        cm::cone_light_config<T> cfg;
        cfg.sample_count = int(r.unit() * T(20)) - 2;
        cfg.step_length = r.in(T(0), T(500));
        cfg.cone_spread = r.in(T(0), T(1));
        cfg.far_distance = r.in(T(-100), T(5000));
        cfg.far_segment_length = r.in(T(0), T(2000));
        const glm::vec<3, T> origin(r.in(T(-1e4), T(1e4))), sun = glm::normalize(glm::vec<3, T>(r.in(T(-1), T(1)), T(0.5), r.in(T(-1), T(1))));
        const T tau = cm::cone_optical_depth(origin, sun, cfg, [](const glm::vec<3, T>&) { return T(0.01); });
        CHECK(ok(tau));
        CHECK(tau >= T(0));
        const int i = int(r.unit() * T(20)) - 2;
        CHECK(ok(cm::cone_sample_distance(cfg, i)));
        CHECK(ok(cm::cone_sample_length(cfg, i)));
        CHECK(ok(cm::cone_sample_position(origin, sun, cfg, i).x));
        const T radius = r.in(T(1e-4), T(1.5));
        CHECK(in_range(cm::cone_solid_angle(radius), T(0), T(4) * cm::pi_v<T>));
        const T disc = cm::sun_disc_radiance(T(1), r.any(), radius, r.any());
        CHECK(ok(disc));
        CHECK(disc >= T(0));
        const T footprint = cm::pixel_footprint(std::fabs(r.any()), r.in(T(0.01), T(10)), r.in(T(1), T(8192)));
        CHECK(footprint >= T(0));
        const T lod = cm::texture_lod(footprint, r.in(T(1e-3), T(1e3)));
        CHECK(lod >= T(0));
        const glm::vec<3, T> forward(T(0), T(0), T(1)), right(T(1), T(0), T(0)), up(T(0), T(1), T(0));
        const glm::vec<3, T> uvz = cm::camera_project(glm::vec<3, T>(r.any(), r.any(), r.any()), forward, right, up, T(0.5), T(16) / T(9));
        CHECK(ok(uvz.z));
        const glm::vec<4, T> fp = cm::texel_bilinear(glm::vec<2, T>(r.in(T(-2), T(2)), r.in(T(-2), T(2))), glm::vec<2, T>(T(320), T(180)));
        CHECK(in_range(fp.z, T(0), T(1)));
        CHECK(in_range(fp.w, T(0), T(1)));
    }
    CHECK(cm::sun_angular_radius<T>() > T(0));
    for (std::uint32_t f = 0; f < 64; ++f) {
        const glm::uvec2 o = cm::temporal_update_offset(f * 2654435761u);
        CHECK(o.x < 4u);
        CHECK(o.y < 4u);
        CHECK(cm::bayer_index_4x4(f * 2654435761u, f * 40503u) < 16u);
    }
}

TEST_CASE_TEMPLATE("fuzz noise: derivatives, curl, Worley and the sequences, finite and in range", T, float, double) {
    inputs<T> r(17);
    for (int k = 0; k < rounds_of_run() / 4; ++k) {
        glm::vec<3, T> p(r.any(), r.any(), r.any());
        p = glm::clamp(p, glm::vec<3, T>(T(-1e30)), glm::vec<3, T>(T(1e30)));
        const int period = int(r.unit() * T(64)) - 4;
        const std::uint32_t seed = std::uint32_t(r.rng());
        CHECK(ok(cm::perlin_noise_derivatives(p, period, seed).x));
        CHECK(ok(cm::curl_noise(p, period, seed).y));
        CHECK(ok(cm::curl_noise(glm::vec<2, T>(p.x, p.y), period, seed).x));
        CHECK(in_range(cm::worley_f1(p, period, seed), T(0), T(2)));
        CHECK(in_range(cm::worley_fbm(p, period, 1 + k % 6, 2, T(0.5), seed), T(0), T(1)));
        CHECK(in_range(cm::worley_fbm_nubis(p, period, seed), T(0), T(1)));
        CHECK(in_range(cm::perlin_worley(p, period, seed), T(0), T(1)));
        const std::uint32_t n = std::uint32_t(r.rng());
        CHECK(in_range(cm::low_discrepancy_r1<T>(n), T(0), T(1)));
        CHECK(in_range(cm::low_discrepancy_r2<T>(n).y, T(0), T(1)));
        CHECK(in_range(cm::triangular_dither<T>(n), T(-1), T(1)));
        CHECK(cm::noise_hash(n) == cm::noise_hash(n));
        CHECK(cm::noise_hash(n, n + 1u, n + 2u, seed) == cm::noise_hash(n, n + 1u, n + 2u, seed));
    }
}

TEST_CASE("fuzz the texture baker: any size and cell count, texels and encodings in range") {
    inputs<float> r(18);
    for (int k = 0; k < rounds_of_run() / 8; ++k) {
        const int cells = r.any_int();
        const glm::vec3 c = cm::bake_curl_texel(glm::vec2(r.in(0.0f, 8.0f), r.in(0.0f, 8.0f)), cells, std::uint32_t(k));
        CHECK(ok(c.x));
        const glm::vec3 w = cm::bake_weather_texel(glm::vec2(r.in(0.0f, 8.0f), r.in(0.0f, 8.0f)), cells, std::uint32_t(k));
        CHECK(in_range(w.x, 0.0f, 1.0f));
        CHECK(ok(cm::bake_coordinate(r.any_int() % 4096, 1 + k % 300, 1 + k % 17)));
        (void)cm::bake_channel_seed(std::uint32_t(k), cm::bake_channel::curl);
        const float v = r.any();
        CHECK(in_range(cm::curl_bake_encode(v), 0.0f, 1.0f));
        CHECK(ok(cm::curl_bake_decode(cm::curl_bake_encode(v))));
        (void)cm::quantize_unorm8(v);
        const glm::ivec2 size(1 + k % 7, 1 + k % 5);
        const float b = cm::texture_bilinear_repeat(glm::vec2(r.any(), r.any()), size, [&](int x, int y) {
            CHECK(in_range(x, 0, size.x - 1));
            CHECK(in_range(y, 0, size.y - 1));
            return 1.0f;
        });
        if (cm_test::ieee_build) CHECK((b == 1.0f || !std::isfinite(b) || std::fabs(b - 1.0f) < 1e-5f));
    }
    // Whole textures: sizes and cell counts from bad to small; an invalid pair bakes nothing.
    for (int size : {-3, 0, 1, 2, 5})
        for (int cells : {-1, 0, 1, 3}) {
            cm::bake_options options;
            options.threads = 2;
            const std::vector<std::uint8_t> base = cm::bake_base_volume(size, cells, options);
            const std::vector<std::uint8_t> detail = cm::bake_detail_volume(size, cells, options);
            const std::vector<std::uint8_t> curl = cm::bake_curl_texture(size, cells, options);
            const std::vector<std::uint8_t> weather = cm::bake_weather_map(size, cells, options);
            const std::size_t n = size > 0 ? std::size_t(size) : 0;
            CHECK((base.empty() || base.size() == n * n * n * 4));
            CHECK((detail.empty() || detail.size() == n * n * n * 3));
            CHECK((curl.empty() || curl.size() == n * n * 3));
            CHECK((weather.empty() || weather.size() == n * n * 3));
            if (size < 1 || cells < 1) CHECK((base.empty() && detail.empty() && curl.empty() && weather.empty()));
            if (size == 2 && cells == 1) CHECK(!base.empty());
        }
}

TEST_CASE("fuzz the fast-math and batch helpers, and the GLSL source functions") {
    inputs<float> r(19);
    for (int k = 0; k < rounds_of_run(); ++k) {
        const float x = r.in(-87.0f, 88.0f);
        const float e = cm::fast::exp(x), v = cm::exp_vectorizable(x);
        CHECK(ok(e));
        CHECK(ok(v));
        CHECK(std::fabs(e - std::exp(x)) <= 6.5e-5f * std::exp(x));
        const float y = r.in(1e-8f, 4.0f);
        CHECK(std::fabs(cm::fast::rsqrt(y) * std::sqrt(y) - 1.0f) <= 2e-3f);
    }
    CHECK(std::string(cm::batch::isa_name(cm::batch::active_isa())).size() > 0);
    // The GLSL sources: every embedded file resolves; unknown modules, missing directories and
    // random include lines give an error message, never a crash.
    const std::vector<std::string_view> names = cm::glsl_file_names();
    CHECK(names.size() > 10);
    for (std::string_view name : names) CHECK(!cm::glsl_embedded_file(name).empty());
    CHECK(cm::glsl_embedded_file("no_such.glsl").empty());
    std::mt19937_64 rng(20);
    const char alphabet[] = "#include \"cloudmath/glsl/phase.glsl\"\n<>/.x";
    for (int k = 0; k < 300; ++k) {
        std::string text;
        for (int i = 0; i < 40; ++i) text += alphabet[rng() % (sizeof alphabet - 1)];
        std::string error;
        (void)cm::glsl_resolve_includes(text, {}, &error);
        (void)cm::glsl_source(text.substr(0, 8), &error);
    }
    std::string error;
    CHECK(cm::glsl_source("no_such_module", &error).empty());
    CHECK(!error.empty());
    error.clear();
    CHECK(cm::glsl_source_from_directory("/no/such/directory", "phase", &error).empty());
    CHECK(!error.empty());
}

TEST_CASE_TEMPLATE("fuzz the sky: scattering, multiple scattering, in-scattering and sky radiance finite and non-negative", T, float, double) {
    inputs<T> r(22);
    const cm::atmosphere_parameters<T> air = cm::earth_atmosphere<T>();
    // A tiny LUT with few directions and steps: the fuzz checks ranges, not accuracy.
    const std::vector<glm::vec<3, T>> lut = cm::atmosphere_multiple_scattering_lut(air, 4, 4, 4, 4, 4);
    const cm::atmosphere_multiple_scattering_table<T> ms{&lut, 4, 4};
    const auto unit = [&]() {
        const glm::vec<3, T> v(r.in(T(-1), T(1)), r.in(T(-1), T(1)), r.in(T(-1), T(1)));
        const T n = std::sqrt(glm::dot(v, v));
        return n > T(1e-3) ? v / n : glm::vec<3, T>(T(0), T(1), T(0));
    };
    for (int k = 0; k < rounds_of_run() / 8; ++k) {
        const T any_altitude = r.any(), any_mu = r.any();
        const glm::vec<3, T> s = cm::atmosphere_scattering_coefficient(air, any_altitude);
        CHECK(ok(s.x));
        CHECK(s.z >= T(0));
        const glm::vec<3, T> p = cm::atmosphere_scattering(air, any_altitude, any_mu);
        if (cm_test::ieee_build || !std::isnan(any_mu)) {
            CHECK(ok(p.y));
            CHECK(p.y >= T(0));
        }
        const T h = r.in(T(0), T(1e5)), mu = r.in(T(-1), T(1));
        const glm::vec<3, T> e = cm::atmosphere_sun_illuminance(air, h, mu, glm::vec<3, T>(T(1e5)));
        for (int c = 0; c < 3; ++c) CHECK(in_range(e[c], T(0), T(1e5)));
        const glm::vec<2, T> uv = cm::atmosphere_multiple_scattering_lut_uv(air, any_altitude, any_mu, glm::vec<2, T>(T(32), T(32)));
        if (cm_test::ieee_build) {
            CHECK(in_range(uv.x, T(0), T(1)));
            CHECK(in_range(uv.y, T(0), T(1)));
        }
        const glm::vec<2, T> am = cm::atmosphere_multiple_scattering_lut_altitude_mu(air, glm::vec<2, T>(r.any(), r.any()), glm::vec<2, T>(T(32), T(32)));
        CHECK(in_range(am.x, T(0), air.top_radius - air.bottom_radius));
        CHECK(in_range(am.y, T(-1), T(1)));
        CHECK(in_range(cm::atmosphere_multiple_scattering_from_lut(air, lut, 4, 4, any_altitude, any_mu).y, T(0), T(1)));
        // The field's source: a vertical moment from none to all of psi, any altitude and view.
        const glm::vec<3, T> field(r.in(T(0), T(1)), r.in(T(0), T(1)), r.in(T(0), T(1)));
        const glm::vec<3, T> src = cm::atmosphere_multiple_scattering_source(air, any_altitude, field, field * r.in(T(0), T(1)), any_mu);
        if (cm_test::ieee_build || (!std::isnan(any_altitude) && !std::isnan(any_mu))) {
            CHECK(ok(src.x));
            CHECK(src.z >= T(0));
        }
        if (k % 16 != 0) continue;  // the marches below cost thousands of exponentials each
        const glm::vec<3, T> psi = cm::atmosphere_multiple_scattering(air, any_altitude, any_mu, 1 + k % 5, 1 + k % 4, 1 + k % 3);
        if (cm_test::ieee_build || (!std::isnan(any_altitude) && !std::isnan(any_mu))) {
            CHECK(ok(psi.x));
            CHECK(psi.z >= T(0));
        }
        const glm::vec<3, T> view = unit(), sun = unit();
        const cm::atmosphere_segment<T> seg = cm::atmosphere_inscatter(air, ms, h, view, sun, r.in(T(-1e3), T(1e7)), 1 + k % 8, 1 + k % 5);
        for (int c = 0; c < 3; ++c) {
            CHECK(in_range(seg.transmittance[c], T(0), T(1)));
            CHECK(ok(seg.radiance[c]));
            CHECK(seg.radiance[c] >= T(0));
        }
        const glm::vec<3, T> sky = cm::atmosphere_sky_radiance(air, ms, h, view, sun, 1 + k % 8, 1 + k % 5);
        CHECK(ok(sky.y));
        CHECK(sky.y >= T(0));
        const glm::vec<3, T> ground = cm::atmosphere_ground_irradiance(air, ms, r.in(T(-1), T(1)), 1 + k % 6, 1 + k % 4, 1 + k % 3);
        CHECK(ok(ground.z));
        CHECK(ground.z >= T(0));
        // The sky-lit ground: any size of values, any view and sun.
        const std::vector<glm::vec<3, T>> on_ground = cm::atmosphere_ground_irradiance_lut(air, ms, k % 5, 1 + k % 4, 1 + k % 3, 1 + k % 2);
        REQUIRE(on_ground.size() == static_cast<std::size_t>(std::max(k % 5, 2)));
        for (const glm::vec<3, T>& irradiance : on_ground) CHECK((ok(irradiance.y) && irradiance.y >= T(0)));
        const cm::atmosphere_multiple_scattering_table<T> lit{&lut, 4, 4, nullptr, &on_ground};
        const glm::vec<3, T> seen = cm::atmosphere_sky_radiance(air, lit, h, view, sun, 1 + k % 8, 1 + k % 5);
        CHECK(ok(seen.x));
        CHECK(seen.x >= sky.x * T(0.9999));  // the sky's light on the ground only adds
    }
    // The refined LUT and its moments: finite and non-negative for odd sizes, counts and passes
    // (0 and 1 too); the moment never above the mean (a squared cosine is at most 1).
    for (int k = 0; k < 6; ++k) {
        std::vector<glm::vec<3, T>> moments;
        const std::vector<glm::vec<3, T>> refined =
            cm::atmosphere_multiple_scattering_refined_lut(air, 2 + k % 3, 2 + k % 2, k % 3, 1 + k, 1 + k % 4, 1 + k % 2, &moments);
        REQUIRE(moments.size() == refined.size());
        for (std::size_t i = 0; i < refined.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                CHECK(ok(refined[i][c]));
                CHECK(refined[i][c] >= T(0));
                CHECK(moments[i][c] >= T(0));
                CHECK(moments[i][c] <= refined[i][c] * T(1.0001) + T(1e-30));
            }
    }
    // The sky's LUTs with every output (atmosphere_make_sky_luts: the moments and the aerosol
    // field), for odd sizes, counts and passes: finite and non-negative, and the sky through
    // them for any view and sun (the sun below the horizon too).
    for (int k = 0; k < 4; ++k) {
        const cm::atmosphere_sky_luts<T> luts = cm::atmosphere_make_sky_luts(air, 2 + k % 3, 2 + k % 2, k % 3, 1 + k, 1 + k % 4, 1 + k % 2);
        const std::size_t texels = std::size_t(luts.width) * std::size_t(luts.height);
        REQUIRE(luts.texels.size() == texels);
        REQUIRE(luts.sun_azimuth_moments.size() == texels);
        REQUIRE(luts.aerosol_field.size() == texels * std::size_t(cm::atmosphere_aerosol_field_nodes));
        for (const glm::vec<3, T>& v : luts.aerosol_field) CHECK((ok(v.x) && ok(v.z) && v.x >= T(0) && v.z >= T(0)));
        for (const glm::vec<3, T>& v : luts.sun_azimuth_moments) CHECK((ok(v.y) && v.y >= T(0)));
        const cm::atmosphere_multiple_scattering_table<T> table = luts.table();
        for (int q = 0; q < 8; ++q) {
            const glm::vec<3, T> seen = cm::atmosphere_sky_radiance(air, table, r.in(T(0), T(1e5)), unit(), unit(), 1 + q % 6, 1 + q % 3);
            for (int c = 0; c < 3; ++c) CHECK((ok(seen[c]) && seen[c] >= T(0)));
        }
        // Stacked for a shader: every part's block, finite and non-negative.
        const std::vector<glm::vec<3, T>> stacked = cm::atmosphere_stacked_table(luts);
        REQUIRE(stacked.size() == texels * std::size_t(cm::atmosphere_stacked_table_parts));
        for (const glm::vec<3, T>& v : stacked) CHECK((ok(v.x) && ok(v.y) && ok(v.z) && v.x >= T(0) && v.y >= T(0) && v.z >= T(0)));
    }
    // LUTs with missing or short parts, or no size: zero blocks, never a read past the end.
    cm::atmosphere_sky_luts<T> partial;
    partial.width = 3;
    partial.height = 2;
    partial.texels.assign(6, glm::vec<3, T>(T(1)));
    partial.aerosol_field.assign(5, glm::vec<3, T>(T(1)));  // short of even one node's block
    const std::vector<glm::vec<3, T>> stacked = cm::atmosphere_stacked_table(partial);
    REQUIRE(stacked.size() == 6u * std::size_t(cm::atmosphere_stacked_table_parts));
    for (std::size_t i = 0; i < stacked.size(); ++i) CHECK(stacked[i].x == (i < 6 ? T(1) : T(0)));
    partial.width = -4;
    CHECK(cm::atmosphere_stacked_table(partial).empty());
}

TEST_CASE_TEMPLATE("fuzz the atmosphere: extinction, optical depth and transmittance in range, the LUT mapping inside it", T, float, double) {
    inputs<T> r(21);
    const cm::atmosphere_parameters<T> air = cm::earth_atmosphere<T>();
    const std::vector<glm::vec<3, T>> lut = cm::atmosphere_transmittance_lut(air, 16, 8, 8);
    for (int k = 0; k < rounds_of_run() / 8; ++k) {
        const T any_altitude = r.any(), any_mu = r.any();
        const glm::vec<3, T> sigma = cm::atmosphere_extinction(air, any_altitude);
        CHECK(ok(sigma.x));
        CHECK(sigma.z >= T(0));
        // Inside the domain: altitudes from the ground to 100 km, any zenith cosine.
        const T h = r.in(T(0), T(1e5)), mu = r.in(T(-1), T(1));
        const T d = cm::atmosphere_distance_to_top(air, h, mu);
        CHECK(ok(d));
        CHECK(d >= T(0));
        const bool ground = cm::atmosphere_ray_hits_ground(air, h, mu);
        if (ground) CHECK(mu < T(0));
        const glm::vec<3, T> tau = cm::atmosphere_optical_depth(air, h, mu, r.in(T(0), T(1e6)), 1 + k % 16);
        CHECK(ok(tau.y));
        CHECK(tau.y >= T(0));
        const glm::vec<3, T> t = cm::atmosphere_transmittance(air, h, mu, 1 + k % 32);
        for (int c = 0; c < 3; ++c) CHECK(in_range(t[c], T(0), T(1)));
        CHECK(in_range(cm::atmosphere_transmittance_from_lut(air, lut, 16, 8, h, mu).y, T(0), T(1)));
        // The LUT mapping for any input lands inside the texture and inside the domain.
        const glm::vec<2, T> uv = cm::atmosphere_transmittance_lut_uv(air, any_altitude, any_mu, glm::vec<2, T>(T(256), T(64)));
        if (cm_test::ieee_build) {
            CHECK(in_range(uv.x, T(0), T(1)));
            CHECK(in_range(uv.y, T(0), T(1)));
        }
        const glm::vec<2, T> am = cm::atmosphere_transmittance_lut_altitude_mu(air, glm::vec<2, T>(r.any(), r.any()), glm::vec<2, T>(T(256), T(64)));
        CHECK(in_range(am.x, T(0), air.top_radius - air.bottom_radius + T(1)));
        CHECK(in_range(am.y, T(-1), T(1)));
        // EV100 inside its domain (positive aperture, time and sensitivity) and exposure.
        const T ev = cm::ev100_from_camera(r.in(T(0.5), T(64)), r.in(T(1e-5), T(60)), r.in(T(25), T(102400)));
        CHECK(ok(ev));
        CHECK(ok(cm::ev100_from_luminance(r.in(T(1e-6), T(1e9)))));
        CHECK(cm::exposure_from_ev100(r.in(T(-10), T(30))) > T(0));
    }
}
