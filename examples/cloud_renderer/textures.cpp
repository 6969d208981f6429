#include "textures.hpp"

#include "atomic_file.hpp"

#include <cloudmath/noise_bake.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace cloud_renderer {
namespace {

constexpr char magic[8] = {'C', 'R', 'T', 'E', 'X', '0', '0', '2'};
constexpr std::uint32_t seed = 0;

// FNV-1a over the texel bytes: detects truncated or damaged cache files.
std::uint64_t checksum(const std::vector<std::uint8_t>& bytes, std::uint64_t h) {
    for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ULL;
    return h;
}

struct header {
    char magic[8];
    std::int32_t base_size, detail_size, weather_size;
    std::uint32_t seed;
    std::uint64_t checksum;
};

std::string cache_path(const std::string& dir, const cloud_textures& t) {
    return dir + "/clouds2_" + std::to_string(t.base_size) + "_" + std::to_string(t.detail_size) + "_" +
           std::to_string(t.weather_size) + "_seed" + std::to_string(seed) + ".bin";
}

std::uint64_t checksum_of(const cloud_textures& t) {
    return checksum(t.curl, checksum(t.weather_wide, checksum(t.weather, checksum(t.detail, checksum(t.base, 1469598103934665603ULL)))));
}

bool read_cache(const std::string& path, cloud_textures& t) {
    std::ifstream in(path, std::ios::binary);
    header h{};
    if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) return false;
    if (std::memcmp(h.magic, magic, sizeof magic) != 0 || h.base_size != t.base_size ||
        h.detail_size != t.detail_size || h.weather_size != t.weather_size || h.seed != seed)
        return false;
    for (std::vector<std::uint8_t>* v : {&t.base, &t.detail, &t.weather, &t.weather_wide, &t.curl})
        if (!in.read(reinterpret_cast<char*>(v->data()), static_cast<std::streamsize>(v->size()))) return false;
    return in.peek() == std::char_traits<char>::eof() && checksum_of(t) == h.checksum;
}

// mkdir -p: every missing directory of `dir` (existing ones are fine; failures show when
// the file is written).
void make_directories(const std::string& dir) {
    for (std::size_t i = 1; i <= dir.size(); ++i)
        if (i == dir.size() || dir[i] == '/') ::mkdir(dir.substr(0, i).c_str(), 0755);
}

// Writes the cache atomically (tools/common/atomic_file.hpp: a temporary beside it, checked,
// renamed): no reader ever sees half a cache, and a failure leaves no temporary behind.
// Returns "" or the reason.
std::string write_cache(const std::string& dir, const std::string& path, const cloud_textures& t) {
    make_directories(dir);
    header h{};
    std::memcpy(h.magic, magic, sizeof magic);
    h.base_size = t.base_size;
    h.detail_size = t.detail_size;
    h.weather_size = t.weather_size;
    h.seed = seed;
    h.checksum = checksum_of(t);
    const std::vector<std::uint8_t>* const parts[] = {&t.base, &t.detail, &t.weather, &t.weather_wide, &t.curl};
    std::size_t size = sizeof h;
    for (const std::vector<std::uint8_t>* v : parts) size += v->size();
    std::string bytes;
    bytes.reserve(size);
    bytes.append(reinterpret_cast<const char*>(&h), sizeof h);
    for (const std::vector<std::uint8_t>* v : parts) bytes.append(reinterpret_cast<const char*>(v->data()), v->size());
    return cloudmath::tools::write_file_atomically(path, bytes);
}

}  // namespace

std::string default_texture_cache_dir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0') return std::string(xdg) + "/cloudmath";
    if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') return std::string(home) + "/.cache/cloudmath";
    return {};
}

bool load_or_bake_textures(const std::string& cache_dir, bool quiet, cloud_textures& t, std::string& why) {
    t.base_size = cloudmath::base_volume_default_size;
    t.detail_size = cloudmath::detail_volume_default_size;
    t.weather_size = cloudmath::weather_map_default_size;
    const auto cube = [](int n) { return static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * static_cast<std::size_t>(n); };
    t.base.assign(cube(t.base_size) * 4, 0);
    t.detail.assign(cube(t.detail_size) * 3, 0);
    t.weather.assign(static_cast<std::size_t>(t.weather_size) * static_cast<std::size_t>(t.weather_size) * 3, 0);
    t.weather_wide_size = 4 * t.weather_size;
    t.weather_wide.assign(static_cast<std::size_t>(t.weather_wide_size) * static_cast<std::size_t>(t.weather_wide_size) * 3, 0);
    t.curl_size = cloudmath::curl_texture_default_size;
    t.curl.assign(static_cast<std::size_t>(t.curl_size) * static_cast<std::size_t>(t.curl_size) * 3, 0);
    const std::string path = cache_dir.empty() ? std::string() : cache_path(cache_dir, t);
    if (!path.empty() && read_cache(path, t)) {
        if (!quiet) std::fprintf(stderr, "textures: read from %s\n", path.c_str());
        return true;
    }

    // Progress over the three bakes, weighted by their texel counts.
    const double total = double(t.base.size() / 4 + t.detail.size() / 3 + t.weather.size() / 3 + t.weather_wide.size() / 3 +
                                t.curl.size() / 3);
    double done_before = 0, weight = 0;
    cloudmath::bake_options options;
    options.seed = seed;
    // One update per percent on a terminal (rewriting the line), per 10% into a log.
    const bool terminal = ::isatty(::fileno(stderr)) != 0;
    const int step = terminal ? 1 : 10;
    int shown = -1;
    if (!quiet)
        options.progress = [&](float f) {
            const int percent = static_cast<int>(100.0 * (done_before + weight * f) / total) / step * step;
            if (percent == shown) return;
            shown = percent;
            std::fprintf(stderr, terminal ? "\rbaking cloud textures (first run; cached afterwards): %3d%%"
                                          : "baking cloud textures (first run; cached afterwards): %3d%%\n",
                         percent);
        };
    weight = double(t.base.size() / 4);
    bool ok = cloudmath::bake_base_volume(t.base.data(), t.base_size, cloudmath::base_volume_default_cells, options);
    done_before += weight;
    weight = double(t.detail.size() / 3);
    ok = ok && cloudmath::bake_detail_volume(t.detail.data(), t.detail_size, cloudmath::detail_volume_default_cells, options);
    done_before += weight;
    weight = double(t.weather.size() / 3);
    ok = ok && cloudmath::bake_weather_map(t.weather.data(), t.weather_size, cloudmath::weather_map_default_cells, options);
    done_before += weight;
    weight = double(t.weather_wide.size() / 3);
    ok = ok && cloudmath::bake_weather_map(t.weather_wide.data(), t.weather_wide_size, 4 * cloudmath::weather_map_default_cells,
                                           options);
    done_before += weight;
    weight = double(t.curl.size() / 3);
    ok = ok && cloudmath::bake_curl_texture(t.curl.data(), t.curl_size, cloudmath::curl_texture_default_cells, options);
    if (!quiet && terminal) std::fprintf(stderr, "\n");
    if (!ok) {
        why = "baking the cloud textures failed";
        return false;
    }
    if (!path.empty()) {
        const std::string error = write_cache(cache_dir, path, t);
        if (error.empty()) {
            if (!quiet) std::fprintf(stderr, "textures: cached in %s\n", path.c_str());
        } else {
            std::fprintf(stderr, "textures: warning: could not write the cache: %s\n", error.c_str());
        }
    }
    return true;
}

}  // namespace cloud_renderer
