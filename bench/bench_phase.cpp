// Benchmarks of phase.hpp (Google Benchmark): ns per evaluation of the phase functions in
// float and double next to their textbook forms (bench/naive.hpp), and the batch entry points
// over 2^20 scattering cosines next to the naive and the library scalar loops and a copy of
// the same size. Names, timing and counters: bench/bench_support.hpp.
//
// Run: bash scripts/bench.sh (all module benchmarks, writes docs/bench.md), or directly
//      build/<dir>/bench/cloudmath_bench_phase --benchmark_min_time=0.05
// Inputs: 4096 (scalar) or 2^20 (batch) cosines mu spread evenly over [-1, 1] by a
// low-discrepancy sequence; g = 0.8 (a typical cloud forward lobe); the Mie fit at a droplet
// diameter of 10 um, in the range where the fit is most expensive to set up.
#include <cloudmath/batch.hpp>
#include <cloudmath/fast_math.hpp>
#include <cloudmath/phase.hpp>

#include "bench_support.hpp"
#include "naive.hpp"

namespace cm = cloudmath;
using cm_bench::batch_arrays;
using cm_bench::opaque;

// The two float loops whose machine code scripts/bench.sh inspects (objdump), compiled alone
// under fixed names; the float benchmarks below call them, so the inspected code is the timed
// code. Every other batch loop is compiled alone the same way (cm_bench::call_alone).
extern "C" CM_BENCH_NOINLINE void cloudmath_bench_batch_phase_hg_exact_float(const float* mu, std::size_t n, float g,
                                                                           float* out) {
    cm::batch::phase_hg(mu, n, g, out);
}
extern "C" CM_BENCH_NOINLINE void cloudmath_bench_naive_loop_phase_hg_float(const float* mu, std::size_t n, float g,
                                                                          float* out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::phase_hg(mu[i], g);
}

namespace {

constexpr double hg_g = 0.8;
constexpr double draine_g = 0.5;
constexpr double draine_alpha = 1.0;
constexpr double mie_diameter_um = 10.0;
constexpr int mie_table_size = 1800;  // one entry per 0.1 degree

template <class T>
std::vector<T> scalar_mu() {
    return cm_bench::sequence<T>(cm_bench::scalar_count, cm_bench::step_1d, -1.0, 1.0);
}

template <class T>
void register_scalar() {
    using cm_bench::register_scalar;
    // Henyey-Greenstein.
    register_scalar<T>("phase_hg", "library", "phase_hg: stable base, 1/(d sqrt d)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(hg_g))](std::size_t i) { return cm::phase_hg(mu[i], g); };
    });
    register_scalar<T>("phase_hg", "naive_pow", "naive: pow(1 + g^2 - 2 g mu, 1.5)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(hg_g))](std::size_t i) { return cm_naive::phase_hg(mu[i], g); };
    });
    register_scalar<T>("phase_hg", "fast", "fast::phase_hg (rsqrt bit trick, 5.3e-3)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(hg_g))](std::size_t i) { return cm::fast::phase_hg(mu[i], g); };
    });
    register_scalar<T>("phase_hg", "schlick", "phase_hg_schlick (no root, up to 90% off)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(hg_g))](std::size_t i) { return cm::phase_hg_schlick(mu[i], g); };
    });
    // Cornette-Shanks.
    register_scalar<T>("phase_cornette_shanks", "library", "phase_cornette_shanks", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(hg_g))](std::size_t i) { return cm::phase_cornette_shanks(mu[i], g); };
    });
    register_scalar<T>("phase_cornette_shanks", "naive_pow", "naive: pow(1 + g^2 - 2 g mu, 1.5)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(hg_g))](std::size_t i) {
            return cm_naive::phase_cornette_shanks(mu[i], g);
        };
    });
    // Draine.
    register_scalar<T>("phase_draine", "library", "phase_draine (g 0.5, alpha 1)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(draine_g)), alpha = opaque(T(draine_alpha))](std::size_t i) {
            return cm::phase_draine(mu[i], g, alpha);
        };
    });
    register_scalar<T>("phase_draine", "naive_pow", "naive: pow(1 + g^2 - 2 g mu, 1.5)", [] {
        return [mu = scalar_mu<T>(), g = opaque(T(draine_g)), alpha = opaque(T(draine_alpha))](std::size_t i) {
            return cm_naive::phase_draine(mu[i], g, alpha);
        };
    });
    // Jendersie & d'Eon Mie fit, 10 um droplets.
    register_scalar<T>("phase_mie_approx", "per_call_params", "phase_mie_approx(mu, d): fit parameters every call", [] {
        return [mu = scalar_mu<T>(), d = opaque(T(mie_diameter_um))](std::size_t i) {
            return cm::phase_mie_approx(mu[i], d);
        };
    });
    register_scalar<T>("phase_mie_approx", "precomputed_params", "phase_mie_approx(mu, params), params once", [] {
        return [mu = scalar_mu<T>(), p = cm::mie_approx_params(opaque(T(mie_diameter_um)))](std::size_t i) {
            return cm::phase_mie_approx(mu[i], p);
        };
    });
    register_scalar<T>("phase_mie_approx", "naive_table", "naive: 1800-entry table over the angle, acos + lerp", [] {
        const cm::mie_approx_parameters<T> p = cm::mie_approx_params(opaque(T(mie_diameter_um)));
        return [mu = scalar_mu<T>(), table = cm_naive::phase_table<T>(mie_table_size, [p](T m) {
                    return cm::phase_mie_approx(m, p);
                })](std::size_t i) { return table(mu[i]); };
    });
}

