// cloudmath/noise_bake.hpp: bakes the tileable textures of a Nubis-style cloud renderer on
// the CPU, multithreaded: the 3D base and detail volumes, the 2D curl texture and a 2D
// weather map, as 8-bit unsigned-normalised texels ready for a GPU upload.
//
// Use:      #include <cloudmath/noise_bake.hpp>   // not in cloudmath.hpp: needs <thread>
//           std::vector<std::uint8_t> base = cloudmath::bake_base_volume();      // 128^3 RGBA8
//           cloudmath::bake_options opts;  opts.seed = 7;  opts.threads = 4;
//           opts.progress = [](float done) { std::fprintf(stderr, "\r%3.0f%%", 100 * done); };
//           std::vector<std::uint8_t> detail = cloudmath::bake_detail_volume(32, 2, opts);
//           // or into your own memory: bool ok = bake_base_volume(ptr, size, cells, opts);
//           Link with threads (CMake: find_package(Threads) and Threads::Threads; -pthread),
//           which glibc before 2.34 and other platforms need for std::thread.
// Textures: (Schneider 2015/2017 sizes: 128^3 RGBA Perlin-Worley + 3 Worley octaves, 32^3 RGB
//           Worley, 128^2 curl; the weather map is ours)
//             base     size^3 RGBA8  R perlin_worley at `cells`; G, B, A worley_fbm_nubis at
//                                    2, 4 and 8 times `cells` (Nubis's "low-frequency fBm"
//                                    is G 0.625 + B 0.25 + A 0.125)
//             detail   size^3 RGB8   worley_fbm_nubis at 1, 2 and 4 times `cells`
//             curl     size^2 RGB8   3D curl_noise on the z = 0 plane, encoded by
//                                    curl_bake_encode (components in [-4, 4] -> [0, 1])
//             weather  size^2 RGB8   R coverage, G cloud type, B precipitation: 2D perlin_fbm
//                                    of 4, 2 and 3 octaves, each mapped by saturate(0.5 + v)
//           The bake_*_texel functions give the float values of one texel (what is quantised)
//           at noise coordinate p, so a shader or test can evaluate the same field.
// Layout:   texel (i, j, k) at byte ((k * size + j) * size + i) * channels: x fastest, then y,
//           then z (rows j for 2D); channels interleaved. Texel i samples the noise at
//           p = (i + 0.5) / size * cells (bake_coordinate), so one texture is one tile of
//           `cells` lattice cells and repeats seamlessly with GL_REPEAT in every axis.
// Quantise: byte = int(v * 255 + 0.5) of v clamped to [0, 1] (quantize_unorm8), round to
//           nearest; decode with byte / 255 (what UNORM8 formats do).
// Defaults: base 128^3 with 4 cells, detail 32^3 with 2 cells, curl 128^2 with 4 cells,
//           weather 256^2 with 4 cells. cells = 4 and 2 put the finest Worley octave of
//           the last channel (8 * 4 * cells cells per tile for base A, 4 * 4 * cells for
//           detail B; weight 0.125) at one cell per texel, and R's first Perlin octave at
//           32 (base) texels per cell: the full frequency range the resolution can hold.
// Limits:   size in [1, 4096] and cells in [1, 1024] (32 * cells must stay well inside int,
//           and p keeps >= 9 fractional bits in float); outside them, or with a null
//           pointer, the pointer versions return false and write nothing, the vector
//           versions return an empty vector. The caller's buffer holds size^3 * 4 (base),
//           size^3 * 3 (detail), size^2 * 3 (curl, weather) bytes.
// Threads:  bake_options::threads workers (0: std::thread::hardware_concurrency(), at most one
//           per z slice or row; the calling thread is one of them) take slices from a shared
//           counter. Each texel depends only on its coordinates, the cells and the seed, so
//           the bytes are identical for any thread count, run and schedule. If a thread
//           cannot be started, the ones that did (at least the caller) do the work.
//           Across builds, floating-point contraction can move a value over a rounding
//           boundary: -march=native (FMA) changed 5 of 2^20 bytes of a 64^3 base volume, by
//           one step, against -O2 (-O3 and -ffast-math without -march changed none).
// Progress: bake_options::progress(fraction done) is called once per finished slice (z slice
//           or row) from whichever thread finished it, under a mutex (never concurrently),
//           with non-decreasing values; the last call passes exactly 1. It must not throw.
// Seeds:    each channel has its own seed, bake_channel_seed(options.seed, channel) =
//           noise_hash(seed) + channel * 2^28. Not seed + channel: fBm octave i uses
//           seed + i, so with G = worley_fbm_nubis(2p, 2 cells, s) and B seeded s + 1, B's
//           first octave worley_noise(4p, 4 cells, s + 1) would be G's second octave exactly
//           (correlation 0.33 between the channels). Spacing 2^28 keeps every octave apart.
// Errors:   no exceptions (the pointer versions are noexcept; the vector versions can only
//           throw std::bad_alloc from the vector itself), no global state.
// Sources:  Schneider, "The real-time volumetric cloudscapes of Horizon Zero Dawn", SIGGRAPH
//           2015 Advances, and "Nubis: authoring real-time volumetric cloudscapes with the
//           Decima engine", SIGGRAPH 2017 Advances; Bridson et al. 2007 (curl noise).
// GLSL twin: none; textures are baked on the CPU and sampled in shaders.
#ifndef CLOUDMATH_NOISE_BAKE_HPP
#define CLOUDMATH_NOISE_BAKE_HPP

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core.hpp"
#include "noise.hpp"

