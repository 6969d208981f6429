// cloudmath_cloud_renderer: a Nubis-style cloudscape drawn with cloudmath's GLSL includes
// (gl_renderer.cpp + shaders/clouds.frag), next to a CPU reference drawn with the C++
// functions (cpu_renderer.cpp). Modes and options: options.cpp (--help).
#include "cpu_renderer.hpp"
#include "gl_renderer.hpp"
#include "image.hpp"
#include "options.hpp"
#include "textures.hpp"
#include "window.hpp"

#include "atomic_file.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

using namespace cloud_renderer;

namespace {

bool load_textures(const options& o, cloud_textures& t) {
    std::string why;
    const std::string dir = o.cache_dir == "none" ? std::string() : (o.cache_dir.empty() ? default_texture_cache_dir() : o.cache_dir);
    if (!load_or_bake_textures(dir, o.quiet, t, why)) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return false;
    }
    return true;
}

std::unique_ptr<gl_renderer> open_gpu(const options& o, const cloud_textures& t) {
    std::string why;
    auto gpu = gl_renderer::create_headless(why);
    if (!gpu) {
        std::fprintf(stderr,
                     "error: cannot render on the GPU: %s.\n"
                     "       The headless mode needs an EGL driver (Debian: libegl-mesa0 and libgl1-mesa-dri for\n"
                     "       Mesa's software renderer); --cpu renders the same image without OpenGL.\n",
                     why.c_str());
        return nullptr;
    }
    if (!o.quiet) std::fprintf(stderr, "OpenGL: %s\n", gpu->device().c_str());
    if (!gpu->upload_textures(t, why)) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return nullptr;
    }
    return gpu;
}

std::string with_suffix(const std::string& path, const char* suffix) {
    const std::size_t dot = path.rfind(".png");
    return dot == std::string::npos ? path + suffix + ".png" : path.substr(0, dot) + suffix + path.substr(dot);
}

// Every output file goes through write_png or write_file_atomically (tools/common): a
// temporary beside the target, checked, renamed; a failure leaves the old file, no
// temporary, a message and exit status 1.
bool save(const image& img, const std::string& path) {
    std::string why;
    if (!write_png(path, img, &why)) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return false;
    }
    std::printf("wrote %s (%d x %d)\n", path.c_str(), img.width, img.height);
    return true;
}

void print_stats(const char* who, const image& img) {
    const image_stats s = statistics(img);
    std::printf("%s: mean brightness %.3f, cloud pixels %.1f%%, NaN pixels %d\n", who, s.mean_brightness,
                100.0 * s.cloud_fraction, s.nan_pixels);
}

// Frame f of the --temporal sequence: the options' scene on frame f, panned and drifted.
scene temporal_scene(const options& o, int f) {
    scene s = o.sc;
    s.frame = static_cast<std::uint32_t>(f);
    s.yaw += o.pan * float(f);
    s.wind.x += o.drift * float(f);
    return s;
}

