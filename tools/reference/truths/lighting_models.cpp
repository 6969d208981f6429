// tools/reference/truths/lighting_models.cpp: see lighting_models.hpp.
#include "lighting_models.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include <cloudmath/phase.hpp>
#include <cloudmath/transmittance.hpp>

namespace cloudmath::reference::lighting {

namespace {

// 8-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun, table 25.4).
constexpr double gl_x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                            0.9602898564975363};
constexpr double gl_w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                            0.1012285362903763};

// Nodes of the integral over optical path t in [0, length] of exp(-t) f(t) dt: composite
// 8-point Gauss-Legendre on panels at most `panel` optical units wide, stopping at t = 60
// where exp(-t) = 9e-27 can no longer matter. Integrating in t keeps the integrand smooth:
// with the substitution u = 1 - exp(-t) the octave terms become (1 - u)^k with small k,
// whose endpoint singularity Gauss-Legendre converges to slowly. The first and last panels
// are cut geometrically toward the ends (halves, quarters, ... 2^-12 of a panel): where a
// ray enters or leaves a sphere on its terminator, the chord toward the sun grows like the
// square root of the distance from the surface, and this grading integrates that endpoint
// singularity to the accuracy of the smooth panels. depth(t) gives the optical depth
// toward the sun at t and behind(t) the optical depth behind the point along the sun
// direction; every weight is multiplied by `scale`.
constexpr int graded_levels = 12;

template <class Depth, class Behind>
ray_quadrature attenuated_nodes(Depth&& depth, Behind&& behind, double length, double panel, double mu,
                                double scale) {
    ray_quadrature q;
    q.mu = mu;
    const bool capped = length > 60.0;
    const double upper = std::min(length, 60.0);
    if (!(upper > 0.0)) return q;
    const int panels = std::max(4, static_cast<int>(std::ceil(upper / panel)));
    const double h = upper / panels;
    auto add_panel = [&](double lo, double hi) {
        const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
        for (int k = 0; k < 4; ++k)
            for (double t : {mid - half * gl_x[k], mid + half * gl_x[k]}) {
                q.weight.push_back(scale * gl_w[k] * half * std::exp(-t));
                q.tau_light.push_back(depth(t));
                q.tau_behind.push_back(behind(t));
                q.tau_view.push_back(t);
            }
    };
    for (int p = 0; p < panels; ++p) {
        const double lo = p * h, hi = p + 1 == panels ? upper : (p + 1) * h;
        if (p == 0) {
            double edge = hi;
            for (int level = 1; level <= graded_levels; ++level) {
                add_panel(std::ldexp(h, -level), edge);
                edge = std::ldexp(h, -level);
            }
            add_panel(0.0, edge);
        } else if (p + 1 == panels && !capped) {
            double edge = lo;
            for (int level = 1; level <= graded_levels; ++level) {
                add_panel(edge, upper - std::ldexp(h, -level));
                edge = upper - std::ldexp(h, -level);
            }
            add_panel(edge, upper);
        } else {
            add_panel(lo, hi);
        }
    }
    return q;
}

// Distances along origin + t dir to the unit sphere, (t0, t1) with t0 <= t1, or false.
bool unit_sphere_hits(const glm::dvec3& o, const glm::dvec3& d, double& t0, double& t1) {
    const double b = glm::dot(o, d);
    const double c = glm::dot(o, o) - 1.0;
    const double disc = b * b - c;
    if (disc <= 0.0) return false;
    // Stable quadratic: q and c / q instead of -b +- sqrt (Numerical Recipes 5.6).
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    t0 = q;
    t1 = q != 0.0 ? c / q : -q;
    if (t0 > t1) std::swap(t0, t1);
    return true;
}

}  // namespace

model make_model(double g_hg, double a, double b, double c, int octaves, attenuation form) {
    model m;
    m.a = a;
    m.b = b;
    m.c = c;
    m.octaves = octaves;
    m.form = form;
    m.phase = [g_hg](double mu, double scale) { return cloudmath::phase_hg(mu, scale * g_hg); };
    return m;
}

const char* attenuation_name(attenuation form) {
    switch (form) {
        case attenuation::beer: return "beer";
        case attenuation::powder: return "powder";
        case attenuation::nubis: return "nubis";
    }
    return "?";
}

