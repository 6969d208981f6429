// tools/reference/truths/volume_truth_main.cpp: cloudmath_volume_truth, ground truth for whole
// cloud images. `render` path-traces a preset of the example renderer with the volume
// tracer (volume_tracer.hpp, cloud_medium.hpp: the scene definition) into a CSV of linear
// radiance and standard error per pixel; `report` renders the renderer's CPU reference
// (render_cpu_linear) for each lighting variant at the same size and writes
// docs/lighting_truth.md with the errors and side-by-side PNGs; `fit-clouds` fits the
// diffusion model's table to the truths (docs/data/diffusion_clouds.txt, read into
// diffusion_models::clouds by cloudmath_lighting_error fit-diffusion).
//
//   cloudmath_volume_truth render --preset ground --width 160 --height 90 --spp 64
//       --out docs/data/truth_ground.csv.gz
//   cloudmath_volume_truth report --presets ground,inside --variant default=
//       --variant march=light=march,light-steps=64                          (one line each)
//
// Exit status: 0 success, 2 bad command line (one-line message on stderr), 1 failure (a
// missing or malformed truth file, textures that cannot be baked, an unwritable output; the
// message names the path). Progress on stderr. Same seed -> same numbers, whatever
// --threads is.
//
// Truth CSV: "# key: value" metadata lines (preset, width, height, spp, seed, phase,
// albedo, threads, seconds), the header r,g,b,se_r,se_g,se_b, then one row per pixel,
// x fastest, y = 0 the BOTTOM row (cloud_renderer::image's order; files with the header
// x,y,r,g,b,se_r,se_g,se_b name each row's pixel and are still read); r, g, b the linear
// radiance in the renderer's units (those of sun_radiance), se_* their standard errors.
// Stored gzip-compressed (truth_NAME.csv.gz, gzip_text.hpp); zcat shows the text.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "atomic_file.hpp"
#include "cli_main.hpp"
#include "cloud_medium.hpp"
#include "cpu_renderer.hpp"
#include "gzip_text.hpp"
#include "lighting_diffusion.hpp"
#include "image.hpp"
#include "phase_table.hpp"
#include "strict_number.hpp"
#include "truth_checkpoint.hpp"

namespace mc = cloudmath::reference::mc;
namespace vt = cloudmath::reference::volume;
namespace cr = cloud_renderer;

namespace {

const char* const usage_text =
    "usage: cloudmath_volume_truth <command> [--flag value ...]\n"
    "\n"
    "Ground truth for the example cloud renderer's presets: a double-precision volumetric\n"
    "path tracer (delta tracking, every order of scattering, sun by next-event estimation,\n"
    "the renderer's sky and ground for escaping paths) over the renderer's own density field.\n"
    "\n"
    "commands:\n"
    "  render   path-trace one preset; CSV of linear rgb radiance and standard error per pixel\n"
    "           flags: --preset NAME --out F.csv|F.csv.gz (.gz: gzip-compressed, as stored)\n"
    "                  [--width 160] [--height 90] [--spp 64]\n"
    "                  [--seed 1] [--phase SPEC] [--threads 0] [--cache DIR] [--shape classic]\n"
    "                  [--sky physical|artistic] (default: physical, every preset's; stored in the file,\n"
    "                  report and fit-clouds render the model under it)\n"
    "                  [--quiet] [--noise-target F [--pilot-spp 64] [--min-spp 32] [--max-spp N]]\n"
    "           --noise-target: adaptive sampling instead of --spp: a pilot run measures each\n"
    "           pixel's variance and cost, then a second run (independent streams, unbiased per\n"
    "           pixel) gives each pixel the paths that reach this noise floor (the rms of the\n"
    "           per-pixel standard errors over the image mean, e.g. 0.03; planned for 85% of\n"
    "           it) at the least cost; a plan that misses it is extended (at most 3 times).\n"
    "           [--checkpoint F] (default OUT.checkpoint) [--resume] [--budget-minutes N]\n"
    "           The render keeps its state in the checkpoint (written every 2 minutes and when\n"
    "           it stops; removed once the truth file is written): --budget-minutes stops it\n"
    "           cleanly after N minutes (exit 3, the checkpoint kept), --resume continues a\n"
    "           checkpoint with the same flags (another preset, sky, size, seed, sampling or a\n"
    "           changed scene is refused), giving the numbers of an uninterrupted render to\n"
    "           the bit. Without --resume an existing checkpoint is refused, never overwritten.\n"
    "           [--light all|sun|sky] (with the physical sky: the sun alone or the sky alone, the\n"
    "           truth's split by source; the file says which, and report renders the model so)\n"
    "           [--orders N] (a diagnosis: light scattered at most N times; the file says so,\n"
    "           report names it and fit-clouds refuses the file)\n"
    "           --phase: a montecarlo phase spec (hg:G, dual_hg:G0,G1,W, cs:G, mie_approx:D,\n"
    "           table:PATH, ...); default the renderer's dual_hg:0.8,-0.25,0.2.\n"
    "  report   the renderer (render_cpu_linear) for each variant against the truth files\n"
    "           flags: [--presets ground,horizon,inside,above] [--selection PRESETS]\n"
    "                  [--variant NAME=SPEC ...] [--data docs/data] [--docs docs]\n"
    "                  [--threads 0] [--cache DIR] [--shape classic] [--frames 8] [--quiet]\n"
    "           --frames: the model's image is the mean of its first N frames (each pixel's\n"
    "           march jitters advance: a still camera's converged image, the temporal scheme's\n"
    "           8 samples), so the renderer's per-frame noise is not counted as model error.\n"
    "           --presets: the evaluation split; --selection: the presets the variants were\n"
    "           chosen on (reported first and marked; the two lists must be disjoint).\n"
    "           --variant: repeatable, SPEC as the renderer's --variant (empty = default);\n"
    "           without any: default=, octaves=lighting=octaves,powder=on,light=cone,ambient=flat,\n"
    "           single=lighting=octaves,octaves=1,light=cone,ambient=flat, mie=phase=mie.\n"
    "           Reads DATA/truth_NAME.csv.gz (or .csv), writes DOCS/lighting_truth.md and\n"
    "           DOCS/images/truth_NAME.png (truth | first variant | difference);\n"
    "           --variant-images: also truth_NAME_VARIANT.png for the other variants\n"
    "           (not stored in the repository: their tables say the numbers).\n"
    "  fit-clouds  the diffusion model's table and peak weights (diffusion_lighting.hpp) by least\n"
    "           squares of the renderer (render_cpu_linear) against stored truths, the ridge\n"
    "           toward diffusion_models::fitted chosen by leave-one-preset-out; prints the fit\n"
    "           flags: [--fit SHAPE:PRESET,...] (default: the selection presets of both fields)\n"
    "                  [--eval SHAPE:PRESET,...] (measured after the fit, disjoint from --fit)\n"
    "                  [--ridge 1e-4,...,1] [--variant SPEC] [--data docs/data] [--out F.txt]\n"
    "                  [--frames 8] (the features of the mean of N frames, as report)\n"
    "                  [--check F.txt] (exit 1 unless F's numbers are this fit's to 1e-4)\n"
    "                  [--sky] (a diagnosis: also fits scales of the sky light's top and bottom,\n"
    "                  printed, not stored) [--threads 0] [--cache DIR] [--quiet]\n"
    "           SHAPE:PRESET reads DATA/truth_PRESET.csv.gz (classic) or DATA/detailed/...\n"
    "  status   where each preset's truth stands (scripts/truth.sh --pending): one line a preset,\n"
    "           PRESET done|checkpoint|stale|short|missing and why\n"
    "           flags: --presets P1,P2 --noise-target F [--data docs/data] [--shape classic]\n"
    "                  [--sky S] [--light L] [--cache DIR]\n"
    "  --shape: the renderer's density field, classic (default: the stored truth's) or\n"
    "           detailed; report refuses truth files traced over the other field.\n"
    "  --cache: the renderer's texture cache (default $XDG_CACHE_HOME/cloudmath or\n"
    "           ~/.cache/cloudmath; 'none' bakes without a cache). --threads 0: all cores.\n";

using cloudmath::reference::usage_error;
using cloudmath::reference::split_list;

using cloudmath::reference::flags;

cr::cloud_textures load_textures(const flags& f, bool quiet) {
    const std::string cache = f.get("--cache", "");
    const std::string dir = cache == "none" ? std::string() : (cache.empty() ? cr::default_texture_cache_dir() : cache);
    cr::cloud_textures t;
    std::string why;
    if (!cr::load_or_bake_textures(dir, quiet, t, why)) throw std::runtime_error(why);
    return t;
}

// The preset with the density field `shape` (--shape: classic unless asked, the field the
// stored docs/data/truth_*.csv.gz were traced over), drawn as the truth is: no air between the
// camera and the clouds, no sun disc, no cloud shadows on its ground (cloud_medium.cpp).
cr::scene preset(const std::string& name, cr::cloud_shape shape = cr::cloud_shape::classic) {
    const cr::scene* s = cr::find_preset(name);
    if (s == nullptr) {
        std::string known;
        for (const cr::scene& p : cr::presets()) known += (known.empty() ? "" : ", ") + p.name;
        throw usage_error("unknown preset '" + name + "' (" + known + ")");
    }
    cr::scene out = *s;
    out.shape = shape;
    out.haze = false;
    out.sun_disc = false;
    out.shadows = false;
    return out;
}

// --sky: the preset's own sky (the physical one) unless asked.
cr::scene with_sky(cr::scene s, const std::string& value) {
    if (value.empty()) return s;
    const std::optional<cr::sky_model> m = cr::sky_model_named(value);
    if (!m) throw usage_error("--sky must be artistic or physical, not '" + value + "'");
    s.sky = *m;
    return s;
}

// --light: all unless asked; sun or sky (the truth's split by source) with the physical sky only.
cr::scene with_light(cr::scene s, const std::string& value) {
    if (value.empty()) return s;
    const std::optional<cr::light_sources> l = cr::light_sources_named(value);
    if (!l) throw usage_error("--light must be all, sun or sky, not '" + value + "'");
    if (*l != cr::light_sources::all && s.sky != cr::sky_model::physical)
        throw usage_error("--light " + value + " needs the physical sky (--sky physical)");
    s.light = *l;
    return s;
}

cr::cloud_shape shape_flag(const std::string& value) {
    if (value == "classic") return cr::cloud_shape::classic;
    if (value == "detailed") return cr::cloud_shape::detailed;
    throw usage_error("--shape must be classic or detailed, not '" + value + "'");
}

std::string fixed(double v, int digits) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}
std::string fixed_1(double v) { return fixed(v, 1); }

