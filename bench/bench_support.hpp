// Shared scaffolding of the per-module lighting benchmarks (bench_phase.cpp, ...): input
// arrays, the scalar per-evaluation loop, the timed batch loop with its ratio counters, and
// the registration helpers. Benchmarks only; never part of the library.
//
// Names. Every benchmark is registered as "<group>/<variant>/<float|double>" (scalar) or
// "batch/<function>/<variant>/<float|double>" (arrays), in a fixed order, so the tables that
// scripts/bench.sh builds from the JSON output always have the same rows. The label holds
// the human-readable description of the variant. In a scalar group the first variant whose
// name starts with "naive" is the baseline that the tables compare against.
//
// Scalar benchmarks evaluate the function once for each of 4096 pre-generated inputs per
// iteration, with benchmark::DoNotOptimize on every result, and report items_per_second
// (ns per evaluation = 1e9 / items_per_second), measured in CPU time.
//
// Batch benchmarks process arrays of 2^20 inputs per iteration. They time each iteration by
// hand with the thread's CPU clock and report counters:
//   ns_per_element     this loop's time per element in its fastest iteration (on a shared
//                      machine, interference only ever adds time; the usual mean is
//                      1e9 / items_per_second),
//   x_copy             its time over that of std::copy of the same number of elements of the
//                      same type, measured earlier in the same run (1 = as fast as memory),
//   speedup_vs_naive   the naive scalar loop's time over this loop's time, the naive loop
//                      being the textbook function per element, measured earlier in the same
//                      run (> 1 = faster than the textbook loop).
#ifndef CLOUDMATH_BENCH_SUPPORT_HPP
#define CLOUDMATH_BENCH_SUPPORT_HPP

#include <benchmark/benchmark.h>
#include <cloudmath/batch.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// Compiles a function alone: never inlined into its callers and, with GCC, not cloned for
// the constant arguments they pass (noipa), so that its code is that of a function called
// with run-time arguments, and can be read with objdump under its own name.
#if defined(__GNUC__) && !defined(__clang__)
#define CM_BENCH_NOINLINE __attribute__((noipa))
#elif defined(__GNUC__)
#define CM_BENCH_NOINLINE __attribute__((noinline))
#else
#define CM_BENCH_NOINLINE
#endif