namespace cloudmath {

// ---------------------------------------------------------------------------------------
// Options, sizes, seeds, encoding.

struct bake_options {
    std::uint32_t seed = 0;               // 0 and every other value are valid seeds
    unsigned threads = 0;                 // 0: std::thread::hardware_concurrency()
    std::function<void(float)> progress;  // fraction done in [0, 1]; see "Progress" above
};

inline constexpr int base_volume_default_size = 128;
inline constexpr int base_volume_default_cells = 4;
inline constexpr int detail_volume_default_size = 32;
inline constexpr int detail_volume_default_cells = 2;
inline constexpr int curl_texture_default_size = 128;
inline constexpr int curl_texture_default_cells = 4;
inline constexpr int weather_map_default_size = 256;
inline constexpr int weather_map_default_cells = 4;
inline constexpr int bake_max_size = 4096;
inline constexpr int bake_max_cells = 1024;

// The noise fields a bake uses, one seed each (bake_channel_seed).
enum class bake_channel : std::uint32_t {
    base_r = 0, base_g, base_b, base_a,
    detail_r, detail_g, detail_b,
    curl,
    weather_coverage, weather_type, weather_precipitation
};

// Seed of one channel: noise_hash(seed) + channel * 2^28 (wrap-around). Channels of one
// bake are 2^28 apart, so the seed + i of fBm octaves and the seed + 101 of perlin_worley's
// Worley part never make two channels share a field.
[[nodiscard]] constexpr std::uint32_t bake_channel_seed(std::uint32_t seed, bake_channel channel) noexcept {
    return noise_hash(seed) + static_cast<std::uint32_t>(channel) * 0x10000000U;
}

// Round to nearest 8-bit unsigned-normalised value: int(v * 255 + 0.5) of v clamped to
// [0, 1] (comparisons only, so a NaN maps to 0 with IEEE semantics).
template <class T>
[[nodiscard]] constexpr std::uint8_t quantize_unorm8(T v) noexcept {
    const T c = v > T(0) ? (v < T(1) ? v : T(1)) : T(0);
    return static_cast<std::uint8_t>(c * T(255) + T(0.5));
}

// Noise coordinate of texel index i along an axis of a size-texel texture that holds
// `cells` lattice cells: (i + 0.5) / size * cells, rounded once to float. Exact when size
// and cells are powers of two, so that bake_coordinate(i + size, ...) == bake_coordinate(i,
// ...) + cells exactly and texel i equals the noise one period away bit for bit.
[[nodiscard]] constexpr float bake_coordinate(int i, int size, int cells) noexcept {
    return static_cast<float>((static_cast<double>(i) + 0.5) * static_cast<double>(cells) /
                              static_cast<double>(size));
}

// Bound of the curl texture's encoding: each component c of curl_noise is stored as
// saturate(c / (2 m) + 0.5) with m = 4. Measured on the baked plane z = 0 (period 4, seeds
// 0..15, 1024^2 samples each): max |component| 3.11 (x), 2.73 (y), 3.59 (z), RMS 0.93 to
// 1.03; hill-climbing from 10^5 random starts over 1024 seeds reached 3.45 (x, y) and 4.44
// (z). The supremum over every gradient configuration is 3.62 for x and y (dpsi/dz <= 0.966
// on a lattice plane), so they never clamp, and 5.31 for z, which clamps only in rare
// extreme configurations. m = 4 keeps a step of 8/255 = 0.031 per byte.
template <class T> inline constexpr T curl_bake_bound = T(4);

// [-m, m] -> [0, 1], clamped beyond (m = curl_bake_bound).
template <class T>
[[nodiscard]] constexpr T curl_bake_encode(T c) noexcept {
    return saturate(c * (T(0.5) / curl_bake_bound<T>) + T(0.5));
}

// [0, 1] -> [-m, m]: the inverse of curl_bake_encode (apply to byte / 255 in a shader:
// curl = (2 texel - 1) * 4). Byte 128 decodes to +0.0157, not 0: 0 has no exact code.
template <class T>
[[nodiscard]] constexpr T curl_bake_decode(T u) noexcept {
    return (T(2) * u - T(1)) * curl_bake_bound<T>;
}

// ---------------------------------------------------------------------------------------
// One texel's values (before quantisation) at noise coordinate p, for the same `cells` and
// seed (options.seed) as the bake. Periodic in every coordinate of p with period `cells`.
// Domain of `cells` for the texel functions: every int. The bakes accept [1, bake_max_cells];
// the texel functions treat cells < 1 as 1 (as the noise functions treat their period) and
// are periodic with period `cells` (up to the rounding of p) for cells up to 2^25 (base:
// its finest octave, the 4p octave of worley_fbm_nubis at 8 cells, has period 32 cells,
// which must stay within the noise functions' 2^30 limit) and 2^26 (detail: 16 cells).
// Above that the periods of the finer octaves saturate at 2^30 (detail::grow_period):
// values stay defined and in [0, 1], but no longer tile. The periods 2, 4 and 8 times
// cells were plain int products before: signed overflow (undefined behaviour) from
// cells = 2^28 (base) and 2^29 (detail), and below -2^28 (base) and -2^29 (detail).

// Base volume RGBA: perlin_worley(p, cells), worley_fbm_nubis(2p, 2 cells), (4p, 4 cells),
// (8p, 8 cells), each with its channel's seed. All in [0, 1].
template <class T>
[[nodiscard]] inline glm::vec<4, T> bake_base_texel(const glm::vec<3, T>& p, int cells,
                                                    std::uint32_t seed = 0) noexcept {
    const int n = detail::clamp_period(cells);
    return glm::vec<4, T>(perlin_worley(p, n, bake_channel_seed(seed, bake_channel::base_r)),
                          worley_fbm_nubis(p * T(2), detail::grow_period(n, 2), bake_channel_seed(seed, bake_channel::base_g)),
                          worley_fbm_nubis(p * T(4), detail::grow_period(n, 4), bake_channel_seed(seed, bake_channel::base_b)),
                          worley_fbm_nubis(p * T(8), detail::grow_period(n, 8), bake_channel_seed(seed, bake_channel::base_a)));
}

// Detail volume RGB: worley_fbm_nubis at (p, cells), (2p, 2 cells), (4p, 4 cells). In [0, 1].
template <class T>
[[nodiscard]] inline glm::vec<3, T> bake_detail_texel(const glm::vec<3, T>& p, int cells,
                                                      std::uint32_t seed = 0) noexcept {
    const int n = detail::clamp_period(cells);
    return glm::vec<3, T>(worley_fbm_nubis(p, n, bake_channel_seed(seed, bake_channel::detail_r)),
                          worley_fbm_nubis(p * T(2), detail::grow_period(n, 2), bake_channel_seed(seed, bake_channel::detail_g)),
                          worley_fbm_nubis(p * T(4), detail::grow_period(n, 4), bake_channel_seed(seed, bake_channel::detail_b)));
}

// Curl texture RGB: curl_bake_encode of each component of curl_noise((p, 0), cells). In [0, 1].
template <class T>
[[nodiscard]] inline glm::vec<3, T> bake_curl_texel(const glm::vec<2, T>& p, int cells,
                                                    std::uint32_t seed = 0) noexcept {
    const glm::vec<3, T> c = curl_noise(glm::vec<3, T>(p, T(0)), cells, bake_channel_seed(seed, bake_channel::curl));
    return glm::vec<3, T>(curl_bake_encode(c.x), curl_bake_encode(c.y), curl_bake_encode(c.z));
}

// Weather map RGB, each saturate(0.5 + perlin_fbm(p, cells, octaves)) (lacunarity 2, gain 0.5):
//   R coverage       4 octaves  (fBm standard deviation 0.19: [-0.5, 0.5] holds +-2.6 sd)
//   G cloud type     2 octaves  (broad regions; sd 0.23, +-2.1 sd)
//   B precipitation  3 octaves  (sd 0.20, +-2.4 sd)
// Measured on 8 seeds x 256^2 texels at 4 cells: every byte value occurs, the mean is 0.500,
// and 0.34% (R), 2.9% (G) and 0.95% (B) of the texels are clamped to 0 or 1. Thresholds
// (where it rains, which type is which) belong to the renderer, e.g.
// height_gradient_for_type(h, G).
template <class T>
[[nodiscard]] inline glm::vec<3, T> bake_weather_texel(const glm::vec<2, T>& p, int cells,
                                                       std::uint32_t seed = 0) noexcept {
    const T coverage = perlin_fbm(p, cells, 4, 2, T(0.5), bake_channel_seed(seed, bake_channel::weather_coverage));
    const T type = perlin_fbm(p, cells, 2, 2, T(0.5), bake_channel_seed(seed, bake_channel::weather_type));
    const T rain = perlin_fbm(p, cells, 3, 2, T(0.5), bake_channel_seed(seed, bake_channel::weather_precipitation));
    return glm::vec<3, T>(saturate(T(0.5) + coverage), saturate(T(0.5) + type), saturate(T(0.5) + rain));
}

// ---------------------------------------------------------------------------------------
// The parallel slice loop.

namespace detail {

constexpr bool valid_bake(int size, int cells) noexcept {
    return size >= 1 && size <= bake_max_size && cells >= 1 && cells <= bake_max_cells;
}

// Runs bake_slice(s) for s in [0, slices) on the option's thread count (the caller is one
// of the workers), reporting progress after each slice under a mutex.
template <class SliceFn>
inline void bake_slices(int slices, const bake_options& options, const SliceFn& bake_slice) noexcept {
    unsigned threads = options.threads != 0 ? options.threads : std::thread::hardware_concurrency();
    if (threads == 0) threads = 1;
    if (threads > static_cast<unsigned>(slices)) threads = static_cast<unsigned>(slices);

    std::atomic<int> next{0};
    std::mutex progress_mutex;
    int done = 0;
    const auto work = [&]() noexcept {
        for (;;) {
            const int s = next.fetch_add(1, std::memory_order_relaxed);
            if (s >= slices) return;
            bake_slice(s);
            if (options.progress) {
                const std::lock_guard<std::mutex> lock(progress_mutex);
                ++done;
                options.progress(done == slices ? 1.0f : static_cast<float>(done) / static_cast<float>(slices));
            }
        }
    };

    std::vector<std::thread> workers;
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND)
    try {
        workers.reserve(threads - 1U);
        for (unsigned t = 1; t < threads; ++t) workers.emplace_back(work);
    } catch (...) {
        // Out of threads or memory: the workers already running and this thread finish
        // the job; the result does not depend on how many there are.
    }
#else
    workers.reserve(threads - 1U);
    for (unsigned t = 1; t < threads; ++t) workers.emplace_back(work);
#endif
    work();
    for (std::thread& worker : workers) worker.join();
}

}  // namespace detail

