// Benchmarks of noise.hpp and noise_bake.hpp (Google Benchmark): nanoseconds per evaluation
// of each noise function in float, and the 128^3 base-volume bake (the most expensive of the
// Nubis textures) on one thread and on all hardware threads, in voxels per second.
//
// Run: bash scripts/bench-noise.sh (builds, runs, writes docs/bench_noise.md), or directly
//      build/<dir>/bench/cloudmath_bench_noise --benchmark_min_time=0.1
// Per-evaluation benchmarks cycle through 4096 points spread over a period-8 tile, so the
// cost includes the branchy cell lookups of real use, not one cached point. "Time" is
// nanoseconds per call. The bakes report items_per_second = voxels/s; the all-threads run
// also reports speedup = its voxels/s over those of the one-thread run (when both ran).
#include <cloudmath/noise.hpp>
#include <cloudmath/noise_bake.hpp>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

namespace cm = cloudmath;

namespace {

constexpr int period = 8;
constexpr std::size_t point_count = 4096;  // power of two: index with a mask

// Points of a low-discrepancy additive recurrence over [0, period)^3: steps 1/g, 1/g^2, 1/g^3
// with g = 1.2207440846 the real root of g^4 = g + 1 (the 3D generalised golden ratio).
const std::vector<glm::vec3>& points() {
    static const std::vector<glm::vec3> p = [] {
        std::vector<glm::vec3> v(point_count);
        double a = 0.5, b = 0.5, c = 0.5;
        for (glm::vec3& q : v) {
            a += 0.8191725133961645;
            b += 0.6710436067037893;
            c += 0.5497004779019703;
            a -= static_cast<double>(static_cast<int>(a));
            b -= static_cast<double>(static_cast<int>(b));
            c -= static_cast<double>(static_cast<int>(c));
            q = glm::vec3(static_cast<float>(a * period), static_cast<float>(b * period), static_cast<float>(c * period));
        }
        return v;
    }();
    return p;
}

template <class Eval>
void per_evaluation(benchmark::State& state, Eval eval) {
    const std::vector<glm::vec3>& p = points();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(eval(p[i]));
        i = (i + 1) & (point_count - 1);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void BM_perlin_noise_3d(benchmark::State& state) {
    per_evaluation(state, [](const glm::vec3& q) { return cm::perlin_noise(q, period); });
}
void BM_perlin_noise_2d(benchmark::State& state) {
    per_evaluation(state, [](const glm::vec3& q) { return cm::perlin_noise(glm::vec2(q.x, q.y), period); });
}
void BM_worley_noise(benchmark::State& state) {
    per_evaluation(state, [](const glm::vec3& q) { return cm::worley_noise(q, period); });
}
void BM_worley_fbm_nubis(benchmark::State& state) {
    per_evaluation(state, [](const glm::vec3& q) { return cm::worley_fbm_nubis(q, period); });
}
void BM_perlin_worley(benchmark::State& state) {
    per_evaluation(state, [](const glm::vec3& q) { return cm::perlin_worley(q, period); });
}
void BM_curl_noise(benchmark::State& state) {
    per_evaluation(state, [](const glm::vec3& q) { return cm::curl_noise(q, period); });
}

// voxels/s of the last one-thread base bake, for the all-threads run's speedup counter.
double one_thread_voxels_per_second = 0;

// The default base volume (128^3 RGBA8, 4 cells); argument: threads (0 = all hardware
// threads). Timed by hand in wall-clock time: the workers' time is not the main thread's CPU
// time. Counters: bake_threads (threads used), voxels_per_second, and for the multi-thread run `speedup`,
// its voxels/s over the one-thread run's (registered first, so it ran first).
void BM_bake_base_volume_128(benchmark::State& state) {
    const int size = cm::base_volume_default_size;
    std::vector<std::uint8_t> out(static_cast<std::size_t>(size) * size * size * 4U);
    cm::bake_options options;
    options.threads = static_cast<unsigned>(state.range(0));
    double seconds = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        const bool ok = cm::bake_base_volume(out.data(), size, cm::base_volume_default_cells, options);
        benchmark::DoNotOptimize(ok);
        benchmark::ClobberMemory();
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        state.SetIterationTime(elapsed);
        seconds += elapsed;
    }
    const double voxels = static_cast<double>(size) * size * size * static_cast<double>(state.iterations());
    state.SetItemsProcessed(static_cast<std::int64_t>(voxels));
    const unsigned hardware = std::thread::hardware_concurrency();
    const unsigned threads = options.threads != 0 ? options.threads : (hardware != 0 ? hardware : 1U);
    const double rate = seconds > 0 ? voxels / seconds : 0;
    state.counters["bake_threads"] = threads;
    state.counters["voxels_per_second"] = rate;
    if (options.threads == 1) {
        one_thread_voxels_per_second = rate;
    } else if (one_thread_voxels_per_second > 0) {
        state.counters["speedup"] = rate / one_thread_voxels_per_second;
    }
}

}  // namespace

BENCHMARK(BM_perlin_noise_3d);
BENCHMARK(BM_perlin_noise_2d);
BENCHMARK(BM_worley_noise);
BENCHMARK(BM_worley_fbm_nubis);
BENCHMARK(BM_perlin_worley);
BENCHMARK(BM_curl_noise);
BENCHMARK(BM_bake_base_volume_128)->ArgName("threads")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(1);

BENCHMARK_MAIN();