namespace cm_bench {

inline constexpr std::size_t scalar_count = 4096;             // inputs per scalar iteration
inline constexpr std::size_t batch_count = std::size_t(1) << 20;  // elements per batch call

template <class T>
const char* type_name() {
    return std::is_same_v<T, float> ? "float" : "double";
}

// Point i of an additive recurrence, frac(0.5 + (i + 1) alpha), in [0, 1): low-discrepancy
// and deterministic. Irrational steps for up to three coordinates: the golden ratio (1D),
// the plastic number (2D, "R2") and the 3D generalised golden ratio, as in bench_noise.cpp.
inline constexpr double step_1d = 0.6180339887498949;
inline constexpr double step_2d[2] = {0.7548776662466927, 0.5698402909980532};
inline constexpr double step_3d[3] = {0.8191725133961645, 0.6710436067037893, 0.5497004779019703};

// n values of the sequence with step `alpha`, mapped linearly onto [lo, hi).
template <class T>
std::vector<T> sequence(std::size_t n, double alpha, double lo, double hi) {
    std::vector<T> v(n);
    double u = 0.5;
    for (T& x : v) {
        u += alpha;
        u -= static_cast<double>(static_cast<long long>(u));
        x = static_cast<T>(lo + (hi - lo) * u);
    }
    return v;
}

// x through an opaque barrier: the compiler cannot constant-fold the value (a scene's g or
// droplet size is a run-time parameter, not a literal). A volatile round trip, not
// benchmark::DoNotOptimize(T&): with GCC 12 and Google Benchmark 1.7.1, that function's
// in-out asm operand handed back garbage for a double here (a denormal g that made every HG
// evaluation 15x slower; google/benchmark issue 903, GCC bug 92597).
template <class T>
T opaque(T x) {
    volatile T v = x;
    return v;
}

// A number for an error message, with all the digits a float or double needs.
inline std::string number_text(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", x);
    return text;
}

// ---------------------------------------------------------------------------------------
// Scalar: eval(i) evaluates the function at input i (0 <= i < count); the result goes
// through DoNotOptimize so that every call is made and its value computed.
template <class Eval>
void per_evaluation(benchmark::State& state, std::size_t count, const std::string& label, Eval&& eval) {
    for (auto _ : state) {
        for (std::size_t i = 0; i < count; ++i) benchmark::DoNotOptimize(eval(i));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
    state.SetLabel(label);
}

// ---------------------------------------------------------------------------------------
// Batch.

// Thread CPU time in seconds (POSIX).
inline double thread_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// ns per element of the loops measured so far in this run, by key ("copy/float",
// "phase_hg/naive_loop/float"): the baselines of the ratio counters. Each benchmark's last
// run (the reported one) overwrites its entry.
inline std::map<std::string, double>& measured_ns_per_element() {
    static std::map<std::string, double> m;
    return m;
}

// Times body() (which processes `count` elements and writes its results to memory) once per
// iteration, records the fastest iteration's ns per element under `key` and sets the counters
// described at the top against the baselines `copy_key` and `naive_key`, when those ran
// before it. Then
// verify() (untimed) returns an error message, empty when the results are right.
template <class Body, class Verify>
void timed_batch(benchmark::State& state, std::size_t count, const std::string& key, const std::string& copy_key,
                 const std::string& naive_key, const std::string& label, Body&& body, Verify&& verify) {
    double fastest = 0;
    bool first = true;
    for (auto _ : state) {
        const double start = thread_seconds();
        body();
        benchmark::ClobberMemory();
        const double elapsed = thread_seconds() - start;
        state.SetIterationTime(elapsed);
        if (first || elapsed < fastest) fastest = elapsed;
        first = false;
    }
    const std::string error = verify();
    if (!error.empty()) {
        state.SkipWithError(error.c_str());
        return;
    }
    const double elements = static_cast<double>(count) * static_cast<double>(state.iterations());
    state.SetItemsProcessed(static_cast<std::int64_t>(elements));
    state.SetLabel(label);
    if (fastest <= 0) return;
    const double ns = fastest * 1e9 / static_cast<double>(count);
    std::map<std::string, double>& measured = measured_ns_per_element();
    measured[key] = ns;
    state.counters["ns_per_element"] = ns;
    const auto copy = measured.find(copy_key);
    if (copy != measured.end() && copy->second > 0) state.counters["x_copy"] = ns / copy->second;
    const auto naive = measured.find(naive_key);
    if (naive != measured.end()) state.counters["speedup_vs_naive"] = naive->second / ns;
}

// The arrays every batch benchmark of one type works on: 2^20 inputs of each kind and one
// output array, allocated and written once (so no page faults are timed).
template <class T>
struct batch_arrays {
    std::vector<T> mu = sequence<T>(batch_count, step_1d, -1.0, 1.0);           // cos of the scattering angle
    std::vector<T> tau = sequence<T>(batch_count, step_2d[0], 0.0, 10.0);       // optical depth (with mu)
    std::vector<T> source = sequence<T>(batch_count, step_2d[0], 0.0, 1.0);     // S of the step integral
    std::vector<T> sigma_t = sequence<T>(batch_count, step_2d[1], 0.0, 0.1);    // extinction, 1/m
    std::vector<T> out = std::vector<T>(batch_count, T(0));

    static batch_arrays& get() {
        static batch_arrays a;
        return a;
    }
};

// Registers the copy loop of one type, the reference of the x_copy counters: std::copy of
// 2^20 elements from one of the input arrays into the output array.
template <class T>
void register_copy() {
    const std::string type = type_name<T>();
    benchmark::RegisterBenchmark(("batch/copy/std_copy/" + type).c_str(), [type](benchmark::State& state) {
        batch_arrays<T>& a = batch_arrays<T>::get();
        timed_batch(state, batch_count, "copy/" + type, "copy/" + type, "", "std::copy of 2^20 elements (memory bound)",
                    [&] {
                        std::copy(a.tau.begin(), a.tau.end(), a.out.begin());
                        benchmark::DoNotOptimize(a.out.data());
                    },
                    [&]() -> std::string { return a.out == a.tau ? "" : "copy differs"; });
    })->UseManualTime();
}

// Calls f(args...) from a function of its own (one per f, a lambda) whose arguments are
// run-time values: every timed loop is compiled as it is when a renderer calls it with its
// own arrays and sizes, not specialised for the benchmark's constants or inlined into the
// benchmark machinery. (With GCC 12, whether a batch.hpp loop vectorises can depend on the
// code around the call: the same batch::phase_hg loop stayed scalar, "control flow in loop",
// when inlined with a constant size and pointers read from a std::vector.)
template <class F, class... Args>
CM_BENCH_NOINLINE void call_alone(F f, Args... args) {
    f(args...);
}

// Tolerances of the checked variants against the scalar library function.
inline constexpr double exact_tolerance = 1e-5;  // exact policy: a few float ulp
inline constexpr double fast_tolerance = 2e-2;   // fast policy: the documented max errors, with margin
inline constexpr double unchecked = -1;
inline constexpr double check_floor = 1e-2;

// One batch-processed function and its variants. reference(arrays, i) is the library's scalar
// function at input i; after timing, each checked variant's output is compared with it at
// 1024 spread indices, and a difference above tolerance * max(|reference|, check_floor) fails
// the benchmark (SkipWithError) instead of timing wrong code. (The floor keeps the check
// relative for ordinary values without failing the fast forms, whose documented errors are
// absolute, on transmittances near 0.) The variant named "naive_loop" is the baseline of the
// speedup_vs_naive counters and must be added first.
template <class T, class Reference>
class batch_function {
public:
    batch_function(std::string name, Reference reference) : name_(std::move(name)), reference_(std::move(reference)) {}

    // run(arrays) processes batch_count elements into arrays.out (through call_alone).
    // tolerance < 0: unchecked (the naive forms differ from the library on purpose).
    // The variant "exact" (the default policy) is registered twice: as users get it (the
    // instruction set that batch.hpp's run-time dispatch picks on this CPU, named in the
    // label) and as "exact_baseline", restricted to the code compiled for the translation
    // unit's flags (SSE2 here), so both copies are timed in the same run.
    template <class Run>
    const batch_function& add(const std::string& variant, const std::string& label, double tolerance, Run run) const {
        if (variant == "exact") {
            const cloudmath::batch::isa dispatched = cloudmath::batch::active_isa();
            add_one(variant, label + " (" + cloudmath::batch::isa_name(dispatched) + ", dispatched)", tolerance, run);
            if (dispatched != cloudmath::batch::isa::baseline)
                add_one("exact_baseline", label + " (baseline code only)", tolerance, [run](batch_arrays<T>& a) {
                    cloudmath::batch::restrict_to_baseline(true);
                    run(a);
                    cloudmath::batch::restrict_to_baseline(false);
                });
            return *this;
        }
        return add_one(variant, label, tolerance, run);
    }

private:
    template <class Run>
    const batch_function& add_one(const std::string& variant, const std::string& label, double tolerance, Run run) const {
        const std::string type = type_name<T>();
        const std::string key = name_ + "/" + variant + "/" + type;
        const std::string naive_key = name_ + "/naive_loop/" + type;
        benchmark::RegisterBenchmark(
            ("batch/" + key).c_str(), [=, reference = reference_](benchmark::State& state) {
                batch_arrays<T>& a = batch_arrays<T>::get();
                timed_batch(
                    state, batch_count, key, "copy/" + type, naive_key, label,
                    [&] {
                        run(a);
                        benchmark::DoNotOptimize(a.out.data());
                    },
                    [&]() -> std::string {
                        if (tolerance < 0) return {};
                        const std::size_t stride = batch_count / 1024;
                        for (std::size_t i = stride / 3; i < batch_count; i += stride) {
                            const double expected = static_cast<double>(reference(a, i));
                            const double got = static_cast<double>(a.out[i]);
                            const double magnitude = expected < 0 ? -expected : expected;
                            const double scale = magnitude > check_floor ? magnitude : check_floor;
                            const double diff = got > expected ? got - expected : expected - got;
                            if (!(diff <= tolerance * scale))
                                return "result " + number_text(got) + " at index " + std::to_string(i) +
                                       " differs from the scalar library's " + number_text(expected);
                        }
                        return {};
                    });
            })->UseManualTime();
        return *this;
    }

    std::string name_;
    Reference reference_;
};

template <class T, class Reference>
batch_function<T, Reference> make_batch_function(std::string name, Reference reference) {
    return batch_function<T, Reference>(std::move(name), std::move(reference));
}

// Registers a scalar benchmark "<group>/<variant>/<type>". make_eval() runs once before the
// timed loop (input generation, tables) and returns the callable eval(i).
template <class T, class MakeEval>
void register_scalar(const std::string& group, const std::string& variant, const std::string& label,
                     MakeEval make_eval) {
    const std::string name = group + "/" + variant + "/" + type_name<T>();
    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
        auto eval = make_eval();
        per_evaluation(state, scalar_count, label, eval);
    });
}

// main() of every module benchmark: the registrations run before the command line is read.
template <class Register>
int run_benchmarks(int argc, char** argv, Register&& register_all) {
    register_all();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

}  // namespace cm_bench

#endif  // CLOUDMATH_BENCH_SUPPORT_HPP