// The median of a list of frame times (0 for none).
double median_of(std::vector<double> ms) {
    if (ms.empty()) return 0.0;
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

// Frames 0..o.temporal-1 of the temporal scheme by render(scene, image&); the last is left in
// `out`; with --save-every, every Nth frame is also written (a failed write: false, the
// reason in `why`). The median host time of the frames after the first 16 (whose history is
// still filling) goes to *median_ms, the median of their GL timestamp times to *median_gpu_ms.
template <class Render>
bool temporal_frames(const options& o, const char* default_out, Render render, image& out, std::string& why,
                     double* median_ms = nullptr, double* median_gpu_ms = nullptr) {
    std::vector<double> ms, gpu_ms;
    for (int f = 0; f < o.temporal; ++f) {
        frame_timing ft;
        if (!render(temporal_scene(o, f), out, ft)) return false;
        if (f >= std::min(16, o.temporal - 1)) {
            ms.push_back(ft.wall_ms);
            gpu_ms.push_back(ft.gpu_ms);
        }
        if (o.save_every > 0 && (f + 1) % o.save_every == 0) {
            char suffix[32];
            std::snprintf(suffix, sizeof suffix, "_f%03d", f);
            if (!write_png(with_suffix(o.out.empty() ? default_out : o.out, suffix), out, &why)) return false;
        }
    }
    if (median_ms != nullptr) *median_ms = median_of(ms);
    if (median_gpu_ms != nullptr) *median_gpu_ms = median_of(gpu_ms);
    return true;
}

// The average of frames 0..n-1 of a scene, each drawn by render(scene, image&) with its
// own march jitter (scene::frame): the converged image of the temporal jitter, the same on
// the CPU and the GPU. Display colours are averaged (what a history buffer holds).
template <class Render>
bool accumulate_frames(scene s, int n, Render render, image& out) {
    for (int f = 0; f < n; ++f) {
        s.frame = static_cast<std::uint32_t>(f);
        image img;
        if (!render(s, img)) return false;
        if (f == 0) out = img;
        else
            for (std::size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] += img.pixels[i];
    }
    for (glm::vec4& p : out.pixels) p /= float(n);
    return true;
}

// The options' image: averaged over o.accumulate frames, or the last of o.temporal frames of
// the temporal scheme, on the CPU and on the GPU. False (with the reason in `why`) only when
// a --save-every frame cannot be written.
bool render_cpu_frames(const options& o, const cloud_textures& t, image& out, std::string& why,
                       texture_read_stats* temporal_reads = nullptr) {
    if (o.temporal > 0) {
        cpu_temporal_renderer r(o.width, o.height, temporal_max_samples);
        const bool ok = temporal_frames(o, "clouds_cpu.png", [&](const scene& s, image& img, frame_timing&) {
            img = r.frame(s, o.var, t);
            return true;
        }, out, why);
        if (temporal_reads != nullptr) *temporal_reads = r.last_reads();
        return ok;
    }
    return accumulate_frames(o.sc, o.accumulate, [&](const scene& s, image& img) {
        img = render_cpu(s, o.var, t, o.width, o.height);
        return true;
    }, out);
}
bool render_gpu_frames(gl_renderer& gpu, const options& o, image& out, std::string& why, double* temporal_ms = nullptr,
                       double* temporal_gpu_ms = nullptr) {
    if (o.temporal > 0) {
        gpu.reset_temporal();
        return temporal_frames(o, "clouds.png", [&](const scene& s, image& img, frame_timing& ft) {
            return gpu.render_temporal(s, o.var, o.width, o.height, img, &ft, why);
        }, out, why, temporal_ms, temporal_gpu_ms);
    }
    return accumulate_frames(o.sc, o.accumulate, [&](const scene& s, image& img) {
        return gpu.render(s, o.var, o.width, o.height, img, nullptr, why);
    }, out);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run_headless(const options& o) {
    cloud_textures t;
    if (!load_textures(o, t)) return 1;
    auto gpu = open_gpu(o, t);
    if (!gpu) return 1;
    image img;
    std::string why;
    frame_timing first, ft;
    // Twice: drivers compile the shader for the GPU at the first draw (Mesa's llvmpipe JIT
    // takes seconds), so the second draw is the frame time.
    double temporal_ms = 0.0, temporal_gpu_ms = 0.0;
    bool ok = true;
    if (o.accumulate > 1 && o.temporal == 0) {
        // The accumulated frames are the timed ones: the first (with the compilation), and
        // the median of the others.
        std::vector<double> wall, gl;
        ok = accumulate_frames(o.sc, o.accumulate, [&](const scene& s, image& frame) {
            frame_timing timing;
            const bool drawn = gpu->render(s, o.var, o.width, o.height, frame, &timing, why);
            if (s.frame == 0) {
                first = timing;
            } else {
                wall.push_back(timing.wall_ms);
                gl.push_back(timing.gpu_ms);
            }
            return drawn;
        }, img);
        ft = frame_timing{median_of(gl), median_of(wall)};
    } else {
        ok = gpu->render(o.sc, o.var, o.width, o.height, img, &first, why) &&
             gpu->render(o.sc, o.var, o.width, o.height, img, &ft, why) &&
             (o.temporal == 0 || render_gpu_frames(*gpu, o, img, why, &temporal_ms, &temporal_gpu_ms));
    }
    if (!ok) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return 1;
    }
    std::printf("GPU: preset %s, %d x %d, %s: %.1f ms per frame (host clock to glFinish; GL timestamps %.1f ms); "
                "first draw %.0f ms (with any shader compilation the driver defers to it)\n",
                o.sc.name.c_str(), o.width, o.height, variant_spec(o.var).c_str(), ft.wall_ms, ft.gpu_ms, first.wall_ms);
    if (o.temporal > 0) {
        std::printf("GPU temporal: %d frames, %.1f ms per frame (median after the first 16; every pass; GL timestamps "
                    "%.1f ms)\n", o.temporal, temporal_ms, temporal_gpu_ms);
        // Where the time goes: 9 more frames (the camera held at the last one's), each pass
        // ended by glFinish and timed apart; the medians. Not in the frame times above.
        std::vector<double> passes[5];
        image spare;
        for (int f = 0; f < 9; ++f) {
            scene s = temporal_scene(o, o.temporal - 1);
            s.frame = static_cast<std::uint32_t>(o.temporal + f);
            frame_timing split;
            split.split_passes = true;
            if (!gpu->render_temporal(s, o.var, o.width, o.height, spare, &split, why)) {
                std::fprintf(stderr, "error: %s\n", why.c_str());
                return 1;
            }
            const double ms[5] = {split.shadow_ms, split.shading_ms, split.background_ms, split.resolve_ms, split.composite_ms};
            for (int i = 0; i < 5; ++i) passes[i].push_back(ms[i]);
        }
        std::printf("GPU temporal passes (each ended by glFinish, medians of 9 frames): shadow-map slice %.1f ms, "
                    "shading %.1f ms, background %.1f ms, resolve %.1f ms, composite %.1f ms\n",
                    median_of(passes[0]), median_of(passes[1]), median_of(passes[2]), median_of(passes[3]), median_of(passes[4]));
    }
    print_stats("GPU image", img);
    return save(img, o.out.empty() ? "clouds.png" : o.out) ? 0 : 1;
}

int run_cpu(const options& o) {
    cloud_textures t;
    if (!load_textures(o, t)) return 1;
    const auto t0 = std::chrono::steady_clock::now();
    texture_read_stats reads;
    image img;
    std::string why;
    if (!render_cpu_frames(o, t, img, why, &reads)) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return 1;
    }
    std::printf("CPU: preset %s, %d x %d, %s: %.2f s\n", o.sc.name.c_str(), o.width, o.height, variant_spec(o.var).c_str(),
                seconds_since(t0));
    print_stats("CPU image", img);
    if (o.temporal > 0) {
        // What the scheme gives up (or gains) against paying for every pixel: the same frame
        // drawn in full, and the texture reads of the last frame against a full frame's.
        const scene last = temporal_scene(o, o.temporal - 1);
        const image full = render_cpu(last, o.var, t, o.width, o.height);
        const texture_read_stats full_reads = count_texture_reads(last, o.var, t, o.width, o.height);
        std::printf("temporal: %d frames; last frame against its full render: PSNR %.2f dB; texture reads per in-layer "
                    "pixel %.1f (full frame %.1f, %.1fx fewer)\n",
                    o.temporal, compare(img, full).psnr_db, reads.mean, full_reads.mean,
                    reads.mean > 0.0 ? full_reads.mean / reads.mean : 0.0);
    }
    return save(img, o.out.empty() ? "clouds_cpu.png" : o.out) ? 0 : 1;
}

