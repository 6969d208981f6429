// cloudmath_phase_error: compares cloudmath's analytic phase functions (HG, dual-lobe HG,
// Cornette-Shanks, Draine, Jendersie-d'Eon) with Lorenz-Mie phase tables and writes the
// report: DOCS/phase_error.md (method, regions, metrics, one results table per Mie table,
// plots), DOCS/phase_error.csv (one row per table and model variant) and three SVGs per
// table in IMAGES (phase_error_<name>.svg, phase_polar_<name>.svg, phase_forward_<name>.svg,
// <name> = the table's file name without .csv).
//
//   cloudmath_phase_error [--docs DIR] [--images DIR] TABLE...
//
// TABLEs are phase_table CSV files (tools/reference/optics/phase_table.hpp); the metadata keys
// distribution, wavelength_um and r_eff_um are shown when present (r_eff_um gives the
// Jendersie-d'Eon variant at d = 2 r_eff). Method: phase_error.hpp. Output is deterministic.
// Exit status: 0 done, 1 a file could not be read or written, 2 bad command line.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "phase_error.hpp"
#include "strict_number.hpp"

namespace ref = cloudmath::reference;
namespace fs = std::filesystem;

namespace {

constexpr const char* tool = "cloudmath_phase_error";

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: cloudmath_phase_error [--docs DIR] [--images DIR] TABLE...\n"
                 "  TABLE          Lorenz-Mie phase table, phase_table CSV format\n"
                 "  --docs DIR     where phase_error.md and phase_error.csv go (default: docs)\n"
                 "  --images DIR   where the SVG plots go (default: DOCS/images)\n"
                 "  --help         this text\n"
                 "Compares cloudmath's analytic phase functions with each table (errors in the\n"
                 "forward, side and backward regions, misdirected energy, fitted parameters).\n");
}

struct settings {
    std::string docs = "docs";
    std::string images;  // empty: docs + "/images"
    std::vector<std::string> tables;
};

struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

settings parse(int argc, char** argv) {
    settings s;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw usage_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--docs")
            s.docs = value();
        else if (a == "--images")
            s.images = value();
        else if (a.size() > 1 && a[0] == '-')
            throw usage_error("unknown option " + a);
        else
            s.tables.push_back(a);
    }
    if (s.docs.empty()) throw usage_error("--docs needs a non-empty value");
    if (s.tables.empty()) throw usage_error("no TABLE given");
    if (s.images.empty()) s.images = (fs::path(s.docs) / "images").generic_string();
    return s;
}

// One table with its results.
struct table_report {
    std::string path, name;
    ref::phase_table table;
    double r_eff_um = 0.0;  // the table's "# r_eff_um:" line; 0 when absent
    std::vector<ref::phase_variant> variants;
    std::vector<ref::phase_comparison> comparisons;
};

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// Relative errors: 3 significant digits, "inf" when the model is 0 where the table is not.
std::string rel(double v) { return std::isinf(v) ? "inf" : fmt("%.3g", v); }