// ---------------------------------------------------------------------------------------
// The truth image: linear radiance and standard error per pixel (row 0 at the bottom).
struct truth_image {
    std::map<std::string, std::string> meta;
    int width = 0, height = 0;
    std::vector<vt::rgb> radiance, std_error;
};

// The rows' header. The pixel is the row's place (x fastest, y = 0 the bottom row): the x, y
// columns of the first files (legacy_header, still read) were a sixth of the stored bytes
// after gzip (issue 39), and a row out of place could only be an error.
constexpr const char* compact_header = "r,g,b,se_r,se_g,se_b";
constexpr const char* legacy_header = "x,y,r,g,b,se_r,se_g,se_b";

std::string format_csv(const truth_image& t, const std::vector<std::string>& meta_order) {
    std::ostringstream o;
    o << "# cloudmath volume truth (tools/reference/truths/volume_truth_main.cpp): linear radiance of a cloud_renderer preset\n";
    for (const std::string& k : meta_order) o << "# " << k << ": " << t.meta.at(k) << '\n';
    o << "# rows: one a pixel, x fastest, y = 0 the bottom row; r, g, b linear radiance (units of sun_radiance), se_* standard errors\n";
    o << compact_header << '\n';
    char line[256];
    for (std::size_t i = 0; i < t.radiance.size(); ++i) {
        const vt::rgb& L = t.radiance[i];
        const vt::rgb& e = t.std_error[i];
        std::snprintf(line, sizeof line, "%.6g,%.6g,%.6g,%.4g,%.4g,%.4g\n", L.r, L.g, L.b, e.r, e.g, e.b);
        o << line;
    }
    return o.str();
}

// The stored truths are gzip-compressed CSV (DIR/truth_NAME.csv.gz; gzip_text.hpp: the same
// bytes of text at a third of the size, issue 39). A plain DIR/truth_NAME.csv, which render
// writes unless --out ends in .gz, is read where no .gz is beside it.
std::string truth_file(const std::string& dir, const std::string& name) {
    const std::string gz = dir + "/truth_" + name + ".csv.gz", plain = dir + "/truth_" + name + ".csv";
    std::error_code ec;
    if (std::filesystem::exists(gz, ec) || !std::filesystem::exists(plain, ec)) return gz;
    return plain;
}

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

truth_image read_truth(const std::string& path) {
    if (!std::ifstream(path)) throw std::runtime_error("cannot read the truth file " + path + " (run: cloudmath_volume_truth render)");
    std::istringstream in(cloudmath::tools::read_data_file(path));
    truth_image t;
    std::string line;
    int line_no = 0;
    bool header = false, compact = false;
    std::size_t next = 0;    // compact rows: the pixel of the next row
    std::vector<bool> seen;  // pixels read so far
    const auto fail = [&](const std::string& why) {
        throw std::runtime_error(path + ":" + std::to_string(line_no) + ": " + why);
    };
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        if (line[0] == '#') {
            const auto kv = cloudmath::reference::parse_metadata_line(line);
            if (!kv.second.empty()) t.meta[kv.first] = kv.second;
            continue;
        }
        if (!header) {
            if (line != compact_header && line != legacy_header)
                fail(std::string("expected the header ") + compact_header + " (or " + legacy_header + ")");
            header = true;
            compact = line == compact_header;
            const auto size = [&](const char* key) {
                const auto it = t.meta.find(key);
                const std::optional<int> v =
                    it == t.meta.end() ? std::nullopt : cloudmath::tools::parse_integer<int>(it->second);
                if (!v) fail("width and height metadata missing or malformed");
                if (*v < 1 || *v > 4096) fail("bad image size");
                return *v;
            };
            t.width = size("width");
            t.height = size("height");
            t.radiance.assign(static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height), {});
            t.std_error = t.radiance;
            seen.assign(t.radiance.size(), false);
            continue;
        }
        // Six cells (eight with the legacy x, y), each the whole number (strict_number.hpp):
        // sscanf took trailing junk and nan.
        std::vector<std::string> cells;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
        const std::size_t want = compact ? 6 : 8, first = compact ? 0 : 2;
        if (cells.size() != want || line.back() == ',')
            fail("malformed row: expected " + std::to_string(want) + " comma-separated cells");
        std::size_t i = 0;
        if (compact) {
            if (next >= seen.size()) fail("more rows than the " + std::to_string(seen.size()) + " pixels of the image");
            i = next++;
        } else {
            const std::optional<int> px = cloudmath::tools::parse_integer<int>(cells[0]);
            const std::optional<int> py = cloudmath::tools::parse_integer<int>(cells[1]);
            if (!px || !py || *px < 0 || *py < 0 || *px >= t.width || *py >= t.height)
                fail("malformed row: pixel '" + cells[0] + "," + cells[1] + "' is not in the image");
            i = static_cast<std::size_t>(*py) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(*px);
        }
        double v[6];
        for (std::size_t c = 0; c < 6; ++c) {
            const std::optional<double> value = cloudmath::tools::parse_finite(cells[c + first]);
            if (!value) fail("malformed row: '" + cells[c + first] + "' is not a finite number");
            v[c] = *value;
        }
        // Compact rows cannot repeat a pixel (each takes the next); named rows can.
        if (!compact && seen[i]) fail("pixel " + cells[0] + "," + cells[1] + " appears twice");
        seen[i] = true;
        t.radiance[i] = {v[0], v[1], v[2]};
        t.std_error[i] = {v[3], v[4], v[5]};
    }
    if (!header) fail("no data");
    // Every pixel once: a truncated file (a render cut short, a partial copy) read 44 of 14400
    // pixels, the rest stayed 0, and the report said rms 175070%.
    const std::size_t read = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), true));
    if (read != seen.size()) {
        const std::size_t missing = static_cast<std::size_t>(std::find(seen.begin(), seen.end(), false) - seen.begin());
        throw std::runtime_error(path + ": " + std::to_string(read) + " of " + std::to_string(seen.size()) +
                                 " pixels (" + std::to_string(t.width) + " x " + std::to_string(t.height) +
                                 "); the first missing is " + std::to_string(missing % std::size_t(t.width)) + "," +
                                 std::to_string(missing / std::size_t(t.width)) + " (truncated file?)");
    }
    return t;
}

// ---------------------------------------------------------------------------------------
// Adaptive sampling for a noise floor (vt::allocate_paths): a pilot of pilot_spp paths per
// pixel gives each pixel's variance per path (r + g + b) and cost per path; the variance is
// smoothed upward over the 3 x 3 neighbourhood (at least half its mean there), so that a
// pixel whose pilot happened to miss its rare bright paths still gets a share from its
// neighbours; the counts then aim at 85% of the noise floor `target` (the rms of the per-pixel
// standard errors over the image mean, the report's definition, with the pilot's mean): 64
// pilot paths underestimate the rare bright paths, and without the margin the floor reached
// was 1.10 and 1.11 times the plan's (cumulus, low_sun_ahead). A plan that still misses is
// extended from the same pilot (truth_checkpoint.hpp).
// The estimate is a second run on streams independent of the pilot's (unbiased per pixel).
vt::truth_checkpoint adaptive_plan(const vt::path_tracer& tracer, const std::vector<vt::camera_ray>& rays, int width,
                                   int height, double target, std::uint64_t pilot_spp, std::uint64_t min_spp,
                                   std::uint64_t max_spp, const mc::run_options& options, bool quiet,
                                   const std::string& name, std::map<std::string, std::string> identity) {
    mc::run_options pilot_options = options;
    pilot_options.progress = nullptr;
    const auto start = std::chrono::steady_clock::now();
    const vt::pilot_estimate pilot = vt::estimate_radiance_pilot(tracer, rays, pilot_spp, pilot_options);
    const double pilot_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t n = rays.size();
    std::vector<double> variance(n);
    double sum = 0.0, pilot_cost = 0.0;
    const auto np = static_cast<double>(pilot_spp);
    for (std::size_t i = 0; i < n; ++i) {
        const vt::rgb_estimate& e = pilot.radiance[i];
        variance[i] = np * (e.r.std_error * e.r.std_error + e.g.std_error * e.g.std_error + e.b.std_error * e.b.std_error);
        sum += e.r.mean + e.g.mean + e.b.mean;
        pilot_cost += np * pilot.cost_per_path[i];
    }
    std::vector<double> smoothed(n);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double around = 0.0;
            int count = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
                    around += variance[static_cast<std::size_t>(yy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(xx)];
                    ++count;
                }
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            smoothed[i] = std::max(variance[i], 0.5 * around / count);
        }
    const double mean = sum / (3.0 * static_cast<double>(n));
    if (!(mean > 0.0)) throw std::runtime_error("render " + name + ": the pilot's image is black, no noise floor to aim at");
    constexpr double margin = 0.85;
    vt::truth_checkpoint plan = vt::adaptive_plan(std::move(identity), std::move(smoothed), pilot.cost_per_path, mean,
                                                  target, margin, min_spp, max_spp);
    plan.seconds = pilot_seconds;
    plan.pilot_note = "pilot " + std::to_string(pilot_spp) + " spp, " + fixed_1(pilot_seconds) + " s, not averaged in";
    if (!quiet) {
        std::uint64_t most = 0, cost = 0;
        for (std::size_t i = 0; i < n; ++i) {
            most = std::max(most, plan.planned[i]);
            cost += static_cast<std::uint64_t>(static_cast<double>(plan.planned[i]) * pilot.cost_per_path[i]);
        }
        std::cerr << "render " << name << ": pilot " << pilot_spp << " spp in " << fixed_1(pilot_seconds) << " s; "
                  << (plan.planned_paths() + n / 2) / n << " spp on average (" << min_spp << " to " << most
                  << "), about " << fixed_1(pilot_seconds * static_cast<double>(cost) / pilot_cost) << " s\n";
    }
    return plan;
}

