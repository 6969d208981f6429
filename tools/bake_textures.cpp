// cloudmath_bake_textures: bakes the tileable cloud noise textures of noise_bake.hpp (base
// and detail volumes, curl texture, weather map) and writes them as raw texel files ready
// for a GPU upload, plus PNG previews: greyscale z slices of every volume channel, the 2D
// textures in RGB, and the base R slice tiled 2 x 2 to show that it repeats without seams.
//
//   cloudmath_bake_textures [--out DIR] [--seed N] [--threads N] [--base-size N]
//                           [--detail-size N] [--curl-size N] [--weather-size N]
//
// Raw files: <name>_<W>x<H>[x<D>]_<rgba8|rgb8>.raw, texel (i, j, k) at byte
// ((k H + j) W + i) * channels (x fastest), channels interleaved, UNORM8. Prints the bake
// time of each texture and the total; a progress line goes to stderr.
// Every file is written atomically (tools/common/atomic_file.hpp: a temporary beside it,
// checked, renamed over it): a failed write names the file, leaves the old one and no
// temporary, and the exit status is 1.
// Built with the examples (CLOUDMATH_BUILD_EXAMPLES); scripts/main.sh runs it.
#include <cloudmath/noise_bake.hpp>

#include "atomic_file.hpp"
#include "png_encode.hpp"
#include "strict_number.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace cm = cloudmath;

namespace {

// Volumes above this size would need gigabytes (512^3 RGBA8 is 512 MiB).
constexpr int max_volume_size = 512;

struct settings {
    std::string out = "textures";
    std::uint32_t seed = 0;
    unsigned threads = 0;
    int base_size = cm::base_volume_default_size;
    int detail_size = cm::detail_volume_default_size;
    int curl_size = cm::curl_texture_default_size;
    int weather_size = cm::weather_map_default_size;
};

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: cloudmath_bake_textures [--out DIR] [--seed N] [--threads N] [--base-size N]\n"
                 "                               [--detail-size N] [--curl-size N] [--weather-size N]\n"
                 "  --out DIR           output directory, created if missing (default: textures)\n"
                 "  --seed N            32-bit seed, 0..4294967295 (default: 0)\n"
                 "  --threads N         worker threads, 0 = all hardware threads (default: 0)\n"
                 "  --base-size N       base volume, N^3 RGBA8, 4 cells (default: %d, at most %d)\n"
                 "  --detail-size N     detail volume, N^3 RGB8, 2 cells (default: %d, at most %d)\n"
                 "  --curl-size N       curl texture, N^2 RGB8, 4 cells (default: %d, at most %d)\n"
                 "  --weather-size N    weather map, N^2 RGB8, 4 cells (default: %d, at most %d)\n"
                 "  A size of 0 skips that texture. Options also take the form --name=value.\n",
                 cm::base_volume_default_size, max_volume_size, cm::detail_volume_default_size, max_volume_size,
                 cm::curl_texture_default_size, cm::bake_max_size, cm::weather_map_default_size, cm::bake_max_size);
}

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "cloudmath_bake_textures: %s\n", message.c_str());
    print_usage(stderr);
    std::exit(2);
}

