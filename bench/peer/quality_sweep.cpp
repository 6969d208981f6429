// The equal-quality sweep (quality_sweep.hpp).
#include "quality_sweep.hpp"

#include "atomic_file.hpp"
#include "image.hpp"
#include "quality_knobs.hpp"
#include "timing.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace peer_bench {

namespace {

using namespace cloud_renderer;

// The converged images. Ours: docs/renderer.md's convergence reference (1024 view steps, none
// refined, 128-step light marches both ways). The
// peer's: its model sampled 8 times more finely both ways, the mean of 4 frames whose start
// offsets are shifted by k / 4 (each pixel's Bayer offset plus that, so 64 offsets per 4 x 4
// block). Each is checked against the same at half its steps and samples.
const char* const our_reference_spec = "steps=1024,refine=1,light=march,light-steps=128,behind=march";
const char* const our_half_spec = "steps=512,light-steps=64";
constexpr int peer_reference_view = 512, peer_reference_light = 48, peer_reference_frames = 4;

// The levels of the equal-quality table (dB).
constexpr double levels[] = {30.0, 35.0, 40.0};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The peer writes display colours that can leave [0, 1] (its contrast tuning); a display
// shows them clamped, as the bench's PNG does.
void clamp_display(image& img) {
    for (glm::vec4& p : img.pixels)
        for (int c = 0; c < 3; ++c) p[c] = std::clamp(std::isfinite(p[c]) ? p[c] : 1.0f, 0.0f, 1.0f);
}

// The mean of `frames` frames of a peer program, start offsets shifted by k / frames.
bool peer_mean(peer_clouds& peer, int program, int frames, image& out, std::string& why) {
    image sum;
    for (int k = 0; k < frames; ++k) {
        double ms = 0;
        image one;
        if (!peer.dispatch_quality(program, float(k) / float(frames), ms, why) || !peer.read_image(one, why)) return false;
        clamp_display(one);
        if (k == 0) sum = one;
        else
            for (std::size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += one.pixels[i];
    }
    for (glm::vec4& p : sum.pixels) p /= float(frames);
    out = sum;
    return true;
}

// One swept setting of one renderer.
struct setting {
    bool peer = false;
    int view_steps = 0, light_steps = 0;
    int program = -1;  // the peer's copy with these knobs
    variant v;         // ours
    timed_row row;
    image img;
    double psnr = 0, psnr_band = 0;
    bool is_default = false;
    std::string label() const { return std::to_string(view_steps) + " / " + std::to_string(light_steps); }
};

std::string db(double x) {
    char text[32];
    if (std::isnan(x)) std::snprintf(text, sizeof text, "-");
    else if (std::isinf(x)) std::snprintf(text, sizeof text, "identical");
    else std::snprintf(text, sizeof text, "%.1f", x);
    return text;
}

// The settings on each renderer's cost-quality front: no other setting is both faster and
// at least as close to its converged image. Sorted by time.
std::vector<const setting*> front(const std::vector<setting>& all, bool peer, bool band) {
    std::vector<const setting*> mine;
    for (const setting& s : all)
        if (s.peer == peer) mine.push_back(&s);
    std::sort(mine.begin(), mine.end(), [](const setting* a, const setting* b) { return a->row.median_ms < b->row.median_ms; });
    std::vector<const setting*> out;
    double best = -std::numeric_limits<double>::infinity();
    for (const setting* s : mine) {
        const double q = band ? s->psnr_band : s->psnr;
        if (q > best) {
            out.push_back(s);
            best = q;
        }
    }
    return out;
}

// The cheapest setting of a renderer at `level` dB or more, nullptr if none reaches it.
const setting* cheapest(const std::vector<setting>& all, bool peer, bool band, double level) {
    const setting* best = nullptr;
    for (const setting& s : all) {
        if (s.peer != peer || (band ? s.psnr_band : s.psnr) < level) continue;
        if (best == nullptr || s.row.median_ms < best->row.median_ms) best = &s;
    }
    return best;
}

// The best PSNR a renderer reached in the sweep, for "reaches at most" when a level is not met.
double best_psnr(const std::vector<setting>& all, bool peer, bool band) {
    double best = -std::numeric_limits<double>::infinity();
    for (const setting& s : all)
        if (s.peer == peer) best = std::max(best, band ? s.psnr_band : s.psnr);
    return best;
}

// Frame time (log scale) against PSNR over the marched pixels: every setting as a point, each
// renderer's front as a line, the three levels as dashed lines.
std::string svg_plot(const std::vector<setting>& all) {
    const double w = 720, h = 420, left = 60, right = 20, top = 30, bottom = 50;
    double t0 = std::numeric_limits<double>::infinity(), t1 = 0, q0 = levels[0], q1 = levels[2];
    for (const setting& s : all) {
        t0 = std::min(t0, s.row.median_ms);
        t1 = std::max(t1, s.row.median_ms);
        if (std::isfinite(s.psnr)) {
            q0 = std::min(q0, s.psnr);
            q1 = std::max(q1, s.psnr);
        }
    }
    const double lt0 = std::floor(std::log10(t0) * 4.0) / 4.0, lt1 = std::ceil(std::log10(t1) * 4.0) / 4.0;
    q0 = std::floor(q0 / 5.0) * 5.0;
    q1 = std::ceil(q1 / 5.0) * 5.0;
    const auto x = [&](double ms) { return left + (std::log10(ms) - lt0) / (lt1 - lt0) * (w - left - right); };
    const auto y = [&](double q) { return top + (q1 - std::clamp(q, q0, q1)) / (q1 - q0) * (h - top - bottom); };
    std::ostringstream svg;
    char line[400];
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
        << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    // Axes, ticks at 1, 2 and 5 times powers of ten, PSNR every 5 dB.
    std::snprintf(line, sizeof line, "<path d=\"M%.1f %.1f V%.1f H%.1f\" stroke=\"black\" fill=\"none\"/>\n", left, top,
                  h - bottom, w - right);
    svg << line;
    for (double decade = std::pow(10.0, std::floor(lt0)); decade <= std::pow(10.0, lt1); decade *= 10.0)
        for (double m : {1.0, 2.0, 5.0}) {
            const double ms = decade * m;
            if (std::log10(ms) < lt0 - 1e-9 || std::log10(ms) > lt1 + 1e-9) continue;
            std::snprintf(line, sizeof line,
                          "<path d=\"M%.1f %.1f V%.1f\" stroke=\"#ddd\"/><text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n",
                          x(ms), top, h - bottom, x(ms), h - bottom + 15, ms);
            svg << line;
        }
    for (double q = q0; q <= q1 + 1e-9; q += 5.0) {
        std::snprintf(line, sizeof line, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", left - 6, y(q) + 4, q);
        svg << line;
    }
    for (double level : levels) {
        std::snprintf(line, sizeof line, "<path d=\"M%.1f %.1f H%.1f\" stroke=\"#999\" stroke-dasharray=\"4 4\"/>\n", left,
                      y(level), w - right);
        svg << line;
    }
    std::snprintf(line, sizeof line,
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">ms per frame (log scale)</text>\n"
                  "<text transform=\"translate(16 %.1f) rotate(-90)\" text-anchor=\"middle\">PSNR against its own converged image (dB)</text>\n",
                  (left + w - right) / 2, h - 12, (top + h - bottom) / 2);
    svg << line;
    const struct {
        bool peer;
        const char* colour;
        const char* name;
    } renderers[] = {{true, "#c0392b", "peer (TerrainEngine-OpenGL)"}, {false, "#2471a3", "ours (default variant)"}};
    double legend_y = top + 12;
    for (const auto& r : renderers) {
        std::string path;
        for (const setting* s : front(all, r.peer, false)) {
            if (!std::isfinite(s->psnr)) continue;
            std::snprintf(line, sizeof line, "%s%.1f %.1f", path.empty() ? "M" : " L", x(s->row.median_ms), y(s->psnr));
            path += line;
        }
        svg << "<path d=\"" << path << "\" stroke=\"" << r.colour << "\" fill=\"none\" stroke-width=\"1.5\"/>\n";
        for (const setting& s : all) {
            if (s.peer != r.peer || !std::isfinite(s.psnr)) continue;
            std::snprintf(line, sizeof line,
                          "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%s\" fill=\"%s\"/><text x=\"%.1f\" y=\"%.1f\" fill=\"%s\" font-size=\"9\">%s</text>\n",
                          x(s.row.median_ms), y(s.psnr), s.is_default ? "5" : "3", r.colour, x(s.row.median_ms) + 5,
                          y(s.psnr) - 4, r.colour, s.label().c_str());
            svg << line;
        }
        std::snprintf(line, sizeof line,
                      "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"/><text x=\"%.1f\" y=\"%.1f\">%s</text>\n",
                      left + 12, legend_y - 4, r.colour, left + 22, legend_y, r.name);
        svg << line;
        legend_y += 16;
    }
    std::snprintf(line, sizeof line,
                  "<text x=\"%.1f\" y=\"%.1f\">labels: view steps / light samples; large dot: the default</text>\n", left + 12,
                  legend_y);
    svg << line << "</svg>\n";
    return svg.str();
}

}  // namespace

bool quality_sweep(gl_renderer& ours, peer_clouds& peer, const scene& scene_in, const sweep_settings& o, std::string& markdown,
                   std::string& why) {
    scene sc = scene_in;  // ours without the dither (a new noise per frame, not the march's error)
    sc.dither = false;
    const auto note = [&](const std::string& text) {
        if (!o.quiet) std::fprintf(stderr, "peer-bench: sweep: %s\n", text.c_str());
    };
    const std::size_t pixels = static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height);

    // The pixels each renderer marches: the peer's are those its fog test lets through (read
    // back from its cloudDistance image), ours every ray above the horizon (from the ground
    // each of them enters the layer). The horizon band: rays within 5 degrees of it.
    const frame_constants k = make_frame_constants(sc);
    std::vector<char> ours_marched(pixels, 0), band(pixels, 0);
    for (int py = 0; py < o.height; ++py)
        for (int px = 0; px < o.width; ++px) {
            const glm::vec3 d = pixel_direction(k, px, py, o.width, o.height);
            const std::size_t i = static_cast<std::size_t>(py) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(px);
            ours_marched[i] = d.y > 0.0f ? 1 : 0;
            band[i] = std::fabs(d.y) <= std::sin(5.0f * 3.14159265f / 180.0f) ? 1 : 0;
        }

    // The peer's knobs at the shipped values must draw the shipped image.
    double shipped_ms = 0;
    image shipped;
    const int knobs_default = peer.add_quality_program(shipped_view_steps, shipped_light_steps, why);
    if (knobs_default < 0 || !peer.dispatch(shipped_ms, why) || !peer.read_image(shipped, why)) return false;
    std::vector<char> peer_marched;
    if (!peer.read_marched(peer_marched, why)) return false;
    image knobs_img;
    if (!peer.dispatch_quality(knobs_default, 0.0f, shipped_ms, why) || !peer.read_image(knobs_img, why)) return false;
    const double knobs_diff = compare(shipped, knobs_img).max_abs;
    if (knobs_diff != 0.0) {
        why = "the peer's copy with explicit knobs at 64 view steps and 6 light samples differs from the shipped shader "
              "by up to " + std::to_string(knobs_diff) + ": quality_knobs.cpp's edits changed its model";
        return false;
    }
    std::vector<char> peer_band(pixels, 0), ours_band(pixels, 0);
    for (std::size_t i = 0; i < pixels; ++i) {
        peer_band[i] = peer_marched[i] && band[i];
        ours_band[i] = ours_marched[i] && band[i];
    }

    // The converged images, and each against the same at half its steps.
    auto t0 = std::chrono::steady_clock::now();
    image peer_reference, peer_half;
    const int peer_ref_program = peer.add_quality_program(peer_reference_view, peer_reference_light, why);
    const int peer_half_program = peer.add_quality_program(peer_reference_view / 2, peer_reference_light / 2, why);
    if (peer_ref_program < 0 || peer_half_program < 0 ||
        !peer_mean(peer, peer_ref_program, peer_reference_frames, peer_reference, why) ||
        !peer_mean(peer, peer_half_program, peer_reference_frames, peer_half, why))
        return false;
    const double peer_reference_s = seconds_since(t0);
    note("the peer's converged image in " + std::to_string(int(peer_reference_s)) + " s");

    const variant base;  // the default
    variant reference_variant = base, half_variant = base;
    why = apply_variant_spec(our_reference_spec, reference_variant);
    if (why.empty()) why = apply_variant_spec(our_reference_spec, half_variant);
    if (why.empty()) why = apply_variant_spec(our_half_spec, half_variant);
    if (!why.empty()) return false;
    t0 = std::chrono::steady_clock::now();
    image ours_reference, ours_half;
    if (!ours.render(sc, reference_variant, o.width, o.height, ours_reference, nullptr, why) ||
        !ours.render(sc, half_variant, o.width, o.height, ours_half, nullptr, why))
        return false;
    const double ours_reference_s = seconds_since(t0);
    note("our converged image in " + std::to_string(int(ours_reference_s)) + " s");

    // The settings, timed in interleaved rounds.
    std::vector<setting> all;
    for (bool is_peer : {true, false})
        for (int vs : o.view_steps)
            for (int ls : o.light_steps) {
                setting s;
                s.peer = is_peer;
                s.view_steps = vs;
                s.light_steps = ls;
                s.is_default = is_peer ? (vs == shipped_view_steps && ls == shipped_light_steps)
                                       : (vs == base.view_steps && ls == base.light_steps);
                if (is_peer) {
                    s.program = vs == shipped_view_steps && ls == shipped_light_steps ? knobs_default
                                                                                      : peer.add_quality_program(vs, ls, why);
                    if (s.program < 0) return false;
                } else {
                    s.v = base;
                    why = apply_variant_spec("steps=" + std::to_string(vs) + ",light-steps=" + std::to_string(ls), s.v);
                    if (!why.empty()) return false;
                }
                all.push_back(std::move(s));
            }
    std::vector<timed_row*> rows;
    for (setting& s : all) {
        if (s.peer)
            s.row.frame = [&peer, p = s.program](double& ms, std::string& w) { return peer.dispatch_quality(p, 0.0f, ms, w); };
        else
            s.row.frame = [&ours, &sc, &o, sp = &s](double& ms, std::string& w) {
                frame_timing t;
                const bool ok = ours.render(sc, sp->v, o.width, o.height, sp->img, &t, w);
                ms = t.wall_ms;
                return ok;
            };
        rows.push_back(&s.row);
    }
    note("timing " + std::to_string(rows.size()) + " settings, " + std::to_string(o.rounds) + " rounds");
    if (!time_rows(rows, o.rounds, why)) return false;
    // Their images: ours from the last timed frame, the peer's drawn once more (its frames
    // are all the same picture: the start offsets do not move).
    for (setting& s : all) {
        if (s.peer) {
            double ms = 0;
            if (!peer.dispatch_quality(s.program, 0.0f, ms, why) || !peer.read_image(s.img, why)) return false;
            clamp_display(s.img);
        }
        const image& reference = s.peer ? peer_reference : ours_reference;
        s.psnr = compare(s.img, reference, s.peer ? peer_marched : ours_marched).psnr_db;
        s.psnr_band = compare(s.img, reference, s.peer ? peer_band : ours_band).psnr_db;
    }
    const setting* peer_default = nullptr;
    const setting* ours_default = nullptr;
    for (const setting& s : all)
        if (s.is_default) (s.peer ? peer_default : ours_default) = &s;
    if (peer_default == nullptr || ours_default == nullptr) {
        why = "the sweep must include both defaults (64 view steps; 6 light samples)";
        return false;
    }

    // How much of each default's error is its jitter's noise, which a temporal filter (ours)
    // or a blur (the peer's post pass) averages away, and how much is bias: the default's
    // mean over 4 frames, the peer's with its offsets shifted by k / 4, ours with its
    // per-frame jitter (frames 0 to 3).
    image peer_averaged, ours_averaged;
    if (!peer_mean(peer, peer_default->program, 4, peer_averaged, why)) return false;
    for (std::uint32_t f = 0; f < 4; ++f) {
        scene sf = sc;
        sf.frame = f;
        image one;
        if (!ours.render(sf, ours_default->v, o.width, o.height, one, nullptr, why)) return false;
        if (f == 0) ours_averaged = one;
        else
            for (std::size_t i = 0; i < pixels; ++i) ours_averaged.pixels[i] += one.pixels[i];
    }
    for (glm::vec4& p : ours_averaged.pixels) p /= 4.0f;

    if (!o.images_dir.empty()) {
        const std::string svg_path = o.images_dir + "/peer_quality.svg";
        std::string error = cloudmath::tools::write_file_atomically(svg_path, svg_plot(all));
        if (!error.empty()) {
            why = error;
            return false;
        }
        const std::pair<const image*, const char*> out[] = {{&peer_reference, "peer_clouds_converged.png"},
                                                            {&ours_reference, "peer_ours_converged.png"}};
        for (const auto& [img, name] : out)
            if (!write_png(o.images_dir + "/" + name, *img, &error)) {
                why = error;
                return false;
            }
    }

    std::ostringstream md;
    char line[640];
    int peer_marched_count = 0, peer_band_count = 0, ours_marched_count = 0, ours_band_count = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        peer_marched_count += peer_marched[i];
        peer_band_count += peer_band[i];
        ours_marched_count += ours_marched[i];
        ours_band_count += ours_band[i];
    }
    std::snprintf(line, sizeof line,
                  "Converged images. Ours: the default without its dither (`--without dither`) and with `%s` (docs/renderer.md's "
                  "convergence reference), %.0f s. The peer's: its shader with %d view steps and %d light samples "
                  "(quality_knobs.cpp), the mean of %d frames with the start offsets shifted by k / %d, %.0f s. Each against "
                  "the same at half the steps and samples (how converged it is): peer %s dB over the pixels it marches, %s dB "
                  "in the horizon band; ours %s dB and %s dB.\n\n",
                  our_reference_spec, ours_reference_s, peer_reference_view, peer_reference_light, peer_reference_frames,
                  peer_reference_frames, peer_reference_s,
                  db(compare(peer_half, peer_reference, peer_marched).psnr_db).c_str(),
                  db(compare(peer_half, peer_reference, peer_band).psnr_db).c_str(),
                  db(compare(ours_half, ours_reference, ours_marched).psnr_db).c_str(),
                  db(compare(ours_half, ours_reference, ours_band).psnr_db).c_str());
    md << line;
    std::snprintf(line, sizeof line,
                  "PSNR over the display images (each renderer's own output in [0, 1]), over the pixels each marches (peer: "
                  "%d, those its fog test keeps; ours: %d, every ray above the horizon) and over those of them in the horizon "
                  "band (rays within 5 degrees of the horizon; peer %d, ours %d pixels). The peer's copy with its shipped "
                  "settings (64 / 6) draws the shipped image exactly (largest difference %g). %d timed rounds, interleaved "
                  "over all %zu settings; the peer's frames are one dispatch, ours one full frame.\n\n",
                  peer_marched_count, ours_marched_count, peer_band_count, ours_band_count, knobs_diff, o.rounds, all.size());
    md << line;