int run_compare(const options& o) {
    cloud_textures t;
    if (!load_textures(o, t)) return 1;
    auto gpu = open_gpu(o, t);
    if (!gpu) return 1;
    image g;
    std::string why;
    frame_timing ft;
    if (!gpu->render(o.sc, o.var, o.width, o.height, g, &ft, why) ||
        ((o.accumulate > 1 || o.temporal > 0) && !render_gpu_frames(*gpu, o, g, why))) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return 1;
    }
    const auto t0 = std::chrono::steady_clock::now();
    image c;
    if (!render_cpu_frames(o, t, c, why)) {
        std::fprintf(stderr, "error: %s\n", why.c_str());
        return 1;
    }
    const double cpu_s = seconds_since(t0);
    const image_difference d = compare(g, c);
    std::printf("preset %s, %d x %d, %s: GPU %.1f ms, CPU %.2f s\n", o.sc.name.c_str(), o.width, o.height,
                variant_spec(o.var).c_str(), ft.wall_ms, cpu_s);
    print_stats("GPU image", g);
    print_stats("CPU image", c);
    std::printf("GPU vs CPU: PSNR %.2f dB, max difference %.4f, RMS %.5f\n", d.psnr_db, d.max_abs, d.rms);
    const std::string out = o.out.empty() ? "clouds.png" : o.out;
    if (!save(g, out) || !save(c, with_suffix(out, "_cpu"))) return 1;
    if (o.min_psnr > 0 && !(d.psnr_db >= o.min_psnr)) {
        std::fprintf(stderr, "error: PSNR %.2f dB is below --min-psnr %.2f\n", d.psnr_db, o.min_psnr);
        return 1;
    }
    return 0;
}

