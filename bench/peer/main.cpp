// cloudmath_peer_bench: times a peer's cloud renderer (TerrainEngine-OpenGL's
// volumetric_clouds.comp, loaded from a checkout given with --peer) and ours
// (examples/cloud_renderer) in one process, on one headless GL 4.5 context, at one image
// size and view; counts the peer's texture reads with an instrumented copy of its shader;
// prints a Markdown report on stdout (scripts/peer-bench.sh puts it in docs/peer_bench.md).
// Not part of the library: built only with -DCLOUDMATH_BUILD_PEER_BENCH=ON.
#include "peer_clouds.hpp"
#include "quality_sweep.hpp"
#include "timing.hpp"

#include "cpu_renderer.hpp"
#include "egl_headless.hpp"
#include "gl_renderer.hpp"
#include "image.hpp"
#include "scene.hpp"
#include "textures.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace cloud_renderer;
using peer_bench::time_rows;
using peer_bench::timed_row;

const char* const usage =
    "usage: cloudmath_peer_bench --peer DIR [options]\n"
    "Times TerrainEngine-OpenGL's volumetric cloud compute shader (read from DIR/shaders, a\n"
    "checkout of fede-vaccaro/TerrainEngine-OpenGL, run unchanged) and cloudmath's example\n"
    "renderer at the same size and view on a headless OpenGL 4.5 context; prints Markdown.\n"
    "  --peer DIR       the peer's checkout (required)\n"
    "  --width N        image width (default 480)\n"
    "  --height N       image height (default 270)\n"
    "  --frames N       timed frames per row, median reported (default 5)\n"
    "  --preset NAME    our scene preset whose view both use (default ground)\n"
    "  --images DIR     write DIR/peer_clouds.png, peer_ours_default.png, peer_ours_temporal.png\n"
    "                   and peer_ours_octaves.png\n"
    "  --cache DIR      our baked texture cache (default ~/.cache/cloudmath; 'none': no cache)\n"
    "  --sweep          also the equal-quality sweep: both renderers at 16-256 view steps and\n"
    "                   3, 6, 12 and 24 light samples against their own converged images\n"
    "  --sweep-rounds N timed rounds of the sweep (default 3)\n"
    "  --sweep-steps L  the sweep's view steps, a comma-separated list (default 16,32,64,128,256)\n"
    "  --sweep-light L  the sweep's light samples, a comma-separated list (default 3,6,12,24)\n"
    "  --quiet          no progress lines on stderr\n"
    "  --help           this text\n";

struct options {
    std::string peer_dir, images_dir, cache_dir, preset = "ground";
    int width = 480, height = 270, frames = 5, sweep_rounds = 3;
    std::vector<int> sweep_steps{16, 32, 64, 128, 256}, sweep_light{3, 6, 12, 24};
    bool quiet = false, sweep = false;
};

bool parse_int(const std::string& text, int lo, int hi, int& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (*end != '\0' || v < lo || v > hi) return false;
    out = static_cast<int>(v);
    return true;
}

