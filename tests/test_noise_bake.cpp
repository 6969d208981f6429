// Tests of noise_bake.hpp: byte-identical bakes for any thread count and run; seamless
// tiling (every wrap-face texel equals the noise one period away, and the difference across
// the wrap is like the difference between neighbouring interior slices, which a
// non-periodic field fails); channel statistics and independence; the progress contract;
// invalid arguments; quantisation, coordinates and the curl encoding.
// Sizes stay small (16^3 volumes, 64^2 images) so the sanitizer build stays fast; sizes and
// cells are powers of two, which makes the noise coordinate one period away exact.
#include <cloudmath/density.hpp>
#include <cloudmath/noise_bake.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace cloudmath;

namespace {

using bytes = std::vector<std::uint8_t>;

// One baked texture with its shape, so the checks below work on any of the four.
struct texture {
    const char* name;
    int dims;      // 2 or 3
    int size;
    int cells;
    int channels;
    bytes data;
};

std::size_t texel_index(const texture& t, int i, int j, int k) {
    const std::size_t n = static_cast<std::size_t>(t.size);
    return ((static_cast<std::size_t>(k) * n + static_cast<std::size_t>(j)) * n + static_cast<std::size_t>(i)) *
           static_cast<std::size_t>(t.channels);
}

// The texture's float values at integer texel index (i, j, k), computed from the
// bake_*_texel functions; indices outside [0, size) are one period away.
std::vector<float> expected_texel(const texture& t, std::uint32_t seed, int i, int j, int k) {
    const float x = bake_coordinate(i, t.size, t.cells), y = bake_coordinate(j, t.size, t.cells),
                z = bake_coordinate(k, t.size, t.cells);
    const std::string name = t.name;
    if (name == "base") {
        const glm::vec4 v = bake_base_texel(glm::vec3(x, y, z), t.cells, seed);
        return {v.x, v.y, v.z, v.w};
    }
    if (name == "detail") {
        const glm::vec3 v = bake_detail_texel(glm::vec3(x, y, z), t.cells, seed);
        return {v.x, v.y, v.z};
    }
    if (name == "curl") {
        const glm::vec3 v = bake_curl_texel(glm::vec2(x, y), t.cells, seed);
        return {v.x, v.y, v.z};
    }
    const glm::vec3 v = bake_weather_texel(glm::vec2(x, y), t.cells, seed);
    return {v.x, v.y, v.z};
}

texture bake(const char* name, int size, int cells, const bake_options& options) {
    const std::string n = name;
    if (n == "base") return {name, 3, size, cells, 4, bake_base_volume(size, cells, options)};
    if (n == "detail") return {name, 3, size, cells, 3, bake_detail_volume(size, cells, options)};
    if (n == "curl") return {name, 2, size, cells, 3, bake_curl_texture(size, cells, options)};
    return {name, 2, size, cells, 3, bake_weather_map(size, cells, options)};
}

// The four textures at test sizes (weather with 8 cells: more independent cells along a
// row make the one wrap pair less noisy against the interior mean).
std::array<texture, 4> bake_all(std::uint32_t seed, unsigned threads) {
    bake_options options;
    options.seed = seed;
    options.threads = threads;
    return {bake("base", 16, 4, options), bake("detail", 16, 2, options), bake("curl", 64, 4, options),
            bake("weather", 64, 8, options)};
}

// Mean absolute byte difference between slice a and slice b perpendicular to `axis`, over
// every texel of the slices and every channel.
double slice_difference(const texture& t, int axis, int a, int b) {
    double sum = 0;
    long count = 0;
    const int depth = t.dims == 3 ? t.size : 1;
    for (int u = 0; u < t.size; ++u)
        for (int v = 0; v < depth; ++v) {
            std::array<int, 3> pa{}, pb{};
            // The other two coordinates are (u, v), in axis order.
            int slot = 0;
            for (int d = 0; d < 3; ++d) {
                if (d == axis) {
                    pa[static_cast<std::size_t>(d)] = a;
                    pb[static_cast<std::size_t>(d)] = b;
                } else {
                    const int value = slot++ == 0 ? u : v;
                    pa[static_cast<std::size_t>(d)] = value;
                    pb[static_cast<std::size_t>(d)] = value;
                }
            }
            if (t.dims == 2 && (pa[2] != 0 || pb[2] != 0)) continue;
            const std::size_t ia = texel_index(t, pa[0], pa[1], pa[2]), ib = texel_index(t, pb[0], pb[1], pb[2]);
            for (int c = 0; c < t.channels; ++c) {
                const std::size_t off = static_cast<std::size_t>(c);
                sum += std::abs(int(t.data[ia + off]) - int(t.data[ib + off]));
                ++count;
            }
        }
    return sum / double(count);
}

struct seam_measure {
    double wrap;      // between the last and the first slice (neighbours across the wrap)
    double interior;  // mean over the size - 1 interior neighbour pairs
};

seam_measure seam(const texture& t, int axis) {
    double interior = 0;
    for (int s = 0; s + 1 < t.size; ++s) interior += slice_difference(t, axis, s, s + 1);
    return {slice_difference(t, axis, t.size - 1, 0), interior / double(t.size - 1)};
}

struct channel_stats {
    double mean;
    int distinct, min, max;
};

channel_stats stats(const texture& t, int channel) {
    std::array<bool, 256> seen{};
    double sum = 0;
    int lo = 255, hi = 0;
    const std::size_t n = t.data.size() / static_cast<std::size_t>(t.channels);
    for (std::size_t p = 0; p < n; ++p) {
        const int b = t.data[p * static_cast<std::size_t>(t.channels) + static_cast<std::size_t>(channel)];
        seen[static_cast<std::size_t>(b)] = true;
        sum += b;
        lo = std::min(lo, b);
        hi = std::max(hi, b);
    }
    return {sum / double(n) / 255.0, int(std::count(seen.begin(), seen.end(), true)), lo, hi};
}

double correlation(const texture& t, int c0, int c1) {
    const std::size_t n = t.data.size() / static_cast<std::size_t>(t.channels);
    double s0 = 0, s1 = 0, s00 = 0, s11 = 0, s01 = 0;
    for (std::size_t p = 0; p < n; ++p) {
        const double a = t.data[p * static_cast<std::size_t>(t.channels) + static_cast<std::size_t>(c0)];
        const double b = t.data[p * static_cast<std::size_t>(t.channels) + static_cast<std::size_t>(c1)];
        s0 += a;
        s1 += b;
        s00 += a * a;
        s11 += b * b;
        s01 += a * b;
    }
    const double m = double(n);
    const double cov = s01 / m - s0 / m * s1 / m;
    return cov / std::sqrt((s00 / m - s0 / m * s0 / m) * (s11 / m - s1 / m * s1 / m));
}

}  // namespace