// ---------------------------------------------------------------------------------------
// Bakes. Pointer versions: false (nothing written) for size outside [1, bake_max_size],
// cells outside [1, bake_max_cells] or a null `out`. Vector versions: empty when invalid.

namespace detail {

// Bakes a size^Dims texture with Channels bytes per texel, one slice (volume) or row (2D
// texture) per task; texel(p) gives the values at the texel's noise coordinate p (glm::vec3
// for volumes, glm::vec2 for 2D textures). One loop for all four bakes.
template <int Dims, int Channels, class Texel>
inline bool bake_texture(std::uint8_t* out, int size, int cells, const bake_options& options,
                         Texel texel) noexcept {
    static_assert(Dims == 2 || Dims == 3, "2D textures and volumes");
    if (out == nullptr || !valid_bake(size, cells)) return false;
    const std::size_t n = static_cast<std::size_t>(size);
    const std::size_t task_bytes = (Dims == 3 ? n * n : n) * static_cast<std::size_t>(Channels);
    bake_slices(size, options, [&](int k) noexcept {
        std::uint8_t* dst = out + static_cast<std::size_t>(k) * task_bytes;
        const float outer = bake_coordinate(k, size, cells);
        for (int j = 0; j < (Dims == 3 ? size : 1); ++j) {
            const float y = Dims == 3 ? bake_coordinate(j, size, cells) : outer;
            for (int i = 0; i < size; ++i, dst += Channels) {
                const float x = bake_coordinate(i, size, cells);
                const auto v = [&] {
                    if constexpr (Dims == 3) return texel(glm::vec3(x, y, outer));
                    else return texel(glm::vec2(x, y));
                }();
                for (int c = 0; c < Channels; ++c) dst[c] = quantize_unorm8(v[c]);
            }
        }
    });
    return true;
}

}  // namespace detail