// The allocation line of a finished truth file.
std::string allocation_note(const vt::truth_checkpoint& c) {
    if (c.noise_target <= 0.0) return "uniform";
    std::uint64_t most = 0;
    for (const std::uint64_t k : c.planned) most = std::max(most, k);
    std::string note = "adaptive for a noise floor of " + fixed_1(100.0 * c.noise_target) + "% (" + c.pilot_note + "; " +
                       std::to_string(c.min_paths) + " to " + std::to_string(most) + " paths per pixel";
    if (c.extensions > 0) note += "; plan extended " + std::to_string(c.extensions) + "x for the target";
    return note + ")";
}

// The run's identity in a checkpoint and its truth file: a resume must match it. orders: the
// --orders limit, 0 for every order (then no "orders" entry, as in checkpoints made before it).
std::map<std::string, std::string> run_identity(const cr::scene& s, int width, int height, const mc::run_options& options,
                                                const std::string& phase, const std::string& sampling,
                                                const std::string& scene_fingerprint, unsigned orders) {
    std::map<std::string, std::string> identity = {{"preset", s.name},
            {"shape", cr::name(s.shape)},
            {"sky", cr::name(s.sky)},
            {"light", cr::name(s.light)},
            {"width", std::to_string(width)},
            {"height", std::to_string(height)},
            {"seed", std::to_string(options.seed)},
            {"phase", phase},
            {"albedo", std::to_string(s.albedo)},
            {"sampling", sampling},
            {"scene", scene_fingerprint}};
    if (orders > 0) identity.emplace("orders", std::to_string(orders));
    return identity;
}

// Exit status of a render stopped by its time budget, its checkpoint kept (scripts/truth.sh).
constexpr int exit_budget_spent = 3;

int run_render(int argc, char** argv) {
    const flags f(argc, argv,
                  {"--preset", "--out", "--width", "--height", "--spp", "--seed", "--phase", "--threads", "--cache", "--shape",
                   "--sky", "--light", "--noise-target", "--pilot-spp", "--min-spp", "--max-spp", "--checkpoint",
                   "--budget-minutes", "--orders"},
                  {"--quiet", "--resume"});
    if (!f.has("--preset")) throw usage_error("render needs --preset NAME");
    if (!f.has("--out")) throw usage_error("render needs --out FILE.csv");
    const std::string out = f.get("--out", "");
    const std::string checkpoint = f.get("--checkpoint", out + ".checkpoint");
    // Checked before hours of tracing; written atomically at the end.
    for (const std::string& path : {out, checkpoint})
        if (const std::string error = cloudmath::tools::check_output_path(path); !error.empty())
            throw std::runtime_error(error);
    const cr::scene s = with_light(with_sky(preset(f.get("--preset", ""), shape_flag(f.get("--shape", "classic"))), f.get("--sky", "")),
                                   f.get("--light", ""));
    const int width = static_cast<int>(f.integer("--width", 160, 1, 4096));
    const int height = static_cast<int>(f.integer("--height", 90, 1, 4096));
    const auto spp = static_cast<std::uint64_t>(f.integer("--spp", 64, 1, 1 << 24));
    // Adaptive sampling (--noise-target): a pilot, then per-pixel path counts for the target.
    std::optional<double> noise_target;
    if (f.has("--noise-target")) {
        if (f.has("--spp")) throw usage_error("--spp and --noise-target exclude each other (the target sets the paths)");
        noise_target = cloudmath::tools::parse_finite(f.get("--noise-target", ""));
        if (!noise_target || !(*noise_target > 0.0 && *noise_target < 1.0))
            throw usage_error("--noise-target must be a fraction of the image mean in (0, 1), not '" +
                              f.get("--noise-target", "") + "'");
    } else if (f.has("--pilot-spp") || f.has("--min-spp") || f.has("--max-spp")) {
        throw usage_error("--pilot-spp, --min-spp and --max-spp need --noise-target");
    }
    const auto pilot_spp = static_cast<std::uint64_t>(f.integer("--pilot-spp", 64, 2, 1 << 20));
    const auto min_spp = static_cast<std::uint64_t>(f.integer("--min-spp", 32, 2, 1 << 24));
    const auto max_spp = static_cast<std::uint64_t>(f.integer("--max-spp", 1 << 20, 2, 1 << 24));
    if (min_spp > max_spp) throw usage_error("--min-spp must not exceed --max-spp");
    // --budget-minutes: stop cleanly (checkpoint written, exit 3) once this much time is spent
    // (a positive number; fractions for tests).
    double budget_minutes = 0.0;
    if (f.has("--budget-minutes")) {
        const std::optional<double> m = cloudmath::tools::parse_finite(f.get("--budget-minutes", ""));
        if (!m || !(*m > 0.0) || *m > 1e6)
            throw usage_error("--budget-minutes must be a positive number of minutes, not '" + f.get("--budget-minutes", "") + "'");
        budget_minutes = *m;
    }
    // --orders N: light scattered at most N times (a diagnosis: --orders 1 with --light sun is
    // the single scattering the model's direct term stands for); 0, the default, every order.
    const auto orders = static_cast<unsigned>(f.integer("--orders", 0, 0, 1 << 20));
    mc::run_options options;
    options.seed = static_cast<std::uint64_t>(f.integer("--seed", 1, 0, 1LL << 62));
    options.threads = static_cast<unsigned>(f.integer("--threads", 0, 0, 1024));
    const bool quiet = f.has("--quiet"), resume = f.has("--resume");
    const std::string phase_spec = f.get("--phase", vt::renderer_phase_spec(s));
    const mc::phase_model phase = mc::make_phase(phase_spec);  // invalid_argument: exit 2
    const bool existing = static_cast<bool>(std::ifstream(checkpoint));
    if (!resume && existing)
        throw std::runtime_error(checkpoint + ": a checkpoint of an unfinished render is there: --resume continues it, "
                                              "or delete it to start over");
    if (resume && !existing) throw std::runtime_error(checkpoint + ": no checkpoint to resume");

    const auto start = std::chrono::steady_clock::now();
    const cr::cloud_textures textures = load_textures(f, quiet);
    const vt::cloud_medium medium(s, textures);
    const vt::lighting light = vt::make_cloud_lighting(s);
    const vt::path_tracer tracer(medium, phase, s.albedo, light, orders);
    const std::vector<vt::camera_ray> rays = vt::make_camera_rays(s, width, height);
    const std::string sampling =
        noise_target ? "adaptive " + std::to_string(*noise_target) + " pilot " + std::to_string(pilot_spp) + " paths " +
                           std::to_string(min_spp) + "-" + std::to_string(max_spp)
                     : "uniform " + std::to_string(spp);
    const std::map<std::string, std::string> identity =
        run_identity(s, width, height, options, phase.spec(), sampling, vt::scene_fingerprint(medium, light, rays), orders);

    vt::truth_checkpoint c;
    if (resume) {
        c = vt::read_checkpoint(checkpoint);
        c.identity.emplace("light", "all");  // checkpoints from before the split by source
        vt::check_same_run(c, identity, checkpoint);
        if (!quiet)
            std::cerr << "render " << s.name << ": resuming " << checkpoint << ", " << c.traced_paths() << " of "
                      << c.planned_paths() << " planned paths traced in " << fixed_1(c.seconds) << " s over " << c.runs
                      << " runs\n";
    } else {
        c = noise_target ? adaptive_plan(tracer, rays, width, height, *noise_target, pilot_spp, min_spp, max_spp, options,
                                         quiet, s.name, identity)
                         : vt::uniform_plan(identity, rays.size(), spp);
        vt::write_checkpoint(checkpoint, c);
    }
    ++c.runs;
    const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double, std::ratio<60>>(budget_minutes));
    const std::uint64_t planned_at_start = c.planned_paths(), traced_at_start = c.traced_paths();
    int shown = -1;
    const auto stop = [&]() {
        if (!quiet && c.planned_paths() > traced_at_start) {
            const double done = static_cast<double>(c.traced_paths() - traced_at_start) /
                                static_cast<double>(c.planned_paths() - traced_at_start);
            const int percent = static_cast<int>(done * 100.0) / 10 * 10;
            if (percent > shown) std::cerr << "render " << s.name << ": " << percent << "%\n";
            shown = std::max(shown, percent);
        }
        return budget_minutes > 0.0 && std::chrono::steady_clock::now() >= deadline;
    };
    // Batches of about 10 s, so the budget is kept to within about that; the checkpoint is
    // written every 2 minutes, so a killed run loses at most that.
    const unsigned threads = options.threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : options.threads;
    const bool done = vt::continue_trace(c, tracer, rays, options, 4 * std::size_t(threads), 10.0, 120.0, stop,
                                         [&](const vt::truth_checkpoint& k) { vt::write_checkpoint(checkpoint, k); });
    if (!done) {
        std::cout << "render " << s.name << ": stopped by the budget of " << budget_minutes << " minutes, "
                  << c.traced_paths() << " of " << c.planned_paths() << " planned paths traced ("
                  << fixed_1(100.0 * static_cast<double>(c.traced_paths()) / static_cast<double>(c.planned_paths()))
                  << "%, " << fixed_1(c.seconds) << " s over " << c.runs << (c.runs == 1 ? " run" : " runs")
                  << "); continue with --resume from "
                  << checkpoint << '\n';
        return exit_budget_spent;
    }
    if (!quiet && c.planned_paths() != planned_at_start)
        std::cerr << "render " << s.name << ": the plan was extended for the noise target (" << c.extensions << "x)\n";

    const std::vector<vt::rgb_estimate> L = vt::estimates(c);
    truth_image t;
    t.width = width;
    t.height = height;
    for (const vt::rgb_estimate& e : L) {
        t.radiance.push_back({e.r.mean, e.g.mean, e.b.mean});
        t.std_error.push_back({e.r.std_error, e.g.std_error, e.b.std_error});
    }
    const std::uint64_t total_paths = c.traced_paths();
    t.meta = {{"preset", s.name},
              {"description", s.description},
              {"shape", cr::name(s.shape)},
              {"sky", cr::name(s.sky)},
              {"light", cr::name(s.light)},
              {"width", std::to_string(width)},
              {"height", std::to_string(height)},
              {"spp", std::to_string((total_paths + rays.size() / 2) / rays.size())},
              {"allocation", allocation_note(c)},
              {"noise floor", fixed(100.0 * vt::noise_floor(L), 2) + "%"},
              {"seed", std::to_string(options.seed)},
              {"phase", phase.spec()},
              {"albedo", std::to_string(s.albedo)},
              {"scene", identity.at("scene")},
              {"threads", std::to_string(threads)},
              {"runs", std::to_string(c.runs)},
              {"seconds", fixed_1(c.seconds)}};
    std::vector<std::string> meta_order = {"preset", "description", "shape", "sky", "light", "width", "height", "spp", "allocation",
                                           "noise floor", "seed", "phase", "albedo", "scene", "threads", "runs", "seconds"};
    if (orders > 0) {
        t.meta.emplace("orders", std::to_string(orders));
        meta_order.insert(std::find(meta_order.begin(), meta_order.end(), "light") + 1, "orders");  // the light's limit
    }
    if (ends_with(out, ".gz")) {
        const std::string why = cloudmath::tools::write_file_atomically(out, cloudmath::tools::gzip_compress(format_csv(t, meta_order)));
        if (!why.empty()) throw std::runtime_error(why);
    } else {
        cloudmath::reference::write_text_file_atomically(out, format_csv(t, meta_order));
    }
    std::remove(checkpoint.c_str());
    std::cout << "render " << s.name << ": " << width << "x" << height << ", " << t.meta.at("spp") << " spp ("
              << t.meta.at("allocation") << "), noise floor " << t.meta.at("noise floor") << ", " << t.meta.at("seconds")
              << " s over " << c.runs << (c.runs == 1 ? " run" : " runs") << " on " << threads << " threads -> " << out
              << '\n';
    return 0;
}

