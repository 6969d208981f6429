// tools/reference/transport/montecarlo_main.cpp: cloudmath_montecarlo, the command-line front end of
// the Monte Carlo reference (montecarlo.hpp): slab fluxes and radiance histograms, slab
// radiance toward given directions, sphere radiance on an orthographic camera.
//
//   cloudmath_montecarlo slab --tau 1 --mu0 1 --phase hg:0.75 --photons 1000000 --out s.csv
//   cloudmath_montecarlo slab-radiance --tau 8 --mu0 0.5 --phase table:mie.csv
//       --views "r:1,0;r:0.5,180;t:0.5,0" --paths 100000 --out r.csv   (one line)
//   cloudmath_montecarlo sphere --tau 10 --view-angle 90 --points 9 --phase hg:0.85 --out p.csv
//
// Exit status: 0 success, 2 bad command line (one-line message on stderr), 1 I/O failure
// (the message names the path). Progress on stderr (with the time left), one summary line
// with the elapsed time on stdout. CSV files: "# key: value" metadata lines (every
// parameter, seed, elapsed time), a header line, then rows with mean and std_error. Same
// seed -> same numbers, whatever --threads is.
// --out is checked before the computation (a missing directory fails at once) and written
// only at the end, atomically (write_text_file_atomically): a killed or failed run leaves
// the old file as it was. A run traces at most max_paths_per_run paths (see the usage).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "atomic_file.hpp"
#include "cli_main.hpp"
#include "montecarlo.hpp"
#include "phase_table.hpp"  // write_text_file_atomically
#include "strict_number.hpp"

namespace mc = cloudmath::reference::mc;