// Base volume, size^3 RGBA8 (bake_base_texel).
[[nodiscard]] inline bool bake_base_volume(std::uint8_t* out, int size, int cells,
                                           const bake_options& options = {}) noexcept {
    return detail::bake_texture<3, 4>(out, size, cells, options,
                                      [&](const glm::vec3& p) { return bake_base_texel(p, cells, options.seed); });
}

// Detail volume, size^3 RGB8 (bake_detail_texel).
[[nodiscard]] inline bool bake_detail_volume(std::uint8_t* out, int size, int cells,
                                             const bake_options& options = {}) noexcept {
    return detail::bake_texture<3, 3>(out, size, cells, options,
                                      [&](const glm::vec3& p) { return bake_detail_texel(p, cells, options.seed); });
}

// Curl texture, size^2 RGB8 (bake_curl_texel).
[[nodiscard]] inline bool bake_curl_texture(std::uint8_t* out, int size, int cells,
                                            const bake_options& options = {}) noexcept {
    return detail::bake_texture<2, 3>(out, size, cells, options,
                                      [&](const glm::vec2& p) { return bake_curl_texel(p, cells, options.seed); });
}

// Weather map, size^2 RGB8 (bake_weather_texel).
[[nodiscard]] inline bool bake_weather_map(std::uint8_t* out, int size, int cells,
                                           const bake_options& options = {}) noexcept {
    return detail::bake_texture<2, 3>(out, size, cells, options,
                                      [&](const glm::vec2& p) { return bake_weather_texel(p, cells, options.seed); });
}

