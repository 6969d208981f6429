// The baked cloud textures (cloudmath/noise_bake.hpp) and their cache on disk.
#ifndef CLOUD_RENDERER_TEXTURES_HPP
#define CLOUD_RENDERER_TEXTURES_HPP

#include <cstdint>
#include <string>
#include <vector>

namespace cloud_renderer {

// Texel layout of noise_bake.hpp: x fastest, then y, then z; channels interleaved; UNORM8.
struct cloud_textures {
    int base_size = 0;     // base volume: base_size^3 RGBA
    int detail_size = 0;   // detail volume: detail_size^3 RGB
    int weather_size = 0;  // weather map: weather_size^2 RGB (the classic shape's)
    // The detailed shape's weather map, 4 times as wide with 4 times the cells (the same
    // features per texel, a 4 times longer period): weather_wide_size^2 RGB.
    int weather_wide_size = 0;
    int curl_size = 0;     // curl texture: curl_size^2 RGB (curl_bake_encode)
    std::vector<std::uint8_t> base, detail, weather, weather_wide, curl;
};

// Reads the textures from `cache_dir` if a cache file with the same sizes, seed and format is
// there and its checksum matches; otherwise bakes them with every core (a progress line on
// stderr unless quiet) and writes the cache, creating missing directories (failing to
// write it is only a warning).
// An empty cache_dir disables the cache. Returns false with a message only if baking fails.
bool load_or_bake_textures(const std::string& cache_dir, bool quiet, cloud_textures& out, std::string& why);

// The default cache directory: $XDG_CACHE_HOME/cloudmath, else $HOME/.cache/cloudmath, else
// empty (no cache).
std::string default_texture_cache_dir();

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_TEXTURES_HPP
