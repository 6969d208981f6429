// tools/reference/truths/atmosphere_truth_main.cpp: cloudmath_atmosphere_truth, the sky's ground
// truth (issue 26). `render` path-traces the set of atmosphere_truth.hpp with the atmosphere
// tracer into a CSV (radiance and standard error per channel, per unit sun illuminance);
// `report` compares the library's model with it and writes docs/atmosphere_truth.md and one
// image per sun elevation (path-traced | model | difference).
//
//   cloudmath_atmosphere_truth render --out docs/data/atmosphere_truth.csv
//   cloudmath_atmosphere_truth report --data docs/data/atmosphere_truth.csv --docs docs
//
// Exit status: 0 success, 2 bad command line, 1 failure (a missing or malformed truth file,
// an unwritable output; the message names the path). Same seed -> same numbers, whatever
// --threads is.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "atmosphere_truth.hpp"
#include "atmosphere_variants.hpp"
#include "atomic_file.hpp"
#include "cli_main.hpp"
#include "png_encode.hpp"
#include "strict_number.hpp"

namespace atmo = cloudmath::reference::atmo;
namespace mc = cloudmath::reference::mc;
using cloudmath::reference::flags;
using cloudmath::reference::usage_error;

namespace {

const char* const usage_text =
    "usage: cloudmath_atmosphere_truth <command> [--flag value ...]\n"
    "\n"
    "Ground truth for the sky: a double-precision path tracer of Earth's air (Bruneton 2017's\n"
    "constants: Rayleigh, Mie, ozone, a Lambertian ground; every order of scattering) seen\n"
    "from sea level, for the sun at 90, 30, 10, 2 and -2 degrees (set truth), or at 60, 20, 5, 0\n"
    "and -1 (set holdout: traced after the model's design was chosen on the truth, never used\n"
    "to choose it).\n"
    "\n"
    "commands:\n"
    "  render   path-trace the set; CSV of radiance and standard error per channel\n"
    "           flags: --out F.csv [--set truth|holdout] [--table-paths 1000000]\n"
    "                  [--panorama-paths 50000] [--seed 1] [--threads 0] [--quiet]\n"
    "  report   the library's model against the truth: docs/atmosphere_<set>.md and\n"
    "           docs/images/atmosphere_sun_<E>.png (path-traced | model | difference)\n"
    "           flags: [--set truth|holdout] [--data docs/data/atmosphere_<set>.csv] [--docs docs]\n"
    "  ground   the ground below the horizon: views down from sea level and 1 km traced for\n"
    "           the sun at 90, 30, 10, 2 and -2 degrees, against the model with a ground lit\n"
    "           by the sun only and by the sun and the sky (a markdown table on stdout)\n"
    "           flags: [--paths 200000] [--seed 1] [--threads 0]\n"
    "  horizon  the sky near the horizon: views 2 and 10 degrees up, toward the sun and away,\n"
    "           for the sun at 2, 6, 20 and 60 degrees. With --out, path-traces them into a CSV;\n"
    "           without, the model against the stored CSV (a markdown table on stdout)\n"
    "           flags: [--out F.csv [--paths 2000000] [--seed 1] [--threads 0] [--quiet]]\n"
    "                  [--data docs/data/atmosphere_horizon.csv]\n"
    "  variants the multiple-scattering variants measured while the model was chosen: a\n"
    "           markdown table of table / panorama rms per sun elevation on stdout\n"
    "           flags: [--set truth|holdout] [--data docs/data/atmosphere_<set>.csv]\n";

// The --set flag's sun elevations (truth by default).
std::vector<double> set_flag(const flags& f, std::string& name) {
    name = f.get("--set", "truth");
    try {
        return atmo::set_sun_elevations(name);
    } catch (const std::invalid_argument& e) {
        throw usage_error(std::string("--set: ") + e.what());
    }
}

std::uint64_t count_flag(const flags& f, const std::string& name, const std::string& fallback) {
    const auto n = cloudmath::tools::parse_count(f.get(name, fallback));
    if (!n || *n == 0 || *n > 10000000000ULL) throw usage_error(name + " must be a count from 1 to 1e10");
    return *n;
}

void write_or_throw(const std::string& path, const std::string& bytes) {
    const std::string error = cloudmath::tools::write_file_atomically(path, bytes);
    if (!error.empty()) throw std::runtime_error(error);
}

int render(int argc, char** argv) {
    const flags f(argc, argv, {"--out", "--set", "--table-paths", "--panorama-paths", "--seed", "--threads"}, {"--quiet"});
    std::string set_name;
    const std::vector<double> elevations = set_flag(f, set_name);
    const std::string out = f.get("--out", "");
    if (out.empty()) throw usage_error("render needs --out");
    const std::uint64_t table_paths = count_flag(f, "--table-paths", "1000000");
    const std::uint64_t panorama_paths = count_flag(f, "--panorama-paths", "50000");
    const auto seed = cloudmath::tools::parse_integer<std::uint64_t>(f.get("--seed", "1"));
    const auto threads = cloudmath::tools::parse_integer<unsigned>(f.get("--threads", "0"));
    if (!seed || !threads) throw usage_error("--seed and --threads must be non-negative integers");
    if (const std::string bad = cloudmath::tools::check_output_path(out); !bad.empty()) throw std::runtime_error(bad);
    const bool quiet = f.has("--quiet");

    const auto air = cloudmath::earth_atmosphere<double>();
    std::vector<atmo::truth_row> rows = atmo::truth_set(elevations);
    mc::run_options options;
    options.seed = *seed;
    options.threads = *threads;
    const auto start = std::chrono::steady_clock::now();
    for (const std::string set : {"table", "panorama"}) {
        std::vector<std::size_t> index;
        std::vector<atmo::sky_query> queries;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            if (rows[i].set != set) continue;
            atmo::sky_query q;
            q.altitude = 0.0;
            q.view = atmo::direction_from_degrees(rows[i].view_elevation, rows[i].view_azimuth);
            q.sun = atmo::direction_from_degrees(rows[i].sun_elevation, 0.0);
            index.push_back(i);
            queries.push_back(q);
        }
        if (!quiet) std::cerr << "tracing the " << set << ": " << queries.size() << " directions\n";
        options.seed = *seed + (set == "table" ? 0u : 1u);
        const auto est = atmo::trace_sky(air, queries, set == "table" ? table_paths : panorama_paths, options);
        for (std::size_t k = 0; k < index.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                rows[index[k]].radiance[c] = est[k].channel[c].mean;
                rows[index[k]].std_error[c] = est[k].channel[c].std_error;
            }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostringstream csv;
    csv.precision(9);
    csv << "# atmosphere " << set_name << ": Earth's air (earth_atmosphere, Bruneton 2017), camera at sea level, sun at azimuth 0\n"
        << "# radiance per unit sun illuminance above the air (1/sr); channels 680, 550, 440 nm\n"
        << "# table paths per channel: " << table_paths << "; panorama paths per channel: " << panorama_paths
        << "; seed: " << *seed << "; seconds: " << static_cast<long>(seconds) << "\n"
        << "set,name,sun_elevation,view_elevation,view_azimuth,r,g,b,se_r,se_g,se_b\n";
    for (const atmo::truth_row& r : rows)
        csv << r.set << ',' << r.name << ',' << r.sun_elevation << ',' << r.view_elevation << ',' << r.view_azimuth << ','
            << r.radiance[0] << ',' << r.radiance[1] << ',' << r.radiance[2] << ',' << r.std_error[0] << ','
            << r.std_error[1] << ',' << r.std_error[2] << '\n';
    write_or_throw(out, csv.str());
    if (!quiet) std::cerr << "wrote " << out << " (" << static_cast<long>(seconds) << " s)\n";
    return 0;
}

std::string percent(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.1f%%", 100.0 * x);
    return buf;
}

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

std::string elevation_name(double e) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%s%g", e < 0 ? "m" : "", std::abs(e));
    return buf;
}