// 0: run, 1: --help printed, 2: bad command line (message printed).
int parse(int argc, char** argv, options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "--help" || flag == "-h") {
            std::fputs(usage, stdout);
            return 1;
        }
        if (flag == "--quiet" || flag == "--sweep") {
            (flag == "--quiet" ? o.quiet : o.sweep) = true;
            continue;
        }
        const bool takes_value = flag == "--peer" || flag == "--width" || flag == "--height" || flag == "--frames" ||
                                 flag == "--preset" || flag == "--images" || flag == "--cache" ||
                                 flag == "--sweep-rounds" || flag == "--sweep-steps" || flag == "--sweep-light";
        if (!takes_value) {
            std::fprintf(stderr, "error: unknown option '%s'\n%s", flag.c_str(), usage);
            return 2;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "error: %s needs a value\n", flag.c_str());
            return 2;
        }
        const std::string value = argv[++i];
        bool ok = true;
        if (flag == "--peer") o.peer_dir = value;
        else if (flag == "--preset") o.preset = value;
        else if (flag == "--images") o.images_dir = value;
        else if (flag == "--cache") o.cache_dir = value;
        else if (flag == "--width") ok = parse_int(value, 16, 8192, o.width);
        else if (flag == "--height") ok = parse_int(value, 16, 8192, o.height);
        else if (flag == "--sweep-rounds") ok = parse_int(value, 1, 1000, o.sweep_rounds);
        else if (flag == "--sweep-steps" || flag == "--sweep-light") {
            std::vector<int>& list = flag == "--sweep-steps" ? o.sweep_steps : o.sweep_light;
            list.clear();
            std::size_t start = 0;
            while (ok && start <= value.size()) {
                const std::size_t comma = std::min(value.find(',', start), value.size());
                int n = 0;
                ok = parse_int(value.substr(start, comma - start), 1, 1024, n);
                list.push_back(n);
                start = comma + 1;
            }
            if (!ok) {
                std::fprintf(stderr, "error: %s must be a comma-separated list of integers 1 to 1024, not '%s'\n",
                             flag.c_str(), value.c_str());
                return 2;
            }
            continue;
        }
        else ok = parse_int(value, 1, 1000, o.frames);
        if (!ok) {
            std::fprintf(stderr, "error: %s must be an integer (%s), not '%s'\n", flag.c_str(),
                         flag == "--frames" || flag == "--sweep-rounds" ? "1 to 1000" : "16 to 8192", value.c_str());
            return 2;
        }
    }
    if (o.peer_dir.empty()) {
        std::fprintf(stderr, "error: --peer DIR is required (a checkout of fede-vaccaro/TerrainEngine-OpenGL)\n%s", usage);
        return 2;
    }
    if (find_preset(o.preset) == nullptr) {
        std::fprintf(stderr, "error: unknown preset '%s'\n", o.preset.c_str());
        return 2;
    }
    return 0;
}

// The 1-minute load average (/proc/loadavg), negative where there is none: the machine may
// be shared, and llvmpipe's times scale with the cores it gets.
double load_average() {
    double load = -1.0;
    if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf", &load) != 1) load = -1.0;
        std::fclose(f);
    }
    return load;
}

int fail(const std::string& why) {
    std::fprintf(stderr, "error: %s\n", why.c_str());
    return 1;
}

