// tools/reference/transport/atmosphere_tracer.hpp: the atmosphere's ground truth (issue 26): a double
// precision Monte Carlo path tracer for a planet's air as cloudmath/atmosphere.hpp describes
// it (spherical shells, Rayleigh + Mie + ozone, a Lambertian ground), every order of
// scattering, lit by a directional sun. It shares no code with the library's sky model
// beyond the parameter struct, the extinction profile and the phase functions' formulas.
//
// Method: the sky radiance seen from a camera is estimated per channel by paths traced from
// the camera. Free flights by delta tracking against a constant majorant (the largest
// extinction over the altitudes, from a 1 m grid plus 1%); at each real collision the
// throughput keeps the single-scattering albedo, the sun is added by next-event estimation
// (phase function times the sun's transmittance by ratio tracking, both unbiased), and the
// path goes on in a direction drawn from the collision's phase (Rayleigh by its exact inverse
// CDF, Cornette-Shanks by Henyey-Greenstein sampling with the weight CS/HG). A path that
// meets the ground adds the Lambertian reflection of the sun and goes on in a
// cosine-distributed direction with the throughput times the albedo; one that leaves the
// air ends. Russian roulette below a throughput of 0.2.
// Units: radiance per unit sun illuminance above the air (1/sr), as atmosphere_sky_radiance.
#ifndef CLOUDMATH_TOOLS_ATMOSPHERE_TRACER_HPP
#define CLOUDMATH_TOOLS_ATMOSPHERE_TRACER_HPP

#include <cstdint>
#include <vector>

#include <cloudmath/atmosphere.hpp>

#include "montecarlo.hpp"

namespace cloudmath::reference::atmo {

// A view from a camera `altitude` metres above the ground; view and sun are unit vectors in
// the camera's frame with +y up (the radial direction), view pointing away from the camera.
struct sky_query {
    double altitude = 0.0;
    mc::vec3 view, sun;
};

struct sky_estimate {
    mc::estimate channel[3];  // 680, 550, 440 nm
};

// `paths` paths per channel for each query; deterministic for a seed (not for a thread count:
// chunks are fixed, see montecarlo_detail.hpp). Throws std::invalid_argument for paths == 0,
// a non-unit direction or an altitude outside [0, top - bottom].
std::vector<sky_estimate> trace_sky(const atmosphere_parameters<double>& air, const std::vector<sky_query>& queries,
                                    std::uint64_t paths, const mc::run_options& options);

// The transmittance from `altitude` towards a direction of zenith cosine mu, by ratio
// tracking with `paths` paths (for the tests: against the library's quadrature).
mc::estimate trace_transmittance(const atmosphere_parameters<double>& air, int channel, double altitude, double mu,
                                 std::uint64_t paths, const mc::run_options& options);

// A direction at `elevation` degrees above the horizon and `azimuth` degrees from the +x
// axis towards +z (the sun's azimuth is 0 in the reports).
mc::vec3 direction_from_degrees(double elevation, double azimuth);

}  // namespace cloudmath::reference::atmo

#endif  // CLOUDMATH_TOOLS_ATMOSPHERE_TRACER_HPP