// Luminance of linear Rec. 709 rgb.
double luminance(const double* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

// sRGB encoding of a linear value in [0, 1].
unsigned char srgb8(double x) {
    x = std::clamp(x, 0.0, 1.0);
    const double v = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(255.0 * v));
}

// One image per sun elevation: the whole sky's panorama (azimuth -180..180, the sun in the
// middle, mirrored from the traced half; elevation 0 at the bottom, 90 at the top), 4 x 4
// pixels per cell, for the truth, the model and the luminance's relative difference (red:
// model brighter, blue: darker, full colour at 20%). Both radiance panels share one
// exposure: the truth's mean luminance to 0.18, then x / (1 + x).
std::string panorama_png(const std::vector<atmo::truth_row>& rows, const std::vector<std::array<double, 3>>& model,
                         double sun_elevation) {
    const int cw = atmo::panorama_azimuths * 2, ch = atmo::panorama_elevations, scale = 4, gap = 4;
    const int pw = cw * scale, ph = ch * scale, width = 3 * pw + 2 * gap;
    std::vector<double> truth_rgb(static_cast<std::size_t>(cw * ch) * 3), model_rgb(truth_rgb.size());
    double mean = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const atmo::truth_row& r = rows[i];
        if (r.set != "panorama" || r.sun_elevation != sun_elevation) continue;
        const int a = static_cast<int>(r.view_azimuth / (180.0 / atmo::panorama_azimuths));
        const int e = static_cast<int>(r.view_elevation / (90.0 / atmo::panorama_elevations));
        for (const int x : {atmo::panorama_azimuths + a, atmo::panorama_azimuths - 1 - a}) {
            const std::size_t k = (static_cast<std::size_t>(e) * static_cast<std::size_t>(cw) + static_cast<std::size_t>(x)) * 3;
            for (std::size_t c = 0; c < 3; ++c) {
                truth_rgb[k + c] = r.radiance[c];
                model_rgb[k + c] = model[i][c];
            }
        }
        mean += luminance(r.radiance);
    }
    mean /= atmo::panorama_azimuths * atmo::panorama_elevations;
    const double exposure = mean > 0 ? 0.18 / mean : 1.0;
    std::vector<unsigned char> px(static_cast<std::size_t>(width * ph) * 3, 255);
    for (int y = 0; y < ph; ++y)
        for (int x = 0; x < pw; ++x) {
            const int cx = x / scale, cy = ch - 1 - y / scale;
            const std::size_t k = (static_cast<std::size_t>(cy) * static_cast<std::size_t>(cw) + static_cast<std::size_t>(cx)) * 3;
            const auto put = [&](int panel, double r, double g, double b) {
                const std::size_t o =
                    (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(panel * (pw + gap) + x)) * 3;
                px[o] = srgb8(r);
                px[o + 1] = srgb8(g);
                px[o + 2] = srgb8(b);
            };
            const auto tone = [&](const std::vector<double>& rgb, int panel) {
                double v[3];
                for (std::size_t c = 0; c < 3; ++c) {
                    const double t = exposure * rgb[k + c];
                    v[c] = t / (1.0 + t);
                }
                put(panel, v[0], v[1], v[2]);
            };
            tone(truth_rgb, 0);
            tone(model_rgb, 1);
            const auto lum = [&](const std::vector<double>& rgb) { return luminance(&rgb[k]); };
            const double lt = lum(truth_rgb);
            const double d = lt > 0 ? std::clamp((lum(model_rgb) / lt - 1.0) / 0.2, -1.0, 1.0) : 0.0;
            put(2, d > 0 ? 1.0 : 1.0 + d, 1.0 - std::abs(d), d < 0 ? 1.0 : 1.0 - d);
        }
    return cloudmath::tools::encode_png(width, ph, 3, px.data(), width * 3);
}

