// tools/reference/transport/atmosphere_tracer.cpp: see atmosphere_tracer.hpp.
#include "atmosphere_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <cloudmath/phase.hpp>

#include "montecarlo_detail.hpp"

namespace cloudmath::reference::atmo {
namespace {

using mc::vec3;
using mc::detail::pi;
using mc::detail::random_stream;

double channel_of(const glm::dvec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

struct medium {
    const atmosphere_parameters<double>& air;
    int c;
    double majorant;

    double extinction(double h) const { return channel_of(atmosphere_extinction(air, h), c); }
    double rayleigh(double h) const {
        return channel_of(air.rayleigh_scattering, c) * std::exp(-std::max(h, 0.0) / air.rayleigh_scale_height);
    }
    double mie(double h) const { return air.mie_scattering * std::exp(-std::max(h, 0.0) / air.mie_scale_height); }
};

double majorant_of(const atmosphere_parameters<double>& air, int c) {
    double most = 0.0;
    const double top = air.top_radius - air.bottom_radius;
    for (double h = 0.0; h <= top; h += 1.0) most = std::max(most, channel_of(atmosphere_extinction(air, h), c));
    return most * 1.01;
}

double altitude_of(const atmosphere_parameters<double>& air, const vec3& p) {
    return std::sqrt(mc::dot(p, p)) - air.bottom_radius;
}

// Distance along d from p to the sphere of radius `radius` (outward crossing, p inside it).
double exit_distance(const vec3& p, const vec3& d, double radius) {
    const double r = std::sqrt(mc::dot(p, p));
    const double c = (r - radius) * (r + radius);  // <= 0 inside
    const double b = mc::dot(p, d);
    const double root = std::sqrt(std::max(b * b - c, 0.0));
    return b <= 0.0 ? root - b : -c / (b + root);
}

// Distance along d from p (outside the sphere) to where it meets the sphere; infinity if not.
double hit_distance(const vec3& p, const vec3& d, double radius) {
    const double r = std::sqrt(mc::dot(p, p));
    const double c = (r - radius) * (r + radius);  // >= 0 outside
    const double b = mc::dot(p, d);
    if (b >= 0.0) return mc::detail::infinity;
    const double disc = b * b - c;
    if (disc < 0.0) return mc::detail::infinity;
    return c / (-b + std::sqrt(disc));  // the near root, without cancellation
}

// Ratio tracking from p along d to the top; 0 if the ray meets the ground.
double ratio_tracking(const medium& m, const vec3& p, const vec3& d, random_stream& rng) {
    if (hit_distance(p, d, m.air.bottom_radius) < mc::detail::infinity) return 0.0;
    const double end = exit_distance(p, d, m.air.top_radius);
    double t = 0.0, T = 1.0;
    for (;;) {
        t += rng.free_path() / m.majorant;
        if (t >= end) return T;
        T *= 1.0 - m.extinction(altitude_of(m.air, p + t * d)) / m.majorant;
    }
}

// Rayleigh's phase, (3/8)(1 + mu^2) on [-1, 1], by its inverse CDF: mu^3 + 3 mu + 4 - 8 u = 0
// (Cardano: one real root).
double sample_rayleigh(double u) {
    const double q = 4.0 - 8.0 * u;
    const double s = std::sqrt(q * q / 4.0 + 1.0);
    return std::cbrt(-q / 2.0 + s) + std::cbrt(-q / 2.0 - s);
}

// A cosine-distributed direction around the unit normal n.
vec3 sample_lambert(const vec3& n, random_stream& rng) {
    const double mu = std::sqrt(rng.uniform());
    return mc::detail::scatter_direction(n, mu, rng.uniform());
}

double trace_path(const medium& m, const sky_query& q, unsigned max_order, random_stream& rng) {
    const atmosphere_parameters<double>& air = m.air;
    vec3 p{0.0, air.bottom_radius + q.altitude, 0.0};
    vec3 d = q.view;
    double beta = 1.0, L = 0.0;
    // order: the scattering events (collisions and ground reflections) so far; the sun's light
    // added at the k-th has been scattered k times. max_order > 0 stops after that many.
    for (unsigned order = 1; max_order == 0 || order <= max_order; ++order) {
        const double ground = hit_distance(p, d, air.bottom_radius);
        const double end = std::min(ground, exit_distance(p, d, air.top_radius));
        double t = 0.0;
        bool collided = false;
        for (;;) {
            t += rng.free_path() / m.majorant;
            if (t >= end) break;
            const double h = altitude_of(air, p + t * d);
            if (rng.uniform() * m.majorant < m.extinction(h)) {
                collided = true;
                break;
            }
        }
        if (collided) {
            p = p + t * d;
            const double h = altitude_of(air, p);
            const double sr = m.rayleigh(h), sm = m.mie(h), st = m.extinction(h);
            if (!(sr + sm > 0.0)) return L;  // a purely absorbing air: the path ends here
            beta *= (sr + sm) / st;
            const double nu = mc::dot(d, q.sun);
            const double phase = (sr * phase_rayleigh(nu) + sm * phase_cornette_shanks(nu, air.mie_g)) / (sr + sm);
            L += beta * phase * ratio_tracking(m, p, q.sun, rng);
            double mu;
            if (rng.uniform() * (sr + sm) < sr) {
                mu = sample_rayleigh(rng.uniform());
            } else {
                mu = sample_phase_hg(air.mie_g, rng.uniform());
                beta *= phase_cornette_shanks(mu, air.mie_g) / phase_hg(mu, air.mie_g);
            }
            d = mc::detail::scatter_direction(d, mu, rng.uniform());
        } else if (ground < mc::detail::infinity) {
            p = p + ground * d;
            const vec3 n = mc::normalized(p);
            p = air.bottom_radius * n;
            const double cos_sun = mc::dot(n, q.sun);
            if (cos_sun > 0.0) L += beta * air.ground_albedo / pi * cos_sun * ratio_tracking(m, p, q.sun, rng);
            beta *= air.ground_albedo;
            d = sample_lambert(n, rng);
            p = p + 1e-3 * n;  // off the surface, so that the next flight starts in the air
        } else {
            return L;  // left the air
        }
        if (beta < mc::detail::roulette_threshold) {
            if (rng.uniform() * mc::detail::roulette_threshold >= beta) return L;
            beta = mc::detail::roulette_threshold;
        }
    }
    return L;
}

void check_query(const atmosphere_parameters<double>& air, const sky_query& q) {
    const auto unit = [](const vec3& v) { return std::abs(mc::dot(v, v) - 1.0) < 1e-9; };
    if (!unit(q.view) || !unit(q.sun)) throw std::invalid_argument("view and sun directions must be unit vectors");
    if (!(q.altitude >= 0.0 && q.altitude <= air.top_radius - air.bottom_radius))
        throw std::invalid_argument("the camera's altitude must lie in the air");
}

}  // namespace

std::vector<sky_estimate> trace_sky(const atmosphere_parameters<double>& air, const std::vector<sky_query>& queries,
                                    std::uint64_t paths, const mc::run_options& options) {
    for (const sky_query& q : queries) check_query(air, q);
    const double majorants[3] = {majorant_of(air, 0), majorant_of(air, 1), majorant_of(air, 2)};
    // Items: query-major, then channel.
    const auto totals = mc::detail::tally_per_item<mc::detail::moments>(
        queries.size() * 3, paths, options, 0xA7305ULL, [&](std::size_t item, random_stream& rng, mc::detail::moments& tally) {
            const int c = static_cast<int>(item % 3);
            const medium m{air, c, majorants[c]};
            tally.add(trace_path(m, queries[item / 3], options.max_order, rng));
        });
    std::vector<sky_estimate> out(queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i)
        for (int c = 0; c < 3; ++c) out[i].channel[c] = mc::detail::make_estimate(totals[i * 3 + static_cast<std::size_t>(c)], paths);
    return out;
}

mc::estimate trace_transmittance(const atmosphere_parameters<double>& air, int channel, double altitude, double mu,
                                 std::uint64_t paths, const mc::run_options& options) {
    const medium m{air, channel, majorant_of(air, channel)};
    const vec3 p{0.0, air.bottom_radius + altitude, 0.0};
    const vec3 d{std::sqrt(std::max(1.0 - mu * mu, 0.0)), mu, 0.0};
    const auto totals = mc::detail::tally_per_item<mc::detail::moments>(
        1, paths, options, 0x7A05ULL,
        [&](std::size_t, random_stream& rng, mc::detail::moments& tally) { tally.add(ratio_tracking(m, p, d, rng)); });
    return mc::detail::make_estimate(totals[0], paths);
}

vec3 direction_from_degrees(double elevation, double azimuth) {
    const double e = elevation * pi / 180.0, a = azimuth * pi / 180.0;
    return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

}  // namespace cloudmath::reference::atmo
