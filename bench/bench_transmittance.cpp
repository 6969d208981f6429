// Benchmarks of transmittance.hpp and the exponentials of fast_math.hpp (Google Benchmark):
// ns per evaluation in float and double next to the textbook forms (bench/naive.hpp), and the
// batch entry points over 2^20 optical depths next to the naive and the library scalar loops
// and a copy of the same size. Names, timing and counters: bench/bench_support.hpp.
//
// Run: bash scripts/bench.sh (all module benchmarks, writes docs/bench.md), or directly
//      build/<dir>/bench/cloudmath_bench_transmittance --benchmark_min_time=0.05
// Inputs: 4096 (scalar) or 2^20 (batch) optical depths spread evenly over [0, 10] by a
// low-discrepancy sequence (transmittance from 1 down to 4.5e-5); powder with k = 2.
#include <cloudmath/batch.hpp>
#include <cloudmath/fast_math.hpp>
#include <cloudmath/transmittance.hpp>

#include <cmath>

#include "bench_support.hpp"
#include "naive.hpp"

namespace cm = cloudmath;
using cm_bench::batch_arrays;
using cm_bench::opaque;

// The two float loops whose machine code scripts/bench.sh inspects (objdump), compiled alone
// under fixed names; the float benchmarks below call them, so the inspected code is the timed
// code. Every other batch loop is compiled alone the same way (cm_bench::call_alone).
extern "C" CM_BENCH_NOINLINE void cloudmath_bench_batch_beer_lambert_exact_float(const float* tau, std::size_t n,
                                                                               float* out) {
    cm::batch::beer_lambert(tau, n, out);
}
extern "C" CM_BENCH_NOINLINE void cloudmath_bench_naive_loop_beer_lambert_float(const float* tau, std::size_t n,
                                                                              float* out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::beer_lambert(tau[i]);
}

namespace {

constexpr double powder_k = 2.0;

template <class T>
std::vector<T> scalar_tau() {
    return cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_1d, 0.0, 10.0);
}

// Registers "<group>/<variant>/<type>" evaluating f(tau) over the scalar optical depths.
template <class T, class F>
void register_tau(const char* group, const char* variant, const char* label, F f) {
    cm_bench::register_scalar<T>(group, variant, label, [f] {
        return [tau = scalar_tau<T>(), f](std::size_t i) { return f(tau[i]); };
    });
}

template <class T>
void register_scalar() {
    // The exponential itself: what the exact batch functions use instead of std::exp.
    register_tau<T>("exp", "naive_std_exp", "std::exp(-tau) (libm call)", [](T t) { return std::exp(-t); });
    register_tau<T>("exp", "exp_vectorizable", "exp_vectorizable(-tau) (1 ulp float)",
                    [](T t) { return cm::exp_vectorizable(-t); });
    register_tau<T>("exp", "fast", "fast::exp(-tau) (4.2e-5)", [](T t) { return cm::fast::exp(-t); });
    // Beer-Lambert.
    register_tau<T>("beer_lambert", "library", "beer_lambert", [](T t) { return cm::beer_lambert(t); });
    register_tau<T>("beer_lambert", "naive", "naive: exp(-tau)", [](T t) { return cm_naive::beer_lambert(t); });
    register_tau<T>("beer_lambert", "fast", "fast::beer_lambert (4.2e-5)", [](T t) { return cm::fast::beer_lambert(t); });
    // Beer-Powder.
    register_tau<T>("beer_powder", "library", "beer_powder (exp and expm1)", [](T t) { return cm::beer_powder(t); });
    register_tau<T>("beer_powder", "naive", "naive: 2 exp(-tau)(1 - exp(-2 tau))",
                    [](T t) { return cm_naive::beer_powder(t); });
    register_tau<T>("beer_powder", "fast", "fast::beer_powder (one fast::exp, 1e-4 abs)",
                    [](T t) { return cm::fast::beer_powder(t); });
    // Powder (no textbook form in naive.hpp: no ratio).
    register_tau<T>("powder", "library", "powder(tau, 2) (expm1)", [](T t) { return cm::powder(t, T(powder_k)); });
    register_tau<T>("powder", "fast", "fast::powder(tau, 2) (4.2e-5 abs)",
                    [](T t) { return cm::fast::powder(t, T(powder_k)); });
    // Nubis attenuation.
    register_tau<T>("nubis_attenuation", "library", "nubis_attenuation", [](T t) { return cm::nubis_attenuation(t); });
    register_tau<T>("nubis_attenuation", "naive", "naive: max(exp(-tau), 0.7 exp(-tau/4))",
                    [](T t) { return cm_naive::nubis_attenuation(t); });
}