TEST_CASE("noise_bake: the same seed gives the same bytes for 1, 2, 3 and all threads, and across runs") {
    const std::array<texture, 4> one = bake_all(7, 1);
    for (const texture& t : one) {
        const std::size_t texels = static_cast<std::size_t>(t.dims == 3 ? t.size * t.size * t.size : t.size * t.size);
        CHECK(t.data.size() == texels * static_cast<std::size_t>(t.channels));
    }
    for (unsigned threads : {1U, 2U, 3U, 0U}) {
        const std::array<texture, 4> again = bake_all(7, threads);
        for (std::size_t n = 0; n < one.size(); ++n) {
            CAPTURE(one[n].name);
            CAPTURE(threads);
            CHECK(again[n].data == one[n].data);
        }
    }
    // More threads than slices: capped, same bytes.
    bake_options many;
    many.seed = 7;
    many.threads = 64;
    CHECK(bake_curl_texture(8, 4, many) == bake_curl_texture(8, 4, bake_options{7, 1, {}}));
}

TEST_CASE("noise_bake: the texels of every wrap face equal the noise one period away") {
    const std::uint32_t seed = 11;
    for (const texture& t : bake_all(seed, 2)) {
        CAPTURE(t.name);
        const int depth = t.dims == 3 ? t.size : 1;
        int checked = 0, equal = 0;
        for (int axis = 0; axis < t.dims; ++axis)
            for (int face : {0, t.size - 1})
                for (int u = 0; u < t.size; ++u)
                    for (int v = 0; v < depth; ++v) {
                        std::array<int, 3> p{};
                        int slot = 0;
                        for (int d = 0; d < 3; ++d)
                            p[static_cast<std::size_t>(d)] = d == axis ? face : (slot++ == 0 ? u : v);
                        if (t.dims == 2) p[2] = 0;
                        // Across the wrap: index + size on the first face, index - size on the last.
                        std::array<int, 3> q = p;
                        q[static_cast<std::size_t>(axis)] += face == 0 ? t.size : -t.size;
                        const std::vector<float> expect = expected_texel(t, seed, q[0], q[1], q[2]);
                        const std::size_t at = texel_index(t, p[0], p[1], p[2]);
                        for (int c = 0; c < t.channels; ++c) {
                            ++checked;
                            equal += t.data[at + static_cast<std::size_t>(c)] ==
                                     quantize_unorm8(expect[static_cast<std::size_t>(c)]);
                        }
                    }
        CHECK(checked > 0);
        CHECK(equal == checked);
    }

    // The same, spelled with the noise.hpp functions directly (not through bake_*_texel).
    const texture base = bake("base", 16, 4, bake_options{seed, 2, {}});
    const float cells = 4.0f;
    for (int j = 0; j < 16; ++j)
        for (int k = 0; k < 16; ++k) {
            const glm::vec3 p(bake_coordinate(0, 16, 4), bake_coordinate(j, 16, 4), bake_coordinate(k, 16, 4));
            const std::size_t at = texel_index(base, 0, j, k);
            CHECK(base.data[at] == quantize_unorm8(perlin_worley(p + glm::vec3(cells, 0, 0), 4,
                                                                 bake_channel_seed(seed, bake_channel::base_r))));
            CHECK(base.data[at + 1] == quantize_unorm8(worley_fbm_nubis((p + glm::vec3(0, cells, 0)) * 2.0f, 8,
                                                                        bake_channel_seed(seed, bake_channel::base_g))));
            CHECK(base.data[at + 3] == quantize_unorm8(worley_fbm_nubis((p - glm::vec3(0, 0, cells)) * 8.0f, 32,
                                                                        bake_channel_seed(seed, bake_channel::base_a))));
        }
    const texture curl = bake("curl", 64, 4, bake_options{seed, 2, {}});
    const texture weather = bake("weather", 64, 4, bake_options{seed, 2, {}});
    for (int j = 0; j < 64; ++j) {
        const float x = bake_coordinate(63, 64, 4) - cells, y = bake_coordinate(j, 64, 4);
        const glm::vec3 c = curl_noise(glm::vec3(x, y, 0.0f), 4, bake_channel_seed(seed, bake_channel::curl));
        const std::size_t at = texel_index(curl, 63, j, 0);
        CHECK(curl.data[at] == quantize_unorm8(curl_bake_encode(c.x)));
        CHECK(curl.data[at + 2] == quantize_unorm8(curl_bake_encode(c.z)));
        const float coverage =
            perlin_fbm(glm::vec2(x, y), 4, 4, 2, 0.5f, bake_channel_seed(seed, bake_channel::weather_coverage));
        CHECK(weather.data[at] == quantize_unorm8(saturate(0.5f + coverage)));
    }
}