namespace detail {

// The vector versions: allocate, bake, or return empty when the arguments are invalid.
template <class Bake>
inline std::vector<std::uint8_t> bake_to_vector(int size, int cells, int dimensions, int channels, Bake bake) {
    if (!valid_bake(size, cells)) return {};
    std::size_t bytes = static_cast<std::size_t>(channels);
    for (int d = 0; d < dimensions; ++d) bytes *= static_cast<std::size_t>(size);
    std::vector<std::uint8_t> texels(bytes);
    if (!bake(texels.data())) texels.clear();
    return texels;
}

}  // namespace detail

[[nodiscard]] inline std::vector<std::uint8_t> bake_base_volume(int size = base_volume_default_size,
                                                                int cells = base_volume_default_cells,
                                                                const bake_options& options = {}) {
    return detail::bake_to_vector(size, cells, 3, 4, [&](std::uint8_t* out) noexcept {
        return bake_base_volume(out, size, cells, options);
    });
}

[[nodiscard]] inline std::vector<std::uint8_t> bake_detail_volume(int size = detail_volume_default_size,
                                                                  int cells = detail_volume_default_cells,
                                                                  const bake_options& options = {}) {
    return detail::bake_to_vector(size, cells, 3, 3, [&](std::uint8_t* out) noexcept {
        return bake_detail_volume(out, size, cells, options);
    });
}

[[nodiscard]] inline std::vector<std::uint8_t> bake_curl_texture(int size = curl_texture_default_size,
                                                                 int cells = curl_texture_default_cells,
                                                                 const bake_options& options = {}) {
    return detail::bake_to_vector(size, cells, 2, 3, [&](std::uint8_t* out) noexcept {
        return bake_curl_texture(out, size, cells, options);
    });
}

