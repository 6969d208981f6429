// Benchmarks of integration.hpp (Google Benchmark): ns per evaluation of the per-step
// scattering integral in float and double next to the two textbook forms (bench/naive.hpp):
// the max(sigma_t, 1e-6) clamp and the Riemann sum S ds, and the batch entry point over 2^20
// steps next to the naive and the library scalar loops and a copy of the same size. Names,
// timing and counters: bench/bench_support.hpp.
//
// Run: bash scripts/bench.sh (all module benchmarks, writes docs/bench.md), or directly
//      build/<dir>/bench/cloudmath_bench_integration --benchmark_min_time=0.05
// Inputs: 4096 (scalar) or 2^20 (batch) pairs (S, sigma_t) of a 2D low-discrepancy sequence,
// S in [0, 1], sigma_t in [0, 0.1] 1/m (clear air to dense cloud), step ds = 25 m, so the
// step's optical depth covers [0, 2.5].
#include <cloudmath/batch.hpp>
#include <cloudmath/integration.hpp>

#include "bench_support.hpp"
#include "naive.hpp"

namespace cm = cloudmath;
using cm_bench::batch_arrays;
using cm_bench::opaque;

namespace {

constexpr double step_length = 25.0;  // m

template <class T>
struct scalar_steps {
    std::vector<T> source = cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_2d[0], 0.0, 1.0);
    std::vector<T> sigma_t = cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_2d[1], 0.0, 0.1);
};

// Registers "integrate_scattering/<variant>/<type>" evaluating f(S, sigma_t, ds).
template <class T, class F>
void register_step(const char* variant, const char* label, F f) {
    cm_bench::register_scalar<T>("integrate_scattering", variant, label, [f] {
        return [in = scalar_steps<T>(), ds = opaque(T(step_length)), f](std::size_t i) {
            return f(in.source[i], in.sigma_t[i], ds);
        };
    });
}

template <class T>
void register_scalar() {
    register_step<T>("library", "integrate_scattering: S ds (1 - exp(-x))/x, x = sigma_t ds",
                     [](T S, T sigma_t, T ds) { return cm::integrate_scattering(S, sigma_t, ds); });
    register_step<T>("naive_clamp", "naive: (S - S exp(-sigma_t ds)) / max(sigma_t, 1e-6)",
                     [](T S, T sigma_t, T ds) { return cm_naive::integrate_scattering_clamped(S, sigma_t, ds); });
    register_step<T>("naive_riemann", "naive: Riemann sum S ds (no in-step decay)",
                     [](T S, T sigma_t, T ds) { return cm_naive::integrate_scattering_riemann(S, sigma_t, ds); });
}

template <class T>
void register_batch() {
    using cm_bench::call_alone;
    const T ds = T(step_length);
    // Each loop compiled alone with run-time arguments (cm_bench::call_alone).
    cm_bench::make_batch_function<T>("integrate_scattering",
                                     [ds](const batch_arrays<T>& a, std::size_t i) {
                                         return cm::integrate_scattering(a.source[i], a.sigma_t[i], ds);
                                     })
        .add("naive_loop", "naive clamp-constant form per element", cm_bench::unchecked,
             [ds](batch_arrays<T>& a) {
                 call_alone([](const T* S, const T* sigma_t, std::size_t n, T d, T* out) {
                     for (std::size_t i = 0; i < n; ++i)
                         out[i] = cm_naive::integrate_scattering_clamped(S[i], sigma_t[i], d);
                 }, a.source.data(), a.sigma_t.data(), a.out.size(), opaque(ds), a.out.data());
             })
        .add("library_loop", "integrate_scattering per element", cm_bench::exact_tolerance,
             [ds](batch_arrays<T>& a) {
                 call_alone([](const T* S, const T* sigma_t, std::size_t n, T d, T* out) {
                     for (std::size_t i = 0; i < n; ++i) out[i] = cm::integrate_scattering(S[i], sigma_t[i], d);
                 }, a.source.data(), a.sigma_t.data(), a.out.size(), opaque(ds), a.out.data());
             })
        .add("exact", "batch::integrate_scattering", cm_bench::exact_tolerance, [ds](batch_arrays<T>& a) {
            call_alone([](const T* S, const T* sigma_t, std::size_t n, T d,
                          T* out) { cm::batch::integrate_scattering(S, sigma_t, n, d, out); },
                       a.source.data(), a.sigma_t.data(), a.out.size(), opaque(ds), a.out.data());
        });
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
