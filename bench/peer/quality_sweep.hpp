// The equal-quality comparison of the peer bench: each renderer swept over its quality knobs
// (view steps, light samples), each setting timed in interleaved rounds and measured as
// PSNR against that renderer's own converged image, then the frame time each needs for 30,
// 35 and 40 dB. The peer's knobs come from quality_knobs.hpp, ours from the variant.
#ifndef CLOUDMATH_PEER_BENCH_QUALITY_SWEEP_HPP
#define CLOUDMATH_PEER_BENCH_QUALITY_SWEEP_HPP

#include "gl_renderer.hpp"
#include "peer_clouds.hpp"
#include "scene.hpp"

#include <string>
#include <vector>

namespace peer_bench {

struct sweep_settings {
    int width = 480, height = 270;
    int rounds = 3;                                  // timed rounds (median reported)
    std::vector<int> view_steps{16, 32, 64, 128, 256};
    std::vector<int> light_steps{3, 6, 12, 24};      // the peer's light samples, our light-steps
    std::string images_dir;                          // peer_quality.svg and the converged images; empty: none
    bool quiet = false;
};

// Runs the sweep on the current context (both renderers set up, the peer prepared at the
// same size and view) and returns its Markdown section in `markdown`.
bool quality_sweep(cloud_renderer::gl_renderer& ours, peer_clouds& peer, const cloud_renderer::scene& sc,
                   const sweep_settings& o, std::string& markdown, std::string& why);

}  // namespace peer_bench

#endif  // CLOUDMATH_PEER_BENCH_QUALITY_SWEEP_HPP
