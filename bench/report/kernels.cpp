// The timed loops of the speed-against-error report; see kernels.hpp for why they are a
// translation unit of their own.
#include "kernels.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <cloudmath/batch.hpp>
#include <cloudmath/cloudmath.hpp>
#include <cloudmath/fast_math.hpp>

namespace cm = cloudmath;

namespace cm_report {
namespace kernels {
namespace {

// Keeps one result in a register: it must be computed, but nothing is stored and the loop
// is not vectorised across calls.
inline void sink(float v) noexcept {
#if defined(__x86_64__)
    __asm__ __volatile__("" : : "x"(v));
#else
    __asm__ __volatile__("" : : "r,m"(v));
#endif
}

float extinction_at(const glm::vec3& p) { return cloud_extinction(p.x, p.y, p.z); }

constexpr float earth_radius = 6371e3f;

}  // namespace

void sink_memory(const void* p) noexcept { __asm__ __volatile__("" : : "r"(p) : "memory"); }

// ---------------------------------------------------------------------------------------
// phase.hpp: (mu[i], g) with g the same for the whole pass (a uniform in a shader).

void hg_library(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::phase_hg(in.mu[i], g));
}
void hg_naive(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::phase_hg(in.mu[i], g));
}
void hg_fast(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::fast::phase_hg(in.mu[i], g));
}
void hg_schlick(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::phase_hg_schlick(in.mu[i], g));
}
void cornette_shanks_library(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::phase_cornette_shanks(in.mu[i], g));
}
void cornette_shanks_naive(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::phase_cornette_shanks(in.mu[i], g));
}
void draine_library(const pass_inputs& in) {
    const float g = in.g, alpha = in.alpha;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::phase_draine(in.mu[i], g, alpha));
}
void draine_naive(const pass_inputs& in) {
    const float g = in.g, alpha = in.alpha;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::phase_draine(in.mu[i], g, alpha));
}
// The diameter varies per element: with one constant diameter the parameter computation
// could be hoisted out of the loop, which is the other variant.
void mie_per_call(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::phase_mie_approx(in.mu[i], in.droplet_d[i]));
}
void mie_precomputed(const pass_inputs& in) {
    const cm::mie_approx_parameters<float> p = in.mie;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::phase_mie_approx(in.mu[i], p));
}
void mie_table(const pass_inputs& in) {
    const cm_naive::phase_table<float>& table = *in.mie_table;
    for (std::size_t i = 0; i < in.n; ++i) sink(table(in.mu[i]));
}

// ---------------------------------------------------------------------------------------
// transmittance.hpp and the fast exponentials: tau[i].

void beer_library(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::beer_lambert(in.tau[i]));
}
void beer_naive(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::beer_lambert(in.tau[i]));
}
void beer_fast(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::fast::beer_lambert(in.tau[i]));
}
void exp_vectorizable_scalar(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::exp_vectorizable(-in.tau[i]));
}
void powder_library(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::powder(in.tau[i], 2.0f));
}
void powder_fast(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::fast::powder(in.tau[i], 2.0f));
}
void beer_powder_library(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::beer_powder(in.tau[i]));
}
void beer_powder_naive(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::beer_powder(in.tau[i]));
}
void beer_powder_fast(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::fast::beer_powder(in.tau[i]));
}
void nubis_library(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::nubis_attenuation(in.tau[i]));
}
void nubis_naive(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::nubis_attenuation(in.tau[i]));
}

// ---------------------------------------------------------------------------------------
// integration.hpp

void step_library(const pass_inputs& in) {
    const float ds = in.ds;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::integrate_scattering(in.S[i], in.sigma[i], ds));
}
void step_clamped(const pass_inputs& in) {
    const float ds = in.ds;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::integrate_scattering_clamped(in.S[i], in.sigma[i], ds));
}
void step_riemann(const pass_inputs& in) {
    const float ds = in.ds;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::integrate_scattering_riemann(in.S[i], in.sigma[i], ds));
}

// A homogeneous slab 1 km thick with source S = 1/m, marched in `steps` equal steps: the
// radiance leaving it. Riemann: S ds per step, then the step's transmittance.
float slab_riemann_value(float sigma, int steps) {
    const float ds = light_path_length / static_cast<float>(steps);
    float luminance = 0.0f, transmittance = 1.0f;
    for (int i = 0; i < steps; ++i) {
        luminance += transmittance * cm_naive::integrate_scattering_riemann(1.0f, sigma, ds);
        transmittance *= cm_naive::beer_lambert(sigma * ds);
    }
    return luminance;
}
float slab_exact_value(float sigma, int steps) {
    const float ds = light_path_length / static_cast<float>(steps);
    cm::march_accumulator<float, float> acc;
    for (int i = 0; i < steps; ++i) acc.add_segment(1.0f, sigma, ds);
    return acc.luminance;
}
void slab_riemann(const pass_inputs& in, int steps) {
    for (std::size_t i = 0; i < in.n_heavy; ++i) sink(slab_riemann_value(in.sigma_slab[i], steps));
}
void slab_exact(const pass_inputs& in, int steps) {
    for (std::size_t i = 0; i < in.n_heavy; ++i) sink(slab_exact_value(in.sigma_slab[i], steps));
}

// ---------------------------------------------------------------------------------------
// geometry.hpp: first root at t >= 0 from altitude h to the sphere at altitude H.

