// Command line of the cloud renderer.
#ifndef CLOUD_RENDERER_OPTIONS_HPP
#define CLOUD_RENDERER_OPTIONS_HPP

#include "scene.hpp"

#include <string>

namespace cloud_renderer {

enum class run_mode { window, headless, cpu, compare, bench, convergence, list_presets, dump_shader, print_sky, help };

// options::pass for `--pass composite`: composite.frag, not a pass of clouds.frag.
inline constexpr int composite_pass_option = 100;

struct options {
    run_mode mode = run_mode::window;
    scene sc = presets().front();
    bool preset_given = false;   // --preset was on the command line (--convergence: that preset alone)
    variant var;
    int width = 1280, height = 720;
    std::string out;             // PNG path (headless, cpu, compare); empty: the mode's default
    std::string bench_out;       // markdown table of --bench; empty: stdout only
    std::string cache_dir;       // texture cache; "none" disables
    int frames = 3;              // --bench: timed frames per variant (after one warm-up);
                                 // window: close after this many frames, if frames_given
    bool frames_given = false;
    int accumulate = 1;          // --headless, --cpu, --compare: average of frames 0..N-1
    int temporal = 0;            // --headless, --cpu, --compare: frames 0..N-1 of the temporal
                                 // scheme, the last one written (0: a full frame)
    float pan = 0.0f;            // --temporal: yaw added per frame (degrees)
    float drift = 0.0f;          // --temporal: wind added per frame along +x (metres)
    int save_every = 0;          // --temporal: also write every Nth frame (FILE_fNNN.png)
    double min_psnr = 0;         // --compare: fail below this (0: never)
    bool quiet = false;
    int pass = 0;                // --dump-shader: clouds.frag's pass (gl_renderer.hpp's clouds_pass), --pass;
                                 // composite_pass_option: composite.frag
};

// Parses argv into `out`. Returns an empty string on success, else a one-line message for
// the user (unknown flag, missing or out-of-range value, ...). Scene flags override the
// preset's values wherever they stand.
std::string parse_options(int argc, const char* const* argv, options& out);
const char* usage_text();

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_OPTIONS_HPP