// The variants of --bench: each is the default with one change; the first is the reference
// that the PSNR column is measured against (many steps, full light march, Mie phase).
struct bench_row {
    const char* label;
    const char* spec;
    bool temporal = false;  // the temporal scheme: frames 0..15 fill the history, then the timed ones
    bool classic = false;   // on the classic density field (scene.hpp's cloud_shape), as the previous default drew
    bool no_shadows = false;  // without the clouds' shadows on the ground (scene::shadows): no shadow-map pass
};
const std::vector<bench_row>& bench_rows() {
    static const std::vector<bench_row> rows = {
        {"reference: 256 steps, light march 32 steps both ways, Mie phase", "steps=256,light=march,light-steps=32,behind=march,phase=mie"},
        {"default: diffusion model, 64 steps refined where opaque, 6-step marches both ways (quadratic, jittered), dual-lobe HG", ""},
        {"temporal scheme: the default on 1 of 16 pixels per frame, resolved from the reprojected history", "", true},
        {"phase: HG", "phase=hg"},
        {"phase: Cornette-Shanks", "phase=cs"},
        {"phase: Mie fit", "phase=mie"},
        {"the previous default: octaves (3, powder, cone 6 samples), flat sky light, classic field", previous_default_spec, false, true},
        {"octaves: 3, powder, cone 6 samples, flat sky light", "lighting=octaves,powder=on,light=cone,ambient=flat"},
        {"octaves: 1, powder, cone", "lighting=octaves,powder=on,light=cone,ambient=flat,octaves=1"},
        {"octaves: 2, powder, cone", "lighting=octaves,powder=on,light=cone,ambient=flat,octaves=2"},
        {"octaves: 8, powder, cone", "lighting=octaves,powder=on,light=cone,ambient=flat,octaves=8"},
        {"sky light not occluded", "ambient=flat"},
        {"octaves: 3, no powder, cone", "lighting=octaves,light=cone"},
        {"octaves: 3, powder, light march 6 steps", "lighting=octaves,powder=on"},
        {"diffusion model, cone both ways", "light=cone,behind=cone"},
        {"diffusion model, cone behind", "behind=cone"},
        {"diffusion model, light from the shadow map both ways (no light march)", "light=map,behind=map"},
        {"the light march stretched to the band's end (no far steps)", "reach=band"},
        {"no refinement of opaque view steps", "refine=1"},
        {"light march: 3 steps", "light-steps=3"},
        {"light march: 12 steps", "light-steps=12"},
        {"naive (Riemann) integration", "integration=naive"},
        {"view steps: 32", "steps=32"},
        {"view steps: 128", "steps=128"},
        {"view steps growing with distance", "schedule=growing"},
        {"no cloud shadows (no shadow-map pass)", "", false, false, true},
    };
    return rows;
}

