// tools/reference/truths/lighting_report.cpp: see lighting_report.hpp.
#include "lighting_report.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <cloudmath/diffusion_lighting.hpp>
#include <cloudmath/multiple_scattering.hpp>

#include "lighting_diffusion.hpp"
#include "phase_error.hpp"  // xml_escape
#include "strict_number.hpp"

namespace cloudmath::reference::lighting {

namespace {

// Fits evaluate thousands of models: 1-optical-unit panels (8 Gauss-Legendre nodes each)
// agree with the 0.25-unit default to better than 1e-7 relative, 1e-4 for the Nubis form
// whose max() has a kink (tested); the errors measured here are 1e-1 and more.
constexpr double fit_panel = 1.0;

bool sphere_sun_behind(const reference_row& r) { return r.is_sphere() && r.sun_deg <= 60.0; }

std::string num(double v, int digits = 3) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}
// A C++ float literal: "1.0f", "0.7094f", "1e-05f".
std::string float_literal(double v, int digits) {
    std::string s = num(v, digits);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s + 'f';
}
std::string pct(double v) {
    if (!std::isfinite(v)) return "inf";
    char buf[48];
    std::snprintf(buf, sizeof buf, v < 0.1 ? "%.1f%%" : "%.0f%%", 100.0 * v);
    return buf;
}
std::string signed_pct(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%+.0f%%", 100.0 * v);
    return buf;
}

const char* form_label(attenuation f) {
    switch (f) {
        case attenuation::beer: return "octaves";
        case attenuation::powder: return "octaves + Beer-Powder";
        case attenuation::nubis: return "octaves + Nubis attenuation";
    }
    return "?";
}

struct variant {
    std::string id, label;
    model_spec spec;
    std::vector<double> radiance;  // per reference row
    bool in_tables = true;         // false: only in the CSV
    // Models that are not octaves (the diffusion model): their form name and cost, which
    // replace attenuation_name(spec.form) and model_cost(spec) when set.
    std::string form;
    int cost = -1;
};

std::string form_of(const variant& v) { return v.form.empty() ? attenuation_name(v.spec.form) : v.form; }
int cost_of(const variant& v) { return v.cost >= 0 ? v.cost : model_cost(v.spec); }

// ---------------------------------------------------------------------------------------
// SVG: rms error per optical thickness, one polyline per variant; log x, log y.
const char* const palette[] = {"#000000", "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                               "#9467bd", "#8c564b", "#e377c2", "#17becf", "#7f7f7f"};

// One legend line: a short stroke in the curve's colour at (x, y - 4) and its label.
void legend_entry(std::ostringstream& s, double x, double y, const char* colour,
                  const std::string& label) {
    s << "<line x1=\"" << x << "\" x2=\"" << x + 24 << "\" y1=\"" << y - 4 << "\" y2=\"" << y - 4
      << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/><text x=\"" << x + 30 << "\" y=\""
      << y << "\">" << xml_escape(label) << "</text>\n";
}

std::string svg_error_vs_tau(const reference_set& set, const std::vector<variant>& vs,
                             const std::vector<double>& taus, const std::string& title) {
    const double W = 920, H = 440, left = 70, right = 370, top = 40, bottom = 50;
    const double pw = W - left - right, ph = H - top - bottom;
    const double x0 = std::log10(taus.front()), x1 = std::log10(taus.back());
    const double y0 = -2.0, y1 = 1.0;  // 1% .. 1000%
    auto X = [&](double tau) { return left + (std::log10(tau) - x0) / (x1 - x0) * pw; };
    auto Y = [&](double e) {
        const double l = std::clamp(std::log10(std::max(e, 1e-2)), y0, y1);
        return top + (y1 - l) / (y1 - y0) * ph;
    };
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n<text x=\"" << left << "\" y=\"22\" font-size=\"14\">"
      << xml_escape(title) << "</text>\n";
    for (int d = -2; d <= 1; ++d) {
        const double y = Y(std::pow(10.0, d));
        s << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << y << "\" y2=\""
          << y << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 6 << "\" y=\"" << y + 4
          << "\" text-anchor=\"end\">" << pct(std::pow(10.0, d)) << "</text>\n";
    }
    for (double t : taus) {
        const double x = X(t);
        s << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << top << "\" y2=\"" << top + ph
          << "\" stroke=\"#eee\"/>\n<text x=\"" << x << "\" y=\"" << top + ph + 16
          << "\" text-anchor=\"middle\">" << num(t) << "</text>\n";
    }
    s << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 10
      << "\" text-anchor=\"middle\">optical thickness (sphere diameter, slab thickness)</text>\n"
      << "<text transform=\"translate(16," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">rms relative error</text>\n"
      << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (std::size_t v = 0; v < vs.size(); ++v) {
        const char* colour = palette[v % 10];
        s << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.8\"";
        if (v >= 10) s << " stroke-dasharray=\"5,3\"";
        s << " points=\"";
        for (double t : taus) {
            const error_summary e = measure(set, vs[v].radiance, [t](const reference_row& r) {
                return r.tau == t;
            });
            s << X(t) << ',' << Y(e.rms) << ' ';
        }
        s << "\"/>\n";
        legend_entry(s, W - right + 12, top + 14 + 18.0 * static_cast<double>(v), colour, vs[v].label);
    }
    s << "</svg>\n";
    return s.str();
}

// SVG: radiance across the sphere (image coordinate u) for one thickness and view angle:
// the Monte Carlo with 2-sigma bars and the models as polylines; linear axes.
std::string svg_sphere_profile(const reference_set& set, const std::vector<variant>& vs,
                               double tau, double angle) {
    // The sphere configuration of the reference nearest to the one asked for.
    double best = HUGE_VAL, near_tau = tau, near_angle = angle;
    for (const reference_row& r : set.rows)
        if (r.is_sphere()) {
            const double d = std::abs(std::log(r.tau / tau)) + std::abs(r.sun_deg - angle) / 30.0;
            if (d < best) {
                best = d;
                near_tau = r.tau;
                near_angle = r.sun_deg;
            }
        }
    tau = near_tau;
    angle = near_angle;
    std::vector<std::size_t> rows;
    for (std::size_t i = 0; i < set.rows.size(); ++i)
        if (set.rows[i].is_sphere() && set.rows[i].tau == tau && set.rows[i].sun_deg == angle)
            rows.push_back(i);
    std::sort(rows.begin(), rows.end(),
              [&](std::size_t a, std::size_t b) { return set.rows[a].u < set.rows[b].u; });
    double ymax = 0.0;
    for (std::size_t i : rows) {
        ymax = std::max(ymax, set.rows[i].radiance + 2 * set.rows[i].std_error);
        for (const variant& v : vs) ymax = std::max(ymax, v.radiance[i]);
    }
    ymax = ymax > 0.0 ? 1.05 * ymax : 1.0;
    const double W = 920, H = 420, left = 70, right = 370, top = 40, bottom = 50;
    const double pw = W - left - right, ph = H - top - bottom;
    auto X = [&](double u) { return left + (u + 1.0) / 2.0 * pw; };
    auto Y = [&](double L) { return top + (1.0 - L / ymax) * ph; };
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n<text x=\"" << left << "\" y=\"22\" font-size=\"14\">"
      << "Sphere, optical diameter " << num(tau) << ", view " << num(angle)
      << " deg from the sun: radiance across the diameter</text>\n";
    for (int k = 0; k <= 4; ++k) {
        const double L = ymax * k / 4.0, y = Y(L);
        s << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << y << "\" y2=\"" << y
          << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 6 << "\" y=\"" << y + 4
          << "\" text-anchor=\"end\">" << num(L, 2) << "</text>\n";
    }
    for (int k = -2; k <= 2; ++k)
        s << "<text x=\"" << X(k / 2.0) << "\" y=\"" << top + ph + 16
          << "\" text-anchor=\"middle\">" << num(k / 2.0) << "</text>\n";
    s << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 10
      << "\" text-anchor=\"middle\">image coordinate u (radii; u &gt; 0 toward the sun)</text>\n"
      << "<text transform=\"translate(16," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">L / F0 (1/sr)</text>\n<rect x=\"" << left
      << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (std::size_t i : rows) {
        const reference_row& r = set.rows[i];
        s << "<line x1=\"" << X(r.u) << "\" x2=\"" << X(r.u) << "\" y1=\""
          << Y(r.radiance - 2 * r.std_error) << "\" y2=\"" << Y(r.radiance + 2 * r.std_error)
          << "\" stroke=\"black\"/><circle cx=\"" << X(r.u) << "\" cy=\"" << Y(r.radiance)
          << "\" r=\"3\"/>\n";
    }
    s << "<circle cx=\"" << W - right + 24 << "\" cy=\"" << top + 10 << "\" r=\"3\"/><text x=\""
      << W - right + 42 << "\" y=\"" << top + 14 << "\">Monte Carlo, 2 sigma</text>\n";
    for (std::size_t v = 0; v < vs.size(); ++v) {
        const char* colour = palette[(v + 1) % 10];
        s << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.8\" points=\"";
        for (std::size_t i : rows) s << X(set.rows[i].u) << ',' << Y(vs[v].radiance[i]) << ' ';
        s << "\"/>\n";
        legend_entry(s, W - right + 12, top + 32 + 18.0 * static_cast<double>(v), colour, vs[v].label);
    }
    s << "</svg>\n";
    return s.str();
}

// Runs jobs on every core, in any order; job(i) must be independent of the others.
void parallel_for(std::size_t count, const std::function<void(std::size_t)>& job) {
    const unsigned threads = std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(),
                                                             static_cast<unsigned>(count)));
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex m;
    auto worker = [&] {
        for (std::size_t i; (i = next++) < count;) {
            try {
                job(i);
            } catch (...) {
                std::lock_guard<std::mutex> lock(m);
                if (!error) error = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

// The set's optical thicknesses, each once, ascending.
std::vector<double> optical_thicknesses(const reference_set& set) {
    std::vector<double> taus;
    for (const reference_row& r : set.rows)
        if (std::find(taus.begin(), taus.end(), r.tau) == taus.end()) taus.push_back(r.tau);
    std::sort(taus.begin(), taus.end());
    return taus;
}

double medium_g(const reference_set& set) {
    if (set.phase_spec.rfind("hg:", 0) != 0)
        throw std::runtime_error("lighting report: the reference phase must be hg:G (the models' "
                                 "octaves are HG), got '" + set.phase_spec + "'");
    const std::optional<double> g = cloudmath::tools::parse_finite(set.phase_spec.substr(3));
    if (!g || !(*g > -1.0 && *g < 1.0))
        throw std::runtime_error("lighting report: the reference phase hg:G needs a number G in (-1, 1), got '" +
                                 set.phase_spec + "'");
    return *g;
}

}  // namespace

const std::vector<row_subset>& fit_ranges() {
    static const std::vector<row_subset> r{
        {"all", "optical thickness 1-100", [](const reference_row&) { return true; }},
        {"thin", "optical thickness 1-10", [](const reference_row& row) { return row.tau <= 10.0; }},
        {"thick", "optical thickness 10-100", [](const reference_row& row) { return row.tau >= 10.0; }},
    };
    return r;
}

const std::vector<row_subset>& report_subsets() {
    static const std::vector<row_subset> s{
        {"all", "all", [](const reference_row&) { return true; }},
        {"tau_1_2", "tau 1-2", [](const reference_row& r) { return r.tau <= 2.0; }},
        {"tau_5_10", "tau 5-10", [](const reference_row& r) { return r.tau >= 5.0 && r.tau <= 10.0; }},
        {"tau_20_100", "tau 20-100", [](const reference_row& r) { return r.tau >= 20.0; }},
        {"sphere_sun_behind", "sphere, sun behind it (view 30-60 deg)", sphere_sun_behind},
        {"sphere_side", "sphere, side-lit (90-120 deg)",
         [](const reference_row& r) { return r.is_sphere() && r.sun_deg >= 90.0 && r.sun_deg <= 120.0; }},
        {"sphere_front", "sphere, sun behind the camera (150-170 deg)",
         [](const reference_row& r) { return r.is_sphere() && r.sun_deg >= 150.0; }},
        {"slab_reflected", "slab, reflected",
         [](const reference_row& r) { return r.geometry == "slab_reflected"; }},
        {"slab_transmitted", "slab, transmitted",
         [](const reference_row& r) { return r.geometry == "slab_transmitted"; }},
        {"slab_low_sun", "slab, sun 80 deg from zenith",
         [](const reference_row& r) { return !r.is_sphere() && r.sun_deg >= 79.0; }},
    };
    return s;
}

int model_cost(const model_spec& s) {
    switch (s.form) {
        case attenuation::beer: return s.octaves;
        case attenuation::powder: return s.octaves + 1;
        case attenuation::nubis: return 2 * s.octaves;
    }
    return s.octaves;
}

report_summary write_report(const report_options& o) {
    const auto t_start = std::chrono::steady_clock::now();
    auto say = [&](const std::string& line) {
        if (o.log) o.log(line);
    };
    const reference_set set = read_reference(o.reference_path);
    const double g = medium_g(set);
    const evaluator ev(set, fit_panel);
    report_summary summary;
    summary.rows = set.rows.size();

    const std::vector<double> taus = optical_thicknesses(set);

    // Every fit range needs rows with radiance > 0: a reference without them is a data
    // failure of that file (exit 1 naming it), not a bad command line (fit_octaves'
    // invalid_argument, exit 2, named no file).
    for (const row_subset& range : fit_ranges()) {
        std::size_t selected = 0;
        for (const reference_row& r : set.rows) if (row_counts(r, range.select)) ++selected;
        if (selected == 0)
            throw std::runtime_error(o.reference_path + ": no row with radiance > 0 in the fit range '" + range.id +
                                     "' (" + std::to_string(set.rows.size()) +
                                     " rows read): the report fits every range (all, thin, thick)");
    }

    // --- Fits: every range x form x octave count.
    const attenuation forms[] = {attenuation::beer, attenuation::powder, attenuation::nubis};
    struct fit_job {
        std::size_t range;
        attenuation form;
        int octaves;
        lighting_fit result;
    };
    std::vector<fit_job> jobs;
    for (std::size_t r = 0; r < fit_ranges().size(); ++r)
        for (attenuation f : forms)
            for (int n = 1; n <= max_octaves; ++n) jobs.push_back({r, f, n, {}});
    std::mutex log_mutex;
    std::size_t done = 0;
    parallel_for(jobs.size(), [&](std::size_t i) {
        fit_job& j = jobs[i];
        j.result = fit_octaves(ev, set, j.form, j.octaves, g, fit_ranges()[j.range].select);
        std::lock_guard<std::mutex> lock(log_mutex);
        ++done;
        say("fit " + std::to_string(done) + "/" + std::to_string(jobs.size()) + ": " +
            fit_ranges()[j.range].id + " " + describe(j.result.spec) + " residual " +
            num(j.result.residual, 4));
    });
    summary.fits = jobs.size();
    auto find_fit = [&](std::size_t range, attenuation f, int n) -> const lighting_fit& {
        for (const fit_job& j : jobs)
            if (j.range == range && j.form == f && j.octaves == n) return j.result;
        throw std::logic_error("missing fit");
    };
    // Chosen octave count per range and form.
    auto chosen_octaves = [&](std::size_t range, attenuation f) {
        double best = HUGE_VAL;
        for (int n = 1; n <= max_octaves; ++n) best = std::min(best, find_fit(range, f, n).residual);
        for (int n = 1; n <= max_octaves; ++n)
            if (find_fit(range, f, n).residual <= best + octave_tolerance) return n;
        return max_octaves;
    };

    // --- Variants of the error tables.
    std::vector<variant> vs;
    auto add = [&](const std::string& id, const std::string& label, const model_spec& s) {
        vs.push_back({id, label, s, ev.radiance(s), true, {}, -1});
    };
    add("single", "single scattering", {attenuation::beer, g, 1, 1, 1, 1});
    add("default_beer_2", "octaves, a = b = c = 0.5, N = 2", {attenuation::beer, g, 0.5, 0.5, 0.5, 2});
    for (attenuation f : forms)
        add(std::string("default_") + attenuation_name(f),
            std::string(form_label(f)) + ", a = b = c = 0.5, N = 3", {f, g, 0.5, 0.5, 0.5, 3});
    for (attenuation f : forms) {
        const int n = chosen_octaves(0, f);
        add(std::string("fit_") + attenuation_name(f),
            std::string(form_label(f)) + ", fitted, N = " + std::to_string(n),
            find_fit(0, f, n).spec);
    }
    // The production values at every other octave count, for the speed-vs-error report's
    // physical-reference column (CSV only).
    for (int n = 4; n <= max_octaves; ++n) {
        add("default_beer_" + std::to_string(n),
            "octaves, a = b = c = 0.5, N = " + std::to_string(n), {attenuation::beer, g, 0.5, 0.5, 0.5, n});
        vs.back().in_tables = false;
    }
    const std::size_t first_preset = vs.size();
    for (const multiple_scattering_preset& p : ms_preset::all)
        add(std::string("preset_") + p.name, std::string("preset ms_preset::") + p.name,
            {attenuation::beer, g, double(p.a), double(p.b), double(p.c), p.octaves});
    // The diffusion models (cloudmath/diffusion_lighting.hpp): 3 exponentials per sample and
    // two more inputs than the octaves (tau_behind, tau_view).
    const diffusion_evaluator dev(set);
    for (const diffusion_model& m : diffusion_models::all) {
        vs.push_back({std::string("preset_diffusion_") + m.name,
                      std::string("diffusion model diffusion_models::") + m.name + " (3 inputs)",
                      {attenuation::beer, g, 0, 0, 0, 0}, dev.radiance(m), true, "diffusion", 3});
    }

    // --- CSV: every variant x subset, then every fit.
    std::ostringstream csv;
    csv << "# generated by cloudmath_lighting_error report from " << o.reference_path << "\n"
        << "kind,id,form,octaves,a,b,c,subset,rows,rms,bias,max,cost\n";
    for (const variant& v : vs)
        for (const row_subset& sub : report_subsets()) {
            const error_summary e = measure(set, v.radiance, sub.select);
            csv << "variant," << v.id << ',' << form_of(v) << ','
                << v.spec.octaves << ',' << num(v.spec.a, 6) << ',' << num(v.spec.b, 6) << ','
                << num(v.spec.c, 6) << ',' << sub.id << ',' << e.rows << ',' << num(e.rms, 6)
                << ',' << num(e.bias, 6) << ',' << num(e.max, 6) << ',' << cost_of(v)
                << '\n';
        }
    for (const fit_job& j : jobs) {
        const std::vector<double> L = ev.radiance(j.result.spec);
        const error_summary e = measure(set, L, fit_ranges()[j.range].select);
        csv << "fit,fit_" << fit_ranges()[j.range].id << ',' << attenuation_name(j.form) << ','
            << j.octaves << ',' << num(j.result.spec.a, 6) << ',' << num(j.result.spec.b, 6)
            << ',' << num(j.result.spec.c, 6) << ',' << fit_ranges()[j.range].id << ','
            << e.rows << ',' << num(e.rms, 6) << ',' << num(e.bias, 6) << ',' << num(e.max, 6)
            << ',' << model_cost(j.result.spec) << '\n';
    }

    // --- Markdown.
    std::ostringstream md;
    auto meta = [&](const std::string& key) {
        for (const auto& [k, v] : set.metadata)
            if (k == key) return v;
        return std::string("?");
    };
    std::size_t sphere_rows = 0;
    for (const reference_row& r : set.rows) sphere_rows += r.is_sphere();
    md << "# Lighting models against the Monte Carlo reference\n\n"
       << "Generated by `cloudmath_lighting_error report --reference " << o.reference_path
       << "` from the repository root (source: [tools/reference/truths/lighting_report.cpp]"
          "(../tools/reference/truths/lighting_report.cpp), [lighting_error.cpp]"
          "(../tools/reference/truths/lighting_error.cpp), [lighting_models.cpp]"
          "(../tools/reference/truths/lighting_models.cpp)); do not edit by hand. The reference is "
          "made by `cloudmath_lighting_error reference` (in " << meta("elapsed_s")
       << " s on this machine's 2 cores) and `bash scripts/reference.sh` runs both. Every "
          "number below, per variant and subset, is also in [lighting_error.csv]"
          "(lighting_error.csv).\n\n"
       << "## What is compared\n\n"
       << "**Reference** ([data/lighting_reference.csv](data/lighting_reference.csv)): the "
          "Monte Carlo path tracer of tools/reference/transport/montecarlo.hpp (all orders of scattering, "
          "double precision), phase function `" << set.phase_spec << "`, albedo "
       << num(set.albedo) << ", " << set.rows.size() << " camera rays: " << sphere_rows
       << " on a sphere (optical diameter " << num(taus.front()) << " to " << num(taus.back())
       << "; an orthographic camera 30, 60, 90, 120, 150 and 170 deg from the sun, 9 rays "
          "across the diameter in the sun's plane) and " << set.rows.size() - sphere_rows
       << " leaving a slab (optical thickness " << num(taus.front()) << " to "
       << num(taus.back()) << ", sun 0, 60 and 80 deg from the zenith, reflected and "
          "transmitted views at exit cosines 1 and 0.5 toward and away from the sun). Paths per "
          "ray: " << meta("paths_per_ray") << "; the reference's own noise (the rms of each "
          "ray's standard error over its image's mean) is " << pct(noise_floor(set, select_all()))
       << ", the floor of every error below.\n\n"
       << "**Models** (tools/reference/truths/lighting_models.hpp): what a real-time renderer "
          "integrates along a camera ray, L = integral of T_view sigma_s M(tau_light, mu) ds with "
          "tau_light the exact optical depth toward the sun and M the sun term: single "
          "scattering HG(mu, g); Wrenninge's octaves sum_{i<N} b^i HG(mu, c^i g) exp(-a^i "
          "tau_light) (cloudmath::multiple_scattering); the same times the Beer-Powder factor "
          "mix(2 (1 - e^(-2 tau_light)), 1, (1 + mu)/2) as the example renderer applies it; the "
          "octaves with Nubis' attenuation max(e^(-a^i tau), 0.7 e^(-a^i tau / 4)) in every "
          "octave; and the diffusion models of cloudmath/diffusion_lighting.hpp, which also see "
          "the optical depth behind the sample along the sun and the optical depth from the "
          "camera (fitted on this reference and two more phase functions over the same rays; "
          "their error on a held-out split is in [lighting_research.md](lighting_research.md)). "
          "The medium's HG g = " << num(g) << " in the models and in the reference, so "
          "the errors are those of the multiple-scattering approximation alone (the phase "
          "function's own error against Mie is in [phase_error.md](phase_error.md)). The ray "
          "integral is evaluated to 1e-7 (1e-4 with the Nubis kink), not ray-marched.\n\n"
       << "**Error**: the rays of one geometry (sphere; slab reflected; slab transmitted), "
          "thickness and sun angle form an image; each ray's error is e = (L_model - L_MC) / "
          "(the image's mean L_MC), relative to the image's typical brightness as a viewer "
          "judges it (per-ray relative errors would be decided by the darkest rays, where the "
          "octave models are 1e9 times too dark behind thick media). *rms* = sqrt(mean e^2), "
          "*bias* = mean e (< 0: too dark), *max* = max |e|. The sphere's rays and the slab's "
          "views count half each. *Cost*: exponentials per sample (N octaves, +1 for the powder "
          "factor, 2N with the Nubis attenuation, 3 for the diffusion models, which also need "
          "the optical depth behind the sample: a second light march in a renderer).\n\n"
       << "**Fits**: a, b, c in (0, 1) minimising the rms over a range of thickness, by "
          "Nelder-Mead in logistic coordinates from three starting points (the best is kept); "
          "for each form, N is the smallest octave count within "
       << pct(octave_tolerance) << " rms of the best N <= " << max_octaves << ".\n\n";

    auto error_table = [&](const std::vector<std::size_t>& subsets) {
        md << "| Model | Cost |";
        for (std::size_t k : subsets) md << ' ' << report_subsets()[k].label << " |";
        md << "\n|---|---|";
        for (std::size_t k = 0; k < subsets.size(); ++k) md << "---|";
        md << '\n';
        for (const variant& v : vs) {
            if (!v.in_tables) continue;
            md << "| " << v.label << " | " << cost_of(v) << " |";
            for (std::size_t k : subsets) {
                const error_summary e = measure(set, v.radiance, report_subsets()[k].select);
                md << ' ' << pct(e.rms) << " / " << signed_pct(e.bias) << " / " << pct(e.max) << " |";
            }
            md << '\n';
        }
        md << '\n';
    };
    md << "## Error by optical thickness\n\nEach cell: rms / bias / max.\n\n";
    error_table({0, 1, 2, 3});
    md << "![rms error per optical thickness](images/lighting_error_vs_tau.svg)\n\n";
    md << "## Error by geometry and sun\n\nEach cell: rms / bias / max.\n\n";
    error_table({4, 5, 6, 7, 8, 9});
    md << "![sphere profile](images/lighting_error_sphere_profile.svg)\n\n";

    // Best model per use.
    md << "## Cheapest model per use\n\nCandidates: every fitted model (each form and octave "
          "count, fitted to the range) and the models with a = b = c = 0.5. *Within 10%* and "
          "*within 1%*: the lowest cost whose rms over the range is at most 10% or 1% (ties: the "
          "smaller rms). *Lowest rms*: the most accurate candidate; *near the lowest*: the "
          "cheapest one whose rms is within 10% (relative) of the lowest.\n\n"
       << "| Range | rms <= 10% | rms <= 1% | Lowest rms | Near the lowest |\n|---|---|---|---|---|\n";
    for (std::size_t r = 0; r < fit_ranges().size(); ++r) {
        std::vector<std::pair<model_spec, double>> cands;
        for (const fit_job& j : jobs)
            if (j.range == r) cands.emplace_back(j.result.spec, j.result.residual);
        for (std::size_t v = 0; v < first_preset; ++v)
            cands.emplace_back(vs[v].spec, measure(set, vs[v].radiance, fit_ranges()[r].select).rms);
        double lowest = HUGE_VAL;
        for (const auto& c : cands) lowest = std::min(lowest, c.second);
        auto cell = [&](double bound, bool by_rms) {
            const std::pair<model_spec, double>* best = nullptr;
            for (const auto& c : cands) {
                if (c.second > bound) continue;
                const bool better = !best ||
                    (by_rms ? c.second < best->second
                            : model_cost(c.first) < model_cost(best->first) ||
                                  (model_cost(c.first) == model_cost(best->first) && c.second < best->second));
                if (better) best = &c;
            }
            if (!best) return std::string("none");
            return describe(best->first) + " (cost " + std::to_string(model_cost(best->first)) +
                   ", rms " + pct(best->second) + ")";
        };
        md << "| " << fit_ranges()[r].label << " | " << cell(0.10, false) << " | "
           << cell(0.01, false) << " | " << cell(lowest, true) << " | "
           << cell(1.1 * lowest, false) << " |\n";
    }
    md << '\n';

    // Fits per range.
    for (std::size_t r = 0; r < fit_ranges().size(); ++r) {
        md << "## Fits, " << fit_ranges()[r].label << "\n\n| N |";
        for (attenuation f : forms) md << ' ' << form_label(f) << ": a, b, c | rms |";
        md << "\n|---|";
        for (std::size_t k = 0; k < 3; ++k) md << "---|---|";
        md << '\n';
        for (int n = 1; n <= max_octaves; ++n) {
            md << "| " << n << " |";
            for (attenuation f : forms) {
                const lighting_fit& fit = find_fit(r, f, n);
                const bool chosen = n == chosen_octaves(r, f);
                const char* mark = chosen ? "**" : "";
                if (n == 1)
                    md << " (nothing to fit) |";
                else
                    md << ' ' << mark << num(fit.spec.a, 3) << ", " << num(fit.spec.b, 3) << ", "
                       << num(fit.spec.c, 3) << mark << " |";
                md << ' ' << mark << pct(fit.residual) << mark << " |";
            }
            md << '\n';
        }
        md << "\nBold: the chosen octave count of each form.\n\n";
    }

    // Library presets.
    md << "## The library's presets\n\ncloudmath::ms_preset in include/cloudmath/"
          "multiple_scattering.hpp, with the error documented there (rms and max over their "
          "range, measured here; tools/reference/truths/test_lighting_presets.cpp checks that the "
          "documented numbers are reproduced from the reference CSV):\n\n"
       << "| Preset | a, b, c | N | Range | rms | max |\n|---|---|---|---|---|---|\n";
    for (const multiple_scattering_preset& p : ms_preset::all) {
        const model_spec s{attenuation::beer, g, double(p.a), double(p.b), double(p.c), p.octaves};
        const double lo = double(p.tau_min), hi = double(p.tau_max);
        const error_summary e = measure(set, ev.radiance(s), [lo, hi](const reference_row& r) {
            return r.tau >= lo && r.tau <= hi;
        });
        md << "| " << p.name << " | " << num(p.a, 4) << ", " << num(p.b, 4) << ", "
           << num(p.c, 4) << " | " << p.octaves << " | " << num(lo) << "-" << num(hi) << " | "
           << num(100.0 * e.rms, 4) << "% | " << num(100.0 * e.max, 4) << "% |\n";
    }
    md << '\n';

    if (!o.choice_header.empty()) {
        const std::size_t slash = o.reference_path.find_last_of('/');
        write_text_file_atomically(o.choice_header,
                                   lighting_choice_header(set, o.reference_path.substr(slash + 1)));
    }
    write_text_file_atomically(o.docs_dir + "/lighting_error.md", md.str());
    write_text_file_atomically(o.docs_dir + "/lighting_error.csv", csv.str());

    std::vector<variant> plot;
    for (std::size_t v = 0; v < vs.size(); ++v)
        if (vs[v].in_tables && (v < first_preset || vs[v].id == "preset_diffusion_fitted"))
            plot.push_back(vs[v]);
    write_text_file_atomically(o.images_dir + "/lighting_error_vs_tau.svg",
               svg_error_vs_tau(set, plot, taus, "Lighting models against Monte Carlo: rms "
                                                 "error per optical thickness (sphere and slab)"));
    std::vector<variant> profile;
    for (const variant& v : vs)
        if (v.id == "single" || v.id == "default_beer" || v.id == "default_powder" ||
            v.id == "fit_beer" || v.id == "fit_nubis" || v.id == "preset_diffusion_fitted")
            profile.push_back(v);
    write_text_file_atomically(o.images_dir + "/lighting_error_sphere_profile.svg",
               svg_sphere_profile(set, profile, 10.0, 90.0));
    summary.images = 2;
    say("report written in " +
        num(std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count()) +
        " s");
    return summary;
}

std::string lighting_choice_header(const reference_set& set, const std::string& reference_name) {
    const std::vector<double> taus = optical_thicknesses(set);
    const double g = medium_g(set);
    const evaluator ev(set);
    const diffusion_evaluator dev(set);
    struct entry {
        std::string name, kind, octaves, diffusion;
        int exponentials, extra_inputs;
        std::vector<double> radiance;
    };
    std::vector<entry> models;
    for (const multiple_scattering_preset& p : ms_preset::all)
        models.push_back({std::string("ms_preset::") + p.name, "octaves", std::string("&ms_preset::") + p.name,
                          "nullptr", p.octaves, 0,
                          ev.radiance({attenuation::beer, g, double(p.a), double(p.b), double(p.c), p.octaves})});
    for (const diffusion_model& m : diffusion_models::all)
        models.push_back({std::string("diffusion_models::") + m.name, "diffusion", "nullptr",
                          std::string("&diffusion_models::") + m.name, 3, 2, dev.radiance(m)});
    std::ostringstream h;
    h << "// cloudmath/lighting_choice_data.hpp: the measured errors behind choose_lighting_model\n"
         "// (lighting_choice.hpp). Generated by cloudmath_lighting_error report from\n// "
      << reference_name << " (phase " << set.phase_spec
      << "); do not edit.\n// rms[i][t]: the rms of (L_model - L_MC) / image mean of model i over the\n"
         "// reference's rays of optical thickness thickness[t].\n"
         "// Included by lighting_choice.hpp between its types and its functions. Included first,\n"
         "// it lets lighting_choice.hpp include it again in that place (the guard is set only\n"
         "// around the data), so either header can come first.\n"
         "#ifndef CLOUDMATH_LIGHTING_CHOICE_DATA_HPP\n#include \"lighting_choice.hpp\"\n#endif\n\n"
         "#ifndef CLOUDMATH_LIGHTING_CHOICE_DATA_HPP\n#define CLOUDMATH_LIGHTING_CHOICE_DATA_HPP\n\n"
         "namespace cloudmath::lighting_choice_data {\n\n"
      << "inline constexpr int thickness_count = " << taus.size() << ";\n"
      << "inline constexpr float thickness[thickness_count] = {";
    for (std::size_t t = 0; t < taus.size(); ++t) h << (t ? ", " : "") << float_literal(taus[t], 6);
    h << "};\ninline constexpr int model_count = " << models.size() << ";\n"
      << "inline constexpr lighting_model_record models[model_count] = {\n";
    for (const entry& e : models)
        h << "    {\"" << e.name << "\", lighting_model_kind::" << e.kind << ", " << e.octaves << ", "
          << e.diffusion << ", " << e.exponentials << ", " << e.extra_inputs << "},\n";
    h << "};\ninline constexpr float rms[model_count][thickness_count] = {\n";
    for (const entry& e : models) {
        h << "    {";
        for (std::size_t t = 0; t < taus.size(); ++t) {
            const double tau = taus[t];
            const error_summary err = measure(set, e.radiance, [tau](const reference_row& r) { return r.tau == tau; });
            h << (t ? ", " : "") << float_literal(err.rms, 4);
        }
        h << "},  // " << e.name << "\n";
    }
    h << "};\n\n}  // namespace cloudmath::lighting_choice_data\n\n#endif  // CLOUDMATH_LIGHTING_CHOICE_DATA_HPP\n";
    return h.str();
}

}  // namespace cloudmath::reference::lighting
