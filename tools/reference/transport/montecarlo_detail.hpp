// tools/reference/transport/montecarlo_detail.hpp: the building blocks the Monte Carlo path tracers
// share (montecarlo.cpp for homogeneous media, volume_tracer.cpp for heterogeneous ones):
// double vectors, phase-sampled scattering directions, the per-chunk xoshiro256++ random
// streams, sample moments and the fixed-chunk thread pool. Not part of a public interface;
// see montecarlo.hpp for the conventions and the sources.
#ifndef CLOUDMATH_TOOLS_MONTECARLO_DETAIL_HPP
#define CLOUDMATH_TOOLS_MONTECARLO_DETAIL_HPP

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "montecarlo.hpp"

namespace cloudmath::reference::mc {

// ---------------------------------------------------------------------------------------
// Vectors.
inline vec3 operator+(const vec3& a, const vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline vec3 operator*(double s, const vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const vec3& a, const vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline vec3 cross(const vec3& a, const vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline vec3 normalized(const vec3& a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

namespace detail {

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double infinity = std::numeric_limits<double>::infinity();

// Paths per chunk: the unit of work and of random streams. Fixed, so results do not depend
// on the thread count.
inline constexpr std::uint64_t paths_per_chunk = 4096;
// Russian roulette: a throughput below this survives with probability throughput / it and
// is then set to it (unbiased).
inline constexpr double roulette_threshold = 0.2;

// Direction at cosine mu and azimuth 2 pi u around the unit vector n. The basis around n is
// the branch-free construction of Duff et al., "Building an Orthonormal Basis, Revisited",
// JCGT 6(1), 2017: continuous everywhere except the sign switch at n.z = 0, and accurate
// near n.z = -1, where Frisvad's original form breaks down.
inline vec3 scatter_direction(const vec3& n, double mu, double u) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    const vec3 t{1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    const vec3 s{b, sign + n.y * n.y * a, -n.y};
    const double sin_theta = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
    const double phi = 2.0 * pi * u;
    const vec3 d = mu * n + sin_theta * (std::cos(phi) * t + std::sin(phi) * s);
    // Renormalise so that rounding does not accumulate over hundreds of scatterings.
    return normalized(d);
}

// Distance from p (|p| <= 1) along the unit vector d to the unit sphere. h = 1 - |p|^2 and
// the two forms avoid cancellation when p is near the surface on either side of the chord.
inline double distance_to_unit_sphere(const vec3& p, const vec3& d) {
    const double h = std::max(0.0, 1.0 - dot(p, p));
    const double b = dot(p, d);
    const double root = std::sqrt(b * b + h);
    return b <= 0.0 ? root - b : h / (b + root);
}

// ---------------------------------------------------------------------------------------
// Random numbers: splitmix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014) turns (seed, stream key) into the state of a xoshiro256++
// generator (Blackman & Vigna 2021).
inline std::uint64_t splitmix64_next(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

class random_stream {
public:
    // One independent stream per (seed, key1, key2): estimators use key1 for what is
    // computed (the view or ray index) and key2 for the chunk.
    random_stream(std::uint64_t seed, std::uint64_t key1, std::uint64_t key2) {
        std::uint64_t h = seed;
        h = splitmix64_next(h) ^ key1;
        h = splitmix64_next(h) ^ key2;
        std::uint64_t st = splitmix64_next(h);
        for (auto& w : s_) w = splitmix64_next(st);
    }
    std::uint64_t next() {
        const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    // Exponentially distributed free path in optical units: -log(1 - u), u in [0, 1).
    double free_path() { return -std::log1p(-uniform()); }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t s_[4];
};

// ---------------------------------------------------------------------------------------
// Sums of the per-sample values and of their squares; merged in a fixed order.
struct moments {
    double sum = 0.0;
    double sum_sq = 0.0;
    void add(double x) {
        sum += x;
        sum_sq += x * x;
    }
    void merge(const moments& o) {
        sum += o.sum;
        sum_sq += o.sum_sq;
    }
};

// Estimate of scale * (mean of the n samples, zeros included); the standard error is that
// of the mean, sqrt(sample variance / n).
inline estimate make_estimate(const moments& m, std::uint64_t n, double scale = 1.0) {
    estimate e;
    e.samples = n;
    if (n == 0) return e;
    const double nd = static_cast<double>(n);
    const double mean = m.sum / nd;
    e.mean = scale * mean;
    if (n < 2) {
        e.std_error = infinity;
        return e;
    }
    const double variance = std::max(0.0, (m.sum_sq - m.sum * mean) / (nd - 1.0));
    e.std_error = std::abs(scale) * std::sqrt(variance / nd);
    return e;
}

// Runs work(i) for i in [0, count) on the requested threads; chunks are taken in order by
// whichever thread is free, results go to per-chunk slots that the caller reduces in order.
inline void run_chunks(std::size_t count, const run_options& options,
                const std::function<void(std::size_t)>& work) {
    unsigned threads = options.threads;
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    threads = static_cast<unsigned>(
        std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
    std::atomic<std::size_t> next{0};
    std::mutex report_mutex;
    std::size_t done = 0;
    std::exception_ptr failure;
    auto worker = [&]() {
        for (;;) {
            const std::size_t i = next.fetch_add(1);
            if (i >= count) return;
            try {
                work(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(report_mutex);
                if (!failure) failure = std::current_exception();
                next.store(count);
                return;
            }
            const std::lock_guard<std::mutex> lock(report_mutex);
            ++done;
            if (options.progress)
                options.progress(static_cast<double>(done) / static_cast<double>(count));
        }
    };
    if (threads <= 1) {
        worker();
    } else {
        std::vector<std::thread> pool;
        pool.reserve(threads);
        for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
        for (auto& th : pool) th.join();
    }
    if (failure) std::rethrow_exception(failure);
}

inline std::uint64_t chunk_count(std::uint64_t samples) {
    return (samples + paths_per_chunk - 1) / paths_per_chunk;
}
inline std::uint64_t chunk_size(std::uint64_t samples, std::uint64_t chunk) {
    return std::min(paths_per_chunk, samples - chunk * paths_per_chunk);
}

// Runs `paths` samples of sample(item, rng, tally) for each of `items` items, in chunks of
// paths_per_chunk with the random stream (seed, key + item, chunk), each chunk into its own
// Tally (default-constructed, with merge()); returns per item the chunks merged in order.
template <class Tally, class SampleFn>
std::vector<Tally> tally_per_item(std::size_t items, std::uint64_t paths, const run_options& options,
                                  std::uint64_t key, SampleFn sample) {
    if (paths == 0) throw std::invalid_argument("path count must be >= 1");
    const auto per_item = static_cast<std::size_t>(chunk_count(paths));
    std::vector<Tally> tallies(per_item * items);
    run_chunks(tallies.size(), options, [&](std::size_t k) {
        const std::size_t item = k / per_item;
        const std::uint64_t chunk = k % per_item;
        random_stream rng(options.seed, key + item, chunk);
        const std::uint64_t n = chunk_size(paths, chunk);
        for (std::uint64_t i = 0; i < n; ++i) sample(item, rng, tallies[k]);
    });
    std::vector<Tally> totals(items);
    for (std::size_t item = 0; item < items; ++item)
        for (std::size_t c = 0; c < per_item; ++c) totals[item].merge(tallies[item * per_item + c]);
    return totals;
}

// The same with paths[item] samples for each item (0 allowed: an empty tally): chunks of
// paths_per_chunk per item with the streams (seed, key + item, chunk), merged in order, so the
// result depends on the counts and the seed only, not on the thread count.
template <class Tally, class SampleFn>
std::vector<Tally> tally_per_item(const std::vector<std::uint64_t>& paths, const run_options& options,
                                  std::uint64_t key, SampleFn sample) {
    std::vector<std::size_t> first(paths.size() + 1, 0);  // chunk index where each item starts
    for (std::size_t item = 0; item < paths.size(); ++item)
        first[item + 1] = first[item] + static_cast<std::size_t>(chunk_count(paths[item]));
    std::vector<Tally> tallies(first.back());
    std::vector<std::size_t> owner(first.back());
    for (std::size_t item = 0; item < paths.size(); ++item)
        for (std::size_t k = first[item]; k < first[item + 1]; ++k) owner[k] = item;
    run_chunks(tallies.size(), options, [&](std::size_t k) {
        const std::size_t item = owner[k];
        const std::uint64_t chunk = k - first[item];
        random_stream rng(options.seed, key + item, chunk);
        const std::uint64_t n = chunk_size(paths[item], chunk);
        for (std::uint64_t i = 0; i < n; ++i) sample(item, rng, tallies[k]);
    });
    std::vector<Tally> totals(paths.size());
    for (std::size_t item = 0; item < paths.size(); ++item)
        for (std::size_t k = first[item]; k < first[item + 1]; ++k) totals[item].merge(tallies[k]);
    return totals;
}

}  // namespace detail

}  // namespace cloudmath::reference::mc

#endif  // CLOUDMATH_TOOLS_MONTECARLO_DETAIL_HPP
