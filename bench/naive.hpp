// Naive textbook forms that cloudmath replaces, for the benchmarks and the speed-vs-error
// report only (never part of the library). Each is written the way public implementations
// write it, so the comparison shows what the careful forms cost and what they fix.
#ifndef CLOUDMATH_BENCH_NAIVE_HPP
#define CLOUDMATH_BENCH_NAIVE_HPP

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace cm_naive {

template <class T> inline constexpr T pi = T(3.14159265358979323846L);

// HG with pow(x, 1.5) and the expanded base 1 + g^2 - 2 g mu.
template <class T>
T phase_hg(T mu, T g) {
    return (T(1) - g * g) / (T(4) * pi<T> * std::pow(T(1) + g * g - T(2) * g * mu, T(1.5)));
}

template <class T>
T phase_cornette_shanks(T mu, T g) {
    return T(3) / (T(8) * pi<T>) * (T(1) - g * g) / (T(2) + g * g) * (T(1) + mu * mu) /
           std::pow(T(1) + g * g - T(2) * g * mu, T(1.5));
}

template <class T>
T phase_draine(T mu, T g, T alpha) {
    return (T(1) - g * g) * (T(1) + alpha * mu * mu) /
           (T(4) * pi<T> * (T(1) + alpha * (T(1) + T(2) * g * g) / T(3)) * std::pow(T(1) + g * g - T(2) * g * mu, T(1.5)));
}

template <class T>
T beer_lambert(T tau) { return std::exp(-tau); }

template <class T>
T beer_powder(T tau) { return T(2) * std::exp(-tau) * (T(1) - std::exp(-T(2) * tau)); }

template <class T>
T nubis_attenuation(T tau) { return std::max(std::exp(-tau), T(0.7) * std::exp(T(-0.25) * tau)); }

// The clamp-constant step integral seen in public code: biased for thin media.
template <class T>
T integrate_scattering_clamped(T S, T sigma_t, T ds) {
    return (S - S * std::exp(-sigma_t * ds)) / std::max(sigma_t, T(1e-6));
}

// Riemann sum: S ds at the step's start, transmittance applied after (no in-step decay).
template <class T>
T integrate_scattering_riemann(T S, T sigma_t, T ds) {
    (void)sigma_t;
    return S * ds;
}

// Textbook ray/sphere: origin at altitude h above a planet of radius R, unit direction with
// zenith cosine mu, sphere of radius R + H centred at the planet centre; first root >= 0.
template <class T>
T ray_sphere_first_hit(T h, T mu, T R, T H) {
    const T oy = R + h;
    const T b = oy * mu;
    const T c = oy * oy - (R + H) * (R + H);
    const T disc = b * b - c;
    if (disc < T(0)) return T(-1);
    const T sq = std::sqrt(disc);
    const T t0 = -b - sq;
    return t0 >= T(0) ? t0 : -b + sq;
}

// Octaves with pow() for the powers, as usually written.
template <class T>
T multiple_scattering(T tau, T mu, T g, T a, T b, T c, int octaves) {
    T sum = T(0);
    for (int i = 0; i < octaves; ++i)
        sum += std::pow(b, T(i)) * phase_hg(mu, std::pow(c, T(i)) * g) * std::exp(-std::pow(a, T(i)) * tau);
    return sum;
}

// A full second ray march toward the light: `steps` midpoint samples over `distance`.
template <class T, class Extinction>
T light_march_optical_depth(const glm::vec<3, T>& origin, const glm::vec<3, T>& dir, T distance, int steps,
                            Extinction&& extinction) {
    const T ds = distance / T(steps);
    T tau = T(0);
    for (int i = 0; i < steps; ++i) tau += extinction(origin + dir * ((T(i) + T(0.5)) * ds)) * ds;
    return tau;
}

// What engines do with MiePlot data: a 1D table of the phase function over the scattering
// angle, looked up with linear interpolation.
template <class T>
struct phase_table {
    std::vector<T> values;  // p at angles i * pi / (n - 1)
    template <class Phase>
    phase_table(int n, Phase&& phase) : values(static_cast<std::size_t>(n)) {
        for (int i = 0; i < n; ++i) values[static_cast<std::size_t>(i)] = phase(std::cos(T(i) * pi<T> / T(n - 1)));
    }
    T operator()(T mu) const {
        const T angle = std::acos(std::clamp(mu, T(-1), T(1)));
        const T x = angle / pi<T> * T(values.size() - 1);
        const std::size_t i = std::min(static_cast<std::size_t>(x), values.size() - 2);
        const T f = x - T(i);
        return values[i] + f * (values[i + 1] - values[i]);
    }
};

}  // namespace cm_naive

#endif  // CLOUDMATH_BENCH_NAIVE_HPP