// The noise floor a stored truth was traced for: its allocation line's "adaptive for a noise
// floor of X%" (none for a uniform allocation).
std::optional<double> noise_target_of(const truth_image& t) {
    const auto it = t.meta.find("allocation");
    const std::string lead = "adaptive for a noise floor of ";
    if (it == t.meta.end() || it->second.rfind(lead, 0) != 0) return std::nullopt;
    const std::string rest = it->second.substr(lead.size());
    const std::optional<double> v = cloudmath::tools::parse_finite(rest.substr(0, rest.find('%')));
    if (!v || !(*v > 0.0 && *v < 100.0)) return std::nullopt;
    return *v / 100.0;
}

// A noise floor short of its target as the report shows them (to 0.1%): a floor of 3.04%
// meets a target of 3%.
bool misses_target(double floor, double target) { return std::round(1000.0 * floor) > std::round(1000.0 * target); }

// The sky a stored truth was traced under: its "sky" line, or for files from before the line
// the artistic sky (render wrote the line from the physical sky's first truth on, and the
// presets' default was the artistic sky until after every file without it was traced).
cr::sky_model traced_sky(const truth_image& t, const std::string& path) {
    const auto it = t.meta.find("sky");
    if (it == t.meta.end()) return cr::sky_model::artistic;
    const std::optional<cr::sky_model> m = cr::sky_model_named(it->second);
    if (!m) throw std::runtime_error(path + ": unknown sky '" + it->second + "' (artistic or physical)");
    return *m;
}

// The light a stored truth was traced with: its "light" line, or all for files from before it.
cr::light_sources traced_light(const truth_image& t, const std::string& path) {
    const auto it = t.meta.find("light");
    if (it == t.meta.end()) return cr::light_sources::all;
    const std::optional<cr::light_sources> l = cr::light_sources_named(it->second);
    if (!l) throw std::runtime_error(path + ": unknown light '" + it->second + "' (all, sun or sky)");
    return *l;
}

// ---------------------------------------------------------------------------------------
// Errors of a model image against the truth (linear rgb, every channel).
struct image_errors {
    double truth_mean = 0, rms = 0, bias = 0, psnr_db = 0, noise_floor = 0;
    // The model's error with the truth's noise taken out in quadrature: sqrt(rms^2 - noise^2)
    // (0 when the rms is within the noise). The truth's noise is independent of the model's
    // error, so rms^2 = excess^2 + noise^2 in expectation.
    double excess = 0;
    int worst_col = 0, worst_row = 0;  // 4 x 4 blocks, from the top left
    double worst_rms = 0, worst_bias = 0;
};

constexpr int blocks = 4;

glm::vec3 display(const vt::rgb& c, float exposure) {
    return cr::tonemap(glm::vec3(static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)), exposure);
}

image_errors compare(const truth_image& t, const cr::image& model, float exposure) {
    image_errors e;
    const std::size_t n = t.radiance.size();
    double sum_t = 0, sum_m = 0, sq = 0, se_sq = 0, tm_sq = 0;
    std::vector<double> block_sq(blocks * blocks, 0.0), block_diff(blocks * blocks, 0.0), block_n(blocks * blocks, 0.0);
    for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(x);
            const vt::rgb& a = t.radiance[i];
            const glm::vec4& m = model.pixels[i];
            const double d[3] = {m.r - a.r, m.g - a.g, m.b - a.b};
            sum_t += a.r + a.g + a.b;
            sum_m += double(m.r) + m.g + m.b;
            const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            sq += dd;
            se_sq += t.std_error[i].r * t.std_error[i].r + t.std_error[i].g * t.std_error[i].g + t.std_error[i].b * t.std_error[i].b;
            const glm::vec3 dt = display(a, exposure) - cr::tonemap(glm::vec3(m), exposure);
            tm_sq += double(glm::dot(dt, dt));
            const int bx = x * blocks / t.width, by = (t.height - 1 - y) * blocks / t.height;  // from the top
            const std::size_t b = static_cast<std::size_t>(by * blocks + bx);
            block_sq[b] += dd;
            block_diff[b] += d[0] + d[1] + d[2];
            block_n[b] += 3.0;
        }
    const double count = 3.0 * static_cast<double>(n);
    e.truth_mean = sum_t / count;
    e.rms = std::sqrt(sq / count) / e.truth_mean;
    e.bias = (sum_m - sum_t) / count / e.truth_mean;
    e.noise_floor = std::sqrt(se_sq / count) / e.truth_mean;
    e.excess = std::sqrt(std::max(0.0, e.rms * e.rms - e.noise_floor * e.noise_floor));
    e.psnr_db = tm_sq > 0 ? 10.0 * std::log10(count / tm_sq) : INFINITY;
    for (int b = 0; b < blocks * blocks; ++b) {
        const auto ub = static_cast<std::size_t>(b);
        if (block_n[ub] == 0) continue;
        const double r = std::sqrt(block_sq[ub] / block_n[ub]) / e.truth_mean;
        if (r >= e.worst_rms) {
            e.worst_rms = r;
            e.worst_bias = block_diff[ub] / block_n[ub] / e.truth_mean;
            e.worst_col = b % blocks;
            e.worst_row = b / blocks;
        }
    }
    return e;
}

// truth | model | difference, 2-pixel gaps; difference = 0.5 + 2 (model - truth) of the
// display images, per channel.
void write_side_by_side(const std::string& path, const truth_image& t, const cr::image& model, float exposure) {
    const int gap = 2;
    cr::image img;
    img.width = 3 * t.width + 2 * gap;
    img.height = t.height;
    img.pixels.assign(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height), glm::vec4(1.0f));
    for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(x);
            const glm::vec3 a = display(t.radiance[i], exposure);
            const glm::vec3 m = cr::tonemap(glm::vec3(model.pixels[i]), exposure);
            img.at(x, y) = glm::vec4(a, 1.0f);
            img.at(t.width + gap + x, y) = glm::vec4(m, 1.0f);
            img.at(2 * (t.width + gap) + x, y) = glm::vec4(glm::clamp(0.5f + 2.0f * (m - a), 0.0f, 1.0f), 1.0f);
        }
    std::string why;  // write_png writes atomically (a temporary beside path, renamed)
    if (!cr::write_png(path, img, &why)) throw std::runtime_error(why);
}

std::string percent(double v) { return fixed(100.0 * v, 1) + "%"; }
std::string signed_percent(double v) { return (v >= 0 ? "+" : "") + fixed(100.0 * v, 1) + "%"; }

