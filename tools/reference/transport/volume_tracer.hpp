// tools/reference/transport/volume_tracer.hpp: a double-precision volumetric path tracer for
// HETEROGENEOUS media, the ground truth of whole cloud images (docs/lighting_truth.md).
// montecarlo.hpp traces homogeneous spheres and slabs with exact free paths; this tracer
// takes any medium through the `medium` interface below (extinction, majorants along rays,
// where rays leave it) and is validated against montecarlo.hpp on those same shapes
// (tools/reference/transport/test_volume_tracer.cpp). cloud_medium.hpp puts the example renderer's
// cloud field behind that interface.
//
// Use:
//   namespace vt = cloudmath::reference::volume;
//   const vt::homogeneous_sphere sphere(5.0);           // radius 1, sigma_t 5
//   vt::lighting light; light.sun_direction = {0, 0, 1}; light.sun_irradiance = {1, 1, 1};
//   const mc::phase_model phase = mc::make_phase("hg:0.85");
//   const vt::path_tracer tracer(sphere, phase, 1.0, light);  // keeps references to all three
//   auto L = vt::estimate_radiance(tracer, rays, 4096, options);   // one rgb_estimate per ray
//
// Conventions: those of montecarlo.hpp (mu = dot(propagation direction of the path away from
// the camera, direction toward the sun); phase functions integrate to 1). The sun is a
// directional source of perpendicular irradiance `sun_irradiance` (rgb); radiances are in
// the same units per steradian. The extinction is grey, the albedo a scalar, so a path's
// throughput is a scalar and only the light it picks up is rgb.
//
// Methods (Woodcock et al. 1965; Novak et al., "Monte Carlo methods for volumetric light
// transport simulation", Computer Graphics Forum 37(2), 2018, sections 4 and 5; Pharr,
// Jakob & Humphreys, "Physically Based Rendering", 4th ed., ch. 14):
//   - free flights by delta (Woodcock) tracking: tentative collisions at the rate of a
//     majorant, accepted as real with probability sigma_t / majorant. The medium hands out
//     piecewise-constant majorants along the ray, so empty space costs one lookup per
//     stretch; any majorant >= sigma_t gives the same expectation (unbiased), a majorant
//     below sigma_t biases it (the media here are tested for it);
//   - next-event estimation toward the sun at every real collision, the transmittance by
//     ratio tracking (product of 1 - sigma_t / majorant over the tentative collisions) with
//     Russian roulette once it falls below 0.1 (survivors get 0.1: unbiased);
//   - every order of scattering: the throughput is multiplied by the albedo and the phase
//     sample's weight (mc::phase_model: exact for HG mixtures, p_true / p_sampled for
//     tabulated sampling), with the Russian roulette of montecarlo.cpp below 0.2;
//   - a path that leaves the medium picks up lighting::escaped (sky or ground radiance).
//     A camera ray's first flight may be limited to a stretch [t_begin, t_end) with its
//     own background (the renderer's view truncation, see cloud_medium.hpp).
//
// Determinism: each ray's paths run in fixed chunks of 4096 with their own xoshiro256++
// stream keyed by (seed, ray, chunk), reduced in order (montecarlo_detail.hpp): results
// are bit-identical for a seed whatever the thread count.
#ifndef CLOUDMATH_TOOLS_VOLUME_TRACER_HPP
#define CLOUDMATH_TOOLS_VOLUME_TRACER_HPP

#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "montecarlo.hpp"
#include "montecarlo_detail.hpp"