int run_bench(const options& o) {
    cloud_textures t;
    if (!load_textures(o, t)) return 1;
    auto gpu = open_gpu(o, t);
    if (!gpu) return 1;
    std::ostringstream table;
    table << "Preset `" << o.sc.name << "`, " << o.width << " x " << o.height << ", " << gpu->device() << ". Times: medians of "
          << o.frames << " frames after one warm-up frame; host: from the draw call to the end of glFinish(); GL: GPU "
          << "timestamps around the draw (Mesa's llvmpipe stamps them when the draw is queued, so only the host column "
          << "means anything there). Every row's frame is all its passes (the shadow map where it has one, the background, the clouds, the composite). "
          << "Temporal rows: frames 16 onward, after 16 frames that fill the "
          << "history; their image is the last frame's. Rows are timed one after another: on a shared machine the "
          << "load moves them by 5-20% between runs, so a row can come out slower than one that does more. "
          << "PSNR: against the first row. Texture reads: the shader's texture() calls per "
          << "pixel whose ray enters the layer, counted on its CPU twin (the same program) at 160 x 90: mean, 95th "
          << "percentile and the light's share (toward the sun, and away from it for the diffusion model).\n\n"
          << "| Variant | --variant | ms per frame (host) | ms per frame (GL timestamps) | PSNR against the reference (dB) "
          << "| texture reads per pixel: mean / p95 / light |\n"
          << "|---|---|---:|---:|---:|---:|\n";
    image reference;
    for (std::size_t r = 0; r < bench_rows().size(); ++r) {
        const bench_row& row = bench_rows()[r];
        variant v = o.var;
        std::string why = apply_variant_spec(row.spec, v);
        image img;
        std::vector<double> wall, gl;
        const int warm_up = row.temporal ? 16 : 1;  // the temporal history fills in 16 frames
        if (row.temporal) gpu->reset_temporal();
        scene row_scene = o.sc;
        if (row.classic) row_scene.shape = cloud_shape::classic;
        if (row.no_shadows) row_scene.shadows = false;
        for (int f = 0; f < warm_up + o.frames && why.empty(); ++f) {
            frame_timing ft;
            scene s = row_scene;
            s.frame = static_cast<std::uint32_t>(f);
            if (!(row.temporal ? gpu->render_temporal(s, v, o.width, o.height, img, &ft, why)
                               : gpu->render(row_scene, v, o.width, o.height, img, &ft, why)))
                break;
            if (f >= warm_up) {
                wall.push_back(ft.wall_ms);
                gl.push_back(ft.gpu_ms);
            }
        }
        if (!why.empty()) {
            std::fprintf(stderr, "error: variant '%s': %s\n", row.spec, why.c_str());
            return 1;
        }
        const double median = median_of(wall), median_gl = median_of(gl);
        if (r == 0) reference = img;
        const double psnr = compare(img, reference).psnr_db;
        char psnr_text[32];
        if (r == 0) std::snprintf(psnr_text, sizeof psnr_text, "reference");
        else if (std::isinf(psnr)) std::snprintf(psnr_text, sizeof psnr_text, "identical");
        else std::snprintf(psnr_text, sizeof psnr_text, "%.1f", psnr);
        texture_read_stats reads;
        if (row.temporal) {
            cpu_temporal_renderer counter(160, 90, temporal_max_samples);
            (void)counter.frame(row_scene, v, t);
            reads = counter.last_reads();
        } else {
            reads = count_texture_reads(row_scene, v, t, 160, 90);
        }
        char line[640];
        char p95_text[32];
        if (row.temporal) std::snprintf(p95_text, sizeof p95_text, "-");  // 15 of 16 pixels read nothing
        else std::snprintf(p95_text, sizeof p95_text, "%.0f", reads.p95);
        std::snprintf(line, sizeof line, "| %s | `%s`%s%s%s | %.1f | %.1f | %s | %.0f / %s / %.0f%% |\n", row.label,
                      *row.spec ? row.spec : "(default)", row.no_shadows ? " `--without shadows`" : "", row.temporal ? " `--temporal`" : "", row.classic ? " `--shape classic`" : "", median, median_gl,
                      psnr_text, reads.mean, p95_text, 100.0 * reads.light_share);
        table << line;
        if (!o.quiet) std::fprintf(stderr, "bench: %s: %.1f ms\n", row.label, median);
    }
    {
        // The shadow map's pass: a fixed cost per frame, outside the per-pixel figures.
        const texture_read_stats d = count_texture_reads(o.sc, o.var, t, 16, 9);
        char note[320];
        std::snprintf(note, sizeof note,
                      "\nThe Beer shadow map's pass (%d^2 texels, %d steps each; every variant with shadows or a map light "
                      "estimate) makes %ld texture reads per frame whatever the image size: %.1f per pixel at %d x %d, "
                      "%.2f at 1920 x 1080.\n",
                      shadow_map_size, shadow_map_steps, d.shadow_map, double(d.shadow_map) / (double(o.width) * double(o.height)),
                      o.width, o.height, double(d.shadow_map) / (1920.0 * 1080.0));
        table << note;
    }
    std::printf("%s", table.str().c_str());
    if (!o.bench_out.empty()) {
        const std::string why = cloudmath::tools::write_file_atomically(o.bench_out, table.str());
        if (!why.empty()) {
            std::fprintf(stderr, "error: %s\n", why.c_str());
            return 1;
        }
        std::printf("wrote %s\n", o.bench_out.c_str());
    }
    return 0;
}