template <class T>
void register_batch() {
    using cm_bench::exact_tolerance;
    using cm_bench::fast_tolerance;
    using cm_bench::unchecked;
    const T g = T(hg_g);
    // Runs loop(mu, n, g, out) over the batch arrays, compiled alone with run-time arguments
    // (cm_bench::call_alone): loop is a lambda, or one of the named float loops above.
    const auto over_mu = [g](auto loop) {
        return [g, loop](batch_arrays<T>& a) {
            cm_bench::call_alone(loop, a.mu.data(), a.mu.size(), opaque(g), a.out.data());
        };
    };

    // Henyey-Greenstein. In float, the naive and exact loops are the named functions that
    // scripts/bench.sh disassembles (the same code as the lambdas).
    const auto hg = cm_bench::make_batch_function<T>(
        "phase_hg", [g](const batch_arrays<T>& a, std::size_t i) { return cm::phase_hg(a.mu[i], g); });
    if constexpr (std::is_same_v<T, float>) {
        hg.add("naive_loop", "naive phase_hg per element", unchecked, over_mu(&cloudmath_bench_naive_loop_phase_hg_float));
    } else {
        hg.add("naive_loop", "naive phase_hg per element", unchecked,
               over_mu([](const T* mu, std::size_t n, T q, T* out) {
                   for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::phase_hg(mu[i], q);
               }));
    }
    hg.add("library_loop", "phase_hg per element", exact_tolerance,
           over_mu([](const T* mu, std::size_t n, T q, T* out) {
               for (std::size_t i = 0; i < n; ++i) out[i] = cm::phase_hg(mu[i], q);
           }));
    if constexpr (std::is_same_v<T, float>) {
        hg.add("exact", "batch::phase_hg", exact_tolerance, over_mu(&cloudmath_bench_batch_phase_hg_exact_float));
    } else {
        hg.add("exact", "batch::phase_hg", exact_tolerance,
               over_mu([](const T* mu, std::size_t n, T q, T* out) { cm::batch::phase_hg(mu, n, q, out); }));
    }
    hg.add("fast", "batch::phase_hg<fast_math>", fast_tolerance,
           over_mu([](const T* mu, std::size_t n, T q, T* out) { cm::batch::phase_hg<cm::fast_math>(mu, n, q, out); }));

    // Cornette-Shanks.
    cm_bench::make_batch_function<T>("phase_cornette_shanks", [g](const batch_arrays<T>& a, std::size_t i) {
        return cm::phase_cornette_shanks(a.mu[i], g);
    })
        .add("naive_loop", "naive phase_cornette_shanks per element", unchecked,
             over_mu([](const T* mu, std::size_t n, T q, T* out) {
                 for (std::size_t i = 0; i < n; ++i) out[i] = cm_naive::phase_cornette_shanks(mu[i], q);
             }))
        .add("library_loop", "phase_cornette_shanks per element", exact_tolerance,
             over_mu([](const T* mu, std::size_t n, T q, T* out) {
                 for (std::size_t i = 0; i < n; ++i) out[i] = cm::phase_cornette_shanks(mu[i], q);
             }))
        .add("exact", "batch::phase_cornette_shanks", exact_tolerance,
             over_mu([](const T* mu, std::size_t n, T q, T* out) { cm::batch::phase_cornette_shanks(mu, n, q, out); }))
        .add("fast", "batch::phase_cornette_shanks<fast_math>", fast_tolerance,
             over_mu([](const T* mu, std::size_t n, T q, T* out) {
                 cm::batch::phase_cornette_shanks<cm::fast_math>(mu, n, q, out);
             }));

    // Mie fit, 10 um: the naive loop is the table lookup engines use for measured phase
    // functions (its interpolation error is the report's business, so it is not checked).
    using params = cm::mie_approx_parameters<T>;
    using table = cm_naive::phase_table<T>;
    const params p = cm::mie_approx_params(T(mie_diameter_um));
    cm_bench::make_batch_function<T>("phase_mie_approx", [p](const batch_arrays<T>& a, std::size_t i) {
        return cm::phase_mie_approx(a.mu[i], p);
    })
        .add("naive_loop", "naive: 1800-entry table lookup per element", unchecked,
             [p](batch_arrays<T>& a) {
                 static const table lookup(mie_table_size, [p](T m) { return cm::phase_mie_approx(m, p); });
                 cm_bench::call_alone(
                     [](const T* mu, std::size_t n, const table* t, T* out) {
                         for (std::size_t i = 0; i < n; ++i) out[i] = (*t)(mu[i]);
                     },
                     a.mu.data(), a.mu.size(), &lookup, a.out.data());
             })
        .add("library_loop", "phase_mie_approx(mu, params) per element", exact_tolerance,
             [p](batch_arrays<T>& a) {
                 cm_bench::call_alone(
                     [](const T* mu, std::size_t n, params q, T* out) {
                         for (std::size_t i = 0; i < n; ++i) out[i] = cm::phase_mie_approx(mu[i], q);
                     },
                     a.mu.data(), a.mu.size(), p, a.out.data());
             })
        .add("exact", "batch::phase_mie_approx", exact_tolerance, [p](batch_arrays<T>& a) {
            cm_bench::call_alone(
                [](const T* mu, std::size_t n, params q, T* out) { cm::batch::phase_mie_approx(mu, n, q, out); },
                a.mu.data(), a.mu.size(), p, a.out.data());
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