// The renderer's image as a still camera converges to it: the mean of `frames` frames
// (frame 0, 1, ...: each pixel's march and light jitters advance, as the temporal scheme's 8
// samples of a still camera do), with the variant's table or `model`.
cr::image render_mean(const cr::scene& s, const cr::variant& v, const cr::cloud_textures& textures, int width, int height,
                      int frames, unsigned threads, const cloudmath::diffusion_model* model = nullptr) {
    cr::image sum;
    for (int fr = 0; fr < frames; ++fr) {
        cr::scene sf = s;
        sf.frame = s.frame + static_cast<std::uint32_t>(fr);
        const cr::image one = model != nullptr ? cr::render_cpu_linear_with(sf, v, textures, width, height, *model, threads)
                                               : cr::render_cpu_linear(sf, v, textures, width, height, threads);
        if (fr == 0) {
            sum = one;
            continue;
        }
        for (std::size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += one.pixels[i];
    }
    for (glm::vec4& px : sum.pixels) px /= float(frames);
    return sum;
}

int run_report(int argc, char** argv) {
    const flags f(argc, argv, {"--presets", "--selection", "--variant", "--data", "--docs", "--threads", "--cache", "--shape", "--frames"},
                  {"--quiet", "--variant-images"});
    // One image a preset unless asked: the other variants' images were most of the
    // repository's weight (issue 39) and their tables carry the numbers.
    const bool variant_images = f.has("--variant-images");
    const int frames = static_cast<int>(f.integer("--frames", 8, 1, 1024));
    const cr::cloud_shape shape = shape_flag(f.get("--shape", "classic"));
    const std::vector<std::string> evaluation = split_list(f.get("--presets", "ground,horizon,inside,above"));
    const std::vector<std::string> selection = split_list(f.get("--selection", ""));
    if (evaluation.empty()) throw usage_error("--presets lists no preset");
    std::vector<std::string> names = selection;
    for (const std::string& n : evaluation) {
        if (std::find(selection.begin(), selection.end(), n) != selection.end())
            throw usage_error("preset '" + n + "' is in both --selection and --presets: the splits must be disjoint");
        names.push_back(n);
    }
    for (const std::string& n : names) (void)preset(n);
    std::vector<std::string> specs;
    for (auto [it, end] = f.values.equal_range("--variant"); it != end; ++it) specs.push_back(it->second);
    if (specs.empty())
        specs = {"default=", std::string("octaves=") + cr::previous_default_spec, "single=lighting=octaves,octaves=1,light=cone,ambient=flat",
                 "mie=phase=mie"};
    std::vector<std::pair<std::string, cr::variant>> variants;
    for (const std::string& spec : specs) {
        const std::size_t eq = spec.find('=');
        if (eq == std::string::npos || eq == 0) throw usage_error("--variant must be NAME=SPEC, not '" + spec + "'");
        cr::variant v;
        const std::string why = cr::apply_variant_spec(spec.substr(eq + 1), v);
        if (!why.empty()) throw usage_error("--variant " + spec + ": " + why);
        variants.emplace_back(spec.substr(0, eq), v);
    }
    const std::string data = f.get("--data", "docs/data"), docs = f.get("--docs", "docs");
    const auto threads = static_cast<unsigned>(f.integer("--threads", 0, 0, 1024));
    const bool quiet = f.has("--quiet");
    // DOCS/images is made here, before any rendering, so that a new --docs folder works and a
    // folder that cannot be made fails at once, not after minutes of rendering.
    {
        std::error_code ec;
        std::filesystem::create_directories(docs + "/images", ec);
        if (ec) throw std::runtime_error("cannot make " + docs + "/images: " + ec.message());
    }

    std::vector<truth_image> truths;
    // One sky for a report: the model is rendered under the sky its truths were traced under.
    std::optional<cr::sky_model> sky;
    // ... and one light (the truth's split by source: all, the sun alone or the sky alone).
    std::optional<cr::light_sources> light;
    // ... and one order limit (the file's "orders" line; none: every order).
    std::optional<std::string> orders;
    for (const std::string& n : names) {
        const std::string path = truth_file(data, n);
        truths.push_back(read_truth(path));
        const cr::sky_model traced_under = traced_sky(truths.back(), path);
        if (sky && *sky != traced_under)
            throw usage_error(path + " was traced under the " + cr::name(traced_under) + " sky, the presets before it under the " +
                              cr::name(*sky) + " one: one report, one sky");
        sky = traced_under;
        const cr::light_sources traced_with = traced_light(truths.back(), path);
        if (light && *light != traced_with)
            throw usage_error(path + " was traced with the light '" + cr::name(traced_with) + "', the presets before it with '" +
                              cr::name(*light) + "': one report, one light");
        light = traced_with;
        const auto o = truths.back().meta.find("orders");
        const std::string traced_orders = o == truths.back().meta.end() ? "all" : o->second;
        if (orders && *orders != traced_orders)
            throw usage_error(path + " keeps light scattered " + traced_orders + " times, the presets before it " + *orders +
                              ": one report, one order limit");
        orders = traced_orders;
        // Files from before the shape existed were traced over the classic field.
        const auto it = truths.back().meta.find("shape");
        const std::string traced = it == truths.back().meta.end() ? "classic" : it->second;
        if (traced != cr::name(shape))
            throw usage_error(path + " was traced over the " + traced + " field, not --shape " +
                              cr::name(shape));
    }
    const cr::cloud_textures textures = load_textures(f, quiet);

    std::ostringstream md;
    md << "# Lighting models against the path-traced truth of whole cloud images\n\n"
       << "Density field: `" << cr::name(shape) << "` (the renderer's `--shape`).\n\n";
    if (*light != cr::light_sources::all)
        md << "Light: **the " << (*light == cr::light_sources::sun ? "sun alone** (no sky light, no ground, a black background)"
                                                                  : "sky alone** (the sky, the lit ground and the background; no sun on the clouds)")
           << ", in the truth (`cloudmath_volume_truth render --light " << cr::name(*light)
           << "`) and in the model alike: the whole's error split by source.\n\n";
    if (*orders != "all")
        md << "Orders: **light scattered at most " << *orders << (*orders == "1" ? " time" : " times")
           << "** in the truth (`cloudmath_volume_truth render --orders " << *orders
           << "`); the model is rendered as the variants say (a diagnosis: compare a variant with the same orders, e.g. "
              "`lighting=octaves,octaves=1` for single scattering).\n\n";
    md << "Generated by `bash scripts/truth.sh"
       << (*sky == cr::sky_model::physical ? " --sky physical" : "")
       << "` (tools/reference/truths/volume_truth_main.cpp; the truth\n"
          "images by `cloudmath_volume_truth render`, this report by `cloudmath_volume_truth report`).\n"
          "The same scene twice: the example renderer's CPU reference (`render_cpu_linear`, the\n"
          "GLSL image's twin, linear radiance before the tonemap; the mean of its first "
       << frames << " frame" << (frames == 1 ? "" : "s") << ",\n"
          "each with its own march jitters: a still camera's converged image) for each lighting variant, and a\n"
          "double-precision volumetric path tracer over the renderer's own density field\n"
          "(`cloud_density`, tools/reference/transport/cloud_medium.hpp): delta tracking, every order of\n"
          "scattering, the sun by next-event estimation with ratio-tracked transmittance, the\n"
       << (*sky == cr::sky_model::artistic ? "renderer's sky (gradient and aureole, no sun disc)"
                                           : "renderer's physical sky (`--sky physical`: the sky-view table, no sun\n"
                                             "disc; the sun by height)")
       << " and ground for paths that leave the\n"
          "layer, albedo 0.99 and the phase given below. Camera rays are the renderer's\n"
          "pixel centres; their first flight meets the clouds only within the renderer's view\n"
          "stretch (35 km) and sees the renderer's background (no sun disc) behind it. What the real-time\n"
          "models leave out (real sky light instead of the ambient term, light from clouds\n"
          "beyond the light march, every scattering order) is what these numbers measure.\n\n"
          "Definitions (over all pixels and the r, g, b channels; linear radiance):\n\n"
          "- **rms**: root mean square of model - truth, over the truth image's mean radiance;\n"
          "- **bias**: (mean of the model - mean of the truth) over the truth's mean;\n"
          "- **PSNR**: on the display images (the renderer's tonemap, 1 - exp(-exposure L) then\n"
          "  gamma 1/2.2, values in [0, 1]), 10 log10(1 / mean squared difference), as the\n"
          "  GPU-vs-CPU test of the renderer;\n"
          "- **worst block**: the image cut into 4 x 4 blocks (column, row from the top left), the\n"
          "  block with the largest rms (still over the whole image's mean), with its bias;\n"
          "- **noise floor**: the truth's own noise, the rms of its per-pixel standard errors over\n"
          "  its mean: an rms error near it is noise, not model error;\n"
          "- **excess**: the model's error with the truth's noise removed in quadrature,\n"
          "  sqrt(rms^2 - noise floor^2) (the two are independent).\n\n"
          "Images (docs/images/truth_PRESET.png, for the first variant; `report --variant-images`\n"
          "also writes truth_PRESET_VARIANT.png for the others): truth | model | difference\n"
          "of the display images, 0.5 + 2 (model - truth) per channel (mid-grey: no difference,\n"
          "brighter: the model is too bright).\n\n";
    md << "Variants (the renderer's `--variant` notation over the defaults; the scene's sun disc, aerial perspective\n"
          "and cloud shadows on the ground off in all of them (scene::sun_disc, haze, shadows), as the truth has no\n"
          "sun disc (18,000 times the irradiance, it would dominate any metric where it is in view), no air between\n"
          "the camera and the clouds and a constant ground):\n\n";
    for (const auto& v : variants) md << "- `" << v.first << "`: `" << cr::variant_spec(v.second) << "`\n";
    md << '\n';

    std::ostringstream sections;
    std::vector<std::vector<double>> rms(variants.size(), std::vector<double>(names.size(), 0.0));
    std::vector<std::vector<double>> excess = rms, psnr = rms;
    std::vector<double> noise(names.size(), 0.0);
    std::ostringstream short_of_target;  // presets whose truth misses its noise target
    std::ostringstream stale;            // presets whose truth was traced over a scene that changed since
    for (std::size_t p = 0; p < names.size(); ++p) {
        const truth_image& t = truths[p];
        const auto meta = [&](const char* key) {
            const auto it = t.meta.find(key);
            return it == t.meta.end() ? std::string("?") : it->second;
        };
        cr::scene s = preset(names[p], shape);
        s.sky = *sky;
        s.light = *light;
        sections << "## " << names[p] << " (" << s.description << ")"
                 << (p < selection.size() ? ", selection split" : "") << "\n\n";
        sections << "Truth: " << t.width << " x " << t.height << " pixels, " << meta("spp") << " paths per pixel, phase `"
           << meta("phase") << "`, seed " << meta("seed") << ", " << meta("seconds") << " s on " << meta("threads")
           << " threads";
        if (t.meta.count("allocation") != 0 && t.meta.at("allocation") != "uniform") sections << "; paths " << t.meta.at("allocation");
        sections << ".";
        bool first = true;
        std::ostringstream table, others;
        table << "| variant | rms | excess | bias | PSNR (dB) | worst block | its rms | its bias |\n|---|---|---|---|---|---|---|---|\n";
        image_errors last{};
        for (std::size_t vi = 0; vi < variants.size(); ++vi) {
            const auto& [vname, v] = variants[vi];
            if (!quiet) std::cerr << "report: " << names[p] << " / " << vname << '\n';
            const cr::image model = render_mean(s, v, textures, t.width, t.height, frames, threads);
            const image_errors e = compare(t, model, cr::display_exposure(s));
            rms[vi][p] = e.rms;
            excess[vi][p] = e.excess;
            psnr[vi][p] = e.psnr_db;
            noise[p] = e.noise_floor;
            table << "| " << vname << " | " << percent(e.rms) << " | " << percent(e.excess) << " | " << signed_percent(e.bias) << " | "
                  << fixed(e.psnr_db, 1) << " | (" << e.worst_col << ", " << e.worst_row << ") | " << percent(e.worst_rms)
                  << " | " << signed_percent(e.worst_bias) << " |\n";
            // truth | model | difference: the first variant's inline, the others' linked when
            // --variant-images writes them.
            const std::string png = "truth_" + names[p] + (first ? std::string() : "_" + vname) + ".png";
            if (first || variant_images) write_side_by_side(docs + "/images/" + png, t, model, cr::display_exposure(s));
            if (first) {
                sections << "\n\n![truth | " << vname << " | difference](images/" << png << ")\n\n";
                first = false;
            } else if (variant_images) {
                others << (others.tellp() > 0 ? ", " : "") << "[" << vname << "](images/" << png << ")";
            }
            last = e;
        }
        sections << table.str();
        if (others.tellp() > 0) sections << "\nTruth | model | difference for the other variants: " << others.str() << ".\n";
        sections << "\nTruth mean radiance " << fixed(last.truth_mean, 4) << ", noise floor " << percent(last.noise_floor) << ".";
        if (const std::optional<double> target = noise_target_of(t); target && misses_target(last.noise_floor, *target)) {
            sections << " **The truth's noise target of " << percent(*target) << " is not met**: its errors here carry more\n"
                        "noise than planned, and it is to be traced further (scripts/truth.sh --pending).";
            short_of_target << (short_of_target.tellp() > 0 ? ", " : "") << names[p] << " (" << percent(last.noise_floor)
                            << " against " << percent(*target) << ")";
        }
        // A truth that records its scene (render's fingerprint of the field, the light and the
        // rays) and whose scene the renderer no longer makes: its errors here mix the model's
        // with the change (for example of the sky), until it is traced again.
        if (const auto scene = t.meta.find("scene"); scene != t.meta.end()) {
            const vt::cloud_medium medium(s, textures);
            if (scene->second != vt::scene_fingerprint(medium, vt::make_cloud_lighting(s), vt::make_camera_rays(s, t.width, t.height))) {
                sections << " **The truth was traced over a scene that has changed since** (its fingerprint differs):\n"
                            "it is stale, and is to be traced again (scripts/truth.sh --pending).";
                stale << (stale.tellp() > 0 ? ", " : "") << names[p];
            }
        }
        sections << "\n\n";
    }
    // The rms of every variant on every preset, the selection split first.
    md << "## Summary: rms over the image mean\n\n";
    if (!selection.empty() && *sky == cr::sky_model::physical)
        md << "The renderer's default lighting model was chosen, and its table (`diffusion_models::clouds`)\n"
              "fitted, on the selection presets under the artistic sky ([../lighting_truth.md](../lighting_truth.md),\n"
              "[../detailed/lighting_truth.md](../detailed/lighting_truth.md)). Here the same scenes differ\n"
              "only by their sun and sky, so they are still marked as the selection split; nothing was chosen\n"
              "or fitted under this sky, and the evaluation presets (the physical presets among them) were\n"
              "never read by a choice or a fit.\n\n";
    else if (!selection.empty() && shape == cr::cloud_shape::classic)
        md << "The renderer's default lighting model (the diffusion model, occluded sky light) was chosen on the\n"
              "selection presets of the time (sun_behind, cumulus, stratus), then measured on the evaluation\n"
              "presets (what had been measured on them before the choice is in\n"
              "[lighting_research.md](lighting_research.md)). Its light estimators (refined view steps, quadratic\n"
              "jittered light marches both ways) were chosen later for convergence against 1024 view steps\n"
              "(docs/renderer.md), not on this data; its far field toward a low sun (`reach=far`) on all five\n"
              "selection presets of both fields, and its table (`diffusion_models::clouds`) was fitted to them\n"
              "(`cloudmath_volume_truth fit-clouds`, data/diffusion_clouds.txt): on the selection presets its\n"
              "errors are in-sample; the evaluation presets were never read by the fit. The variants other\n"
              "than `fitted_table` carry the same table.\n\n";
    else if (!selection.empty())
        md << "The renderer's default lighting model was chosen on the classic field's selection presets\n"
              "([../lighting_truth.md](../lighting_truth.md)) and its light estimators for convergence\n"
              "(docs/renderer.md); its far field toward a low sun (`reach=far`) was chosen, and its table\n"
              "(`diffusion_models::clouds`) fitted, on the selection split of both fields, this field's\n"
              "included: the selection presets' errors here are in-sample, the evaluation presets' out of\n"
              "sample ([../lighting_research.md](../lighting_research.md)).\n\n";
    // One summary table: a value per variant and preset, optionally the truth's noise floor first.
    const auto summary_table = [&](const std::vector<std::vector<double>>& value, bool in_db, bool noise_row) {
        md << "| variant |";
        for (std::size_t p = 0; p < names.size(); ++p) md << ' ' << names[p] << (p < selection.size() ? " (selection)" : "") << " |";
        md << "\n|---|";
        for (std::size_t p = 0; p < names.size(); ++p) md << "---:|";
        md << '\n';
        if (noise_row) {
            md << "| *the truth's noise floor* |";
            for (std::size_t p = 0; p < names.size(); ++p) md << ' ' << percent(noise[p]) << " |";
            md << '\n';
        }
        for (std::size_t vi = 0; vi < variants.size(); ++vi) {
            md << "| " << variants[vi].first << " |";
            for (std::size_t p = 0; p < names.size(); ++p) md << ' ' << (in_db ? fixed(value[vi][p], 1) : percent(value[vi][p])) << " |";
            md << '\n';
        }
        md << '\n';
    };
    summary_table(rms, false, false);
    md << "## Excess error: sqrt(rms^2 - noise floor^2)\n\n";
    summary_table(excess, false, true);
    if (short_of_target.tellp() > 0)
        md << "Truths whose noise floor misses the target they were traced for (their errors above carry more of\n"
              "the truth's noise; scripts/truth.sh --pending traces them further): "
           << short_of_target.str() << ".\n\n";
    if (stale.tellp() > 0)
        md << "Truths traced over a scene that has changed since (stale; their errors above mix the model's with\n"
              "the change, and scripts/truth.sh --pending traces them again): "
           << stale.str() << ".\n\n";
    md << "## PSNR of the display images (dB)\n\n";
    summary_table(psnr, true, false);
    md << sections.str();
    cloudmath::reference::write_text_file_atomically(docs + "/lighting_truth.md", md.str());
    std::cout << "report: " << names.size() << " presets x " << variants.size() << " variants -> " << docs
              << "/lighting_truth.md\n";
    return 0;
}


// ---------------------------------------------------------------------------------------
// fit-clouds: the diffusion model's fitted numbers (table and peak weights) by least squares
// on whole-cloud truth images, each preset weighted by 1 / (its mean^2 x its values), ridge
// toward the homogeneous-media fit (diffusion_models::fitted); leave-one-preset-out over
// the fit's presets chooses the ridge.
// Fitted number i of a model: its table, then its peak weights (cr::diffusion_feature_count).
constexpr auto model_table_size = static_cast<std::size_t>(cloudmath::diffusion_layout::table_size);
float& model_number(cloudmath::diffusion_model& m, std::size_t i) {
    return i < model_table_size ? m.table[i] : m.peak[i - model_table_size];
}
float model_number(const cloudmath::diffusion_model& m, std::size_t i) {
    return i < model_table_size ? m.table[i] : m.peak[i - model_table_size];
}

struct normal_equations {
    std::vector<double> A, b;  // count^2, count
    double c = 0.0;            // sum of squared residuals at theta = 0
    double rms_at(const std::vector<double>& theta) const {
        const std::size_t n = b.size();
        double q = c;
        for (std::size_t i = 0; i < n; ++i) {
            double row = 0.0;
            for (std::size_t j = 0; j < n; ++j) row += A[i * n + j] * theta[j];
            q += theta[i] * row - 2.0 * theta[i] * b[i];
        }
        return std::sqrt(std::max(q, 0.0));
    }
};

// Solves (A + lambda I) x = b + lambda x0 by Cholesky (A symmetric positive semidefinite).
std::vector<double> ridge_solve(std::vector<double> A, std::vector<double> b, double lambda, const std::vector<double>& x0) {
    const std::size_t n = b.size();
    for (std::size_t i = 0; i < n; ++i) {
        A[i * n + i] += lambda;
        b[i] += lambda * x0[i];
    }
    for (std::size_t j = 0; j < n; ++j) {
        double d = A[j * n + j];
        for (std::size_t k = 0; k < j; ++k) d -= A[j * n + k] * A[j * n + k];
        if (!(d > 0.0)) throw std::runtime_error("fit-clouds: normal equations not positive definite");
        const double l = std::sqrt(d);
        A[j * n + j] = l;
        for (std::size_t i = j + 1; i < n; ++i) {
            double v = A[i * n + j];
            for (std::size_t k = 0; k < j; ++k) v -= A[i * n + k] * A[j * n + k];
            A[i * n + j] = v / l;
        }
    }
    std::vector<double> y(n), x(n);
    for (std::size_t i = 0; i < n; ++i) {
        double v = b[i];
        for (std::size_t k = 0; k < i; ++k) v -= A[i * n + k] * y[k];
        y[i] = v / A[i * n + i];
    }
    for (std::size_t i = n; i-- > 0;) {
        double v = y[i];
        for (std::size_t k = i + 1; k < n; ++k) v -= A[k * n + i] * x[k];
        x[i] = v / A[i * n + i];
    }
    return x;
}

// The fit's default presets: the selection split of both fields (scripts/truth.sh).
const char* const fit_clouds_presets =
    "classic:sun_behind,classic:cumulus,classic:stratus,classic:low_sun_ahead,classic:low_sun_behind,"
    "detailed:sun_behind,detailed:cumulus,detailed:stratus,detailed:low_sun_ahead,detailed:low_sun_behind";

int run_fit_clouds(int argc, char** argv) {
    const flags f(argc, argv, {"--fit", "--eval", "--variant", "--data", "--threads", "--cache", "--ridge", "--out", "--check", "--frames"},
                  {"--quiet", "--sky"});
    const int frames = static_cast<int>(f.integer("--frames", 8, 1, 1024));
    const bool fit_sky = f.has("--sky");
    const std::vector<std::string> fit_list = split_list(f.get("--fit", fit_clouds_presets));
    const std::vector<std::string> eval_list = split_list(f.get("--eval", ""));
    if (fit_list.size() < 2) throw usage_error("--fit needs at least two shape:preset items (leave-one-out)");
    cr::variant v;
    const std::string spec = f.get("--variant", "");
    const std::string why = cr::apply_variant_spec(spec, v);
    if (!why.empty()) throw usage_error("--variant: " + why);
    if (v.lighting != cr::lighting_model::diffusion) throw usage_error("--variant: fit-clouds fits the diffusion model (lighting=diffusion)");
    std::vector<double> ridges;
    for (const std::string& r : split_list(f.get("--ridge", "1e-4,3e-4,1e-3,3e-3,1e-2,3e-2,1e-1,1"))) {
        const std::optional<double> value = cloudmath::tools::parse_finite(r);
        if (!value || !(*value > 0.0) || !std::isfinite(*value)) throw usage_error("--ridge values must be positive numbers, not '" + r + "'");
        ridges.push_back(*value);
    }
    if (ridges.empty()) throw usage_error("--ridge lists no value");
    const auto item_parts = [](const std::string& item) {
        const std::size_t colon = item.find(':');
        if (colon == std::string::npos) throw usage_error("'" + item + "' is not shape:preset");
        return std::make_pair(shape_flag(item.substr(0, colon)), item.substr(colon + 1));
    };
    for (const std::string& item : fit_list) (void)preset(item_parts(item).second);
    for (const std::string& item : eval_list) {
        (void)preset(item_parts(item).second);
        if (std::find(fit_list.begin(), fit_list.end(), item) != fit_list.end())
            throw usage_error("'" + item + "' is in both --fit and --eval: the splits must be disjoint");
    }
    const std::string data = f.get("--data", "docs/data");
    const auto threads = static_cast<unsigned>(f.integer("--threads", 0, 0, 1024));
    const bool quiet = f.has("--quiet");
    const auto load = [&](const std::string& item, cr::scene& s, truth_image& t) {
        const auto [shape, name] = item_parts(item);
        s = preset(name, shape);
        const std::string path = truth_file(data + (shape == cr::cloud_shape::detailed ? "/detailed" : ""), name);
        t = read_truth(path);
        const auto it = t.meta.find("shape");
        if ((it == t.meta.end() ? std::string("classic") : it->second) != cr::name(shape))
            throw std::runtime_error(path + " was not traced over the " + std::string(cr::name(shape)) + " field");
        s.sky = traced_sky(t, path);
        s.light = traced_light(t, path);
        if (t.meta.count("orders") != 0)
            throw std::runtime_error(path + " was traced with --orders " + t.meta.at("orders") +
                                     " (a diagnosis, light scattered at most that many times): the model is fitted to every order");
    };
    std::vector<std::pair<cr::scene, truth_image>> fit_data(fit_list.size());
    for (std::size_t i = 0; i < fit_list.size(); ++i) load(fit_list[i], fit_data[i].first, fit_data[i].second);
    const cr::cloud_textures textures = load_textures(f, quiet);

    constexpr std::size_t nm = cr::diffusion_feature_count;
    const std::size_t n = nm + (fit_sky ? 2 : 0);
    std::vector<double> theta0(n, 0.0);  // the homogeneous-media fit, what the ridge pulls toward
    for (std::size_t i = 0; i < nm; ++i)
        theta0[i] = double(model_number(cloudmath::diffusion_models::fitted, i));
    std::ostringstream text;
    text << "# cloudmath whole-cloud fit of the diffusion model's table and peak weights\n"
         << "# (cloudmath_volume_truth fit-clouds, bash scripts/truth.sh --fit; read by cloudmath_lighting_error\n"
         << "# fit-diffusion into diffusion_models::clouds). Least squares of the renderer's CPU reference\n"
         << "# (render_cpu_linear, variant '" << spec << "' with sun, haze and shadows off; the mean of its\n"
         << "# first " << frames << " frames, a still camera's converged image) against the\n"
         << "# path-traced truth, each preset weighted by 1 / (its mean^2 x its values), ridge toward\n"
         << "# diffusion_models::fitted; the ridge chosen by leave-one-preset-out over the fitted presets.\n"
         << "# The evaluation presets (ground, horizon, inside, above) are not read.\n"
         << "# fitted on: ";
    for (std::size_t i = 0; i < fit_list.size(); ++i) text << (i ? "," : "") << fit_list[i];
    text << '\n';
    std::vector<normal_equations> eqs;
    for (std::size_t k = 0; k < fit_list.size(); ++k) {
        const cr::scene& s = fit_data[k].first;
        const truth_image& t = fit_data[k].second;
        if (!quiet) std::cerr << "fit-clouds: " << fit_list[k] << '\n';
        // The features of the mean of `frames` frames (render_mean's image), summed frame by frame.
        cr::diffusion_features feat = cr::render_cpu_diffusion_features(s, v, textures, t.width, t.height, threads);
        for (int fr = 1; fr < frames; ++fr) {
            cr::scene sf = s;
            sf.frame = s.frame + static_cast<std::uint32_t>(fr);
            const cr::diffusion_features more = cr::render_cpu_diffusion_features(sf, v, textures, t.width, t.height, threads);
            for (std::size_t i = 0; i < feat.grad.size(); ++i) feat.grad[i] += more.grad[i];
            for (std::size_t i = 0; i < feat.fixed.size(); ++i) feat.fixed[i] += more.fixed[i];
            for (std::size_t i = 0; i < feat.sky.size(); ++i) feat.sky[i] += more.sky[i];
        }
        const float inv_frames = 1.0f / float(frames);
        for (float& g : feat.grad) g *= inv_frames;
        for (glm::vec3& c : feat.fixed) c *= inv_frames;
        for (float& g : feat.sky) g *= inv_frames;
        normal_equations e;
        e.A.assign(n * n, 0.0);
        e.b.assign(n, 0.0);
        double mean = 0.0;
        for (const vt::rgb& L : t.radiance) mean += L.r + L.g + L.b;
        const double count = 3.0 * double(t.radiance.size());
        mean /= count;
        if (!(mean > 0.0)) throw std::runtime_error(fit_list[k] + ": the truth image is black");
        const double w = 1.0 / (mean * mean * count);
        const glm::dvec3 sun(feat.sun_radiance);
        const double sun_sq = glm::dot(sun, sun);
        std::vector<glm::dvec3> a(n);
        for (std::size_t px = 0; px < t.radiance.size(); ++px) {
            const float* g = &feat.grad[px * nm];
            const glm::dvec3 r(t.radiance[px].r - double(feat.fixed[px].r), t.radiance[px].g - double(feat.fixed[px].g),
                               t.radiance[px].b - double(feat.fixed[px].b));
            e.c += w * glm::dot(r, r);
            if (!fit_sky) {
                const double sr = glm::dot(sun, r);
                for (std::size_t i = 0; i < n; ++i) {
                    if (g[i] == 0.0f) continue;
                    e.b[i] += w * sr * double(g[i]);
                    const double gi = w * sun_sq * double(g[i]);
                    for (std::size_t j = 0; j <= i; ++j) e.A[i * n + j] += gi * double(g[j]);
                }
                continue;
            }
            for (std::size_t i = 0; i < nm; ++i) a[i] = sun * double(g[i]);
            a[nm] = glm::dvec3(feat.ambient_top) * double(feat.sky[2 * px]);
            a[nm + 1] = glm::dvec3(feat.ambient_bottom) * double(feat.sky[2 * px + 1]);
            for (std::size_t i = 0; i < n; ++i) {
                if (a[i] == glm::dvec3(0.0)) continue;
                e.b[i] += w * glm::dot(a[i], r);
                for (std::size_t j = 0; j <= i; ++j) e.A[i * n + j] += w * glm::dot(a[i], a[j]);
            }
        }
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < i; ++j) e.A[j * n + i] = e.A[i * n + j];
        eqs.push_back(std::move(e));
    }
    const auto total = [&](std::size_t skip) {
        normal_equations sum;
        sum.A.assign(n * n, 0.0);
        sum.b.assign(n, 0.0);
        for (std::size_t k = 0; k < eqs.size(); ++k) {
            if (k == skip) continue;
            for (std::size_t i = 0; i < n * n; ++i) sum.A[i] += eqs[k].A[i];
            for (std::size_t i = 0; i < n; ++i) sum.b[i] += eqs[k].b[i];
        }
        return sum;
    };
    // rms here: the linear model's (the max(0, ...) clamps left out), over the truth's mean,
    // the truth's noise included.
    text << "# rms per fitted preset with diffusion_models::fitted:";
    for (const normal_equations& e : eqs) text << ' ' << percent(e.rms_at(theta0));
    text << "\n# leave-one-preset-out: ridge, then each preset's rms fitted without it, then their rms\n";
    double best_lambda = ridges.front(), best_cv = INFINITY;
    for (double lambda : ridges) {
        double cv = 0.0;
        text << "# ridge " << lambda << ":";
        for (std::size_t q = 0; q < eqs.size(); ++q) {
            const normal_equations sum = total(q);
            const double r = eqs[q].rms_at(ridge_solve(sum.A, sum.b, lambda, theta0));
            cv += r * r / double(eqs.size());
            text << ' ' << percent(r);
        }
        cv = std::sqrt(cv);
        text << "; " << percent(cv) << '\n';
        if (cv < best_cv) {
            best_cv = cv;
            best_lambda = lambda;
        }
    }
    const normal_equations all = total(eqs.size());
    const std::vector<double> theta = ridge_solve(all.A, all.b, best_lambda, theta0);
    text << "# chosen ridge " << best_lambda << "; rms per fitted preset with it:";
    for (const normal_equations& e : eqs) text << ' ' << percent(e.rms_at(theta));
    text << "\nkind,index,value\n";
    if (fit_sky) std::cout << "# sky scales - 1: top " << theta[nm] << ", bottom " << theta[nm + 1] << '\n';
    char line[96];
    for (std::size_t i = 0; i < nm; ++i) {
        const bool table = i < model_table_size;
        std::snprintf(line, sizeof line, "%s,%zu,%.9g\n", table ? "table" : "peak", table ? i : i - model_table_size, theta[i]);
        text << line;
    }
    std::cout << text.str();
    if (f.has("--check")) {
        // The stored fit is this one: every number within 1e-4 (relative to max(1, |value|)),
        // read as fit-diffusion reads it into the headers.
        const std::string path = f.get("--check", "");
        const cloudmath::diffusion_model stored = cloudmath::reference::lighting::read_clouds_model(path);
        double worst = 0.0;
        for (std::size_t i = 0; i < nm; ++i) {
            worst = std::max(worst, std::abs(double(model_number(stored, i)) - theta[i]) / std::max(1.0, std::abs(theta[i])));
        }
        if (!(worst <= 1e-4)) {
            std::cerr << "fit-clouds --check: " << path << " differs from the refit by " << worst << '\n';
            return 1;
        }
        std::cerr << "fit-clouds --check: " << path << " is reproduced (largest difference " << worst << ")\n";
    }
    if (f.has("--out")) cloudmath::reference::write_text_file_atomically(f.get("--out", ""), text.str());
    // Measured with the library function (clamps and all) on the --eval presets.
    cloudmath::diffusion_model m{};
    m.name = "clouds";
    for (std::size_t i = 0; i < nm; ++i) model_number(m, i) = float(theta[i]);
    for (const std::string& item : eval_list) {
        cr::scene s;
        truth_image t;
        load(item, s, t);
        const image_errors before =
            compare(t, render_mean(s, v, textures, t.width, t.height, frames, threads, &cloudmath::diffusion_models::fitted), cr::display_exposure(s));
        const image_errors after = compare(t, render_mean(s, v, textures, t.width, t.height, frames, threads, &m), cr::display_exposure(s));
        std::cout << "eval " << item << ": excess " << percent(before.excess) << " -> " << percent(after.excess) << ", PSNR "
                  << fixed(before.psnr_db, 1) << " -> " << fixed(after.psnr_db, 1) << " dB, bias " << signed_percent(before.bias)
                  << " -> " << signed_percent(after.bias) << '\n';
    }
    return 0;
}
}  // namespace