TEST_CASE("noise_bake: no seams: the difference across the wrap is like that between interior neighbours") {
    // Over 64 seeds and both axes the worst ratios at these sizes were 1.06 (base), 1.09
    // (detail), 0.53 (curl) and 1.33 (weather); curl is low because the quintic fade makes
    // the field flattest at lattice planes, where the wrap always is.
    for (const texture& t : bake_all(3, 2)) {
        for (int axis = 0; axis < t.dims; ++axis) {
            const seam_measure s = seam(t, axis);
            CAPTURE(t.name);
            CAPTURE(axis);
            CAPTURE(s.wrap);
            CAPTURE(s.interior);
            CHECK(s.interior > 0.5);  // the noise varies between slices, so the ratio means something
            CHECK(s.wrap / s.interior < 1.5);
        }
    }
}

TEST_CASE("noise_bake: the seam measure sees a seam where the field does not tile") {
    // Channel 0 of each texture along x, on 64 lines (8 x 8 rows of a 64^3 volume, or the 64
    // rows of a 64^2 image), with the field's period `period`: the bake's own period tiles,
    // a period of one more cell (the tile cut at 4 of 5 cells) does not, and fails the
    // criterion of the test above (measured cut ratios 3 to 11).
    const auto ratio = [](const std::string& name, int period) {
        const bool volume = name == "base" || name == "detail";
        const int size = 64, cells = name == "detail" ? 2 : 4;
        std::vector<std::vector<int>> lines;
        for (int line = 0; line < 64; ++line) {
            const float y = bake_coordinate(volume ? (line % 8) * 8 : line, size, cells);
            const float z = bake_coordinate(volume ? (line / 8) * 8 : 0, size, cells);
            std::vector<int> values;
            for (int i = 0; i < size; ++i) {
                const float x = bake_coordinate(i, size, cells);
                float v = 0;
                if (name == "base") v = bake_base_texel(glm::vec3(x, y, z), period, 0U).x;
                if (name == "detail") v = bake_detail_texel(glm::vec3(x, y, z), period, 0U).x;
                if (name == "curl") v = bake_curl_texel(glm::vec2(x, y), period, 0U).x;
                if (name == "weather") v = bake_weather_texel(glm::vec2(x, y), period, 0U).x;
                values.push_back(quantize_unorm8(v));
            }
            lines.push_back(values);
        }
        double wrap = 0, interior = 0;
        for (const std::vector<int>& v : lines) {
            wrap += std::abs(v.back() - v.front());
            for (std::size_t i = 0; i + 1 < v.size(); ++i) interior += std::abs(v[i + 1] - v[i]);
        }
        return wrap / (interior / double(size - 1));
    };
    for (const char* name : {"base", "detail", "curl", "weather"}) {
        const int cells = std::string(name) == "detail" ? 2 : 4;
        const double tiles = ratio(name, cells), cut = ratio(name, cells + 1);
        CAPTURE(name);
        CAPTURE(tiles);
        CAPTURE(cut);
        CHECK(tiles < 1.5);
        CHECK(cut > 1.5);
    }
}