int report(int argc, char** argv) {
    const flags f(argc, argv, {"--set", "--data", "--docs"}, {});
    std::string set_name;
    const std::vector<double> elevations = set_flag(f, set_name);
    const bool holdout = set_name == "holdout";
    const std::string data = f.get("--data", "docs/data/atmosphere_" + set_name + ".csv");
    const std::string docs = f.get("--docs", "docs");
    const std::vector<atmo::truth_row> rows = atmo::read_truth(data, elevations);
    const std::vector<std::array<double, 3>> model = atmo::model_radiance(rows);

    std::ostringstream md;
    md << (holdout ? "# The sky against its held-out path-traced truth\n\n" : "# The sky against its path-traced truth\n\n")
       << "Generated by `cloudmath_atmosphere_truth report` from `" << data
       << "` (the truth: `cloudmath_atmosphere_truth render`, see [atmosphere.md](atmosphere.md)). The model is "
          "`atmosphere_sky_radiance` in float with the 32 x 32 multiple-scattering LUT of "
          "`atmosphere_multiple_scattering_refined_lut` (64 directions, 20 steps, 3 passes) with its moments and aerosol "
          "field (`atmosphere_make_sky_luts`), 32 view steps and 32 sun steps; the camera is at sea level, the sun at azimuth 0. Errors are model / truth - 1 "
          "per channel (680, 550, 440 nm); `noise` is the rms of the truth's own relative standard errors.\n\n"
       << (holdout ? "This set (`--set holdout`) was traced after the model's design was chosen on the truth's sun "
                     "elevations and was never used to choose it: its errors are out of sample.\n\n"
                   : "")
       << "## Summary\n\n"
       << "| sun elevation | table rms | table worst | panorama rms (solid-angle weighted) | panorama worst | truth noise "
          "(table / panorama) |\n|---:|---:|---:|---:|---:|---:|\n";
    for (double e : elevations) {
        const atmo::error_summary t = atmo::summarise(rows, model, "table", e);
        const atmo::error_summary p = atmo::summarise(rows, model, "panorama", e);
        md << "| " << e << " | " << percent(t.rms).substr(1) << " | " << percent(t.worst) << " | " << percent(p.rms).substr(1)
           << " | " << percent(p.worst) << " | " << percent(t.noise).substr(1) << " / " << percent(p.noise).substr(1)
           << " |\n";
    }
    md << "\n## The table's directions\n\n"
       << "Radiance per unit sun illuminance (1/sr), r g b; the truth's relative standard error of the blue channel "
          "in brackets.\n\n"
       << "| sun | direction | elevation, azimuth | truth | model | error r, g, b |\n|---:|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const atmo::truth_row& r = rows[i];
        if (r.set != "table") continue;
        md << "| " << r.sun_elevation << " | " << r.name << " | " << r.view_elevation << ", " << r.view_azimuth << " | "
           << number(r.radiance[0]) << " " << number(r.radiance[1]) << " " << number(r.radiance[2]) << " ("
           << percent(r.std_error[2] / r.radiance[2]).substr(1) << ") | " << number(model[i][0]) << " "
           << number(model[i][1]) << " " << number(model[i][2]) << " | ";
        for (std::size_t c = 0; c < 3; ++c) md << percent(model[i][c] / r.radiance[c] - 1.0) << (c < 2 ? ", " : " |\n");
    }
    md << "\n## Images\n\nEach: path-traced | model | luminance difference (red: model brighter, blue: darker, full "
          "colour at 20%); the whole sky from azimuth -180 to 180 with the sun in the middle, elevation 0 to 90.\n\n";
    for (double e : elevations) {
        const std::string name = "images/atmosphere_sun_" + elevation_name(e) + ".png";
        const std::string png = panorama_png(rows, model, e);
        if (png.empty()) throw std::runtime_error(docs + "/" + name + ": cannot encode the image");
        write_or_throw(docs + "/" + name, png);
        md << "Sun at " << e << " degrees:\n\n![sky, sun at " << e << " degrees](" << name << ")\n\n";
    }
    write_or_throw(docs + "/atmosphere_" + set_name + ".md", md.str());
    std::cout << "wrote " << docs << "/atmosphere_" << set_name << ".md\n";
    return 0;
}

