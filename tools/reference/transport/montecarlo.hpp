// tools/reference/transport/montecarlo.hpp: the Monte Carlo reference of cloudmath, a double-precision
// volumetric path tracer for homogeneous media (plane-parallel slab, sphere), the ground truth
// the library's real-time lighting approximations are measured against.
//
// Use:
//   namespace mc = cloudmath::reference::mc;
//   const mc::phase_model p = mc::make_phase("hg:0.85");
//   mc::run_options opt; opt.threads = 2; opt.seed = 7;
//   mc::slab_flux_result f = mc::trace_slab({1.0, 1.0, 1.0}, p, 1000000, 20, opt);
//   // f.reflected.mean +- f.reflected.std_error ...
//   auto cam = mc::make_sphere_camera_line(90.0, 9);
//   auto L = mc::sphere_radiance({10.0, 1.0, cam.sun_direction}, p, cam.rays, 100000, opt);
//
// Conventions (those of include/cloudmath/phase.hpp):
//   mu = cosine of the scattering angle = dot(view_dir, light_dir), view_dir pointing away
//   from the camera, light_dir toward the light; mu = +1 is forward scattering. A photon
//   travelling along w_in and scattered into w_out has mu = dot(w_in, w_out).
//   Phase functions integrate to 1 over the sphere (1/sr).
//   The sun is a directional source of perpendicular irradiance F0 = 1. Radiances are L/F0
//   (units 1/sr); the direct solar beam (a delta in direction) is never part of a radiance.
//
// Methods (Marchuk et al., "The Monte Carlo Methods in Atmospheric Optics", Springer 1980;
// Pharr, Jakob & Humphreys, "Physically Based Rendering", 3rd ed. 2016, ch. 13-15 and
// section 15.2 for volumetric path tracing with next-event estimation):
//   - free paths are sampled exactly, exp(-s) in optical units (homogeneous medium);
//   - forward tracing (trace_slab) is analog: a collision absorbs the photon with
//     probability 1 - albedo, so every photon ends in exactly one of R, T_diffuse,
//     T_direct, A (or "beyond the maximum order"), and their sum is 1 per photon;
//   - backward tracing (slab_radiance, sphere_radiance) starts at the camera, adds at every
//     scattering vertex throughput * albedo * p(mu) * (transmittance toward the sun), then
//     multiplies the throughput by albedo, samples the phase function and continues;
//     Russian roulette below a throughput of 0.2 (survivors get 0.2: unbiased);
//   - phase functions that cannot be inverted in closed form are sampled from a
//     piecewise-linear tabulation and the throughput is multiplied by p_true / p_sampled,
//     which keeps every estimator unbiased (measured |weight - 1| per scattering: < 3e-4 for
//     cs:0.85 and mie_approx up to 50 um, 2e-3 for cs:0.99);
//   - max_order = N > 0 keeps only light scattered at most N times (1 = single scattering).
//
// Determinism: work is split into fixed chunks, each with its own random stream derived from
// (seed, chunk key) by splitmix64 into a xoshiro256++ generator (Blackman & Vigna, "Scrambled
// linear pseudorandom number generators", ACM TOMS 47, 2021). Chunks are reduced in a fixed
// order, so results are bit-identical for a given seed whatever the thread count.
// Standard errors: sqrt(sample variance / N) over the per-photon (per-path) values.
#ifndef CLOUDMATH_TOOLS_MONTECARLO_HPP
#define CLOUDMATH_TOOLS_MONTECARLO_HPP

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "phase_table.hpp"

namespace cloudmath::reference::mc {

// A Monte Carlo estimate: sample mean, its standard error and the number of samples.
struct estimate {
    double mean = 0.0;
    double std_error = 0.0;
    std::uint64_t samples = 0;
};

struct vec3 {
    double x = 0.0, y = 0.0, z = 0.0;
};

// ---------------------------------------------------------------------------------------
// Phase functions. A model is a mixture of lobes; the specs are
//   isotropic | rayleigh | hg:G | dual_hg:G0,G1,W | cs:G | draine:G,ALPHA | mie_approx:D_UM
//   | table:PATH
// with the functions of cloudmath/phase.hpp (dual_hg = (1 - W) HG(G0) + W HG(G1);
// mie_approx = Jendersie & d'Eon 2023 fit for droplet diameter D in micrometres).
// Sampling: isotropic and HG lobes exactly (sample_phase_hg); Rayleigh, Cornette-Shanks,
// Draine and the Draine lobe of mie_approx from their tabulation on default_angles_deg()
// (piecewise linear in mu) with weight p_true / p_sampled. "table:PATH" reads a phase table
// (read_phase_table) and is both evaluated and sampled as that table, divided by its exact
// integral, so its weight is 1.
class phase_model {
public:
    struct sample_result {
        double mu;      // cosine of the scattering angle
        double weight;  // p_true(mu) / pdf(mu); exactly 1 when exact_sampling()
    };