[[nodiscard]] inline std::vector<std::uint8_t> bake_weather_map(int size = weather_map_default_size,
                                                                int cells = weather_map_default_cells,
                                                                const bake_options& options = {}) {
    return detail::bake_to_vector(size, cells, 2, 3, [&](std::uint8_t* out) noexcept {
        return bake_weather_map(out, size, cells, options);
    });
}

// ---------------------------------------------------------------------------------------
// Sampling a baked texture on the CPU as the GPU does, for the host side of an engine
// (density queries for gameplay or audio, tests): texture_trilinear_repeat(uvw, size, fetch)
// is what texture() returns at mip level 0 for a 3D texture with GL_LINEAR filtering and
// GL_REPEAT wrapping: texel centres at (i + 0.5) / size, weights from the fractional part,
// indices wrapped into [0, size) for any uvw (negative and beyond 1 included).
// texture_bilinear_repeat(uv, size, fetch) is the same in 2D. fetch(i, j, k) (2D: fetch(i,
// j)) returns texel (i, j, k) as a float or glm vector; for this file's 8-bit layout, the
// channels' bytes / 255 (see the Layout note above). Domain: every size component >= 1
// (smaller is taken as 1); a NaN or Inf coordinate gives a NaN result (IEEE builds) and
// never an index outside [0, size).
namespace detail {

// floor(x) modulo size in [0, size) and the fraction x - floor(x), without an int
// conversion of anything outside [0, size - 1] (NaN: index 0, by floor_to_int).
template <class T>
inline int wrapped_texel(T x, int size, T& fraction) noexcept {
    const T cell = std::floor(x);
    fraction = x - cell;
    const T m = cell - T(size) * std::floor(cell / T(size));  // in [0, size] (rounding)
    return floor_to_int(m, 0, size - 1);  // NaN too, in every build (-ffast-math included)
}

}  // namespace detail

template <class T, class Fetch>
[[nodiscard]] inline auto texture_trilinear_repeat(const glm::vec<3, T>& uvw, const glm::ivec3& size,
                                                   const Fetch& fetch) {
    const glm::ivec3 n(size.x > 1 ? size.x : 1, size.y > 1 ? size.y : 1, size.z > 1 ? size.z : 1);
    T fx, fy, fz;
    const int x0 = detail::wrapped_texel(uvw.x * T(n.x) - T(0.5), n.x, fx);
    const int y0 = detail::wrapped_texel(uvw.y * T(n.y) - T(0.5), n.y, fy);
    const int z0 = detail::wrapped_texel(uvw.z * T(n.z) - T(0.5), n.z, fz);
    const int x1 = x0 + 1 < n.x ? x0 + 1 : 0, y1 = y0 + 1 < n.y ? y0 + 1 : 0, z1 = z0 + 1 < n.z ? z0 + 1 : 0;
    const auto c00 = glm::mix(fetch(x0, y0, z0), fetch(x1, y0, z0), fx);
    const auto c10 = glm::mix(fetch(x0, y1, z0), fetch(x1, y1, z0), fx);
    const auto c01 = glm::mix(fetch(x0, y0, z1), fetch(x1, y0, z1), fx);
    const auto c11 = glm::mix(fetch(x0, y1, z1), fetch(x1, y1, z1), fx);
    return glm::mix(glm::mix(c00, c10, fy), glm::mix(c01, c11, fy), fz);
}

template <class T, class Fetch>
[[nodiscard]] inline auto texture_bilinear_repeat(const glm::vec<2, T>& uv, const glm::ivec2& size, const Fetch& fetch) {
    const glm::ivec2 n(size.x > 1 ? size.x : 1, size.y > 1 ? size.y : 1);
    T fx, fy;
    const int x0 = detail::wrapped_texel(uv.x * T(n.x) - T(0.5), n.x, fx);
    const int y0 = detail::wrapped_texel(uv.y * T(n.y) - T(0.5), n.y, fy);
    const int x1 = x0 + 1 < n.x ? x0 + 1 : 0, y1 = y0 + 1 < n.y ? y0 + 1 : 0;
    return glm::mix(glm::mix(fetch(x0, y0), fetch(x1, y0), fx), glm::mix(fetch(x0, y1), fetch(x1, y1), fx), fy);
}

}  // namespace cloudmath

#endif  // CLOUDMATH_NOISE_BAKE_HPP