// ---------------------------------------------------------------------------------------
// status: where each preset's truth stands, for scripts/truth.sh --pending. One line a preset:
// "PRESET STATE detail", STATE one of
//   done        a truth that meets the noise target, over the scene the renderer makes now
//               (or traced before truth files recorded their scene, which cannot be checked);
//   checkpoint  an unfinished render to resume (its file read and checked);
//   stale       a truth or checkpoint over a scene that changed since (field, sky, sun, camera);
//   short       a truth whose noise floor misses the target;
//   missing     no truth.
// A malformed checkpoint or truth file is an error (exit 1), as everywhere.
int run_status(int argc, char** argv) {
    const flags f(argc, argv, {"--presets", "--data", "--shape", "--sky", "--light", "--noise-target", "--cache"}, {"--quiet"});
    const std::vector<std::string> names = split_list(f.get("--presets", ""));
    if (names.empty()) throw usage_error("status needs --presets P1,P2,...");
    const std::optional<double> target = cloudmath::tools::parse_finite(f.get("--noise-target", ""));
    if (!target || !(*target > 0.0 && *target < 1.0)) throw usage_error("status needs --noise-target in (0, 1)");
    const std::string data = f.get("--data", "docs/data");
    const cr::cloud_shape shape = shape_flag(f.get("--shape", "classic"));
    const std::string sky = f.get("--sky", "");
    std::optional<cr::cloud_textures> textures;
    // The fingerprint of the scene the renderer makes now, at the file's size.
    const auto fingerprint_now = [&](const std::string& name, int width, int height) {
        if (!textures) textures = load_textures(f, true);
        const cr::scene s = with_light(with_sky(preset(name, shape), sky), f.get("--light", ""));
        const vt::cloud_medium medium(s, *textures);
        return vt::scene_fingerprint(medium, vt::make_cloud_lighting(s), vt::make_camera_rays(s, width, height));
    };
    for (const std::string& name : names) {
        (void)preset(name, shape);  // an unknown name: exit 2
        const std::string truth_path = truth_file(data, name), checkpoint = truth_path + ".checkpoint";
        std::cout << name << ' ';
        if (std::ifstream(checkpoint)) {
            const vt::truth_checkpoint c = vt::read_checkpoint(checkpoint);
            const auto size = [&](const char* key) {
                const auto it = c.identity.find(key);
                const std::optional<int> v =
                    it == c.identity.end() ? std::nullopt : cloudmath::tools::parse_integer<int>(it->second);
                if (!v || *v < 1 || *v > 4096) throw std::runtime_error(checkpoint + ": no image size in its run");
                return *v;
            };
            const auto scene = c.identity.find("scene");
            const bool same = scene != c.identity.end() && scene->second == fingerprint_now(name, size("width"), size("height"));
            std::cout << (same ? "checkpoint " : "stale ") << c.traced_paths() << " of " << c.planned_paths()
                      << " planned paths in " << fixed_1(c.seconds) << " s over " << c.runs << " runs"
                      << (same ? "" : ", traced over a scene that changed since") << '\n';
            continue;
        }
        if (!std::ifstream(truth_path)) {
            std::cout << "missing\n";
            continue;
        }
        const truth_image t = read_truth(truth_path);
        const auto scene = t.meta.find("scene");
        if (scene != t.meta.end() && scene->second != fingerprint_now(name, t.width, t.height)) {
            std::cout << "stale traced over a scene that changed since\n";
            continue;
        }
        std::vector<vt::rgb_estimate> e(t.radiance.size());
        for (std::size_t i = 0; i < e.size(); ++i) {
            e[i].r = {t.radiance[i].r, t.std_error[i].r, 0};
            e[i].g = {t.radiance[i].g, t.std_error[i].g, 0};
            e[i].b = {t.radiance[i].b, t.std_error[i].b, 0};
        }
        const double floor = vt::noise_floor(e);
        std::cout << (misses_target(floor, *target) ? "short" : "done") << " noise floor " << percent(floor) << ", target "
                  << percent(*target) << (scene == t.meta.end() ? ", scene not recorded" : "") << '\n';
    }
    return 0;
}

int main(int argc, char** argv) {
    return cloudmath::reference::run_subcommand_tool("cloudmath_volume_truth", usage_text, argc, argv, [&](const std::string& command) {
        if (command == "render") return run_render(argc, argv);
        if (command == "report") return run_report(argc, argv);
        if (command == "fit-clouds") return run_fit_clouds(argc, argv);
        if (command == "status") return run_status(argc, argv);
        throw usage_error("unknown command '" + command + "' (render, report, fit-clouds)");
    });
}
