// Tests of tools/reference/lighting_models: the radiance integrals against closed forms of
// single scattering and of each Wrenninge octave in a slab and along a sphere's diameter.
#include <doctest/doctest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include <cloudmath/phase.hpp>

#include "lighting_models.hpp"

namespace lm = cloudmath::reference::lighting;

namespace {
constexpr double pi = 3.14159265358979323846;
double hg(double mu, double g) {  // textbook HG in double, independent of the library
    return (1 - g * g) / (4 * pi * std::pow(1 + g * g - 2 * g * mu, 1.5));
}
}  // namespace

TEST_CASE("sun term: octave sum, powder and Nubis forms") {
    const auto beer = lm::make_model(0.8, 0.5, 0.4, 0.3, 3, lm::attenuation::beer);
    const double tau = 2.0, mu = 0.3;
    double want = 0.0;
    for (int i = 0; i < 3; ++i)
        want += std::pow(0.4, i) * hg(mu, 0.8 * std::pow(0.3, i)) * std::exp(-std::pow(0.5, i) * tau);
    CHECK(lm::sun_term(beer, tau, mu) == doctest::Approx(want).epsilon(1e-12));

    const auto powder = lm::make_model(0.8, 0.5, 0.4, 0.3, 3, lm::attenuation::powder);
    const double w = 0.5 + 0.5 * mu;
    CHECK(lm::sun_term(powder, tau, mu) ==
          doctest::Approx(want * (2 * (1 - std::exp(-2 * tau)) * (1 - w) + w)).epsilon(1e-12));

    const auto nubis = lm::make_model(0.8, 1.0, 1.0, 1.0, 1, lm::attenuation::nubis);
    CHECK(lm::sun_term(nubis, 0.1, mu) == doctest::Approx(hg(mu, 0.8) * std::exp(-0.1)).epsilon(1e-12));
    CHECK(lm::sun_term(nubis, 10.0, mu) ==
          doctest::Approx(hg(mu, 0.8) * 0.7 * std::exp(-2.5)).epsilon(1e-12));
}

TEST_CASE("slab: reflected and transmitted radiance of each octave in closed form") {
    // Octave i attenuates with a^i tau_light: reflected
    //   b^i p_i mu0 / (mu0 + a^i mv) (1 - exp(-tau (a^i / mu0 + 1 / mv))),
    // transmitted (camera below, looking up at cosine mv)
    //   b^i p_i mu0 / (mu0 - a^i mv) (exp(-a^i tau / mu0) - exp(-tau / mv)).
    const double a = 0.5, b = 0.6, c = 0.7, g = 0.85, albedo = 0.9;
    const auto m = lm::make_model(g, a, b, c, 3, lm::attenuation::beer);
    for (double tau : {0.01, 1.0, 8.0, 100.0})
        for (double mu0 : {1.0, 0.5, 0.2})
            for (double mv : {1.0, 0.45, 0.1}) {
                const double s0 = std::sqrt(1 - mu0 * mu0), sv = std::sqrt(1 - mv * mv);
                for (int up = 0; up < 2; ++up) {
                    const glm::dvec3 view(sv * 0.6, sv * 0.8, up ? mv : -mv);
                    const double mu = view.x * s0 + view.z * mu0;
                    double want = 0.0;
                    for (int i = 0; i < 3; ++i) {
                        const double ai = std::pow(a, i);
                        const double p = std::pow(b, i) * hg(mu, g * std::pow(c, i));
                        if (!up)
                            want += p * mu0 / (mu0 + ai * mv) * -std::expm1(-tau * (ai / mu0 + 1 / mv));
                        else if (std::abs(mu0 - ai * mv) > 1e-9)
                            want += p * mu0 / (mu0 - ai * mv) * (std::exp(-ai * tau / mu0) - std::exp(-tau / mv));
                        else
                            want += p * tau / mv * std::exp(-tau / mv);
                    }
                    want *= albedo;
                    CAPTURE(tau);
                    CAPTURE(mu0);
                    CAPTURE(mv);
                    CAPTURE(up);
                    CHECK(lm::slab_radiance(m, tau, mu0, albedo, view) ==
                          doctest::Approx(want).epsilon(1e-9));
                }
            }
}

TEST_CASE("sphere: the sun behind the camera, along the diameter") {
    // The sample at x past the entry point sees the sun through the same x: tau_light =
    // sigma x, so L = albedo p(-1) (1 - exp(-2 tau_d)) / 2 for sigma = tau_d / 2.
    const auto m = lm::make_model(0.85, 1, 1, 1, 1, lm::attenuation::beer);
    for (double tau_d : {0.001, 1.0, 10.0, 100.0}) {
        const double want = 0.7 * hg(-1.0, 0.85) * -std::expm1(-2 * tau_d) / 2;
        CHECK(lm::sphere_radiance(m, tau_d, 0.7, {0, 0, -1}, {0, 0, -3}, {0, 0, 1}) ==
              doctest::Approx(want).epsilon(1e-10));
    }
    // Missing rays and rays starting past the sphere give 0.
    CHECK(lm::sphere_radiance(m, 10, 1, {0, 0, -1}, {0, 1.5, -3}, {0, 0, 1}) == 0.0);
    CHECK(lm::sphere_radiance(m, 10, 1, {0, 0, -1}, {0, 0, 3}, {0, 0, 1}) == 0.0);
}

TEST_CASE("sphere: independent midpoint quadrature off the axis") {
    // A 20000-step midpoint rule in s with the chord computed from the quadratic directly.
    const auto m = lm::make_model(0.85, 0.5, 0.5, 0.5, 3, lm::attenuation::nubis);
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.3, 0.8, -0.2));
    const glm::dvec3 o(0.4, -0.3, -4.0), d(0, 0, 1);
    for (double tau_d : {0.5, 5.0, 50.0}) {
        const double sigma = tau_d / 2;
        const double half = std::sqrt(1 - 0.25);  // |o_xy| = 0.5
        const double t0 = 4.0 - half, len = 2 * half;
        const int n = 20000;
        double sum = 0.0;
        for (int k = 0; k < n; ++k) {
            const double x = (k + 0.5) * len / n;
            const glm::dvec3 p = o + (t0 + x) * d;
            const double b = glm::dot(p, sun), c = glm::dot(p, p) - 1;
            const double chord = -b + std::sqrt(b * b - c);
            sum += sigma * std::exp(-sigma * x) * lm::sun_term(m, sigma * chord, glm::dot(d, sun)) * len / n;
        }
        CHECK(lm::sphere_radiance(m, tau_d, 1.0, sun, o, d) == doctest::Approx(sum).epsilon(2e-5));
    }
}