    md << "| Renderer | view steps | light samples | ms per frame | against the peer's default | PSNR, marched pixels (dB) | "
          "PSNR, horizon band (dB) |\n|---|---:|---:|---:|---:|---:|---:|\n";
    for (const setting& s : all) {
        std::snprintf(line, sizeof line, "| %s%s | %d | %d | %.1f (%.1f-%.1f) | %.2fx | %s | %s |\n", s.peer ? "peer" : "ours",
                      s.is_default ? " (default)" : "", s.view_steps, s.light_steps, s.row.median_ms, s.row.min_ms,
                      s.row.max_ms, s.row.median_ms / peer_default->row.median_ms, db(s.psnr).c_str(), db(s.psnr_band).c_str());
        md << line;
    }

    std::snprintf(line, sizeof line,
                  "\nEach default's mean over 4 frames of its jitter (the peer's start offsets shifted by k / 4, ours its "
                  "per-frame jitter; what a temporal filter or the peer's blur pass would approach), against its converged "
                  "image: peer %s dB over its marched pixels, %s dB in the horizon band (one frame: %s and %s); ours %s and "
                  "%s dB (one frame: %s and %s).\n",
                  db(compare(peer_averaged, peer_reference, peer_marched).psnr_db).c_str(),
                  db(compare(peer_averaged, peer_reference, peer_band).psnr_db).c_str(), db(peer_default->psnr).c_str(),
                  db(peer_default->psnr_band).c_str(), db(compare(ours_averaged, ours_reference, ours_marched).psnr_db).c_str(),
                  db(compare(ours_averaged, ours_reference, ours_band).psnr_db).c_str(), db(ours_default->psnr).c_str(),
                  db(ours_default->psnr_band).c_str());
    md << line;