namespace {

// The most paths (photons for slab; paths per view or ray times views or rays otherwise)
// one run may trace: about 20 minutes at 1e7 paths/s, hours on a small machine. Beyond it
// the run is refused rather than left running for a day; split it over several --seed
// values and average the results instead.
constexpr double max_paths_per_run = 1e10;

const char* const usage_text =
    "usage: cloudmath_montecarlo <command> [--flag value ...]\n"
    "\n"
    "Monte Carlo reference for homogeneous media (double precision, sun irradiance F0 = 1,\n"
    "radiances L/F0 in 1/sr, the direct solar beam excluded from radiances).\n"
    "\n"
    "commands:\n"
    "  slab           forward photon tracing in a plane-parallel slab lit from the top:\n"
    "                 R, T_diffuse, T_direct, A with standard errors; CSV of the azimuthally\n"
    "                 averaged reflected/transmitted radiance in bins of exit cosine.\n"
    "                 flags: --tau 1 --mu0 1 --phase hg:0.85 --albedo 1 --photons 1000000\n"
    "                        --bins 20 [--max-order N] [--threads 1] [--seed 1] [--out F.csv]\n"
    "  slab-radiance  backward tracing with next-event estimation: radiance leaving the slab\n"
    "                 toward the listed directions.\n"
    "                 flags: --tau 1 --mu0 1 --phase hg:0.85 --albedo 1 --views \"r:1,0\"\n"
    "                        --paths 100000 [--max-order N] [--threads 1] [--seed 1] [--out F]\n"
    "                 --views: 'r:MU,PHI' (camera above, looking down) or 't:MU,PHI' (below,\n"
    "                 looking up), separated by ';'. MU = exit cosine, PHI = relative azimuth\n"
    "                 in degrees, 0 = the camera faces the sun's azimuth (forward side).\n"
    "  sphere         backward tracing in a sphere of radius 1 and optical diameter --tau,\n"
    "                 seen by an orthographic camera whose direction makes --view-angle\n"
    "                 degrees with the direction toward the sun (0 = sun behind the sphere).\n"
    "                 flags: --tau 10 --view-angle 90 --points 9 | --grid N --phase hg:0.85\n"
    "                        --albedo 1 --paths 100000 [--max-order N] [--threads 1]\n"
    "                        [--seed 1] [--out F.csv]\n"
    "                 --points N: N rays along the diameter in the sun/view plane (u > 0 is\n"
    "                 the sunward side); --grid N: N x N rays over the square [-1, 1]^2.\n"
    "\n"
    "phase specs: isotropic, rayleigh, hg:G, dual_hg:G0,G1,W, cs:G, draine:G,ALPHA,\n"
    "             mie_approx:D_UM, table:PATH (phase table CSV, see phase_table.hpp)\n"
    "--max-order N keeps light scattered at most N times (1 = single scattering); 0 = all.\n"
    "--threads 0 uses every core. Counts take digits or exponent forms (1e6).\n"
    "A run traces at most 1e10 paths (--photons, or --paths times the views or rays): more\n"
    "would run for hours; split such a run over several --seed values instead.\n"
    "--out is written only when the run is done, through a temporary file renamed over it:\n"
    "a failed or interrupted run leaves the old file as it was.\n"
    "Exit status: 0 ok, 1 I/O failure, 2 bad command line.\n";

using cloudmath::reference::usage_error;

// "--name value" pairs, checked against the flags a command accepts.
class flags {
public:
    flags(int argc, char** argv, const std::set<std::string>& allowed) {
        for (int i = 2; i < argc; ++i) {
            const std::string name = argv[i];
            if (name.rfind("--", 0) != 0) throw usage_error("unexpected argument '" + name + "'");
            const std::string key = name.substr(2);
            if (allowed.count(key) == 0) throw usage_error("unknown flag '" + name + "'");
            if (i + 1 >= argc) throw usage_error("flag '" + name + "' needs a value");
            if (values_.count(key) != 0) throw usage_error("flag '" + name + "' given twice");
            values_[key] = argv[++i];
        }
    }
    bool has(const std::string& key) const { return values_.count(key) != 0; }
    std::string text(const std::string& key, const std::string& fallback) const {
        const auto it = values_.find(key);
        return it == values_.end() ? fallback : it->second;
    }
    double number(const std::string& key, double fallback, double lo, double hi,
                  bool lo_open = false) const {
        if (!has(key)) return fallback;
        const std::string& t = values_.at(key);
        const std::optional<double> parsed = cloudmath::tools::parse_finite(t);
        const double v = parsed.value_or(0.0);
        if (!parsed || (lo_open ? !(v > lo) : !(v >= lo)) || !(v <= hi)) {
            std::ostringstream m;
            m << "--" << key << " '" << t << "': expected a number in " << (lo_open ? "(" : "[")
              << lo << ", " << hi << "]";
            throw usage_error(m.str());
        }
        return v;
    }
    // Non-negative integer; accepts exponent forms such as 1e6 (strict_number.hpp).
    std::uint64_t count(const std::string& key, std::uint64_t fallback, std::uint64_t lo) const {
        if (!has(key)) return fallback;
        const std::string& t = values_.at(key);
        const std::optional<std::uint64_t> v = cloudmath::tools::parse_count(t);
        if (!v || *v < lo)
            throw usage_error("--" + key + " '" + t + "': expected an integer >= " +
                              std::to_string(lo));
        return *v;
    }

private:
    std::map<std::string, std::string> values_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// "40 s", "12 min", "3.5 h".
std::string duration_text(double seconds) {
    char buf[32];
    if (seconds < 120.0) std::snprintf(buf, sizeof buf, "%.0f s", seconds);
    else if (seconds < 7200.0) std::snprintf(buf, sizeof buf, "%.0f min", seconds / 60.0);
    else std::snprintf(buf, sizeof buf, "%.1f h", seconds / 3600.0);
    return buf;
}

// Single updating progress line on stderr with the time left (extrapolated from the time
// so far, once a second has passed); run_chunks never calls it concurrently.
mc::progress_callback progress_line(const std::string& label) {
    struct state {
        int last = -1;
        std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    };
    auto st = std::make_shared<state>();
    return [label, st](double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (percent == st->last) return;
        st->last = percent;
        const double elapsed = seconds_since(st->start);
        std::string left;
        if (fraction > 0.0 && percent < 100 && elapsed >= 1.0)
            left = ", about " + duration_text(elapsed * (1.0 - fraction) / fraction) + " left";
        std::fprintf(stderr, "\r%s ... %d%%%s   ", label.c_str(), percent, left.c_str());
        if (percent >= 100) std::fputc('\n', stderr);
        std::fflush(stderr);
    };
}

// Refuses a run above max_paths_per_run; what names the count ("--paths 1e9 x 9 rays").
void check_path_budget(double paths, const std::string& what) {
    if (paths <= max_paths_per_run) return;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", paths);
    throw usage_error(what + " = " + buf +
                      " paths: above the limit of 1e10 per run (hours of work); use fewer, or "
                      "split the run over several --seed values");
}

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", v + 0.0);  // + 0.0 turns -0 into 0
    return buf;
}

// The output CSV: its path checked before the computation, so that a bad path fails at
// once without touching an existing file; the text collected in memory and written at the
// end through a temporary file renamed over the path (write_text_file_atomically), so that
// a killed or failed run leaves the old file as it was.
class csv_output {
public:
    explicit csv_output(const std::string& path) : path_(path) {
        if (path_.empty()) return;
        const std::string error = cloudmath::tools::check_output_path(path_);
        if (!error.empty()) throw std::runtime_error(error);
    }
    bool enabled() const { return !path_.empty(); }
    std::ostream& stream() { return text_; }
    void finish() {
        if (enabled()) cloudmath::reference::write_text_file_atomically(path_, text_.str());
    }

private:
    std::string path_;
    std::ostringstream text_;
};

struct common_settings {
    mc::run_options run;
    std::string phase_spec;
    double albedo = 1.0;
};

const std::set<std::string> common_flags = {"phase", "albedo", "max-order", "threads", "seed",
                                            "out"};

common_settings read_common(const flags& f, const std::string& label) {
    common_settings c;
    c.phase_spec = f.text("phase", "hg:0.85");
    c.albedo = f.number("albedo", 1.0, 0.0, 1.0);
    c.run.max_order = static_cast<unsigned>(f.count("max-order", 0, 0));
    c.run.threads = static_cast<unsigned>(f.count("threads", 1, 0));
    c.run.seed = f.count("seed", 1, 0);
    c.run.progress = progress_line(label);
    return c;
}

void write_common_metadata(std::ostream& o, const std::string& command,
                           const common_settings& c, double elapsed) {
    o << "# tool: cloudmath_montecarlo " << command << '\n'
      << "# phase: " << c.phase_spec << '\n'
      << "# albedo: " << fmt(c.albedo) << '\n'
      << "# max_order: " << c.run.max_order << (c.run.max_order == 0 ? " (all orders)" : "")
      << '\n'
      << "# seed: " << c.run.seed << '\n'
      << "# threads: " << c.run.threads << '\n'
      << "# elapsed_s: " << fmt(elapsed) << '\n'
      << "# units: radiance is L/F0 in 1/sr (sun perpendicular irradiance F0 = 1); the "
         "direct solar beam is excluded\n";
}

std::string pm(const mc::estimate& e) { return fmt(e.mean) + " +- " + fmt(e.std_error); }

// ---------------------------------------------------------------------------------------
int run_slab(int argc, char** argv) {
    std::set<std::string> allowed = common_flags;
    allowed.insert({"tau", "mu0", "photons", "bins"});
    const flags f(argc, argv, allowed);
    const common_settings c = read_common(f, "slab");
    mc::slab_parameters slab;
    slab.tau = f.number("tau", 1.0, 0.0, 1e6, true);
    slab.mu0 = f.number("mu0", 1.0, 0.0, 1.0, true);
    slab.albedo = c.albedo;
    const std::uint64_t photons = f.count("photons", 1000000, 1);
    check_path_budget(static_cast<double>(photons), "--photons " + f.text("photons", "1000000"));
    const auto bins = static_cast<unsigned>(f.count("bins", 20, 1));
    if (bins > 100000) throw usage_error("--bins: at most 100000");
    const mc::phase_model phase = mc::make_phase(c.phase_spec);
    csv_output out(f.text("out", ""));

    const auto t0 = std::chrono::steady_clock::now();
    const mc::slab_flux_result r = mc::trace_slab(slab, phase, photons, bins, c.run);
    const double elapsed = seconds_since(t0);

    const double sum = r.reflected.mean + r.transmitted_diffuse.mean +
                       r.transmitted_direct.mean + r.absorbed.mean + r.beyond_max_order.mean;
    std::cout << "R          = " << pm(r.reflected) << '\n'
              << "T_diffuse  = " << pm(r.transmitted_diffuse) << '\n'
              << "T_direct   = " << pm(r.transmitted_direct)
              << "   (exp(-tau/mu0) = " << fmt(std::exp(-slab.tau / slab.mu0)) << ")\n"
              << "A          = " << pm(r.absorbed) << '\n';
    if (c.run.max_order != 0)
        std::cout << "beyond order " << c.run.max_order << " = " << pm(r.beyond_max_order)
                  << '\n';
    std::cout << "R+T+A" << (c.run.max_order != 0 ? "+beyond" : "") << " = " << fmt(sum)
              << "   (mean photon weight " << pm(r.photon_weight) << ")\n";
    if (out.enabled()) {
        std::ostream& o = out.stream();
        write_common_metadata(o, "slab", c, elapsed);
        o << "# tau: " << fmt(slab.tau) << "\n# mu0: " << fmt(slab.mu0)
          << "\n# photons: " << photons << "\n# bins: " << bins
          << "\n# reflected: " << fmt(r.reflected.mean) << " +- " << fmt(r.reflected.std_error)
          << "\n# transmitted_diffuse: " << fmt(r.transmitted_diffuse.mean) << " +- "
          << fmt(r.transmitted_diffuse.std_error)
          << "\n# transmitted_direct: " << fmt(r.transmitted_direct.mean) << " +- "
          << fmt(r.transmitted_direct.std_error) << "\n# absorbed: " << fmt(r.absorbed.mean)
          << " +- " << fmt(r.absorbed.std_error)
          << "\n# beyond_max_order: " << fmt(r.beyond_max_order.mean) << " +- "
          << fmt(r.beyond_max_order.std_error)
          << "\n# histogram: azimuthally averaged radiance over each bin of exit cosine mu "
             "(weight mu dmu); side r = leaving the top, t = leaving the bottom\n"
          << "side,mu_low,mu_high,mu_centre,radiance,std_error\n";
        for (int side = 0; side < 2; ++side) {
            const auto& h = side == 0 ? r.reflected_radiance : r.transmitted_radiance;
            for (std::size_t b = 0; b < h.size(); ++b)
                o << (side == 0 ? "r," : "t,") << fmt(r.mu_edges[b]) << ','
                  << fmt(r.mu_edges[b + 1]) << ',' << fmt(0.5 * (r.mu_edges[b] + r.mu_edges[b + 1]))
                  << ',' << fmt(h[b].mean) << ',' << fmt(h[b].std_error) << '\n';
        }
        out.finish();
    }
    std::cout << "slab done in " << fmt(elapsed) << " s: " << photons << " photons, "
              << fmt(static_cast<double>(photons) / elapsed) << " photons/s\n";
    return 0;
}

int run_slab_radiance(int argc, char** argv) {
    std::set<std::string> allowed = common_flags;
    allowed.insert({"tau", "mu0", "views", "paths"});
    const flags f(argc, argv, allowed);
    const common_settings c = read_common(f, "slab-radiance");
    mc::slab_parameters slab;
    slab.tau = f.number("tau", 1.0, 0.0, 1e6, true);
    slab.mu0 = f.number("mu0", 1.0, 0.0, 1.0, true);
    slab.albedo = c.albedo;
    const std::string view_list = f.text("views", "r:1,0");
    const std::vector<mc::slab_view> views = mc::parse_slab_views(view_list);
    const std::uint64_t paths = f.count("paths", 100000, 1);
    check_path_budget(static_cast<double>(paths) * static_cast<double>(views.size()),
                      "--paths " + f.text("paths", "100000") + " x " + std::to_string(views.size()) +
                          " views");
    const mc::phase_model phase = mc::make_phase(c.phase_spec);
    csv_output out(f.text("out", ""));

    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<mc::estimate> L = mc::slab_radiance(slab, phase, views, paths, c.run);
    const double elapsed = seconds_since(t0);

    std::vector<double> angle(views.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
        angle[i] = mc::slab_view_scattering_angle_deg(slab, views[i]);
        std::cout << (views[i].transmitted ? "t" : "r") << " mu=" << fmt(views[i].mu)
                  << " phi=" << fmt(views[i].phi_deg)
                  << " (single-scattering angle " << fmt(angle[i]) << " deg): L/F0 = " << pm(L[i])
                  << '\n';
    }
    if (out.enabled()) {
        std::ostream& o = out.stream();
        write_common_metadata(o, "slab-radiance", c, elapsed);
        o << "# tau: " << fmt(slab.tau) << "\n# mu0: " << fmt(slab.mu0) << "\n# views: "
          << view_list << "\n# paths_per_view: " << paths
          << "\n# geometry: side r = camera above looking down, t = camera below looking up; "
             "mu = exit cosine; phi_deg = relative azimuth, 0 = camera facing the sun's "
             "azimuth\n"
          << "side,mu,phi_deg,scattering_angle_deg,radiance,std_error\n";
        for (std::size_t i = 0; i < views.size(); ++i)
            o << (views[i].transmitted ? "t," : "r,") << fmt(views[i].mu) << ','
              << fmt(views[i].phi_deg) << ',' << fmt(angle[i]) << ',' << fmt(L[i].mean) << ','
              << fmt(L[i].std_error) << '\n';
        out.finish();
    }
    const double total = static_cast<double>(paths) * static_cast<double>(views.size());
    std::cout << "slab-radiance done in " << fmt(elapsed) << " s: " << views.size()
              << " views x " << paths << " paths, " << fmt(total / elapsed) << " paths/s\n";
    return 0;
}

int run_sphere(int argc, char** argv) {
    std::set<std::string> allowed = common_flags;
    allowed.insert({"tau", "view-angle", "points", "grid", "paths"});
    const flags f(argc, argv, allowed);
    const common_settings c = read_common(f, "sphere");
    mc::sphere_parameters sphere;
    sphere.optical_diameter = f.number("tau", 10.0, 0.0, 1e6, true);
    sphere.albedo = c.albedo;
    const double view_angle = f.number("view-angle", 90.0, 0.0, 180.0);
    if (f.has("points") && f.has("grid")) throw usage_error("give --points or --grid, not both");
    const bool grid = f.has("grid");
    const auto n = static_cast<unsigned>(grid ? f.count("grid", 0, 1) : f.count("points", 9, 1));
    if (n > 4096) throw usage_error("--points/--grid: at most 4096");
    const std::uint64_t paths = f.count("paths", 100000, 1);
    const double rays = grid ? static_cast<double>(n) * static_cast<double>(n) : static_cast<double>(n);
    check_path_budget(static_cast<double>(paths) * rays, "--paths " + f.text("paths", "100000") + " x " +
                                                             std::to_string(static_cast<std::uint64_t>(rays)) + " rays");
    const mc::phase_model phase = mc::make_phase(c.phase_spec);
    csv_output out(f.text("out", ""));

    const mc::sphere_camera cam = grid ? mc::make_sphere_camera_grid(view_angle, n)
                                       : mc::make_sphere_camera_line(view_angle, n);
    sphere.sun_direction = cam.sun_direction;
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<mc::estimate> L = mc::sphere_radiance(sphere, phase, cam.rays, paths, c.run);
    const double elapsed = seconds_since(t0);

    if (!grid)
        for (std::size_t i = 0; i < L.size(); ++i)
            std::cout << "u=" << fmt(cam.u[i]) << ": L/F0 = " << pm(L[i]) << '\n';
    if (out.enabled()) {
        std::ostream& o = out.stream();
        write_common_metadata(o, "sphere", c, elapsed);
        o << "# optical_diameter: " << fmt(sphere.optical_diameter)
          << "\n# view_angle_deg: " << fmt(view_angle) << "\n# camera: "
          << (grid ? "grid " : "line ") << n << "\n# paths_per_ray: " << paths
          << "\n# geometry: sphere of radius 1 at the origin, sun toward +z, orthographic "
             "camera looking along (sin a, 0, cos a); u along the sun/view plane (u > 0 "
             "sunward), v = view x u\n"
          << "index,u,v,origin_x,origin_y,origin_z,dir_x,dir_y,dir_z,radiance,std_error\n";
        for (std::size_t i = 0; i < L.size(); ++i) {
            const mc::ray& r = cam.rays[i];
            o << i << ',' << fmt(cam.u[i]) << ',' << fmt(cam.v[i]) << ',' << fmt(r.origin.x)
              << ',' << fmt(r.origin.y) << ',' << fmt(r.origin.z) << ',' << fmt(r.direction.x)
              << ',' << fmt(r.direction.y) << ',' << fmt(r.direction.z) << ','
              << fmt(L[i].mean) << ',' << fmt(L[i].std_error) << '\n';
        }
        out.finish();
    }
    const double total = static_cast<double>(paths) * static_cast<double>(cam.rays.size());
    std::cout << "sphere done in " << fmt(elapsed) << " s: " << cam.rays.size() << " rays x "
              << paths << " paths, " << fmt(total / elapsed) << " paths/s\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return cloudmath::reference::run_subcommand_tool("cloudmath_montecarlo", usage_text, argc, argv, [&](const std::string& command) {
        if (command == "slab") return run_slab(argc, argv);
        if (command == "slab-radiance") return run_slab_radiance(argc, argv);
        if (command == "sphere") return run_sphere(argc, argv);
        throw usage_error("unknown command '" + command + "' (slab, slab-radiance, sphere)");
    });
}