// --convergence: for every preset, the variant (and the same with one setting changed per
// row) against a converged render of the same lighting model: 1024 view steps (none
// refined) and 128-step light marches toward the sun and behind the sample. CPU renders (the
// GPU image's twin), PSNR over the display image and over the horizon band (pixels whose ray
// is within 5 degrees of the horizon), and the texture reads.
int run_convergence(const options& o) {
    cloud_textures t;
    if (!load_textures(o, t)) return 1;
    const variant base = o.var;
    const char* const reference_spec = "steps=1024,refine=1,light=march,light-steps=128,behind=march";
    // The variant, then one change each: the other step schedule, 4x the view steps, and
    // converged light (which error dominates: the view march's or the light estimate's).
    const std::pair<std::string, std::string> rows[] = {
        {"the variant", ""},
        {"the variant, temporal scheme: frame 127 of a still camera", "temporal"},
        {"the other step schedule", o.var.schedule == step_schedule::uniform ? "schedule=growing" : "schedule=uniform"},
        {"4x the view steps", "steps=" + std::to_string(std::min(1024, 4 * o.var.view_steps))},
        {"no refinement of opaque view steps", "refine=1"},
        {"the cone behind the sample", "behind=cone"},
        {"the light march stretched to the band's end", "reach=band"},
        {"light marches of 128 steps both ways", "light=march,light-steps=128,behind=march"}};
    std::ostringstream table;
    table << "| Preset | Variant | PSNR, image (dB) | PSNR, horizon band (dB) | frame to frame, horizon band (dB) | "
             "texture reads per pixel per frame |\n"
          << "|---|---|---:|---:|---:|---:|\n";
    const auto t0 = std::chrono::steady_clock::now();
    for (const scene& preset : presets()) {
        if (o.preset_given && preset.name != o.sc.name) continue;  // --preset: that one alone
        scene s = preset;
        s.dither = false;  // its new noise each frame would floor the frame-to-frame column
        variant reference_variant = base;
        (void)apply_variant_spec(reference_spec, reference_variant);
        const image reference = render_cpu(s, reference_variant, t, o.width, o.height);
        // The horizon band: |elevation| <= 5 degrees (the camera has no roll).
        const frame_constants k = make_frame_constants(s);
        std::vector<char> band(reference.pixels.size(), 0);
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                const glm::vec3 d = pixel_direction(k, x, y, o.width, o.height);
                band[static_cast<std::size_t>(y) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(x)] =
                    std::fabs(d.y) <= std::sin(5.0f * 3.14159265f / 180.0f) ? 1 : 0;
            }
        for (const auto& [label, row_spec] : rows) {
            variant v = base;
            const bool temporal = row_spec == "temporal";
            const std::string why = temporal ? std::string() : apply_variant_spec(row_spec, v);
            if (!why.empty()) {
                std::fprintf(stderr, "error: %s\n", why.c_str());
                return 1;
            }
            image img, next;  // frames f and f + 1: their difference is the flicker a still camera sees
            texture_read_stats reads;
            if (temporal) {
                // 128 frames: every pixel shaded 8 times (8 jitter offsets), the running mean's cap.
                cpu_temporal_renderer r(o.width, o.height, temporal_max_samples);
                for (std::uint32_t f = 0; f <= 128; ++f) {
                    scene sf = s;
                    sf.frame = f;
                    (f == 128 ? next : img) = r.frame(sf, v, t);
                    if (f == 127) reads = r.last_reads();
                }
            } else {
                img = render_cpu(s, v, t, o.width, o.height);
                scene s1 = s;
                s1.frame = 1;
                next = render_cpu(s1, v, t, o.width, o.height);
                reads = count_texture_reads(s, v, t, o.width, o.height);
            }
            const double whole = compare(img, reference).psnr_db, horizon = compare(img, reference, band).psnr_db;
            const double flicker = compare(img, next, band).psnr_db;
            char line[512];
            const auto db = [](double x) {
                char text[32];
                if (std::isnan(x)) std::snprintf(text, sizeof text, "-");
                else if (std::isinf(x)) std::snprintf(text, sizeof text, "identical");
                else std::snprintf(text, sizeof text, "%.1f", x);
                return std::string(text);
            };
            const bool plain = row_spec.empty() || temporal;
            std::snprintf(line, sizeof line, "| %s | %s%s%s%s | %.1f | %s | %s | %.0f |\n", s.name.c_str(), label.c_str(),
                          plain ? "" : " (`", plain ? "" : row_spec.c_str(), plain ? "" : "`)", whole, db(horizon).c_str(),
                          db(flicker).c_str(), reads.mean);
            table << line;
        }
        if (!o.quiet) std::fprintf(stderr, "convergence: %s (%.0f s)\n", s.name.c_str(), seconds_since(t0));
    }
    std::printf("Variant: `%s`, without the dither. Reference: the same with `%s`. %d x %d, CPU renderer (the GPU image's twin); "
                "horizon band: pixels whose ray is within 5 degrees of the horizon; frame to frame: PSNR between two "
                "consecutive frames of a still camera in the horizon band (their jitter differs: the flicker; the "
                "temporal scheme: frames 127 and 128); texture reads: per frame, per pixel whose ray enters the cloud "
                "layer (the temporal scheme shades 1 of 16 pixels per frame).\n\n%s",
                variant_spec(base).c_str(), reference_spec, o.width, o.height, table.str().c_str());
    return 0;
}

