// Benchmarks of cone_sampling.hpp (Google Benchmark): ns per optical depth toward the sun in
// float and double, from Schneider's 6-sample cone (5 near samples and the far one) and from
// a full second ray march (bench/naive.hpp) of 8, 16, 32 and 64 steps over the distance the
// cone reaches, both through the same smooth analytic extinction field. The cone has no batch
// form. Names and timing: bench/bench_support.hpp.
//
// Run: bash scripts/bench.sh (all module benchmarks, writes docs/bench.md), or directly
//      build/<dir>/bench/cloudmath_bench_cone_sampling --benchmark_min_time=0.05
// Inputs: 4096 sample points spread over a 2 km x 1 km x 2 km box by a 3D low-discrepancy
// sequence; one sun direction. Cone: 60 m steps, spread 0.5, far sample at 600 m standing for
// 60 m (the cone_sampling.hpp example), so it reaches 630 m, the march's distance.
#include <cloudmath/cone_sampling.hpp>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bench_support.hpp"
#include "naive.hpp"

namespace cm = cloudmath;

namespace {

// A Gaussian puff of cloud: extinction 0.05 / m at its centre, 400 m standard deviation.
// Smooth and analytic, one exp per lookup, the same for both methods.
template <class T>
struct smooth_extinction {
    glm::vec<3, T> centre = glm::vec<3, T>(T(0), T(500), T(0));
    T peak = T(0.05);
    T inv_two_sigma2 = T(1) / (T(2) * T(400) * T(400));
    T operator()(const glm::vec<3, T>& p) const {
        const glm::vec<3, T> d = p - centre;
        return peak * std::exp(-glm::dot(d, d) * inv_two_sigma2);
    }
};

template <class T>
std::vector<glm::vec<3, T>> sample_points() {
    const std::size_t n = cm_bench::scalar_count;
    const std::vector<T> x = cm_bench::sequence<T>(n, cm_bench::step_3d[0], -1000.0, 1000.0);
    const std::vector<T> y = cm_bench::sequence<T>(n, cm_bench::step_3d[1], 0.0, 1000.0);
    const std::vector<T> z = cm_bench::sequence<T>(n, cm_bench::step_3d[2], -1000.0, 1000.0);
    std::vector<glm::vec<3, T>> p(n);
    for (std::size_t i = 0; i < n; ++i) p[i] = glm::vec<3, T>(x[i], y[i], z[i]);
    return p;
}

template <class T>
glm::vec<3, T> sun_direction() {
    return glm::normalize(glm::vec<3, T>(T(0.3), T(0.8), T(0.52)));
}

template <class T>
cm::cone_light_config<T> cone_config() {
    return cm::cone_light_config<T>{6, T(60), T(0.5), T(600), T(60)};
}

template <class T>
T cone_reach() {
    const cm::cone_light_config<T> c = cone_config<T>();
    return c.far_distance + c.far_segment_length / T(2);
}

template <class T>
void register_scalar() {
    cm_bench::register_scalar<T>("optical_depth", "cone_6", "cone_optical_depth, 6 samples (far one included)", [] {
        return [p = sample_points<T>(), dir = sun_direction<T>(), cfg = cone_config<T>(),
                ext = smooth_extinction<T>()](std::size_t i) { return cm::cone_optical_depth(p[i], dir, cfg, ext); };
    });
    for (int steps : {8, 16, 32, 64}) {
        const std::string s = std::to_string(steps);
        cm_bench::register_scalar<T>("optical_depth", ("naive_march_" + s).c_str(),
                                     "naive: full light march, " + s + " steps over 630 m", [steps] {
                                         return [p = sample_points<T>(), dir = sun_direction<T>(),
                                                 distance = cm_bench::opaque(cone_reach<T>()),
                                                 count = cm_bench::opaque(steps),
                                                 ext = smooth_extinction<T>()](std::size_t i) {
                                             return cm_naive::light_march_optical_depth(p[i], dir, distance, count,
                                                                                        ext);
                                         };
                                     });
    }
}

}  // namespace

int main(int argc, char** argv) {
    return cm_bench::run_benchmarks(argc, argv, [] {
        register_scalar<float>();
        register_scalar<double>();
    });
}