    // Phase function in 1/sr at cosine mu (clamped to [-1, 1]).
    [[nodiscard]] double evaluate(double mu) const;
    // Density, per steradian, of the mu returned by sample().
    [[nodiscard]] double sampling_pdf(double mu) const;
    // Draws mu for u uniform in [0, 1).
    [[nodiscard]] sample_result sample(double u) const;
    // True when sample() draws exactly from evaluate() (every weight is 1).
    [[nodiscard]] bool exact_sampling() const { return exact_; }
    [[nodiscard]] const std::string& spec() const { return spec_; }

    enum class shape { isotropic, hg, rayleigh, cornette_shanks, draine, table };
    struct lobe {
        shape kind = shape::isotropic;
        double weight = 1.0;  // mixture weight, the weights sum to 1
        double g = 0.0;
        double alpha = 0.0;
        // Tabulation the lobe is sampled from (and, for shape::table, evaluated as).
        std::shared_ptr<const phase_table> table;
    };
    // A mixture of lobes (weights are normalised to sum 1; zero-weight lobes are dropped).
    // make_phase is the usual way to build one. Throws std::invalid_argument for no lobe of
    // positive weight or a tabulated lobe without its table.
    phase_model(std::string spec, std::vector<lobe> lobes);

private:
    std::string spec_;
    std::vector<lobe> lobes_;
    bool exact_ = true;
};

// Parses a spec (see above). Throws std::invalid_argument naming the problem for a malformed
// spec or a parameter out of range (|g| >= 1, W outside [0, 1], ALPHA < 0, D outside
// (0, 50]); read_phase_table's std::runtime_error (naming the path) for an unreadable table.
[[nodiscard]] phase_model make_phase(const std::string& spec);

// ---------------------------------------------------------------------------------------
// Run options shared by every estimator.
using progress_callback = std::function<void(double fraction_done)>;

struct run_options {
    std::uint64_t seed = 1;
    unsigned threads = 1;    // 0 = std::thread::hardware_concurrency()
    unsigned max_order = 0;  // 0 = all orders; N keeps light scattered at most N times
    // Called with the fraction of work done (0 .. 1) after each finished chunk, from the
    // worker threads but never concurrently. May be empty.
    progress_callback progress;
};

// ---------------------------------------------------------------------------------------
// Plane-parallel slab: optical thickness tau, homogeneous, single-scattering albedo omega,
// no ground (black, non-reflecting below), lit from the top by a collimated sun whose
// direction makes cosine mu0 with the upward normal. Sun beam azimuth 0.
struct slab_parameters {
    double tau = 1.0;
    double mu0 = 1.0;     // (0, 1]
    double albedo = 1.0;  // [0, 1]
};

// Forward (analog) photon tracing. Fractions are of the power incident on the slab top
// (mu0 F0 per unit area):
//   reflected             leaves through the top
//   transmitted_diffuse   leaves through the bottom after at least one scattering
//   transmitted_direct    leaves through the bottom unscattered (expected exp(-tau/mu0))
//   absorbed              absorbed at a collision (probability 1 - albedo per collision)
//   beyond_max_order      with max_order = N: reached a collision after N scatterings (the
//                         photon is stopped there); 0 when max_order = 0
// Per photon the five add up to the photon's weight (1 for exactly sampled phase functions,
// so then R + T_d + T_dir + A + beyond = 1 exactly; in expectation otherwise).
// Radiance histograms: azimuthally averaged radiance of the diffuse light leaving the top
// (reflected) and the bottom (transmitted) in `bins` equal bins of exit cosine mu (measured
// from the outward normal), L/F0 in 1/sr: bin value = mu0 * (weight fraction in the bin) /
// (2 pi (mu_hi - mu_lo) mu_centre), which is the average of L over azimuth and over the bin
// with weight mu dmu (mu_centre = (mu_lo + mu_hi)/2 is exact for that weight).
struct slab_flux_result {
    estimate reflected, transmitted_diffuse, transmitted_direct, absorbed, beyond_max_order;
    std::vector<double> mu_edges;  // bins + 1 edges, 0 .. 1
    std::vector<estimate> reflected_radiance;    // per bin, L/F0 (1/sr)
    std::vector<estimate> transmitted_radiance;  // per bin, L/F0 (1/sr)
    // Mean final photon weight: exactly 1 for exactly sampled phase functions, and the sum
    // of the five fractions above (to rounding) in every case.
    estimate photon_weight;
};
[[nodiscard]] slab_flux_result trace_slab(const slab_parameters& slab, const phase_model& phase,
                                          std::uint64_t photons, unsigned bins,
                                          const run_options& options);

// A viewing direction for slab radiance. Reflected: camera above the slab looking down;
// transmitted: camera below looking up. mu = cosine of the exit direction of the light with
// the outward normal (0, 1]. phi_deg = relative azimuth (DISORT's convention): the azimuth
// of the light's exit direction minus the azimuth of the sun beam's propagation direction.
// phi = 0: the camera faces the sun's azimuth (forward-scattering side; a transmitted view
// with mu = mu0 looks straight at the sun); phi = 180: the sun is behind the camera
// (backscattering side, a reflected view with mu = mu0 is the exact backscatter).
// Cosine of the single-scattering angle: reflected  -mu mu0 + s s0 cos(phi),
//                                        transmitted  mu mu0 + s s0 cos(phi),
// with s = sqrt(1 - mu^2), s0 = sqrt(1 - mu0^2).
struct slab_view {
    bool transmitted = false;
    double mu = 1.0;
    double phi_deg = 0.0;
};
// Parses "r:MU,PHI;t:MU,PHI;..." (r = reflected, t = transmitted). Throws
// std::invalid_argument on a malformed list or mu outside (0, 1].
[[nodiscard]] std::vector<slab_view> parse_slab_views(const std::string& list);
// Cosine of the single-scattering angle of a view (formula above).
[[nodiscard]] double slab_view_scattering_cosine(const slab_parameters& slab,
                                                 const slab_view& view);
// The same angle in degrees, from atan2(|v x s|, v . s): exact near 0 and 180 degrees, where
// acos of the cosine loses half the digits.
[[nodiscard]] double slab_view_scattering_angle_deg(const slab_parameters& slab,
                                                    const slab_view& view);

// Backward tracing with next-event estimation toward the sun: L/F0 (1/sr) of the diffuse
// light leaving the slab in each view direction (paths_per_view paths each). The direct
// solar beam is excluded.
[[nodiscard]] std::vector<estimate> slab_radiance(const slab_parameters& slab,
                                                  const phase_model& phase,
                                                  const std::vector<slab_view>& views,
                                                  std::uint64_t paths_per_view,
                                                  const run_options& options);

// ---------------------------------------------------------------------------------------
// Homogeneous sphere of radius 1 centred at the origin, extinction sigma_t =
// optical_diameter / 2, lit by a directional sun (sun_direction points toward the sun,
// normalised internally; F0 = 1).
struct sphere_parameters {
    double optical_diameter = 10.0;  // tau_d = 2 sigma_t
    double albedo = 1.0;
    vec3 sun_direction{0.0, 0.0, 1.0};
};

// A camera ray: origin and direction (normalised internally).
struct ray {
    vec3 origin;
    vec3 direction;
};

// Backward tracing with next-event estimation, the transmittance toward the sun being
// exp(-sigma_t * chord to the surface along the sun direction) (analytic). L/F0 (1/sr) of
// the scattered light reaching each ray's origin against its direction (paths_per_ray
// each); rays that miss the sphere give exactly 0; an origin inside the sphere is allowed.
[[nodiscard]] std::vector<estimate> sphere_radiance(const sphere_parameters& sphere,
                                                    const phase_model& phase,
                                                    const std::vector<ray>& rays,
                                                    std::uint64_t paths_per_ray,
                                                    const run_options& options);

// Orthographic camera on the sphere. Sun along +z; the camera looks along
// view_direction = (sin a, 0, cos a), a = view_angle_deg, so dot(view_direction, sun) =
// cos a is the single-scattering cosine mu: a = 0 looks at the sphere with the sun behind
// it (forward scattering), 90 sideways, 180 with the sun behind the camera. axis_u is the
// image axis in the sun/view plane, perpendicular to the view, turned toward the sun
// (dot(axis_u, sun) >= 0; for a = 0 or 180 it is -+x); axis_v = view x axis_u. Ray origins
// are at coordinates (u, v) on the image plane 2 units in front of the centre.
struct sphere_camera {
    vec3 sun_direction;
    vec3 view_direction;
    vec3 axis_u, axis_v;
    std::vector<double> u, v;  // image coordinates of each ray (units of the radius)
    std::vector<ray> rays;
};
// `points` rays along the diameter in the sun/view plane, u at the centres of `points`
// equal cells of [-1, 1] (odd counts include the centre), v = 0.
[[nodiscard]] sphere_camera make_sphere_camera_line(double view_angle_deg, unsigned points);
// n x n rays at the cell centres of [-1, 1]^2, row-major with u fastest, v from -1 to 1.
[[nodiscard]] sphere_camera make_sphere_camera_grid(double view_angle_deg, unsigned n);

}  // namespace cloudmath::reference::mc

#endif  // CLOUDMATH_TOOLS_MONTECARLO_HPP