// "g = 0.85, alpha = 5" for the report, "g=0.85;alpha=5" (machine readable) for the CSV.
std::string parameter_text(const ref::phase_variant& v, bool for_csv) {
    std::string s;
    for (const auto& [name, value] : v.parameters) {
        if (!s.empty()) s += for_csv ? ";" : ", ";
        s += name + (for_csv ? "=" + fmt("%.9g", value) : " = " + fmt("%.5g", value));
    }
    return s;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

double cos_deg(double theta) {
    if (theta == 90.0) return 0.0;
    if (theta == 180.0) return -1.0;
    return std::cos(theta * (3.14159265358979323846 / 180.0));
}

// Colour by family, dashes for the variants that are not fitted.
void style(const std::string& id, ref::plot_curve& c) {
    static const std::map<std::string, std::pair<const char*, const char*>> styles = {
        {"hg_moment", {"#1f77b4", "6,4"}},       {"hg_fit", {"#1f77b4", ""}},
        {"dual_frostbite", {"#ff7f0e", "6,4"}},  {"dual_fit", {"#ff7f0e", ""}},
        {"cs_moment", {"#2ca02c", "6,4"}},       {"cs_fit", {"#2ca02c", ""}},
        {"schlick_moment", {"#8c564b", "6,4"}},  {"draine_fit", {"#9467bd", ""}},
        {"mie_approx_d2reff", {"#d62728", "6,4"}},
        {"mie_approx_dfit", {"#d62728", "2,3"}}, {"mie_approx_fit", {"#d62728", ""}},
    };
    const auto it = styles.find(id);
    c.colour = it == styles.end() ? "#7f7f7f" : it->second.first;
    c.dash = it == styles.end() ? "" : it->second.second;
    c.width = 1.3;
}

std::vector<ref::plot_curve> curves_of(const table_report& r) {
    std::vector<ref::plot_curve> curves;
    ref::plot_curve mie;
    mie.label = "Lorenz-Mie table";
    mie.colour = "black";
    mie.width = 2.2;
    mie.theta_deg = r.table.theta_deg;
    mie.phase = r.table.phase;
    curves.push_back(mie);
    for (const auto& v : r.variants) {
        ref::plot_curve c;
        c.label = v.label;
        style(v.id, c);
        c.theta_deg = r.table.theta_deg;
        for (double theta : c.theta_deg) c.phase.push_back(v.model(cos_deg(theta)));
        curves.push_back(std::move(c));
    }
    return curves;
}

void write_text(const fs::path& path, const std::string& text) {
    ref::write_text_file_atomically(path.string(), text);
}

std::string describe(const table_report& r) {
    std::string s;
    const std::string dist = r.table.meta("distribution"), wl = r.table.meta("wavelength_um"),
                      reff = r.table.meta("r_eff_um");
    if (!dist.empty()) s += dist;
    if (!wl.empty()) s += (s.empty() ? "" : ", ") + std::string("wavelength ") + wl + " um";
    if (!reff.empty()) s += (s.empty() ? "" : ", ") + std::string("r_eff ") + reff + " um";
    return s;
}

std::string markdown(const std::vector<table_report>& reports, const std::string& command,
                     const std::string& image_dir) {
    const auto& regions = ref::phase_error_regions();
    std::ostringstream md;
    md << "# Analytic phase functions against Lorenz-Mie tables\n\n"
       << "Generated by `" << command
       << "`, run from the repository root (the tool is "
          "built with CLOUDMATH_BUILD_EXAMPLES=ON as build/<dir>/tools/reference/"
          "cloudmath_phase_error; source: "
       << "[tools/reference/optics/phase_error_main.cpp](../tools/reference/optics/phase_error_main.cpp) and "
       << "[phase_error.cpp](../tools/reference/optics/phase_error.cpp)); do not edit by hand, rerun "
          "the command after changing a phase function or a table. The same numbers, one row "
          "per table and model variant, are in [phase_error.csv](phase_error.csv).\n\n";

    md << "## Summary: misdirected energy\n\n"
       << "Fraction of the scattered light each model sends in the wrong directions "
          "(0.5 x the integral of |p_model - p_Mie| over the sphere; 0 = identical, 1 = "
          "disjoint).\n\n| Variant |";
    for (const auto& r : reports) md << ' ' << r.name << " |";
    md << "\n|---|";
    for (std::size_t i = 0; i < reports.size(); ++i) md << "---|";
    md << '\n';
    std::vector<std::string> ids;
    std::map<std::string, std::string> labels;
    for (const auto& r : reports)
        for (const auto& v : r.variants)
            if (labels.emplace(v.id, v.label).second) ids.push_back(v.id);
    for (const auto& id : ids) {
        md << "| " << labels[id] << " |";
        for (const auto& r : reports) {
            std::string cell = " - ";
            for (std::size_t k = 0; k < r.variants.size(); ++k)
                if (r.variants[k].id == id)
                    cell = ' ' + fmt("%.3f", r.comparisons[k].misdirected_energy) + ' ';
            md << cell << '|';
        }
        md << '\n';
    }

    md << "\n## How it is measured\n\n"
       << "Convention: mu = cos(scattering angle), mu = +1 is forward (0 deg). Every table is "
          "a phase function in 1/sr on its own grid of scattering angles, linear in mu between "
          "rows (tools/reference/optics/phase_table.hpp).\n\n"
       << "**Regions** (scattering angle; each interval includes its lower end, the last "
          "also 180 deg):\n\n| Region | Angles | Why |\n|---|---|---|\n";
    for (const auto& g : regions)
        md << "| " << g.name << " | [" << fmt("%g", g.theta_min_deg) << ", "
           << fmt("%g", g.theta_max_deg) << (&g == &regions.back() ? "]" : ")") << " deg | "
           << g.why << " |\n";
    md << "\n**Metrics** of a model p_model against the table p_Mie:\n\n"
       << "- *rms* (per region): exp(r) - 1 with r the RMS over the region's solid angle of "
          "ln(p_model/p_Mie): a typical relative factor, symmetric in too high and too low "
          "(0.10 = typically 10% off, 1.0 = typically a factor 2 off).\n"
       << "- *max* (per region): the largest |p_model/p_Mie - 1| and the angle where it "
          "occurs (a model 30x too low gives 0.97, 30x too high gives 29).\n"
       << "- *misdirected energy*: 0.5 x integral of |p_model - p_Mie| dOmega over the whole "
          "sphere, the share of the scattered light sent in wrong directions (the total "
          "variation distance of the two distributions).\n"
       << "- *mean cosine* and *integral* of the model, against the table's (the model's "
          "integral checks the quadrature: every model is normalised analytically).\n\n"
       << "**Quadrature**: the table's angles plus the region boundaries, each interval cut "
          "into "
       << ref::compare_subdivisions
       << " equal steps of angle. The table is "
          "evaluated with its own linear-in-mu interpolation, the model exactly; integrals are "
          "trapezoids in mu (exact for the table), and |p_model - p_Mie| is integrated exactly "
          "for a difference linear between nodes, sign changes included. Maxima are taken over "
          "the nodes.\n\n"
       << "**Fits** minimise sum_i w_i (ln p_model(mu_i) - ln p_Mie(mu_i))^2 over the table's "
          "rows, w_i = the angular width of row i in degrees: uniform weight per degree of "
          "scattering angle. The rows are much denser near 0 and 180 deg, so equal row weights "
          "would fit mostly the peaks; solid-angle weights (sin theta) would give almost no "
          "weight to the forward peak, which carries about half of the light and draws the "
          "silver lining; per degree, every direction of a view sweeping around the sun counts "
          "the same. Log space makes a factor 2 cost the same at 1000/sr and 0.03/sr. "
          "The minimiser is Nelder-Mead (Nelder & Mead 1965) on transformed parameters (g = "
          "0.9999 tanh x, weights = logistic x, alpha and d = exp x), from several starting "
          "points (one-lobe models: the table's mean cosine and 0.3, 0.7, 0.9, 0.97; dual HG: "
          "12 combinations; Draine: 9; Jendersie-d'Eon: the published fit at d = 4 to 40 um "
          "and one generic start), each restarted until it stops improving; the best is kept. "
          "*Residual* in the tables is the minimised quantity as an RMS: sqrt(sum w_i r_i^2 / "
          "sum w_i), r_i = ln(p_model/p_Mie) (0.1 = typically 10% off per degree of angle); it "
          "is given for every variant, fitted or not.\n\n"
       << "**Variants**: HG with g = the table's mean cosine (moment matched) and fitted; the "
          "dual-lobe HG of Frostbite (Hillaire 2016: g0 = 0.8, g1 = -0.5, w = 0.5) and fitted "
          "(w = weight of the g1 lobe); Schlick's rational form (Blasi et al. 1993) with k(g) for "
          "g = the table's mean cosine, cloudmath's cheaper stand-in for HG; Cornette-Shanks (1992) with the g whose CS mean cosine "
          "3g(4+g^2)/(5(2+g^2)) equals the table's, and fitted; Draine (2003) with g and alpha "
          "fitted (alpha = 1 with matched mean cosine is the CS row); Jendersie & d'Eon (2023) "
          "`phase_mie_approx` with droplet diameter d = 2 r_eff, with d fitted, and with its "
          "four parameters (g_hg, g_draine, alpha, w_draine) fitted directly.\n";

    for (std::size_t t = 0; t < reports.size(); ++t) {
        const table_report& r = reports[t];
        const std::string desc = describe(r);
        md << "\n## " << r.name << "\n\n"
           << "Table `" << r.path << "`" << (desc.empty() ? "" : ": " + desc) << ". "
           << r.table.theta_deg.size() << " angles; integral " << fmt("%.6f", r.table.integral())
           << ", mean cosine " << fmt("%.5f", r.table.mean_cosine() / r.table.integral());
        const std::string g_meta = r.table.meta("asymmetry_g");
        if (!g_meta.empty()) md << " (metadata asymmetry_g " << g_meta << ")";
        md << ". Share of the light in each region:";
        for (const auto& e : r.comparisons.front().regions)
            md << ' ' << e.region.name << ' ' << fmt("%.3f", e.table_energy)
               << (&e == &r.comparisons.front().regions.back() ? "." : ",");
        md << "\n\n| Variant | Parameters | Residual |";
        for (const auto& g : regions) md << ' ' << g.name << " rms / max (at deg) |";
        md << " Misdirected energy | Mean cosine | Integral |\n|---|---|---|";
        for (std::size_t i = 0; i < regions.size(); ++i) md << "---|";
        md << "---|---|---|\n";
        for (std::size_t k = 0; k < r.variants.size(); ++k) {
            const auto& v = r.variants[k];
            const auto& c = r.comparisons[k];
            md << "| " << v.label << " | " << parameter_text(v, false) << " | "
               << fmt("%.3f", v.residual) << " |";
            for (const auto& e : c.regions)
                md << ' ' << rel(e.rms_factor) << " / " << rel(e.max_rel_error) << " ("
                   << fmt("%g", e.max_at_deg) << ") |";
            md << ' ' << fmt("%.4f", c.misdirected_energy) << " | "
               << fmt("%.4f", c.model_mean_cosine) << " | " << fmt("%.5f", c.model_integral)
               << " |\n";
        }
        md << "\nTable: mean cosine " << fmt("%.4f", r.comparisons.front().table_mean_cosine)
           << ". Dashed lines: moment matched, published or size-based variants; solid: "
              "fitted.\n\n"
           << "![" << r.name << ": phase functions, log scale](" << image_dir << "/phase_error_"
           << r.name << ".svg)\n\n"
           << "![" << r.name << ": forward peak](" << image_dir << "/phase_forward_" << r.name
           << ".svg)\n\n"
           << "![" << r.name << ": polar plot](" << image_dir << "/phase_polar_" << r.name
           << ".svg)\n";
    }
    return md.str();
}

std::string csv(const std::vector<table_report>& reports) {
    std::ostringstream out;
    out << "table,distribution,wavelength_um,r_eff_um,table_integral,table_mean_cosine,variant,"
           "function,method,parameters,residual_rms_ln";
    for (const auto& g : ref::phase_error_regions())
        out << ',' << g.name << "_rms_factor," << g.name << "_max_rel_error," << g.name
            << "_max_at_deg," << g.name << "_misdirected";
    out << ",misdirected_energy,model_integral,model_mean_cosine\n";
    for (const auto& r : reports)
        for (std::size_t k = 0; k < r.variants.size(); ++k) {
            const auto& v = r.variants[k];
            const auto& c = r.comparisons[k];
            out << csv_field(r.name) << ',' << csv_field(r.table.meta("distribution")) << ','
                << csv_field(r.table.meta("wavelength_um")) << ','
                << csv_field(r.table.meta("r_eff_um")) << ',' << fmt("%.9g", c.table_integral)
                << ',' << fmt("%.9g", c.table_mean_cosine) << ',' << v.id << ',' << v.function
                << ',' << csv_field(v.method) << ',' << csv_field(parameter_text(v, true)) << ','
                << fmt("%.6g", v.residual);
            for (const auto& e : c.regions)
                out << ',' << fmt("%.6g", e.rms_factor) << ',' << fmt("%.6g", e.max_rel_error)
                    << ',' << fmt("%g", e.max_at_deg) << ',' << fmt("%.6g", e.misdirected);
            out << ',' << fmt("%.6g", c.misdirected_energy) << ',' << fmt("%.9g", c.model_integral)
                << ',' << fmt("%.9g", c.model_mean_cosine) << '\n';
        }
    return out.str();
}

std::string shell_word(const std::string& s) {
    if (!s.empty() && s.find_first_of(" \t\"'$\\`*?") == std::string::npos) return s;
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
            print_usage(stdout);
            return 0;
        }
    settings s;
    try {
        s = parse(argc, argv);
    } catch (const usage_error& e) {
        std::fprintf(stderr, "%s: %s (see --help)\n", tool, e.what());
        return 2;
    }
    const auto start = std::chrono::steady_clock::now();

    std::vector<table_report> reports;
    std::set<std::string> names;
    for (const auto& path : s.tables) {
        table_report r;
        r.path = path;
        r.name = fs::path(path).stem().string();
        if (!names.insert(r.name).second) {
            std::fprintf(stderr, "%s: two tables named %s (their plots would collide)\n", tool,
                         r.name.c_str());
            return 2;
        }
        try {
            r.table = ref::read_phase_table(path);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", tool, e.what());
            return 1;
        }
        // Read strictly (strict_number.hpp): strtod turned "abc" into 0 without a word.
        const std::string reff = r.table.meta("r_eff_um");
        const std::optional<double> r_eff = reff.empty() ? std::optional<double>(0.0) : cloudmath::tools::parse_finite(reff);
        if (!r_eff) {
            std::fprintf(stderr, "%s: %s: r_eff_um '%s' is not a number\n", tool, path.c_str(), reff.c_str());
            return 1;
        }
        r.r_eff_um = *r_eff;
        reports.push_back(std::move(r));
    }

    const double n = static_cast<double>(reports.size());
    for (std::size_t t = 0; t < reports.size(); ++t) {
        table_report& r = reports[t];
        const double r_eff = r.r_eff_um;
        r.variants = ref::phase_variants(r.table, r_eff, [&](double f) {
            std::fprintf(stderr, "\r%s: fitting %s ... %3.0f%%", tool, r.name.c_str(),
                         100.0 * (static_cast<double>(t) + f) / n);
            std::fflush(stderr);
        });
        for (const auto& v : r.variants) r.comparisons.push_back(ref::compare(r.table, v.model));
    }
    std::fprintf(stderr, "\r%s: fitting done%*s\n", tool, 40, "");

    std::string command = tool;
    for (int i = 1; i < argc; ++i) command += " " + shell_word(argv[i]);
    try {
        std::error_code ec;
        fs::create_directories(s.docs, ec);
        if (ec) throw std::runtime_error("cannot create directory " + s.docs);
        fs::create_directories(s.images, ec);
        if (ec) throw std::runtime_error("cannot create directory " + s.images);
        std::string image_dir = fs::absolute(s.images)
                                    .lexically_normal()
                                    .lexically_relative(fs::absolute(s.docs).lexically_normal())
                                    .generic_string();
        if (image_dir.empty()) image_dir = ".";
        while (image_dir.size() > 1 && image_dir.back() == '/') image_dir.pop_back();
        for (const auto& r : reports) {
            const auto curves = curves_of(r);
            const std::string what = describe(r);
            const std::string title = r.name + (what.empty() ? "" : "\n" + what);
            write_text(fs::path(s.images) / ("phase_error_" + r.name + ".svg"),
                       ref::svg_phase_cartesian(curves, title));
            write_text(
                fs::path(s.images) / ("phase_forward_" + r.name + ".svg"),
                ref::svg_phase_cartesian(
                    curves, r.name + ": forward peak" + (what.empty() ? "" : "\n" + what), 10.0));
            write_text(fs::path(s.images) / ("phase_polar_" + r.name + ".svg"),
                       ref::svg_phase_polar(curves, title));
        }
        write_text(fs::path(s.docs) / "phase_error.md", markdown(reports, command, image_dir));
        write_text(fs::path(s.docs) / "phase_error.csv", csv(reports));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", tool, e.what());
        return 1;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::size_t variants = 0;
    for (const auto& r : reports) variants += r.variants.size();
    std::printf(
        "%s: %zu table(s), %zu model variants; wrote %s, %s and %zu SVGs in %s in "
        "%.1f s\n",
        tool, reports.size(), variants, (fs::path(s.docs) / "phase_error.md").string().c_str(),
        (fs::path(s.docs) / "phase_error.csv").string().c_str(), 3 * reports.size(),
        s.images.c_str(), seconds);
    return 0;
}