// The files a mode will write, checked before any work (a missing or unwritable directory
// fails at once, not after minutes of rendering); the writes themselves are checked again.
std::vector<std::string> output_files(const options& o) {
    switch (o.mode) {
    case run_mode::headless: return {o.out.empty() ? "clouds.png" : o.out};
    case run_mode::cpu: return {o.out.empty() ? "clouds_cpu.png" : o.out};
    case run_mode::compare: {
        const std::string out = o.out.empty() ? "clouds.png" : o.out;
        return {out, with_suffix(out, "_cpu")};
    }
    case run_mode::bench:
        if (o.bench_out.empty()) return {};
        return {o.bench_out};
    default: return {};
    }
}

// --print-sky: the frame constants that describe the sky and the sun (make_frame_constants),
// as JSON with 9 significant digits: what the web demo's physical sky (web/demo/physical_sky.js)
// is checked against.
std::string sky_json(const scene& sc) {
    const frame_constants f = make_frame_constants(sc);
    std::string out = "{\"preset\": \"" + sc.name + "\", \"sky\": \"" + name(sc.sky) + "\"";
    const auto number = [](double x) {
        char b[32];
        std::snprintf(b, sizeof b, "%.9g", x);
        return std::string(b);
    };
    const auto vec = [&](const glm::vec3& v) { return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]"; };
    const auto field = [&](const char* key, const std::string& value) { out += std::string(", \"") + key + "\": " + value; };
    field("sun_radiance", vec(f.sun_radiance));
    std::string heights = "[";
    for (std::size_t i = 0; i < std::size(f.sun_by_height); ++i) heights += (i ? ", " : "") + vec(f.sun_by_height[i]);
    field("sun_by_height", heights + "]");
    field("sky_zenith", vec(f.sky_zenith));
    field("sky_horizon", vec(f.sky_horizon));
    field("ground", vec(f.ground));
    field("ambient_top", vec(f.ambient_top));
    field("ambient_bottom", vec(f.ambient_bottom));
    field("ev100", number(double(f.ev100)));
    field("exposure", number(double(f.exposure)));
    return out + "}\n";
}
}  // namespace