int ground(int argc, char** argv) {
    const flags f(argc, argv, {"--paths", "--seed", "--threads"}, {});
    const std::uint64_t paths = count_flag(f, "--paths", "200000");
    const auto seed = cloudmath::tools::parse_integer<std::uint64_t>(f.get("--seed", "1"));
    const auto threads = cloudmath::tools::parse_integer<unsigned>(f.get("--threads", "0"));
    if (!seed || !threads) throw usage_error("--seed and --threads must be non-negative integers");
    mc::run_options options;
    options.seed = *seed;
    options.threads = *threads;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<atmo::ground_row> rows =
        atmo::ground_check({atmo::truth_sun_elevations.begin(), atmo::truth_sun_elevations.end()}, paths, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto errors = [](const double* model, const atmo::ground_row& r) {
        std::string out;
        for (int c = 0; c < 3; ++c) out += (c ? " " : "") + percent(model[c] / r.truth[c] - 1.0);
        return out;
    };
    std::ostringstream md;
    char line[256];
    md << "| sun | camera | view | truth r, g, b (1/sr) | truth's noise (blue) | ground lit by the sun only | by the sun and the sky |\n"
          "|---:|---:|---:|---|---:|---|---|\n";
    for (const atmo::ground_row& r : rows) {
        std::snprintf(line, sizeof line, "| %g | %g m | %g | %.4g, %.4g, %.4g | %.1f%% | ", r.sun_elevation, r.altitude,
                      r.view_elevation, r.truth[0], r.truth[1], r.truth[2], 100.0 * r.std_error[2] / r.truth[2]);
        md << line << errors(r.sun_only, r) << " | " << errors(r.sky_lit, r) << " |\n";
    }
    std::snprintf(line, sizeof line, "%llu paths per channel and view, seed %llu, %.1f s\n",
                  static_cast<unsigned long long>(paths), static_cast<unsigned long long>(*seed), seconds);
    md << '\n' << line;
    std::cout << md.str();
    return 0;
}

// The sky near the horizon: with --out, path-traces the horizon set (16 views) into a CSV;
// otherwise the model against the stored CSV, a markdown table on stdout (docs/atmosphere.md's;
// ctest reference.atmosphere_horizon checks that the doc holds it).
int horizon(int argc, char** argv) {
    const flags f(argc, argv, {"--out", "--data", "--paths", "--seed", "--threads"}, {"--quiet"});
    const std::string out = f.get("--out", "");
    std::vector<atmo::truth_row> rows = atmo::horizon_set();
    if (!out.empty()) {
        const std::uint64_t paths = count_flag(f, "--paths", "2000000");
        const auto seed = cloudmath::tools::parse_integer<std::uint64_t>(f.get("--seed", "1"));
        const auto threads = cloudmath::tools::parse_integer<unsigned>(f.get("--threads", "0"));
        if (!seed || !threads) throw usage_error("--seed and --threads must be non-negative integers");
        if (const std::string bad = cloudmath::tools::check_output_path(out); !bad.empty()) throw std::runtime_error(bad);
        mc::run_options options;
        options.seed = *seed;
        options.threads = *threads;
        std::vector<atmo::sky_query> queries;
        for (const atmo::truth_row& r : rows) {
            atmo::sky_query q;
            q.altitude = 0.0;
            q.view = atmo::direction_from_degrees(r.view_elevation, r.view_azimuth);
            q.sun = atmo::direction_from_degrees(r.sun_elevation, 0.0);
            queries.push_back(q);
        }
        const auto start = std::chrono::steady_clock::now();
        const auto est = atmo::trace_sky(cloudmath::earth_atmosphere<double>(), queries, paths, options);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::ostringstream csv;
        csv.precision(9);
        csv << "# atmosphere horizon: Earth's air (earth_atmosphere, Bruneton 2017), camera at sea level, sun at azimuth 0\n"
            << "# radiance per unit sun illuminance above the air (1/sr); channels 680, 550, 440 nm\n"
            << "# paths per channel: " << paths << "; seed: " << *seed << "; seconds: " << static_cast<long>(seconds) << "\n"
            << "set,name,sun_elevation,view_elevation,view_azimuth,r,g,b,se_r,se_g,se_b\n";
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const atmo::truth_row& r = rows[i];
            csv << r.set << ',' << r.name << ',' << r.sun_elevation << ',' << r.view_elevation << ',' << r.view_azimuth;
            for (int c = 0; c < 3; ++c) csv << ',' << est[i].channel[c].mean;
            for (int c = 0; c < 3; ++c) csv << ',' << est[i].channel[c].std_error;
            csv << '\n';
        }
        write_or_throw(out, csv.str());
        if (!f.has("--quiet")) std::cerr << "wrote " << out << " (" << static_cast<long>(seconds) << " s)\n";
        return 0;
    }
    const std::string data = f.get("--data", "docs/data/atmosphere_horizon.csv");
    rows = atmo::read_rows(data, rows);
    const std::vector<std::array<double, 3>> model = atmo::model_radiance(rows);
    std::ostringstream md;
    char line[256];
    md << "| sun | view | toward | model / truth - 1: r, g, b | the truth's noise (worst channel) |\n"
          "|---:|---:|---|---|---:|\n";
    double sum = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const atmo::truth_row& r = rows[i];
        double e[3], noise = 0.0;
        for (int c = 0; c < 3; ++c) {
            e[c] = model[i][static_cast<std::size_t>(c)] / r.radiance[c] - 1.0;
            sum += e[c] * e[c];
            if (std::abs(e[c]) > std::abs(worst)) worst = e[c];
            noise = std::max(noise, r.std_error[c] / r.radiance[c]);
        }
        std::snprintf(line, sizeof line, "| %g | %g up | %s | %+.2f%%, %+.2f%%, %+.2f%% | %.2f%% |\n", r.sun_elevation,
                      r.view_elevation, r.view_azimuth == 0.0 ? "the sun" : "away", 100.0 * e[0], 100.0 * e[1],
                      100.0 * e[2], 100.0 * noise);
        md << line;
    }
    std::snprintf(line, sizeof line, "\nrms %.2f%%, worst %+.2f%% over the %zu values (model: the documented defaults, %s).\n",
                  100.0 * std::sqrt(sum / (3.0 * static_cast<double>(rows.size()))), 100.0 * worst, 3 * rows.size(),
                  "atmosphere_make_sky_luts' 32 x 32 LUTs, 32 view and 32 sun steps");
    md << line;
    std::cout << md.str();
    return 0;
}

