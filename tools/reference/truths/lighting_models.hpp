// tools/reference/truths/lighting_models.hpp: the real-time lighting models of cloudmath evaluated
// for the two homogeneous test media of the Monte Carlo reference (montecarlo.hpp), so that
// their radiance can be compared pixel by pixel with the path-traced ground truth.
//
// What a real-time renderer computes (examples/cloud_renderer, Hillaire 2015's integration):
//   L(ray) = integral over the ray of  T_view(s) sigma_s F0 M(tau_light(s), mu) ds,
// with T_view the transmittance from the camera, tau_light the optical depth from the sample
// toward the sun, mu = dot(view_dir, sun_dir) and M the "sun term" of a model:
//   beer    M = sum_{i<N} b^i p(mu, c^i g) exp(-a^i tau)            (Wrenninge octaves;
//           N = 1 is exact single scattering)
//   powder  M = beer-form M times mix(2 (1 - e^(-2 tau)), 1, (1 + mu) / 2): the Beer-Powder
//           factor of Schneider 2015 as the example renderer applies it
//   nubis   M = sum_{i<N} b^i p(mu, c^i g) max(e^(-a^i tau), 0.7 e^(-0.25 a^i tau))
//           (Schneider 2017's attenuation in every octave)
// The integral is evaluated to about 1e-9 relative (composite Gauss-Legendre over the optical
// path, panels `panel` optical units wide), so the error measured against the Monte Carlo is
// the model's, not a ray march's.
// Units: radiance in units of the sun's perpendicular irradiance F0 (1/sr), as montecarlo.hpp.
#ifndef CLOUDMATH_TOOLS_LIGHTING_MODELS_HPP
#define CLOUDMATH_TOOLS_LIGHTING_MODELS_HPP

#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace cloudmath::reference::lighting {

enum class attenuation { beer, powder, nubis };

// One lighting model: octave parameters, attenuation form and the octaves' phase function.
struct model {
    double a = 1.0, b = 1.0, c = 1.0;  // Wrenninge's extinction, contribution, eccentricity
    int octaves = 1;
    attenuation form = attenuation::beer;
    // phase(mu, scale): the phase function with eccentricities scaled by c^i (default HG
    // with g = 0.85 through cloudmath::phase_hg).
    std::function<double(double, double)> phase;
};

[[nodiscard]] model make_model(double g_hg, double a, double b, double c, int octaves,
                               attenuation form);
[[nodiscard]] const char* attenuation_name(attenuation form);

// The sun term M(tau_light, mu) of the model (1/sr).
[[nodiscard]] double sun_term(const model& m, double tau_light, double mu);

// The radiance integral along one test-medium ray, independent of the model: the nodes of
// the quadrature over the optical path, so that L = sum_k weight[k] M(tau_light[k], mu).
// Fitting a model to the reference evaluates thousands of models on the same rays; the
// geometry (sphere chords, depths) is then computed once.
struct ray_quadrature {
    double mu = 0.0;                        // cosine of the single-scattering angle
    std::vector<double> weight, tau_light;  // albedo x quadrature weight x exp(-t); depth
    // The inputs of the chord-diffusion model (cloudmath/diffusion_lighting.hpp) at each
    // node: the optical depth behind the node along the sun direction (from the node away
    // from the sun to where the medium ends) and the optical depth t from the camera side.
    std::vector<double> tau_behind, tau_view;
};
// Radiance of a model along a ray: sum_k weight[k] sun_term(m, tau_light[k], mu).
[[nodiscard]] double radiance(const model& m, const ray_quadrature& q);

// Homogeneous sphere of radius 1, optical diameter tau_d (sigma_t = tau_d / 2), albedo,
// unit vector sun toward the sun. Radiance along the ray origin + t dir (dir unit); 0 (no
// nodes) when the ray misses.
[[nodiscard]] ray_quadrature sphere_quadrature(double tau_d, double albedo,
                                               const glm::dvec3& sun, const glm::dvec3& origin,
                                               const glm::dvec3& dir, double panel = 0.25);
[[nodiscard]] double sphere_radiance(const model& m, double tau_d, double albedo,
                                     const glm::dvec3& sun, const glm::dvec3& origin,
                                     const glm::dvec3& dir, double panel = 0.25);

// Plane-parallel slab of optical thickness tau, sun from the top at cosine mu0 (> 0).
// view_dir is the direction the camera looks along (unit, z up, the slab between optical
// depths 0 at the top and tau at the bottom): view_dir.z < 0 looks down from above
// (reflected light), view_dir.z > 0 looks up from below (transmitted diffuse light, the
// direct sun excluded). sun = (sqrt(1 - mu0^2), 0, mu0). Throws std::invalid_argument for
// mu0 <= 0.
// The slab's unit vector toward the sun for the cosine mu0: (sqrt(1 - mu0^2), 0, mu0).
[[nodiscard]] glm::dvec3 slab_sun_direction(double mu0);
[[nodiscard]] ray_quadrature slab_quadrature(double tau, double mu0, double albedo,
                                             const glm::dvec3& view_dir, double panel = 0.25);
[[nodiscard]] double slab_radiance(const model& m, double tau, double mu0, double albedo,
                                   const glm::dvec3& view_dir, double panel = 0.25);

}  // namespace cloudmath::reference::lighting

#endif  // CLOUDMATH_TOOLS_LIGHTING_MODELS_HPP