TEST_CASE("noise_bake: channel statistics are in plausible ranges") {
    // Ranges (measured means at these sizes and seeds 0..3: base R 0.61, Worley channels
    // 0.69-0.71, curl 0.47-0.53 (its z = 0 plane holds only 16 lattice cells), weather 0.50):
    //   base R (Perlin-Worley)                 mean in [0.45, 0.75]
    //   base GBA, detail RGB (Worley fBm)      mean in [0.60, 0.80] (1 - F1/sqrt(3) averages 0.70)
    //   curl RGB (zero-mean field, 0 -> 0.5)   mean in [0.40, 0.60], no byte clamped at 0 or 255
    //   weather RGB (saturate(0.5 + fBm))      mean in [0.40, 0.60], reaches below 0.1 and above 0.9
    //   every channel                          more than 50 distinct byte values
    for (std::uint32_t seed : {0U, 1U, 2U, 3U}) {
        for (const texture& t : bake_all(seed, 2)) {
            const std::string name = t.name;
            for (int c = 0; c < t.channels; ++c) {
                const channel_stats s = stats(t, c);
                CAPTURE(seed);
                CAPTURE(name);
                CAPTURE(c);
                CAPTURE(s.mean);
                CHECK(s.distinct > 50);
                if (name == "base" && c == 0) {
                    CHECK(s.mean >= 0.45);
                    CHECK(s.mean <= 0.75);
                } else if (name == "base" || name == "detail") {
                    CHECK(s.mean >= 0.60);
                    CHECK(s.mean <= 0.80);
                } else if (name == "curl") {
                    CHECK(s.mean >= 0.40);
                    CHECK(s.mean <= 0.60);
                    CHECK(s.min > 0);
                    CHECK(s.max < 255);
                } else {
                    CHECK(s.mean >= 0.40);
                    CHECK(s.mean <= 0.60);
                    CHECK(s.min < 26);
                    CHECK(s.max > 229);
                }
            }
        }
    }
}

TEST_CASE("noise_bake: the channels of a texture are independent fields") {
    // |correlation| < 0.15 between every two channels (measured at most 0.03 for the volumes
    // and 0.11 for the 128^2 images over 8 seeds). Seeding the channels s, s + 1, ... instead
    // of bake_channel_seed makes B's first octave G's second one: correlation 0.32 to 0.35.
    bake_options options;
    options.threads = 2;
    for (std::uint32_t seed : {0U, 5U}) {
        options.seed = seed;
        const std::array<texture, 4> textures{bake("base", 16, 4, options), bake("detail", 16, 2, options),
                                              bake("curl", 128, 16, options), bake("weather", 128, 16, options)};
        for (const texture& t : textures)
            for (int c0 = 0; c0 < t.channels; ++c0)
                for (int c1 = c0 + 1; c1 < t.channels; ++c1) {
                    CAPTURE(t.name);
                    CAPTURE(c0);
                    CAPTURE(c1);
                    CHECK(std::abs(correlation(t, c0, c1)) < 0.15);
                }
        // The trap the channel seeds avoid, measured the same way.
        texture naive{"naive", 3, 16, 4, 2, {}};
        for (int k = 0; k < 16; ++k)
            for (int j = 0; j < 16; ++j)
                for (int i = 0; i < 16; ++i) {
                    const glm::vec3 p(bake_coordinate(i, 16, 4), bake_coordinate(j, 16, 4), bake_coordinate(k, 16, 4));
                    naive.data.push_back(quantize_unorm8(worley_fbm_nubis(p * 2.0f, 8, seed)));
                    naive.data.push_back(quantize_unorm8(worley_fbm_nubis(p * 4.0f, 16, seed + 1U)));
                }
        CHECK(correlation(naive, 0, 1) > 0.25);
    }
    // The channel seeds of one bake are 2^28 apart (mod 2^32), whatever the seed.
    for (std::uint32_t seed : {0U, 1U, 0xffffffffU, 123456789U}) {
        for (std::uint32_t a = 0; a <= static_cast<std::uint32_t>(bake_channel::weather_precipitation); ++a)
            for (std::uint32_t b = a + 1; b <= static_cast<std::uint32_t>(bake_channel::weather_precipitation); ++b) {
                const std::uint32_t d = bake_channel_seed(seed, static_cast<bake_channel>(b)) -
                                        bake_channel_seed(seed, static_cast<bake_channel>(a));
                CHECK(d % 0x10000000U == 0U);
                CHECK(d != 0U);
            }
    }
}

