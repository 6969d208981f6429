// The instrumented copy of the peer's clouds shader, built in memory at run time for counting
// texture reads only (the timed run compiles the peer's file unchanged). It wraps texture()
// and textureLod() in counting functions with a macro, flags the reads made inside the
// peer's light function (raymarchToLight) and whether the pixel was marched at all
// (raymarchToCloud ran), and writes three uints per pixel to a storage buffer.
#ifndef CLOUDMATH_PEER_BENCH_INSTRUMENT_HPP
#define CLOUDMATH_PEER_BENCH_INSTRUMENT_HPP

#include <string>

namespace peer_bench {

// Storage buffer binding of the counters (the peer's shader uses none) and its layout:
// per pixel, row-major from the bottom row, {all reads, reads in the light function, marched}.
inline constexpr unsigned counter_binding = 0;
inline constexpr unsigned counters_per_pixel = 3;
// Uniform (ivec2) with the image size, so that invocations past the edge write nothing.
inline constexpr const char* counter_size_uniform = "cm_size";

struct instrumented_shader {
    std::string source;       // empty on failure
    bool light_attributed = false;  // raymarchToLight found: its reads are counted apart
    std::string light_note;   // why they are not, when not
};

// The counting version of `peer_source` (volumetric_clouds.comp). Without the light
// function's landmarks it still counts all reads (light_attributed false, light_note why);
// without raymarchToCloud, #version or main it fails: empty source and the reason in `why`.
instrumented_shader instrument_texture_reads(const std::string& peer_source, std::string& why);

}  // namespace peer_bench

#endif  // CLOUDMATH_PEER_BENCH_INSTRUMENT_HPP