    md << "\nThe frame time each needs for a level: its cheapest swept setting at that PSNR or more (view steps / light "
          "samples), in the same run.\n\n"
          "| Level | over | peer: setting, ms | ours: setting, ms | ours / peer |\n|---|---|---|---|---:|\n";
    for (bool use_band : {false, true})
        for (double level : levels) {
            const setting* p = cheapest(all, true, use_band, level);
            const setting* u = cheapest(all, false, use_band, level);
            const auto cell = [&](const setting* s, bool is_peer) {
                char text[96];
                if (s) std::snprintf(text, sizeof text, "%s, %.1f", s->label().c_str(), s->row.median_ms);
                else std::snprintf(text, sizeof text, "not reached (best %s dB)", db(best_psnr(all, is_peer, use_band)).c_str());
                return std::string(text);
            };
            char ratio[32] = "-";
            if (p && u) std::snprintf(ratio, sizeof ratio, "%.2fx", u->row.median_ms / p->row.median_ms);
            std::snprintf(line, sizeof line, "| %.0f dB | %s | %s | %s | %s |\n", level,
                          use_band ? "horizon band" : "marched pixels", cell(p, true).c_str(), cell(u, false).c_str(), ratio);
            md << line;
        }
    // The reading in one sentence, from the numbers above.
    md << "\nIn one sentence: ";
    for (bool use_band : {false, true}) {
        md << (use_band ? "; in the horizon band " : "at equal quality over the pixels each marches, our frame takes ");
        bool first = true;
        for (double level : {35.0, 40.0}) {
            const setting* p = cheapest(all, true, use_band, level);
            const setting* u = cheapest(all, false, use_band, level);
            char text[160];
            if (p && u) std::snprintf(text, sizeof text, "%.2fx the peer's time at %.0f dB", u->row.median_ms / p->row.median_ms, level);
            else if (u) std::snprintf(text, sizeof text, "%.1f ms at %.0f dB, which the peer does not reach", u->row.median_ms, level);
            else if (p) std::snprintf(text, sizeof text, "no setting at %.0f dB (the peer: %.1f ms)", level, p->row.median_ms);
            else std::snprintf(text, sizeof text, "neither reaches %.0f dB", level);
            md << (first ? "" : " and ") << text;
            first = false;
        }
    }
    md << ".\n";
    markdown = md.str();
    return true;
}

}  // namespace peer_bench