int main(int argc, char** argv) {
    options o;
    const std::string error = parse_options(argc, argv, o);
    if (!error.empty()) {
        std::fprintf(stderr, "cloudmath_cloud_renderer: %s\n", error.c_str());
        return 2;
    }
    for (const std::string& path : output_files(o))
        if (const std::string why = cloudmath::tools::check_output_path(path); !why.empty()) {
            std::fprintf(stderr, "error: %s\n", why.c_str());
            return 1;
        }
    switch (o.mode) {
    case run_mode::help: std::printf("%s", usage_text()); return 0;
    case run_mode::list_presets:
        for (const scene& s : presets())
            std::printf("%-11s %s (camera %g m, pitch %g, sun elevation %g, coverage %g, type %g)\n", s.name.c_str(),
                        s.description.c_str(), double(s.camera_altitude), double(s.pitch), double(s.sun_elevation),
                        double(s.coverage), double(s.cloud_type));
        return 0;
    case run_mode::dump_shader:
        std::printf("%s", o.pass == composite_pass_option ? composite_shader_source(o.sc).c_str()
                                                          : fragment_shader_source(o.var, o.sc, static_cast<clouds_pass>(o.pass)).c_str());
        return 0;
    case run_mode::print_sky: std::printf("%s", sky_json(o.sc).c_str()); return 0;
    case run_mode::headless: return run_headless(o);
    case run_mode::cpu: return run_cpu(o);
    case run_mode::compare: return run_compare(o);
    case run_mode::bench: return run_bench(o);
    case run_mode::convergence: return run_convergence(o);
    case run_mode::window: break;
    }
    cloud_textures t;
    if (!load_textures(o, t)) return 1;
    return run_window(o, t);
}