int variants(int argc, char** argv) {
    const flags f(argc, argv, {"--set", "--data"}, {});
    std::string set_name;
    const std::vector<double> elevations = set_flag(f, set_name);
    const std::string data = f.get("--data", "docs/data/atmosphere_" + set_name + ".csv");
    const std::vector<atmo::truth_row> rows = atmo::read_truth(data, elevations);
    std::ostringstream md;
    md << "| variant (" << set_name << ": table / panorama rms)";
    for (double e : elevations) md << " | sun " << e;
    md << " |\n|---";
    for (std::size_t i = 0; i < elevations.size(); ++i) md << "|---:";
    md << "|\n";
    for (const atmo::ms_variant& v : atmo::ms_variants()) {
        const std::vector<std::array<double, 3>> model = atmo::variant_radiance(v, rows);
        md << "| " << v.name;
        for (double e : elevations)
            md << " | " << percent(atmo::summarise(rows, model, "table", e).rms).substr(1) << " / "
               << percent(atmo::summarise(rows, model, "panorama", e).rms).substr(1);
        md << " |\n";
    }
    std::cout << md.str();
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return cloudmath::reference::run_subcommand_tool("cloudmath_atmosphere_truth", usage_text, argc, argv,
                                                     [&](const std::string& command) {
                                                         if (command == "render") return render(argc, argv);
                                                         if (command == "report") return report(argc, argv);
                                                         if (command == "variants") return variants(argc, argv);
                                                         if (command == "ground") return ground(argc, argv);
                                                         if (command == "horizon") return horizon(argc, argv);
                                                         throw usage_error("unknown command " + command);
                                                     });
}