TEST_CASE("noise_bake: seeds change every channel") {
    const std::array<texture, 4> a = bake_all(0, 2), b = bake_all(1, 2);
    for (std::size_t n = 0; n < a.size(); ++n) {
        for (int c = 0; c < a[n].channels; ++c) {
            std::size_t differ = 0, total = 0;
            for (std::size_t p = static_cast<std::size_t>(c); p < a[n].data.size();
                 p += static_cast<std::size_t>(a[n].channels)) {
                differ += a[n].data[p] != b[n].data[p];
                ++total;
            }
            CAPTURE(a[n].name);
            CAPTURE(c);
            CHECK(double(differ) > 0.8 * double(total));
        }
    }
}

TEST_CASE("noise_bake: progress is serialised, non-decreasing, once per slice, and ends at exactly 1") {
    for (unsigned threads : {1U, 2U, 3U}) {
        std::vector<float> calls;
        std::atomic<int> inside{0};
        std::atomic<bool> overlapped{false};
        bake_options options;
        options.threads = threads;
        options.progress = [&](float done) {
            if (inside.fetch_add(1) != 0) overlapped = true;
            calls.push_back(done);  // unsynchronised on purpose: the bake must serialise us
            inside.fetch_sub(1);
        };
        CAPTURE(threads);
        REQUIRE(bake_detail_volume(8, 2, options).size() == 8U * 8U * 8U * 3U);
        CHECK_FALSE(overlapped.load());
        REQUIRE(calls.size() == 8U);  // one per z slice
        CHECK(calls.back() == 1.0f);
        CHECK(calls.front() > 0.0f);
        for (std::size_t n = 1; n < calls.size(); ++n) CHECK(calls[n] >= calls[n - 1]);
        for (float f : calls) CHECK((f >= 0.0f && f <= 1.0f));

        calls.clear();
        REQUIRE(bake_weather_map(24, 4, options).size() == 24U * 24U * 3U);
        CHECK(calls.size() == 24U);  // one per row
        CHECK(calls.back() == 1.0f);
        calls.clear();
        REQUIRE(bake_curl_texture(5, 4, options).size() == 5U * 5U * 3U);
        CHECK(calls.size() == 5U);
        CHECK(calls.back() == 1.0f);
        calls.clear();
        std::vector<std::uint8_t> base(4U * 4U * 4U * 4U);
        REQUIRE(bake_base_volume(base.data(), 4, 4, options));
        CHECK(calls.size() == 4U);
        CHECK(calls.back() == 1.0f);
    }
}

TEST_CASE("noise_bake: invalid sizes, cells or pointers give empty results and write nothing") {
    const bake_options options;
    for (int size : {0, -1, -128, bake_max_size + 1}) {
        CAPTURE(size);
        CHECK(bake_base_volume(size, 4, options).empty());
        CHECK(bake_detail_volume(size, 2, options).empty());
        CHECK(bake_curl_texture(size, 4, options).empty());
        CHECK(bake_weather_map(size, 4, options).empty());
    }
    for (int cells : {0, -4, bake_max_cells + 1}) {
        CAPTURE(cells);
        CHECK(bake_base_volume(4, cells, options).empty());
        CHECK(bake_detail_volume(4, cells, options).empty());
        CHECK(bake_curl_texture(4, cells, options).empty());
        CHECK(bake_weather_map(4, cells, options).empty());
        std::vector<std::uint8_t> canary(4U * 4U * 4U * 4U, 0xA5);
        CHECK_FALSE(bake_base_volume(canary.data(), 4, cells, options));
        CHECK_FALSE(bake_detail_volume(canary.data(), 4, cells, options));
        CHECK_FALSE(bake_curl_texture(canary.data(), 4, cells, options));
        CHECK_FALSE(bake_weather_map(canary.data(), 4, cells, options));
        CHECK_FALSE(bake_base_volume(canary.data(), 0, 4, options));
        CHECK(std::all_of(canary.begin(), canary.end(), [](std::uint8_t b) { return b == 0xA5; }));
    }
    CHECK_FALSE(bake_base_volume(nullptr, 4, 4, options));
    CHECK_FALSE(bake_detail_volume(nullptr, 4, 2, options));
    CHECK_FALSE(bake_curl_texture(nullptr, 4, 4, options));
    CHECK_FALSE(bake_weather_map(nullptr, 4, 4, options));
    // The smallest valid bake: one texel (cells may exceed size).
    CHECK(bake_base_volume(1, 1, options).size() == 4U);
    CHECK(bake_detail_volume(1, 8, options).size() == 3U);
    // No progress call for an invalid bake.
    int calls = 0;
    bake_options counting;
    counting.progress = [&calls](float) { ++calls; };
    CHECK(bake_weather_map(0, 4, counting).empty());
    CHECK(calls == 0);
}