template <class T>
void register_batch() {
    using cm_bench::exact_tolerance;
    using cm_bench::fast_tolerance;
    using cm_bench::unchecked;
    // Runs loop(tau, n, out) over the batch arrays, compiled alone with run-time arguments
    // (cm_bench::call_alone): loop is a lambda, or one of the named float loops above.
    const auto over_tau = [](auto loop) {
        return [loop](batch_arrays<T>& a) { cm_bench::call_alone(loop, a.tau.data(), a.tau.size(), a.out.data()); };
    };

    // Beer-Lambert. In float, the naive and exact loops are the named functions that
    // scripts/bench.sh disassembles (the same code as the lambdas).
    const auto bl = cm_bench::make_batch_function<T>(
        "beer_lambert", [](const batch_arrays<T>& a, std::size_t i) { return cm::beer_lambert(a.tau[i]); });
    if constexpr (std::is_same_v<T, float>) {
        bl.add("naive_loop", "naive beer_lambert per element", unchecked,
               over_tau(&cloudmath_bench_naive_loop_beer_lambert_float));
    } else {
        bl.add("naive_loop", "naive beer_lambert per element", unchecked,
               over_tau([](const T* tau, std::size_t n, T* out) {
                   for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::beer_lambert(tau[i]);
               }));
    }
    bl.add("library_loop", "beer_lambert per element", exact_tolerance,
           over_tau([](const T* tau, std::size_t n, T* out) {
               for (std::size_t i = 0; i < n; ++i) out[i] = cm::beer_lambert(tau[i]);
           }));
    if constexpr (std::is_same_v<T, float>) {
        bl.add("exact", "batch::beer_lambert", exact_tolerance,
               over_tau(&cloudmath_bench_batch_beer_lambert_exact_float));
    } else {
        bl.add("exact", "batch::beer_lambert", exact_tolerance,
               over_tau([](const T* tau, std::size_t n, T* out) { cm::batch::beer_lambert(tau, n, out); }));
    }
    bl.add("fast", "batch::beer_lambert<fast_math>", fast_tolerance,
           over_tau([](const T* tau, std::size_t n, T* out) { cm::batch::beer_lambert<cm::fast_math>(tau, n, out); }));

    // Beer-Powder.
    cm_bench::make_batch_function<T>("beer_powder",
                                     [](const batch_arrays<T>& a, std::size_t i) { return cm::beer_powder(a.tau[i]); })
        .add("naive_loop", "naive beer_powder per element", unchecked,
             over_tau([](const T* tau, std::size_t n, T* out) {
                 for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::beer_powder(tau[i]);
             }))
        .add("library_loop", "beer_powder per element", exact_tolerance,
             over_tau([](const T* tau, std::size_t n, T* out) {
                 for (std::size_t i = 0; i < n; ++i) out[i] = cm::beer_powder(tau[i]);
             }))
        .add("exact", "batch::beer_powder", exact_tolerance,
             over_tau([](const T* tau, std::size_t n, T* out) { cm::batch::beer_powder(tau, n, out); }))
        .add("fast", "batch::beer_powder<fast_math>", fast_tolerance,
             over_tau([](const T* tau, std::size_t n, T* out) { cm::batch::beer_powder<cm::fast_math>(tau, n, out); }));

    // Nubis attenuation.
    cm_bench::make_batch_function<T>(
        "nubis_attenuation", [](const batch_arrays<T>& a, std::size_t i) { return cm::nubis_attenuation(a.tau[i]); })
        .add("naive_loop", "naive nubis_attenuation per element", unchecked,
             over_tau([](const T* tau, std::size_t n, T* out) {
                 for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::nubis_attenuation(tau[i]);
             }))
        .add("library_loop", "nubis_attenuation per element", exact_tolerance,
             over_tau([](const T* tau, std::size_t n, T* out) {
                 for (std::size_t i = 0; i < n; ++i) out[i] = cm::nubis_attenuation(tau[i]);
             }))
        .add("exact", "batch::nubis_attenuation", exact_tolerance,
             over_tau([](const T* tau, std::size_t n, T* out) { cm::batch::nubis_attenuation(tau, n, out); }))
        .add("fast", "batch::nubis_attenuation<fast_math>", fast_tolerance,
             over_tau([](const T* tau, std::size_t n, T* out) {
                 cm::batch::nubis_attenuation<cm::fast_math>(tau, n, out);
             }));
}

}  // namespace

int main(int argc, char** argv) {
    return cm_bench::run_benchmarks(argc, argv, [] {
        register_scalar<float>();
        register_scalar<double>();
        cm_bench::register_copy<float>();
        cm_bench::register_copy<double>();
        register_batch<float>();
        register_batch<double>();
    });
}
