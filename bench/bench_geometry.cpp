// Benchmarks of geometry.hpp (Google Benchmark): ns per evaluation in float and double of the
// planet-scale ray/sphere intersection next to the textbook form (bench/naive.hpp), which
// loses tens of metres in float at Earth radius, and of the other per-ray geometry a cloud
// march calls (cloud_layer_segment once per ray, altitude_along_ray once per step). Geometry
// has no batch form. Names and timing: bench/bench_support.hpp.
//
// Run: bash scripts/bench.sh (all module benchmarks, writes docs/bench.md), or directly
//      build/<dir>/bench/cloudmath_bench_geometry --benchmark_min_time=0.05
// Inputs: 4096 (altitude, cos_zenith) pairs of a 2D low-discrepancy sequence, altitude in
// [0, 4000] m and cos_zenith in [-1, 1]; Earth radius 6371 km; the sphere and the layer top
// at 4000 m (so every ray starts inside and hits it), layer bottom 1500 m.
#include <cloudmath/geometry.hpp>

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "bench_support.hpp"
#include "naive.hpp"

namespace cm = cloudmath;
using cm_bench::opaque;

namespace {

constexpr double earth_radius = 6371e3;  // m
constexpr double layer_bottom = 1500.0;  // m
constexpr double layer_top = 4000.0;     // m

template <class T>
struct rays {
    std::vector<T> altitude = cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_2d[0], 0.0, 4000.0);
    std::vector<T> cos_zenith = cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_2d[1], -1.0, 1.0);
};

// Registers "<group>/<variant>/<type>" evaluating f(altitude, cos_zenith, R) per ray.
template <class T, class F>
void register_ray(const char* group, const char* variant, const char* label, F f) {
    cm_bench::register_scalar<T>(group, variant, label, [f] {
        return [in = rays<T>(), R = opaque(T(earth_radius)), f](std::size_t i) {
            return f(in.altitude[i], in.cos_zenith[i], R);
        };
    });
}

template <class T>
void register_scalar() {
    register_ray<T>("ray_sphere", "library_altitude", "ray_sphere_intersect_altitude (both roots, no cancellation)",
                    [](T h, T mu, T R) { return cm::ray_sphere_intersect_altitude(h, mu, R, T(layer_top)); });
    register_ray<T>("ray_sphere", "naive_first_hit", "naive: |o|^2 - r^2 discriminant, first root",
                    [](T h, T mu, T R) { return cm_naive::ray_sphere_first_hit(h, mu, R, T(layer_top)); });
    register_ray<T>("ray_sphere", "library_vec3", "ray_sphere_intersect (vec3 origin and direction)",
                    [](T h, T mu, T R) {
                        const T s = std::sqrt(std::max((T(1) - mu) * (T(1) + mu), T(0)));
                        return cm::ray_sphere_intersect(glm::vec<3, T>(T(0), R + h, T(0)), glm::vec<3, T>(s, mu, T(0)),
                                                        glm::vec<3, T>(T(0)), R + T(layer_top));
                    });
    register_ray<T>("cloud_layer_segment", "library", "cloud_layer_segment (three spheres, ground included)",
                    [](T h, T mu, T R) { return cm::cloud_layer_segment(h, mu, R, T(layer_bottom), T(layer_top)); });
    register_ray<T>("altitude_along_ray", "library", "altitude_along_ray at t = 1000 m",
                    [](T h, T mu, T R) { return cm::altitude_along_ray(h, mu, R, T(1000)); });
}

}  // namespace

int main(int argc, char** argv) {
    return cm_bench::run_benchmarks(argc, argv, [] {
        register_scalar<float>();
        register_scalar<double>();
    });
}