double sun_term(const model& m, double tau_light, double mu) {
    double sum = 0.0, ai = 1.0, bi = 1.0, ci = 1.0;
    for (int i = 0; i < m.octaves; ++i) {
        const double t = m.form == attenuation::nubis
                             ? cloudmath::nubis_attenuation(ai * tau_light)
                             : cloudmath::beer_lambert(ai * tau_light);
        sum += bi * m.phase(mu, ci) * t;
        ai *= m.a;
        bi *= m.b;
        ci *= m.c;
    }
    if (m.form == attenuation::powder) {
        const double w = 0.5 + 0.5 * mu;
        sum *= 2.0 * cloudmath::powder(tau_light, 2.0) * (1.0 - w) + w;
    }
    return sum;
}

double radiance(const model& m, const ray_quadrature& q) {
    double sum = 0.0;
    for (std::size_t k = 0; k < q.weight.size(); ++k)
        sum += q.weight[k] * sun_term(m, q.tau_light[k], q.mu);
    return sum;
}

ray_quadrature sphere_quadrature(double tau_d, double albedo, const glm::dvec3& sun,
                                 const glm::dvec3& origin, const glm::dvec3& dir,
                                 double panel) {
    double t0 = 0.0, t1 = 0.0;
    if (!unit_sphere_hits(origin, dir, t0, t1) || t1 <= 0.0) return {};
    t0 = std::max(t0, 0.0);
    const double sigma = 0.5 * tau_d;
    // Optical path t from the entry point: sigma_s T_view ds = albedo exp(-t) dt.
    auto depth = [&](double t) {
        const glm::dvec3 p = origin + (t0 + t / sigma) * dir;
        double e0 = 0.0, e1 = 0.0;
        const double chord = unit_sphere_hits(p, sun, e0, e1) ? std::max(e1, 0.0) : 0.0;
        return sigma * chord;
    };
    auto behind = [&](double t) {
        const glm::dvec3 p = origin + (t0 + t / sigma) * dir;
        double e0 = 0.0, e1 = 0.0;
        const double chord = unit_sphere_hits(p, -sun, e0, e1) ? std::max(e1, 0.0) : 0.0;
        return sigma * chord;
    };
    return attenuated_nodes(depth, behind, sigma * (t1 - t0), panel, glm::dot(dir, sun), albedo);
}

double sphere_radiance(const model& m, double tau_d, double albedo, const glm::dvec3& sun,
                       const glm::dvec3& origin, const glm::dvec3& dir, double panel) {
    return radiance(m, sphere_quadrature(tau_d, albedo, sun, origin, dir, panel));
}

glm::dvec3 slab_sun_direction(double mu0) {
    return {std::sqrt(std::max(0.0, 1.0 - mu0 * mu0)), 0.0, mu0};
}

ray_quadrature slab_quadrature(double tau, double mu0, double albedo,
                               const glm::dvec3& view_dir, double panel) {
    if (!(mu0 > 0.0)) throw std::invalid_argument("slab_quadrature: mu0 must be > 0");
    const double vz = view_dir.z;
    if (vz == 0.0) return {};
    const glm::dvec3 sun = slab_sun_direction(mu0);
    const double mv = std::abs(vz);
    // Optical path t along the ray from where it enters; depth below the top is t mv when
    // looking down, tau - t mv when looking up.
    auto depth = [&](double t) {
        const double below_top = vz < 0.0 ? t * mv : tau - t * mv;
        return std::max(below_top, 0.0) / mu0;
    };
    auto behind = [&](double t) {
        const double below_top = vz < 0.0 ? t * mv : tau - t * mv;
        return std::max(tau - below_top, 0.0) / mu0;
    };
    return attenuated_nodes(depth, behind, tau / mv, panel, glm::dot(view_dir, sun), albedo);
}

double slab_radiance(const model& m, double tau, double mu0, double albedo,
                     const glm::dvec3& view_dir, double panel) {
    return radiance(m, slab_quadrature(tau, mu0, albedo, view_dir, panel));
}

}  // namespace cloudmath::reference::lighting