TEST_CASE("noise_bake: default sizes and cells") {
    CHECK(base_volume_default_size == 128);
    CHECK(base_volume_default_cells == 4);
    CHECK(detail_volume_default_size == 32);
    CHECK(detail_volume_default_cells == 2);
    CHECK(curl_texture_default_size == 128);
    CHECK(weather_map_default_size == 256);
    // The cheap defaults are baked here; the 128^3 base runs in the tool and the benchmark.
    CHECK(bake_curl_texture().size() == 128U * 128U * 3U);
    CHECK(bake_weather_map().size() == 256U * 256U * 3U);
    CHECK(bake_curl_texture() == bake_curl_texture(128, 4, bake_options{}));
}

TEST_CASE_TEMPLATE("noise_bake: quantize_unorm8 rounds to nearest and clamps", T, float, double) {
    CHECK(quantize_unorm8(T(0)) == 0);
    CHECK(quantize_unorm8(T(1)) == 255);
    CHECK(quantize_unorm8(T(0.5)) == 128);                    // 127.5 rounds up
    CHECK(quantize_unorm8(T(0.49) / T(255)) == 0);
    CHECK(quantize_unorm8(T(0.51) / T(255)) == 1);
    CHECK(quantize_unorm8(T(254.49) / T(255)) == 254);
    CHECK(quantize_unorm8(T(-1)) == 0);
    CHECK(quantize_unorm8(T(2)) == 255);
    CHECK(quantize_unorm8(T(1e30)) == 255);
    CHECK(quantize_unorm8(-T(1e30)) == 0);
    for (int b = 0; b <= 255; ++b) CHECK(int(quantize_unorm8(T(b) / T(255))) == b);
}

TEST_CASE("noise_bake: texel coordinates are centres, exact one period away for powers of two") {
    CHECK(bake_coordinate(0, 16, 4) == 0.125f);
    CHECK(bake_coordinate(15, 16, 4) == 3.875f);
    CHECK(bake_coordinate(0, 1, 1) == 0.5f);
    CHECK(bake_coordinate(1, 3, 1) == doctest::Approx(0.5f));
    for (int size : {1, 2, 16, 128, 256})
        for (int cells : {1, 2, 4, 32})
            for (int i = 0; i < size; i += 7) {
                CHECK(bake_coordinate(i + size, size, cells) == bake_coordinate(i, size, cells) + float(cells));
                CHECK(bake_coordinate(i - size, size, cells) == bake_coordinate(i, size, cells) - float(cells));
            }
}

TEST_CASE_TEMPLATE("noise_bake: curl encoding maps [-4, 4] to [0, 1] and back", T, float, double) {
    CHECK(curl_bake_bound<T> == T(4));
    CHECK(curl_bake_encode(T(0)) == T(0.5));
    CHECK(curl_bake_encode(T(4)) == T(1));
    CHECK(curl_bake_encode(T(-4)) == T(0));
    CHECK(curl_bake_encode(T(9)) == T(1));
    CHECK(curl_bake_encode(T(-9)) == T(0));
    for (int n = -40; n <= 40; ++n) {
        const T c = T(n) / T(10);
        CHECK(curl_bake_decode(curl_bake_encode(c)) == doctest::Approx(c).epsilon(1e-6).scale(4));
    }
    // Bytes decode within half a step (4/255) of the field they encode.
    const glm::vec<3, T> c = curl_noise(glm::vec<3, T>(T(0.3), T(1.7), T(0)), 4, bake_channel_seed(5, bake_channel::curl));
    const glm::vec<3, T> e = bake_curl_texel(glm::vec<2, T>(T(0.3), T(1.7)), 4, 5);
    for (int k = 0; k < 3; ++k) {
        const T decoded = curl_bake_decode(T(quantize_unorm8(e[k])) / T(255));
        CHECK(std::abs(decoded - c[k]) <= T(4) / T(255) + T(1e-5));
    }
}