int run(const options& o) {
    const scene sc = *find_preset(o.preset);
    std::string why;

    // The peer's files first: a wrong --peer fails before any slow work.
    const char* shader_files[] = {"volumetric_clouds.comp", "perlinworley.comp", "worley.comp", "weather.comp", "sky.frag", "screen.vert"};
    for (const char* name : shader_files) {
        const std::string path = o.peer_dir + "/shaders/" + name;
        if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
            std::fclose(f);
        } else {
            return fail("cannot read " + path + " (--peer must name a checkout of fede-vaccaro/TerrainEngine-OpenGL)");
        }
    }

    // One context for both: 4.5 core (the peer's compute shaders need 4.3, ours 4.1).
    auto context = cloudmath_egl::headless_context::open(4, 5, cloudmath_egl::platform::any, why);
    if (!context) return fail("no OpenGL 4.5 context: " + why);
    auto ours = gl_renderer::create_for_current_context(&cloudmath_egl::gl_proc, why);
    if (!ours) return fail(why);
    cloud_textures textures;
    const std::string cache = o.cache_dir == "none" ? std::string() : (o.cache_dir.empty() ? default_texture_cache_dir() : o.cache_dir);
    if (!load_or_bake_textures(cache, o.quiet, textures, why) || !ours->upload_textures(textures, why)) return fail(why);
    if (!o.quiet) std::fprintf(stderr, "peer-bench: OpenGL: %s\n", ours->device().c_str());

    const variant defaults;
    const char* const no_light_march_spec = "light=map,behind=map";
    variant octaves;
    const char* octaves_spec = previous_default_spec;
    why = apply_variant_spec(octaves_spec, octaves);
    if (!why.empty()) return fail(why);

    const frame_constants k = make_frame_constants(sc);
    peer_bench::peer_view view;
    view.yaw_deg = sc.yaw;
    view.pitch_deg = sc.pitch;
    view.fov_y_deg = sc.fov_y;
    view.sun_dir = k.sun_dir;
    auto peer = peer_bench::peer_clouds::create(o.peer_dir, &cloudmath_egl::gl_proc, o.quiet, why);
    if (!peer || !peer->prepare(o.width, o.height, view, why)) return fail(why);

    // The rows. Both renderers share the context: the peer leaves image units, a storage
    // buffer and its program bound, and ours binds everything it draws with on each frame.
    image ours_default_img, ours_temporal_img, ours_octaves_img, peer_img;
    // The previous default drew the classic density field (scene.hpp's cloud_shape).
    scene classic = sc;
    classic.shape = cloud_shape::classic;
    const auto full_frame = [&](const scene& s, const variant& v, image& img) {
        return [&ours, &o, sp = &s, vp = &v, ip = &img](double& ms, std::string& w) {
            frame_timing t;
            const bool ok = ours->render(*sp, *vp, o.width, o.height, *ip, &t, w);
            ms = t.wall_ms;
            return ok;
        };
    };
    timed_row peer_row, ours_default, ours_temporal, ours_octaves, ours_no_march;
    image ours_no_march_img;
    // The default with its light taken from the Beer shadow map both ways: no light march at
    // all, so the view march's own cost (a lower bound of the default's frame for any light
    // estimate).
    variant no_light_march = defaults;
    why = apply_variant_spec(no_light_march_spec, no_light_march);
    if (!why.empty()) return fail(why);
    peer_row.frame = [&peer](double& ms, std::string& w) { return peer->dispatch(ms, w); };
    ours_default.frame = full_frame(sc, defaults, ours_default_img);
    ours_octaves.frame = full_frame(classic, octaves, ours_octaves_img);
    ours_no_march.frame = full_frame(sc, no_light_march, ours_no_march_img);
    // Temporal: frames count up from 0; the first 16 fill the history, 16 onward are timed
    // (both passes: the 1-in-16 shading pass and the resolve).
    std::uint32_t temporal_frame = 0;
    ours->reset_temporal();
    ours_temporal.warm_up = 16;
    ours_temporal.frame = [&](double& ms, std::string& w) {
        scene s = sc;
        s.frame = temporal_frame++;
        frame_timing t;
        const bool ok = ours->render_temporal(s, defaults, o.width, o.height, ours_temporal_img, &t, w);
        ms = t.wall_ms;
        return ok;
    };
    const double load_before = load_average();
    if (!o.quiet) std::fprintf(stderr, "peer-bench: timing 5 rows, %d rounds\n", o.frames);
    if (!time_rows({&peer_row, &ours_default, &ours_temporal, &ours_octaves, &ours_no_march}, o.frames, why))
        return fail(why);
    const double load_after = load_average();
    if (!peer->read_image(peer_img, why)) return fail(why);
    if (!o.quiet)
        std::fprintf(stderr, "peer-bench: peer %.1f ms, ours default %.1f ms, temporal %.1f ms, previous default %.1f ms\n",
                     peer_row.median_ms, ours_default.median_ms, ours_temporal.median_ms, ours_octaves.median_ms);

    peer_bench::peer_reads reads;
    if (!peer->count_reads(reads, why)) return fail(why);
    // The counters must not change what the peer draws: the instrumented run's image against
    // the timed one's (same inputs, so same branches, same pixels).
    image counted_img;
    if (!peer->read_image(counted_img, why)) return fail(why);
    const double instrumented_diff = compare(peer_img, counted_img).max_abs;

    // Our reads for reference, from the CPU twin of the same shader at 160 x 90 (as the
    // --bench table of docs/renderer.md counts them).
    const texture_read_stats ours_reads = count_texture_reads(sc, defaults, textures, 160, 90);
    const texture_read_stats octaves_reads = count_texture_reads(classic, octaves, textures, 160, 90);
    cpu_temporal_renderer temporal_counter(160, 90, temporal_max_samples);
    (void)temporal_counter.frame(sc, defaults, textures);
    const texture_read_stats temporal_reads = temporal_counter.last_reads();

    if (!o.images_dir.empty()) {
        const std::pair<const image*, const char*> out[] = {{&peer_img, "peer_clouds.png"},
                                                            {&ours_default_img, "peer_ours_default.png"},
                                                            {&ours_temporal_img, "peer_ours_temporal.png"},
                                                            {&ours_octaves_img, "peer_ours_octaves.png"}};
        for (const auto& [img, name] : out) {
            const std::string path = o.images_dir + "/" + name;
            if (!write_png(path, *img)) return fail("cannot write " + path);
        }
    }
    const image_stats peer_stats = statistics(peer_img);

    std::printf("Device: `%s`. Image %d x %d. Times: host clock from before the draw or dispatch to the end of "
                "glFinish(), median (min-max) of %d frames after warm-up, timed in rounds of one frame per row.",
                ours->device().c_str(), o.width, o.height, o.frames);
    if (load_before >= 0)
        std::printf(" Load average (1 min) before / after timing: %.1f / %.1f on %u cores.", load_before, load_after,
                    std::thread::hardware_concurrency());
    std::printf("\n\n");
    std::printf("View: our preset `%s` (heading %.0f deg, pitch %.0f deg, vertical FOV %.0f deg, sun %.0f deg high at "
                "heading %.0f deg), imposed on both; the peer keeps its own clouds, sky and camera height (800 m).\n\n",
                sc.name.c_str(), double(sc.yaw), double(sc.pitch), double(sc.fov_y), double(sc.sun_elevation),
                double(sc.sun_azimuth));
    std::printf("| Renderer | One frame | ms per frame | against the peer |\n|---|---|---:|---:|\n");
    // The ratio of medians measured in the same interleaved rounds (the number to compare).
    const auto row = [&peer_row](const char* who, const char* what, const timed_row& r) {
        std::printf("| %s | %s | %.1f (%.1f-%.1f) | %.2fx |\n", who, what, r.median_ms, r.min_ms, r.max_ms,
                    r.median_ms / peer_row.median_ms);
    };
    row("peer: TerrainEngine-OpenGL `volumetric_clouds.comp`",
        "one compute dispatch at full resolution (64 view steps, 6-sample light cone; warm-up: 1 dispatch)", peer_row);
    row("ours: default variant", "`gl_renderer::render`, one full frame (warm-up: 1 frame)", ours_default);
    row("ours: temporal scheme", "`render_temporal`, 1 of 16 pixels shaded + reprojection (frames 16 onward)", ours_temporal);
    char octaves_label[160];
    std::snprintf(octaves_label, sizeof octaves_label, "`gl_renderer::render` with `%s`, `--shape classic` (warm-up: 1 frame)", octaves_spec);
    row("ours: previous default", octaves_label, ours_octaves);
    char no_march_label[200];
    std::snprintf(no_march_label, sizeof no_march_label,
                  "`gl_renderer::render` with `%s`: no light march, the view march's own cost (warm-up: 1 frame)",
                  no_light_march_spec);
    row("ours: default, light from the shadow map only", no_march_label, ours_no_march);

    char light_text[320];
    if (reads.light_attributed)
        std::snprintf(light_text, sizeof light_text, "%.0f%% of them in its light function (raymarchToLight)",
                      100.0 * reads.light_share);
    else
        std::snprintf(light_text, sizeof light_text, "the light function's share not counted (%s)", reads.light_note.c_str());
    std::printf("\nTexture reads per pixel (texture() and textureLod() calls), peer: counted on the GPU by an "
                "instrumented copy of its shader at %d x %d, over the %d of %d pixels it marches through its cloud "
                "layer (those that pass its fog test; the others read only the sky): mean %.1f, 95th percentile %.0f, "
                "%s. Over all pixels: mean %.1f.\n",
                o.width, o.height, reads.marched, reads.pixels, reads.mean, reads.p95, light_text, reads.mean_all);
    std::printf("The instrumented copy's image differs from the timed one's by at most %g (colour units).\n",
                instrumented_diff);
    std::printf("Ours, for reference (the CPU twin of our shader at 160 x 90, pixels whose ray enters the layer): "
                "default mean %.0f, p95 %.0f, light %.0f%%; temporal scheme %.1f per pixel per frame; previous default "
                "(classic field) mean %.0f, p95 %.0f, light %.0f%%.\n",
                ours_reads.mean, ours_reads.p95, 100.0 * ours_reads.light_share, temporal_reads.mean, octaves_reads.mean,
                octaves_reads.p95, 100.0 * octaves_reads.light_share);
    std::printf("\nPeer image: mean brightness %.3f, %.0f%% of pixels with cloud opacity above 0.1, %d NaN pixels.\n",
                peer_stats.mean_brightness, 100.0 * peer_stats.cloud_fraction, peer_stats.nan_pixels);

    if (o.sweep) {
        peer_bench::sweep_settings sw;
        sw.width = o.width;
        sw.height = o.height;
        sw.rounds = o.sweep_rounds;
        sw.view_steps = o.sweep_steps;
        sw.light_steps = o.sweep_light;
        sw.images_dir = o.images_dir;
        sw.quiet = o.quiet;
        std::string section;
        if (!peer_bench::quality_sweep(*ours, *peer, sc, sw, section, why)) return fail(why);
        std::printf("\n## Equal quality: each renderer against its own converged image\n\n%s", section.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    options o;
    const int parsed = parse(argc, argv, o);
    if (parsed == 1) return 0;
    if (parsed == 2) return 2;
    return run(o);
}