namespace cloudmath::reference::volume {

using mc::vec3;

struct rgb {
    double r = 0.0, g = 0.0, b = 0.0;
};

// Where a ray leaves a medium for good: its distance, and whether it ends on an opaque
// surface (the ground) instead of escaping to the sky.
struct medium_exit {
    double distance = 0.0;
    bool ground = false;
};

// visit(t0, t1, majorant): majorant >= sigma_t everywhere on the ray's stretch [t0, t1);
// return false to stop the traversal.
using majorant_visitor = std::function<bool(double t0, double t1, double majorant)>;

// A participating medium with grey extinction. Lengths in the medium's own unit (the
// extinction is per that unit).
class medium {
public:
    virtual ~medium() = default;
    // sigma_t at p (>= 0).
    [[nodiscard]] virtual double extinction(const vec3& p) const = 0;
    // Where the ray from p along the unit vector d leaves the medium (0 when it never
    // meets it); beyond it the extinction is 0 along the ray.
    [[nodiscard]] virtual medium_exit exit(const vec3& p, const vec3& d) const = 0;
    // Visits stretches of [t_min, t_max) of the ray (p, d) in order with their majorants,
    // until visit returns false. Stretches left out (or visited with majorant 0) must be
    // empty (sigma_t = 0 there).
    virtual void majorants(const vec3& p, const vec3& d, double t_min, double t_max,
                           const majorant_visitor& visit) const = 0;
};

// A homogeneous body: sigma_t inside, 0 outside, handing out the majorant majorant_scale *
// sigma_t on the ray's chord through it (majorant_scale >= 1: a looser bound, the same
// expectation). The shapes below give the chord.
class homogeneous_medium : public medium {
public:
    homogeneous_medium(double sigma_t, double majorant_scale);
    [[nodiscard]] double extinction(const vec3& p) const override;
    [[nodiscard]] medium_exit exit(const vec3& p, const vec3& d) const override;
    void majorants(const vec3& p, const vec3& d, double t_min, double t_max,
                   const majorant_visitor& visit) const override;

protected:
    [[nodiscard]] virtual bool contains(const vec3& p) const = 0;
    // [a, b) of the ray (p, d) inside the body, t >= 0; (0, 0) when it misses.
    [[nodiscard]] virtual std::pair<double, double> chord(const vec3& p, const vec3& d) const = 0;

private:
    double sigma_t_, majorant_;
};

// Sphere of radius 1 at the origin.
class homogeneous_sphere final : public homogeneous_medium {
public:
    explicit homogeneous_sphere(double sigma_t, double majorant_scale = 1.0)
        : homogeneous_medium(sigma_t, majorant_scale) {}

private:
    [[nodiscard]] bool contains(const vec3& p) const override;
    [[nodiscard]] std::pair<double, double> chord(const vec3& p, const vec3& d) const override;
};

// Slab 0 <= z <= tau with sigma_t = 1 (lengths in optical depth).
class homogeneous_slab final : public homogeneous_medium {
public:
    explicit homogeneous_slab(double tau, double majorant_scale = 1.0);

private:
    [[nodiscard]] bool contains(const vec3& p) const override;
    [[nodiscard]] std::pair<double, double> chord(const vec3& p, const vec3& d) const override;
    double tau_;
};

// The light: a directional sun and, optionally, what a path sees when it leaves the medium
// at p along d (ground: it ends on the ground). Empty: black.
struct lighting {
    vec3 sun_direction{0.0, 0.0, 1.0};  // toward the sun, normalised internally
    rgb sun_irradiance{1.0, 1.0, 1.0};  // perpendicular irradiance
    // Optional: the sun's perpendicular irradiance at a point, when it varies (the renderer's
    // physical sky: by altitude); replaces sun_irradiance when set.
    std::function<rgb(const vec3& p)> sun_at;
    std::function<rgb(const vec3& p, const vec3& d, bool ground)> escaped;
};

// A camera ray: its first flight meets the medium only on [t_begin, t_end) (t_end =
// infinity: up to the medium's exit); passing it unscattered it sees `background`
// (when t_end is finite) or lighting::escaped (when it reaches the exit).
struct camera_ray {
    vec3 origin;
    vec3 direction;  // normalised internally
    double t_begin = 0.0;
    double t_end = std::numeric_limits<double>::infinity();
    rgb background;
};

struct rgb_estimate {
    mc::estimate r, g, b;
};

class path_tracer {
public:
    // The medium, the phase function and the light must outlive the tracer. albedo in
    // [0, 1]; max_order = N > 0 keeps light scattered at most N times.
    path_tracer(const medium& m, const mc::phase_model& phase, double albedo,
                const lighting& light, unsigned max_order = 0);

    // One path sample of the radiance reaching the ray's origin against its direction.
    [[nodiscard]] rgb sample(const camera_ray& ray, mc::detail::random_stream& rng) const;

