// Benchmarks of multiple_scattering.hpp (Google Benchmark): ns per evaluation of Wrenninge's
// octave sum for 1 to 8 octaves in float and double, with the octave count known at run
// time, fixed at compile time (multiple_scattering<N>), in the textbook pow() form
// (bench/naive.hpp) and with the fast approximations (fast::multiple_scattering); and the
// batch entry point (3 octaves) over 2^20 samples next to the naive and the library scalar
// loops and a copy of the same size. Names, timing and counters: bench/bench_support.hpp.
//
// Run: bash scripts/bench.sh (all module benchmarks, writes docs/bench.md), or directly
//      build/<dir>/bench/cloudmath_bench_multiple_scattering --benchmark_min_time=0.05
// Inputs: 4096 (scalar) or 2^20 (batch) pairs (tau, mu), tau in [0, 10] and mu in [-1, 1]
// from low-discrepancy sequences; g = 0.8, a = b = c = 0.5 (the usual production values).
#include <cloudmath/batch.hpp>
#include <cloudmath/fast_math.hpp>
#include <cloudmath/multiple_scattering.hpp>

#include <string>
#include <utility>

#include "bench_support.hpp"
#include "naive.hpp"

namespace cm = cloudmath;
using cm_bench::batch_arrays;
using cm_bench::opaque;

namespace {

constexpr double ms_g = 0.8;
constexpr double ms_abc = 0.5;
constexpr int max_octaves = 8;
constexpr int batch_octaves = 3;

template <class T>
struct scalar_samples {
    std::vector<T> tau = cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_2d[0], 0.0, 10.0);
    std::vector<T> mu = cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_2d[1], -1.0, 1.0);
};

// Registers "octaves_<N>/<variant>/<type>" evaluating f(tau, mu, g, a, b, c, octaves) with
// the parameters and the octave count behind an opaque barrier (runtime values).
template <class T, class F>
void register_octaves(int octaves, const char* variant, const std::string& label, F f) {
    cm_bench::register_scalar<T>("octaves_" + std::to_string(octaves), variant, label, [f, octaves] {
        return [in = scalar_samples<T>(), g = opaque(T(ms_g)), abc = opaque(T(ms_abc)), count = opaque(octaves),
                f](std::size_t i) { return f(in.tau[i], in.mu[i], g, abc, abc, abc, count); };
    });
}

template <class T, int N>
void register_octave_count() {
    const std::string n = std::to_string(N);
    register_octaves<T>(N, "runtime", "multiple_scattering(..., " + n + "), count at run time",
                        [](T tau, T mu, T g, T a, T b, T c, int octaves) {
                            return cm::multiple_scattering(tau, mu, g, a, b, c, octaves);
                        });
    register_octaves<T>(N, "compile_time", "multiple_scattering<" + n + ">(...)",
                        [](T tau, T mu, T g, T a, T b, T c, int) {
                            return cm::multiple_scattering<N>(tau, mu, g, a, b, c);
                        });
    register_octaves<T>(N, "naive_pow", "naive: pow(b, i) HG(mu, pow(c, i) g) exp(-pow(a, i) tau)",
                        [](T tau, T mu, T g, T a, T b, T c, int octaves) {
                            return cm_naive::multiple_scattering(tau, mu, g, a, b, c, octaves);
                        });
    register_octaves<T>(N, "fast", "fast::multiple_scattering (5.4e-3)",
                        [](T tau, T mu, T g, T a, T b, T c, int octaves) {
                            return cm::fast::multiple_scattering(tau, mu, g, a, b, c, octaves);
                        });
}

template <class T, int... N>
void register_scalar(std::integer_sequence<int, N...>) {
    (register_octave_count<T, N + 1>(), ...);
}

// The arguments of batch::multiple_scattering after the arrays.
template <class T>
struct octave_parameters {
    T g, a, b, c;
    int octaves;
};

template <class T>
void register_batch() {
    using cm_bench::call_alone;
    using P = octave_parameters<T>;
    const P q{T(ms_g), T(ms_abc), T(ms_abc), T(ms_abc), batch_octaves};
    // Each loop compiled alone with run-time arguments (cm_bench::call_alone).
    const auto run = [q](auto loop) {
        return [q, loop](batch_arrays<T>& a) {
            call_alone(loop, a.tau.data(), a.mu.data(), a.out.size(), opaque(q.g), opaque(q.a), q.octaves, a.out.data());
        };
    };
    cm_bench::make_batch_function<T>("multiple_scattering",
                                     [q](const batch_arrays<T>& a, std::size_t i) {
                                         return cm::multiple_scattering(a.tau[i], a.mu[i], q.g, q.a, q.b, q.c,
                                                                        q.octaves);
                                     })
        .add("naive_loop", "naive pow() form per element, 3 octaves", cm_bench::unchecked,
             run([](const T* tau, const T* mu, std::size_t n, T g, T abc, int octaves, T* out) {
                 for (std::size_t i = 0; i < n; ++i)
                     out[i] = cm_naive::multiple_scattering(tau[i], mu[i], g, abc, abc, abc, octaves);
             }))
        .add("library_loop", "multiple_scattering per element, 3 octaves", cm_bench::exact_tolerance,
             run([](const T* tau, const T* mu, std::size_t n, T g, T abc, int octaves, T* out) {
                 for (std::size_t i = 0; i < n; ++i)
                     out[i] = cm::multiple_scattering(tau[i], mu[i], g, abc, abc, abc, octaves);
             }))
        .add("exact", "batch::multiple_scattering, 3 octaves", cm_bench::exact_tolerance,
             run([](const T* tau, const T* mu, std::size_t n, T g, T abc, int octaves, T* out) {
                 cm::batch::multiple_scattering(tau, mu, n, g, abc, abc, abc, octaves, out);
             }))
        .add("fast", "batch::multiple_scattering<fast_math>, 3 octaves", cm_bench::fast_tolerance,
             run([](const T* tau, const T* mu, std::size_t n, T g, T abc, int octaves, T* out) {
                 cm::batch::multiple_scattering<cm::fast_math>(tau, mu, n, g, abc, abc, abc, octaves, out);
             }));
}

}  // namespace

int main(int argc, char** argv) {
    return cm_bench::run_benchmarks(argc, argv, [] {
        register_scalar<float>(std::make_integer_sequence<int, max_octaves>());
        register_scalar<double>(std::make_integer_sequence<int, max_octaves>());
        cm_bench::register_copy<float>();
        cm_bench::register_copy<double>();
        register_batch<float>();
        register_batch<double>();
    });
}