TEST_CASE("noise_bake: the measured curl bound holds on the baked plane") {
    // Documented in noise_bake.hpp: components of curl_noise on z = 0 stay inside [-4, 4]
    // (x and y provably inside +-3.62). Dense sample: 4 seeds x 128^2 texels.
    float peak = 0.0f, peak_xy = 0.0f;
    for (std::uint32_t seed : {0U, 1U, 2U, 3U})
        for (int j = 0; j < 128; ++j)
            for (int i = 0; i < 128; ++i) {
                const glm::vec3 c =
                    curl_noise(glm::vec3(bake_coordinate(i, 128, 4), bake_coordinate(j, 128, 4), 0.0f), 4,
                               bake_channel_seed(seed, bake_channel::curl));
                peak_xy = std::max({peak_xy, std::abs(c.x), std::abs(c.y)});
                peak = std::max({peak, peak_xy, std::abs(c.z)});
            }
    CAPTURE(peak_xy);
    CHECK(peak_xy < 3.63f);
    CAPTURE(peak);
    CHECK(peak < curl_bake_bound<float>);
    CHECK(peak > 2.0f);  // the bound is not wastefully loose either
    // The weather map and detail texel functions are the values the bake quantises.
    const glm::vec3 w = bake_weather_texel(glm::vec2(1.3f, 2.6f), 4, 9U);
    const glm::vec3 d = bake_detail_texel(glm::vec3(1.3f, 2.6f, 0.2f), 2, 9U);
    for (int k = 0; k < 3; ++k) {
        CHECK((w[k] >= 0.0f && w[k] <= 1.0f));
        CHECK((d[k] >= 0.0f && d[k] <= 1.0f));
    }
}

TEST_CASE_TEMPLATE("texture_trilinear_repeat / texture_bilinear_repeat: GL_LINEAR with GL_REPEAT on the CPU", T, float, double) {
    // A 4 x 3 x 2 texture whose texel (i, j, k) holds (i, 10 j, 100 k, 1): at texel centres the
    // texel itself; between two centres the mean; across the wrap the last and the first.
    const glm::ivec3 size(4, 3, 2);
    const auto fetch = [&](int i, int j, int k) {
        REQUIRE(i >= 0);
        REQUIRE(i < size.x);
        REQUIRE(j >= 0);
        REQUIRE(j < size.y);
        REQUIRE(k >= 0);
        REQUIRE(k < size.z);
        return glm::vec<4, T>(T(i), T(10 * j), T(100 * k), T(1));
    };
    using v3 = glm::vec<3, T>;
    const auto centre = [&](int i, int j, int k) {
        return v3((T(i) + T(0.5)) / T(size.x), (T(j) + T(0.5)) / T(size.y), (T(k) + T(0.5)) / T(size.z));
    };
    for (int k = 0; k < size.z; ++k)
        for (int j = 0; j < size.y; ++j)
            for (int i = 0; i < size.x; ++i) {
                const glm::vec<4, T> v = texture_trilinear_repeat(centre(i, j, k), size, fetch);
                CHECK(v.x == doctest::Approx(double(i)));
                CHECK(v.y == doctest::Approx(double(10 * j)));
                CHECK(v.z == doctest::Approx(double(100 * k)));
                CHECK(v.w == doctest::Approx(1.0));
                // One period away in every axis, negative too: the same value.
                const glm::vec<4, T> w = texture_trilinear_repeat(centre(i, j, k) + v3(T(-3), T(2), T(5)), size, fetch);
                CHECK(w.x == doctest::Approx(double(i)).epsilon(1e-5));
                CHECK(w.y == doctest::Approx(double(10 * j)).epsilon(1e-5));
            }
    // Halfway between texel 1 and 2 in x: the mean; at u = 0 (between the last texel, 3, and
    // the first, 0): their mean 1.5, by the wrap.
    const glm::vec<4, T> mid = texture_trilinear_repeat(v3(T(2) / T(4), centre(0, 1, 0).y, centre(0, 1, 0).z), size, fetch);
    CHECK(mid.x == doctest::Approx(1.5));
    const glm::vec<4, T> edge = texture_trilinear_repeat(v3(T(0), centre(0, 0, 1).y, T(0)), size, fetch);
    CHECK(edge.x == doctest::Approx(1.5));
    CHECK(edge.z == doctest::Approx(50.0));  // z = 0: halfway between slice 1 and slice 0
    // 2D, and a degenerate size (taken as 1: every coordinate reads texel 0).
    const auto fetch2 = [](int i, int j) { return T(i + 2 * j); };
    CHECK(texture_bilinear_repeat(glm::vec<2, T>(T(0.25), T(0.75)), glm::ivec2(2, 2), fetch2) == doctest::Approx(2.0));
    CHECK(texture_bilinear_repeat(glm::vec<2, T>(T(0.5), T(0.75)), glm::ivec2(2, 2), fetch2) == doctest::Approx(2.5));
    CHECK(texture_bilinear_repeat(glm::vec<2, T>(T(0.3), T(7.1)), glm::ivec2(0, -4), fetch2) == doctest::Approx(0.0));
    // NaN and Inf coordinates: NaN out, no index outside the texture (fetch REQUIREs it).
    if (cm_test::ieee_build) {
        CHECK(std::isnan(texture_trilinear_repeat(v3(cm_test::make_nan<T>(), T(0), T(0)), size, fetch).x));
        CHECK(std::isnan(texture_trilinear_repeat(v3(T(0), cm_test::make_inf<T>(), T(0)), size, fetch).y));
        CHECK(std::isnan(texture_bilinear_repeat(glm::vec<2, T>(-cm_test::make_inf<T>(), T(0)), glm::ivec2(2, 2), fetch2)));
    }
    // Huge coordinates stay in range.
    (void)texture_trilinear_repeat(v3(T(1e30), T(-1e30), T(3e9)), size, fetch);
}