    // Distance of the first real collision on [t0, t1) of the ray (p, d), or infinity
    // (delta tracking).
    [[nodiscard]] double free_flight(const vec3& p, const vec3& d, double t0, double t1,
                                     mc::detail::random_stream& rng) const;
    // Unbiased estimate of the transmittance from p along d over [0, t1) (ratio tracking
    // with Russian roulette).
    [[nodiscard]] double transmittance(const vec3& p, const vec3& d, double t1,
                                       mc::detail::random_stream& rng) const;

private:
    const medium& medium_;
    const mc::phase_model& phase_;
    double albedo_;
    const lighting& light_;
    vec3 sun_;
    unsigned max_order_;
};

// paths_per_ray path samples per ray (fixed chunks, see above): mean and standard error
// per channel. options.max_order is ignored (set it on the tracer).
[[nodiscard]] std::vector<rgb_estimate> estimate_radiance(const path_tracer& tracer,
                                                          const std::vector<camera_ray>& rays,
                                                          std::uint64_t paths_per_ray,
                                                          const mc::run_options& options);

// The same with paths_per_ray[i] paths for ray i (a ray given 0 gets mean and standard error
// 0: callers give every ray at least 2). Same seed and counts -> the same numbers.
[[nodiscard]] std::vector<rgb_estimate> estimate_radiance(const path_tracer& tracer,
                                                          const std::vector<camera_ray>& rays,
                                                          const std::vector<std::uint64_t>& paths_per_ray,
                                                          const mc::run_options& options);

// ---------------------------------------------------------------------------------------
// Paths traced chunk by chunk, for a render that stops and resumes (truth_checkpoint.hpp).
// A chunk is what estimate_radiance runs under one random stream: chunk k of ray i draws
// from the stream (seed, estimate key + i, k), the same stream estimate_radiance gives it, so
// a ray's chunks 0, 1, ... merged in that order are estimate_radiance's numbers to the bit,
// however the chunks were spread over runs. A chunk holds at most mc::detail::paths_per_chunk
// paths.
struct path_tally {
    mc::detail::moments r, g, b;  // sums and sums of squares per channel
    std::uint64_t paths = 0;
    double lookups = 0.0;         // extinction lookups (the pilot's cost measure)
    void merge(const path_tally& o) {
        r.merge(o.r);
        g.merge(o.g);
        b.merge(o.b);
        paths += o.paths;
        lookups += o.lookups;
    }
};
struct chunk_job {
    std::size_t ray = 0;
    std::uint64_t chunk = 0;
    std::uint64_t paths = 0;  // 1 .. paths_per_chunk
};
// One tally per job, in the jobs' order (the threads of options take jobs as they free up).
// Throws std::invalid_argument for a ray index out of range or a path count outside
// [1, paths_per_chunk].
[[nodiscard]] std::vector<path_tally> trace_chunks(const path_tracer& tracer, const std::vector<camera_ray>& rays,
                                                   const std::vector<chunk_job>& jobs, const mc::run_options& options);

// A ray's estimate from its merged tally (the standard error 0 below 2 paths, as
// estimate_radiance's).
[[nodiscard]] rgb_estimate make_rgb_estimate(const path_tally& t);

// ---------------------------------------------------------------------------------------
// Adaptive sampling in two stages (variance reduction that keeps every pixel unbiased).
// A pilot run measures each ray's variance per path and its cost per path; allocate_paths
// then gives each ray the path count that reaches a target total variance at the least
// cost, and a second run with streams independent of the pilot's makes the estimates. The
// counts depend on the pilot only, never on the samples they are averaged with, so each
// ray's mean stays unbiased (a count chosen from the same samples would bias it); the pilot
// is not averaged in.
//
// The pilot: paths_per_ray paths per ray on streams of their own (seed, pilot key); per ray
// its estimate and its mean cost per path, counted as extinction lookups (deterministic,
// unlike a clock) plus one for the path itself.
struct pilot_estimate {
    std::vector<rgb_estimate> radiance;
    std::vector<double> cost_per_path;
};
[[nodiscard]] pilot_estimate estimate_radiance_pilot(const path_tracer& tracer, const std::vector<camera_ray>& rays,
                                                     std::uint64_t paths_per_ray, const mc::run_options& options);

// variance[i]: ray i's variance per path (>= 0; summed over what is estimated), cost[i] its
// cost per path (> 0). Minimises the total cost sum n_i cost_i subject to
// sum variance_i / n_i <= target_variance_sum: n_i proportional to sqrt(variance_i / cost_i)
// (Neyman allocation with costs; Cochran, "Sampling Techniques", 3rd ed., 5.5), each in
// [min_paths, max_paths] (the multiplier found by bisection with those bounds). Throws
// std::invalid_argument on mismatched sizes, a negative or non-finite variance, a cost that
// is not positive and finite, target_variance_sum <= 0, or min_paths < 2 or > max_paths.
// When even max_paths everywhere misses the target, every ray gets max_paths and
// predicted_variance_sum says by how much.
struct path_allocation {
    std::vector<std::uint64_t> paths;
    double predicted_variance_sum = 0.0;  // sum variance_i / n_i
    double predicted_cost = 0.0;          // sum n_i cost_i
};
[[nodiscard]] path_allocation allocate_paths(const std::vector<double>& variance, const std::vector<double>& cost,
                                             double target_variance_sum, std::uint64_t min_paths,
                                             std::uint64_t max_paths);

}  // namespace cloudmath::reference::volume

#endif  // CLOUDMATH_TOOLS_VOLUME_TRACER_HPP