// A decimal integer in [lo, hi], the whole string (no sign, no spaces, no suffix).
unsigned long parse_number(const std::string& flag, const std::string& text, unsigned long lo, unsigned long hi) {
    bool digits = !text.empty();
    for (char c : text) digits = digits && c >= '0' && c <= '9';
    const std::optional<unsigned long> parsed = digits ? cloudmath::tools::parse_integer<unsigned long>(text) : std::nullopt;
    if (!parsed) usage_error("bad value '" + text + "' for " + flag + ": expected a whole number");
    const unsigned long value = *parsed;
    if (value < lo || value > hi)
        usage_error("value " + text + " for " + flag + " is out of range [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
    return value;
}

settings parse_arguments(int argc, char** argv) {
    settings s;
    for (int a = 1; a < argc; ++a) {
        std::string flag = argv[a], value;
        if (flag == "--help" || flag == "-h") {
            print_usage(stdout);
            std::exit(0);
        }
        const std::size_t eq = flag.find('=');
        const bool has_inline_value = flag.rfind("--", 0) == 0 && eq != std::string::npos;
        if (has_inline_value) {
            value = flag.substr(eq + 1);
            flag = flag.substr(0, eq);
        }
        const auto take_value = [&]() {
            if (has_inline_value) return value;
            if (a + 1 >= argc) usage_error("missing value after " + flag);
            return std::string(argv[++a]);
        };
        const auto size_value = [&](int max) {
            return static_cast<int>(parse_number(flag, take_value(), 0, static_cast<unsigned long>(max)));
        };
        if (flag == "--out") {
            s.out = take_value();
            if (s.out.empty()) usage_error("--out needs a directory name");
        } else if (flag == "--seed") {
            s.seed = static_cast<std::uint32_t>(parse_number(flag, take_value(), 0, 4294967295UL));
        } else if (flag == "--threads") {
            s.threads = static_cast<unsigned>(parse_number(flag, take_value(), 0, 1024));
        } else if (flag == "--base-size") {
            s.base_size = size_value(max_volume_size);
        } else if (flag == "--detail-size") {
            s.detail_size = size_value(max_volume_size);
        } else if (flag == "--curl-size") {
            s.curl_size = size_value(cm::bake_max_size);
        } else if (flag == "--weather-size") {
            s.weather_size = size_value(cm::bake_max_size);
        } else {
            usage_error("unknown option '" + std::string(argv[a]) + "'");
        }
    }
    return s;
}

bool stderr_is_terminal() {
#if defined(__unix__) || defined(__APPLE__)
    return isatty(STDERR_FILENO) == 1;
#else
    return false;
#endif
}

// One progress line per texture on stderr: redrawn in place on a terminal, otherwise
// written once when the texture is done (logs stay readable).
class progress_line {
public:
    explicit progress_line(std::string label) : label_(std::move(label)), live_(stderr_is_terminal()) {}

    // Called by the bake, serialised; prints only when the whole percentage changes.
    void update(float fraction) {
        const int percent = static_cast<int>(fraction * 100.0f);
        if (!live_ || percent == last_percent_) return;
        last_percent_ = percent;
        std::fprintf(stderr, "\r  baking %s: %3d%%", label_.c_str(), percent);
        std::fflush(stderr);
    }
    void finish(double seconds) const {
        std::fprintf(stderr, "%s  baking %s: 100%% (%.1f ms)\n", live_ ? "\r" : "", label_.c_str(), seconds * 1e3);
    }

private:
    std::string label_;
    bool live_;
    int last_percent_ = -1;
};

// "" or the reason the file could not be written (naming it).
std::string write_raw(const std::filesystem::path& path, const std::vector<std::uint8_t>& texels) {
    return cloudmath::tools::write_file_atomically(
        path.string(), std::string_view(reinterpret_cast<const char*>(texels.data()), texels.size()));
}

// The PNG encoded in memory (stbi_write_png would truncate the old file first and ignore
// write errors), then written like the raw files.
std::string write_png(const std::filesystem::path& path, int width, int height, int channels,
                      const std::vector<std::uint8_t>& pixels) {
    const std::string png = cloudmath::tools::encode_png(width, height, channels, pixels.data(), width * channels);
    if (png.empty()) return "cannot encode '" + path.string() + "' as PNG";
    return cloudmath::tools::write_file_atomically(path.string(), png);
}

// Channel c of z slice k of a size^3 volume with `channels` interleaved channels.
std::vector<std::uint8_t> volume_slice(const std::vector<std::uint8_t>& volume, int size, int channels, int k, int c) {
    const std::size_t n = static_cast<std::size_t>(size), ch = static_cast<std::size_t>(channels);
    std::vector<std::uint8_t> slice(n * n);
    const std::size_t base = static_cast<std::size_t>(k) * n * n;
    for (std::size_t t = 0; t < n * n; ++t) slice[t] = volume[(base + t) * ch + static_cast<std::size_t>(c)];
    return slice;
}

// A greyscale image repeated 2 x 2 (seams would show as lines through the middle).
std::vector<std::uint8_t> tile_2x2(const std::vector<std::uint8_t>& image, int size) {
    const std::size_t n = static_cast<std::size_t>(size);
    std::vector<std::uint8_t> tiled(4 * n * n);
    for (std::size_t y = 0; y < 2 * n; ++y)
        for (std::size_t x = 0; x < 2 * n; ++x) tiled[y * 2 * n + x] = image[(y % n) * n + (x % n)];
    return tiled;
}

struct result {
    bool ok = true;
    std::vector<std::string> files;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    const settings s = parse_arguments(argc, argv);
    const std::filesystem::path out(s.out);
    std::error_code error;
    std::filesystem::create_directories(out, error);
    if (error) {
        std::fprintf(stderr, "cloudmath_bake_textures: cannot create '%s': %s\n", s.out.c_str(),
                     error.message().c_str());
        return 1;
    }
    const unsigned hardware = std::thread::hardware_concurrency();
    const unsigned threads = s.threads != 0 ? s.threads : (hardware != 0 ? hardware : 1U);
    std::printf("cloudmath_bake_textures: seed %u, %u thread%s, output %s\n", s.seed, threads,
                threads == 1 ? "" : "s", s.out.c_str());

    bool ok = true;
    double total_bake = 0;
    const auto start_all = std::chrono::steady_clock::now();
    const auto note = [&](const char* name, const std::string& shape, double seconds, const result& r) {
        std::printf("  %-8s %-20s %9.1f ms  ", name, shape.c_str(), seconds * 1e3);
        for (std::size_t f = 0; f < r.files.size(); ++f) std::printf("%s%s", f ? ", " : "", r.files[f].c_str());
        std::printf("\n");
        std::fflush(stdout);
        total_bake += seconds;
        ok = ok && r.ok;
    };
    // Bakes one texture with a progress line, returns its texels and the bake seconds.
    const auto bake = [&](const std::string& label, auto&& run) {
        progress_line line(label);
        cm::bake_options options;
        options.seed = s.seed;
        options.threads = s.threads;
        options.progress = [&line](float fraction) { line.update(fraction); };
        const auto start = std::chrono::steady_clock::now();
        std::vector<std::uint8_t> texels = run(options);
        const double seconds = seconds_since(start);
        line.finish(seconds);
        return std::make_pair(std::move(texels), seconds);
    };
    const auto save = [&](result& r, const std::string& name, const std::string& why) {
        r.files.push_back(name);
        if (!why.empty()) {
            std::fprintf(stderr, "cloudmath_bake_textures: %s\n", why.c_str());
            r.ok = false;
        }
    };

    // Volumes: raw file, greyscale PNGs of every channel at z = 0 and z = size / 2.
    const auto volume = [&](const char* name, int size, int channels, const char* channel_names, auto&& run) {
        if (size == 0) return;
        const std::string dims = std::to_string(size) + "x" + std::to_string(size) + "x" + std::to_string(size);
        const std::string format = channels == 4 ? "rgba8" : "rgb8";
        auto [texels, seconds] = bake(std::string(name) + " " + dims + " " + format, run);
        result r;
        r.ok = !texels.empty();
        const std::string raw = std::string(name) + "_" + dims + "_" + format + ".raw";
        save(r, raw, write_raw(out / raw, texels));
        std::vector<int> slices{0};
        if (size / 2 != 0) slices.push_back(size / 2);
        for (int k : slices) {
            for (int c = 0; c < channels; ++c) {
                const std::string png = std::string(name) + "_" + channel_names[c] + "_z" + std::to_string(k) + ".png";
                save(r, png, write_png(out / png, size, size, 1, volume_slice(texels, size, channels, k, c)));
            }
        }
        if (std::string(name) == "base") {
            const std::string png = "base_r_z0_tiled2x2.png";
            save(r, png, write_png(out / png, 2 * size, 2 * size, 1, tile_2x2(volume_slice(texels, size, channels, 0, 0), size)));
        }
        note(name, dims + " " + format, seconds, r);
    };
    // 2D textures: raw file and the RGB image.
    const auto image = [&](const char* name, int size, auto&& run) {
        if (size == 0) return;
        const std::string dims = std::to_string(size) + "x" + std::to_string(size);
        auto [texels, seconds] = bake(std::string(name) + " " + dims + " rgb8", run);
        result r;
        r.ok = !texels.empty();
        const std::string raw = std::string(name) + "_" + dims + "_rgb8.raw";
        save(r, raw, write_raw(out / raw, texels));
        const std::string png = std::string(name) + "_" + dims + ".png";
        save(r, png, write_png(out / png, size, size, 3, texels));
        note(name, dims + " rgb8", seconds, r);
    };

    volume("base", s.base_size, 4, "rgba", [&](const cm::bake_options& o) {
        return cm::bake_base_volume(s.base_size, cm::base_volume_default_cells, o);
    });
    volume("detail", s.detail_size, 3, "rgb", [&](const cm::bake_options& o) {
        return cm::bake_detail_volume(s.detail_size, cm::detail_volume_default_cells, o);
    });
    image("curl", s.curl_size, [&](const cm::bake_options& o) {
        return cm::bake_curl_texture(s.curl_size, cm::curl_texture_default_cells, o);
    });
    image("weather", s.weather_size, [&](const cm::bake_options& o) {
        return cm::bake_weather_map(s.weather_size, cm::weather_map_default_cells, o);
    });

    std::printf("  total bake %.2f s (with file writing: %.2f s) on %u thread%s\n", total_bake,
                seconds_since(start_all), threads, threads == 1 ? "" : "s");
    if (!ok) {
        std::fprintf(stderr, "cloudmath_bake_textures: some files could not be written\n");
        return 1;
    }
    return 0;
}
