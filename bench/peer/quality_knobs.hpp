// The peer's quality knobs made explicit: a copy of its clouds shader (volumetric_clouds.comp)
// with the view march's step count, the light march's sample count and a per-frame jitter
// offset as constants, built in memory by text edits at landmarks that must each occur once.
// At 64 view steps, 6 light samples and jitter 0 the copy computes exactly what the shipped
// shader does (the bench checks the images are identical); elsewhere it keeps the peer's
// model and changes only how finely it is sampled:
//   - the light march keeps the shipped reach, 6 steps of 0.6 view steps at 64 view steps
//     (the shipped code ties it to the view step: 256 view steps would shorten it 4 times);
//   - its cone offsets keep their shape (the 6 kernel vectors, cycled, at the same radii);
//   - the texture level stays a function of how far along the ray a sample is (the shipped
//     `i/16` counts steps), and the light march's switch to the detailed density stays at
//     the same optical depth (the shipped `density > 0.3` sums samples);
//   - the Bayer start offset is shifted by a uniform `cm_jitter` in [0, 1) (fract), so a
//     converged image averages frames with different offsets.
#ifndef CLOUDMATH_PEER_BENCH_QUALITY_KNOBS_HPP
#define CLOUDMATH_PEER_BENCH_QUALITY_KNOBS_HPP

#include <string>

namespace peer_bench {

// The shipped shader's settings.
inline constexpr int shipped_view_steps = 64;
inline constexpr int shipped_light_steps = 6;
// The uniform (float) that shifts the start offsets; 0 is the shipped offset.
inline constexpr const char* jitter_uniform = "cm_jitter";

// The copy of `peer_source` with view_steps (1..4096) view steps and light_steps (1..1024)
// light samples. Empty, with the reason in `why`, when a landmark is missing or repeated (a
// peer checkout other than the one the edits were written for) or a count is out of range.
std::string with_quality_knobs(const std::string& peer_source, int view_steps, int light_steps, std::string& why);

}  // namespace peer_bench

#endif  // CLOUDMATH_PEER_BENCH_QUALITY_KNOBS_HPP
