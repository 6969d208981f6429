// The timed loops of the speed-against-error report (bench/report/speed_vs_error.cpp).
//
// They live in their own small translation unit, kernels.cpp, on purpose: in the report's
// large file GCC's inliner runs out of budget and leaves some library calls out of line
// (fast::phase_hg, the exp kernel, batch HG's per-element kernel, which then also stops the
// batch loop from vectorising). Here every call inlines as it would in a user's file, so
// the times measure the code, not the size of the file that calls it. The batch wrappers
// are also what the report measures the batch errors with, so the timed code and the
// measured code are the same.
#ifndef CLOUDMATH_REPORT_KERNELS_HPP
#define CLOUDMATH_REPORT_KERNELS_HPP

#include <cstddef>

#include <glm/vec3.hpp>

#include <cloudmath/phase.hpp>

#include "naive.hpp"

namespace cm_report {

// A smooth analytic extinction field (1/m) for the light-march comparison: between 0.002
// and 0.022 1/m with features of a few hundred metres, so the optical depth over a 1 km
// light path is a few to twenty. Templated so the report evaluates it in long double too.
template <class T>
T cloud_extinction(T x, T y, T z) {
    using std::cos;
    using std::sin;
    return T(0.01) * (T(1.2) + sin(T(0.004) * x + T(0.3)) * sin(T(0.005) * y + T(1.1)) * cos(T(0.003) * z - T(0.7)));
}

// Cone used by the report: 6 samples, 5 near ones every 100 m (midpoints 50 .. 450 m) and
// the far one at 750 m standing for 500 m, so the samples cover the same 1 km as the marches.
inline constexpr float light_path_length = 1000.0f;
inline constexpr int cone_samples = 6;
inline constexpr float cone_step = 100.0f, cone_far_distance = 750.0f, cone_far_length = 500.0f;

// Inputs of one timed pass (arrays in random order, see speed_vs_error.cpp).
struct pass_inputs {
    std::size_t n = 0;            // length of the light-function arrays
    const float* mu = nullptr;    // cosines, uniform on [-1, 1]
    const float* tau = nullptr;   // optical depths
    const float* S = nullptr;     // step source terms
    const float* sigma = nullptr; // step extinctions, 1/m
    const float* droplet_d = nullptr;  // Mie fit diameters, um
    float* out = nullptr;         // batch output, n elements
    float g = 0.8f, alpha = 22.0f, ds = 10.0f;
    cloudmath::mie_approx_parameters<float> mie{};  // precomputed Mie fit parameters
    const cm_naive::phase_table<float>* mie_table = nullptr;
    std::size_t n_heavy = 0;      // length of the march arrays
    const glm::vec3* origin = nullptr;
    const glm::vec3* dir = nullptr;
    const float* sigma_slab = nullptr;  // homogeneous-slab extinctions, 1/m (1 km slab)
};

// The three optical depths of input i of the diffusion model's pass: tau[i] toward the sun,
// the same array read at two other positions for behind and from the camera.
inline void diffusion_depths(const float* tau, std::size_t n, std::size_t i, float& behind, float& view) {
    behind = tau[(i * 7u + 3u) % n];
    view = tau[(i * 13u + 5u) % n] * 0.25f;
}

namespace kernels {

// Scalar passes: one call per input, each result kept in a register (an empty asm sink), so
// calls are neither removed nor vectorised across inputs.
void hg_library(const pass_inputs& in);
void hg_naive(const pass_inputs& in);
void hg_fast(const pass_inputs& in);
void hg_schlick(const pass_inputs& in);
void cornette_shanks_library(const pass_inputs& in);
void cornette_shanks_naive(const pass_inputs& in);
void draine_library(const pass_inputs& in);
void draine_naive(const pass_inputs& in);
void mie_per_call(const pass_inputs& in);  // diameter per element
void mie_precomputed(const pass_inputs& in);
void mie_table(const pass_inputs& in);

void beer_library(const pass_inputs& in);
void beer_naive(const pass_inputs& in);
void beer_fast(const pass_inputs& in);
void exp_vectorizable_scalar(const pass_inputs& in);
void powder_library(const pass_inputs& in);  // k = 2
void powder_fast(const pass_inputs& in);
void beer_powder_library(const pass_inputs& in);
void beer_powder_naive(const pass_inputs& in);
void beer_powder_fast(const pass_inputs& in);
void nubis_library(const pass_inputs& in);
void nubis_naive(const pass_inputs& in);

void step_library(const pass_inputs& in);
void step_clamped(const pass_inputs& in);
void step_riemann(const pass_inputs& in);
void slab_riemann(const pass_inputs& in, int steps);
void slab_exact(const pass_inputs& in, int steps);

void ray_sphere_altitude(const pass_inputs& in);  // camera 1.8 m, sphere 1500 m, R = 6371 km
void ray_sphere_naive(const pass_inputs& in);
void ray_sphere_haines(const pass_inputs& in);

void multiple_scattering_library(const pass_inputs& in, int octaves);  // a = b = c = 0.5
void multiple_scattering_fast(const pass_inputs& in, int octaves);
void multiple_scattering_naive(const pass_inputs& in, int octaves);
// diffusion_scattering (diffusion_models::fitted, albedo 0.99): tau_sun = tau[i], tau_behind and
// tau_view from the same array at other indices (diffusion_depths below).
void diffusion_library(const pass_inputs& in);

void cone(const pass_inputs& in, float spread);
void light_march(const pass_inputs& in, int steps);

// The same computations for one input, for the error measurement of the variants whose
// scalar result is more than one library call.
float slab_riemann_value(float sigma, int steps);
float slab_exact_value(float sigma, int steps);
float ray_sphere_altitude_value(float h, float mu, float R, float H);
float ray_sphere_haines_value(float h, float mu, float R, float H);
float cone_value(const glm::vec3& origin, const glm::vec3& dir, float spread);
float light_march_value(const glm::vec3& origin, const glm::vec3& dir, int steps);

// Batch forms (also used to measure the batch errors).
void batch_hg_exact(const float* mu, std::size_t n, float g, float* out);
void batch_hg_fast(const float* mu, std::size_t n, float g, float* out);
void batch_cornette_shanks_exact(const float* mu, std::size_t n, float g, float* out);
void batch_mie(const float* mu, std::size_t n, const cloudmath::mie_approx_parameters<float>& p, float* out);
void batch_beer_exact(const float* tau, std::size_t n, float* out);
void batch_beer_fast(const float* tau, std::size_t n, float* out);
void exp_vectorizable_loop(const float* tau, std::size_t n, float* out);  // plain loop, no batch function
void batch_beer_powder_exact(const float* tau, std::size_t n, float* out);
void batch_beer_powder_fast(const float* tau, std::size_t n, float* out);
void batch_nubis_exact(const float* tau, std::size_t n, float* out);
void batch_integrate(const float* S, const float* sigma, std::size_t n, float ds, float* out);
void batch_multiple_scattering_exact(const float* tau, const float* mu, std::size_t n, float g, float a, float b, float c,
                                     int octaves, float* out);
void batch_multiple_scattering_fast(const float* tau, const float* mu, std::size_t n, float g, float a, float b, float c,
                                    int octaves, float* out);

// Forces the stores of a batch call to happen before the timer stops.
void sink_memory(const void* p) noexcept;

}  // namespace kernels
}  // namespace cm_report

#endif  // CLOUDMATH_REPORT_KERNELS_HPP