TEST_CASE("the default base volume and coverage: what coverage 0.5 covers (docs/integration.md)") {
    // nubis_base_cloud of the default bake (4 cells; at 64^3 here, the default is 128^3 of the
    // same field) and the share of space apply_coverage leaves cloudy at each coverage.
    bake_options options;
    options.threads = 2;
    const int size = 64;
    const std::vector<std::uint8_t> base = bake_base_volume(size, base_volume_default_cells, options);
    REQUIRE(base.size() == std::size_t(size) * size * size * 4);
    std::size_t mid = 0, over_half = 0, over_07 = 0;
    const std::size_t n = base.size() / 4;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec4 t(base[4 * i] / 255.0f, base[4 * i + 1] / 255.0f, base[4 * i + 2] / 255.0f, base[4 * i + 3] / 255.0f);
        const float b = nubis_base_cloud(t);
        mid += b >= 0.5f && b <= 0.8f;
        over_half += apply_coverage(b, 0.5f) > 0.0f;
        over_07 += apply_coverage(b, 0.3f) > 0.0f;
    }
    const double f_mid = double(mid) / double(n), f_half = double(over_half) / double(n), f_03 = double(over_07) / double(n);
    MESSAGE("base cloud in [0.5, 0.8]: " << f_mid << "; cloudy at coverage 0.5: " << f_half << ", at 0.3: " << f_03);
    CHECK(f_mid > 0.85);    // the base cloud sits in a narrow band...
    CHECK(f_half > 0.85);   // ...so coverage 0.5 is overcast,
    CHECK(f_03 < 0.6);      // and coverage 0.3 leaves about half of it (before the weather map and
                            // the height profile thin it further: the presets' 0.27-0.33 are scattered)
}

// Regression (fuzzing, UBSan): the texel functions multiplied cells by 2, 4 and 8 in int,
// signed overflow (undefined behaviour) from cells = 2^28 (base) and 2^29 (detail); the
// sanitize build aborts on it. Now cells < 1 acts as 1 and the periods saturate at 2^30:
// every int gives values in [0, 1].
TEST_CASE("noise_bake: texel functions for every int cells: no overflow, values in [0, 1], cells < 1 acts as 1") {
    const int int_max = std::numeric_limits<int>::max(), int_min = std::numeric_limits<int>::min();
    const glm::vec3 p(0.37f, 1.61f, 2.9f);
    const glm::dvec3 pd(0.37, 1.61, 2.9);
    for (int cells : {1 << 25, 1 << 27, 1 << 28, (1 << 28) + 1, 1 << 29, 1 << 30, int_max, 0, -1, -(1 << 28) - 1, -(1 << 29) - 1, int_min}) {
        INFO("cells = " << cells);
        const glm::vec4 b = bake_base_texel(p, cells, 7U);
        const glm::vec3 d = bake_detail_texel(p, cells, 7U);
        const glm::dvec4 bd = bake_base_texel(pd, cells, 7U);
        const glm::dvec3 dd = bake_detail_texel(pd, cells, 7U);
        for (int c = 0; c < 4; ++c) {
            CHECK(b[c] >= 0.0f);
            CHECK(b[c] <= 1.0f);
            CHECK(bd[c] >= 0.0);
            CHECK(bd[c] <= 1.0);
        }
        for (int c = 0; c < 3; ++c) {
            CHECK(d[c] >= 0.0f);
            CHECK(d[c] <= 1.0f);
            CHECK(dd[c] >= 0.0);
            CHECK(dd[c] <= 1.0);
        }
        if (cells < 1) {  // documented: treated as 1
            CHECK(b == bake_base_texel(p, 1, 7U));
            CHECK(d == bake_detail_texel(p, 1, 7U));
        }
    }
    // Up to the documented limit (2^25 base, 2^26 detail) the channels are the noise at 2, 4
    // and 8 times cells exactly, as for the bake sizes.
    for (int cells : {4, 1 << 25}) {
        const glm::vec4 b = bake_base_texel(p, cells, 7U);
        CHECK(b.w == worley_fbm_nubis(p * 8.0f, 8 * cells, bake_channel_seed(7U, bake_channel::base_a)));
        const glm::vec3 d = bake_detail_texel(p, 2 * cells, 7U);
        CHECK(d.z == worley_fbm_nubis(p * 4.0f, 8 * cells, bake_channel_seed(7U, bake_channel::detail_b)));
    }
}