float ray_sphere_altitude_value(float h, float mu, float R, float H) {
    const glm::vec2 roots = cm::ray_sphere_intersect_altitude(h, mu, R, H);
    return roots.x >= 0.0f ? roots.x : roots.y;
}
// The general form, as an engine calls it: a vec3 origin at R + h over the planet centre.
float ray_sphere_haines_value(float h, float mu, float R, float H) {
    const glm::vec3 origin(0.0f, R + h, 0.0f);
    const glm::vec3 dir(std::sqrt(std::max(0.0f, (1.0f - mu) * (1.0f + mu))), mu, 0.0f);
    const glm::vec2 roots = cm::ray_sphere_intersect(origin, dir, glm::vec3(0.0f), R + H);
    return roots.x >= 0.0f ? roots.x : roots.y;
}
void ray_sphere_altitude(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(ray_sphere_altitude_value(1.8f, in.mu[i], earth_radius, 1500.0f));
}
void ray_sphere_naive(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::ray_sphere_first_hit(1.8f, in.mu[i], earth_radius, 1500.0f));
}
void ray_sphere_haines(const pass_inputs& in) {
    for (std::size_t i = 0; i < in.n; ++i) sink(ray_sphere_haines_value(1.8f, in.mu[i], earth_radius, 1500.0f));
}

// ---------------------------------------------------------------------------------------
// multiple_scattering.hpp: (tau[i], mu[i]), g = 0.8, a = b = c = 0.5, run-time octave count.

void multiple_scattering_library(const pass_inputs& in, int octaves) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::multiple_scattering(in.tau[i], in.mu[i], g, 0.5f, 0.5f, 0.5f, octaves));
}
void multiple_scattering_fast(const pass_inputs& in, int octaves) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm::fast::multiple_scattering(in.tau[i], in.mu[i], g, 0.5f, 0.5f, 0.5f, octaves));
}
void diffusion_library(const pass_inputs& in) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) {
        float behind, view;
        diffusion_depths(in.tau, in.n, i, behind, view);
        sink(cm::diffusion_scattering(in.tau[i], behind, view, in.mu[i], g, 0.99f, cm::diffusion_models::fitted));
    }
}
void multiple_scattering_naive(const pass_inputs& in, int octaves) {
    const float g = in.g;
    for (std::size_t i = 0; i < in.n; ++i) sink(cm_naive::multiple_scattering(in.tau[i], in.mu[i], g, 0.5f, 0.5f, 0.5f, octaves));
}

// ---------------------------------------------------------------------------------------
// cone_sampling.hpp: optical depth over 1 km toward the light.

float cone_value(const glm::vec3& origin, const glm::vec3& dir, float spread) {
    const cm::cone_light_config<float> cfg{cone_samples, cone_step, spread, cone_far_distance, cone_far_length};
    return cm::cone_optical_depth(origin, dir, cfg, extinction_at);
}
float light_march_value(const glm::vec3& origin, const glm::vec3& dir, int steps) {
    return cm_naive::light_march_optical_depth(origin, dir, light_path_length, steps, extinction_at);
}
void cone(const pass_inputs& in, float spread) {
    for (std::size_t i = 0; i < in.n_heavy; ++i) sink(cone_value(in.origin[i], in.dir[i], spread));
}
void light_march(const pass_inputs& in, int steps) {
    for (std::size_t i = 0; i < in.n_heavy; ++i) sink(light_march_value(in.origin[i], in.dir[i], steps));
}

// ---------------------------------------------------------------------------------------
// Batch forms.

void batch_hg_exact(const float* mu, std::size_t n, float g, float* out) { cm::batch::phase_hg<cm::exact_math>(mu, n, g, out); }
void batch_hg_fast(const float* mu, std::size_t n, float g, float* out) { cm::batch::phase_hg<cm::fast_math>(mu, n, g, out); }
void batch_cornette_shanks_exact(const float* mu, std::size_t n, float g, float* out) {
    cm::batch::phase_cornette_shanks<cm::exact_math>(mu, n, g, out);
}
void batch_mie(const float* mu, std::size_t n, const cm::mie_approx_parameters<float>& p, float* out) {
    cm::batch::phase_mie_approx(mu, n, p, out);
}
void batch_beer_exact(const float* tau, std::size_t n, float* out) { cm::batch::beer_lambert<cm::exact_math>(tau, n, out); }
void batch_beer_fast(const float* tau, std::size_t n, float* out) { cm::batch::beer_lambert<cm::fast_math>(tau, n, out); }
void exp_vectorizable_loop(const float* tau, std::size_t n, float* out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = cm::exp_vectorizable(-tau[i]);
}
void batch_beer_powder_exact(const float* tau, std::size_t n, float* out) { cm::batch::beer_powder<cm::exact_math>(tau, n, out); }
void batch_beer_powder_fast(const float* tau, std::size_t n, float* out) { cm::batch::beer_powder<cm::fast_math>(tau, n, out); }
void batch_nubis_exact(const float* tau, std::size_t n, float* out) { cm::batch::nubis_attenuation<cm::exact_math>(tau, n, out); }
void batch_integrate(const float* S, const float* sigma, std::size_t n, float ds, float* out) {
    cm::batch::integrate_scattering(S, sigma, n, ds, out);
}
void batch_multiple_scattering_exact(const float* tau, const float* mu, std::size_t n, float g, float a, float b, float c,
                                     int octaves, float* out) {
    cm::batch::multiple_scattering<cm::exact_math>(tau, mu, n, g, a, b, c, octaves, out);
}
void batch_multiple_scattering_fast(const float* tau, const float* mu, std::size_t n, float g, float a, float b, float c,
                                    int octaves, float* out) {
    cm::batch::multiple_scattering<cm::fast_math>(tau, mu, n, g, a, b, c, octaves, out);
}

}  // namespace kernels
}  // namespace cm_report
