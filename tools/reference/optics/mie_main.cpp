// tools/reference/optics/mie_main.cpp: cloudmath_mie, the command-line front end of the Lorenz-Mie
// reference (mie.hpp) and the droplet-distribution phase tables (size_distribution.hpp).
//
//   cloudmath_mie --distribution c1 --wavelength 0.55 --out docs/data/mie_c1_0.55um.csv
//   cloudmath_mie --distribution gamma --reff 10 --alpha 6 --out mie_gamma_reff10um_0.55um.csv
//   cloudmath_mie --sphere --m 1.33,-1e-5 --x 100 [--angles 0,90,180]
//
// Exit status: 0 success, 1 I/O failure (the message names the path), 2 bad command line.
// The table format is described in phase_table.hpp; the metadata lines record every input
// and the integral of the table before it was divided by it (normalisation is explicit).
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "atomic_file.hpp"
#include "mie.hpp"
#include "phase_table.hpp"
#include "size_distribution.hpp"
#include "strict_number.hpp"

namespace {

using namespace cloudmath::reference;

constexpr const char* usage_text = R"(usage:
  cloudmath_mie --distribution c1|gamma [options]   mean phase table of a droplet distribution
  cloudmath_mie --sphere --m RE,IM --x X [--angles DEG,...]   one sphere

distribution options:
  --distribution c1      Deirmendjian cloud C.1: n(r) = 2.373 r^6 exp(-1.5 r), r in um
  --distribution gamma   modified gamma n(r) ~ r^alpha exp(-b r^gamma), b from --reff
  --reff UM              effective radius in um (gamma only, required)
  --alpha A              gamma shape alpha (default 6)
  --gamma G              gamma shape gamma (default 1)
  --wavelength UM        wavelength in um (default 0.55)
  --m RE,IM              refractive index (default: water, 1.333,-1.96e-9 at 0.55 um and
                         1.33,0 at 0.70 um; required at other wavelengths). The sign of IM
                         does not matter: |IM| is the absorption
  --step DX              base size-parameter step of the radius quadrature (default 0.1)
  --tolerance T          relative tolerance of the adaptive refinement (default 0.01)
  --threads N            worker threads (default: hardware threads)
  --out PATH             write the table (CSV, see tools/reference/optics/phase_table.hpp)
  --quiet                no progress line
sphere options:
  --sphere               print Q_ext, Q_sca, Q_abs, Q_back and g of one sphere
  --x X                  size parameter 2 pi r / lambda, 1e-30 .. 1e5 (1e-3 .. 1e4 tested
                         against published values; below 1e-30 the series underflows and
                         the Rayleigh limit Q_sca = 8/3 x^4 |(m^2-1)/(m^2+2)|^2 applies)
  --angles DEG,...       also print S1, S2 and the phase function at these angles
  --help                 this text
)";

struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct io_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The whole text, finite, decimal (strict_number.hpp: std::stod took " 5", "0x1p3", ...).
double parse_number(const std::string& flag, const std::string& text) {
    const std::optional<double> v = cloudmath::tools::parse_finite(text);
    if (!v) throw usage_error(flag + ": not a number: '" + text + "'");
    return *v;
}

std::vector<double> parse_list(const std::string& flag, const std::string& text) {
    std::vector<double> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(parse_number(flag, item));
    if (out.empty()) throw usage_error(flag + ": empty list");
    return out;
}

std::string number(double v);  // below

std::complex<double> parse_index(const std::string& text) {
    const std::vector<double> v = parse_list("--m", text);
    if (v.size() != 2) throw usage_error("--m: expected RE,IM, got '" + text + "'");
    if (!(v[0] > 0.0)) throw usage_error("--m: the real part must be > 0");
    if (!(std::abs(std::complex<double>(v[0], v[1])) <= mie_max_index_modulus))
        throw usage_error("--m: |m| must be at most 1000, not " + number(std::abs(std::complex<double>(v[0], v[1]))));
    return {v[0], v[1]};
}

std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

std::string index_text(std::complex<double> m) { return number(m.real()) + "," + number(m.imag()); }

struct options {
    bool sphere = false;
    std::string distribution;
    std::optional<double> reff, x;
    double alpha = 6.0, gamma = 1.0, wavelength = 0.55, step = 0.1, tolerance = 1e-2;
    std::optional<std::complex<double>> m;
    std::vector<double> angles;
    unsigned threads = 0;
    std::string out;
    bool quiet = false;
    bool help = false;
    std::vector<std::string> given;  // flags seen, for the mode checks
};

options parse(int argc, char** argv) {
    options o;
    for (int i = 1; i < argc; ++i) {
        std::string flag = argv[i], value;
        bool has_value = false;
        const auto eq = flag.find('=');
        if (flag.rfind("--", 0) == 0 && eq != std::string::npos) {
            value = flag.substr(eq + 1);
            flag = flag.substr(0, eq);
            has_value = true;
        }
        const auto take = [&]() -> std::string {
            if (has_value) return value;
            if (i + 1 >= argc) throw usage_error(flag + ": missing value");
            return argv[++i];
        };
        const auto no_value = [&]() {
            if (has_value) throw usage_error(flag + " takes no value");
        };
        o.given.push_back(flag);
        if (flag == "--help" || flag == "-h") {
            no_value();
            o.help = true;
        } else if (flag == "--sphere") {
            no_value();
            o.sphere = true;
        } else if (flag == "--quiet") {
            no_value();
            o.quiet = true;
        } else if (flag == "--distribution") {
            o.distribution = take();
            if (o.distribution != "c1" && o.distribution != "gamma")
                throw usage_error("--distribution: expected c1 or gamma, got '" + o.distribution +
                                  "'");
        } else if (flag == "--reff") {
            o.reff = parse_number(flag, take());
            if (!(*o.reff > 0.0)) throw usage_error("--reff must be > 0");
        } else if (flag == "--alpha") {
            o.alpha = parse_number(flag, take());
            if (!(o.alpha > -1.0)) throw usage_error("--alpha must be > -1");
        } else if (flag == "--gamma") {
            o.gamma = parse_number(flag, take());
            if (!(o.gamma > 0.0)) throw usage_error("--gamma must be > 0");
        } else if (flag == "--wavelength") {
            o.wavelength = parse_number(flag, take());
            if (!(o.wavelength > 0.0)) throw usage_error("--wavelength must be > 0");
        } else if (flag == "--m") {
            o.m = parse_index(take());
        } else if (flag == "--step") {
            o.step = parse_number(flag, take());
            if (!(o.step > 0.0 && o.step <= 10.0)) throw usage_error("--step must lie in (0, 10]");
        } else if (flag == "--tolerance") {
            o.tolerance = parse_number(flag, take());
            if (!(o.tolerance > 0.0 && o.tolerance <= 1.0))
                throw usage_error("--tolerance must lie in (0, 1]");
        } else if (flag == "--threads") {
            const double t = parse_number(flag, take());
            if (!(t >= 1.0 && t <= 1024.0) || t != std::floor(t))
                throw usage_error("--threads must be an integer in 1 .. 1024");
            o.threads = static_cast<unsigned>(t);
        } else if (flag == "--out") {
            o.out = take();
            if (o.out.empty()) throw usage_error("--out: empty path");
        } else if (flag == "--x") {
            o.x = parse_number(flag, take());
            if (!(*o.x >= mie_min_size_parameter && *o.x <= 1e5))
                throw usage_error("--x must lie in [1e-30, 1e5] (below 1e-30 the series underflows: "
                                  "the Rayleigh limit applies)");
        } else if (flag == "--angles") {
            o.angles = parse_list(flag, take());
            for (double a : o.angles)
                if (!(a >= 0.0 && a <= 180.0))
                    throw usage_error("--angles: each angle must lie in [0, 180]");
        } else {
            throw usage_error("unknown option '" + flag + "'");
        }
    }
    if (o.help) return o;
    const auto seen = [&](const char* f) {
        for (const auto& g : o.given)
            if (g == f) return true;
        return false;
    };
    if (o.sphere) {
        for (const char* f : {"--distribution", "--reff", "--alpha", "--gamma", "--wavelength",
                              "--step", "--tolerance", "--threads", "--out"})
            if (seen(f)) throw usage_error(std::string(f) + " does not apply to --sphere");
        if (!o.x) throw usage_error("--sphere needs --x");
        if (!o.m) throw usage_error("--sphere needs --m");
        if (!(std::abs(*o.m) * *o.x <= mie_max_index_size_parameter))
            throw usage_error("--m and --x: |m| x must be at most 1e6 (the series runs |m| x steps), not " +
                              number(std::abs(*o.m) * *o.x));
    } else {
        if (o.distribution.empty()) throw usage_error("give --distribution c1|gamma or --sphere");
        for (const char* f : {"--x", "--angles"})
            if (seen(f)) throw usage_error(std::string(f) + " applies to --sphere only");
        if (o.distribution == "gamma" && !o.reff)
            throw usage_error("--distribution gamma needs --reff");
        if (o.distribution == "c1")
            for (const char* f : {"--reff", "--alpha", "--gamma"})
                if (seen(f))
                    throw usage_error(std::string(f) + " applies to --distribution gamma only");
        if (!o.m) {
            o.m = default_water_index(o.wavelength);
            if (!o.m)
                throw usage_error("no default refractive index at this wavelength: give --m RE,IM");
        }
    }
    return o;
}

int run_sphere(const options& o) {
    const double deg = 3.14159265358979323846 / 180.0;
    std::vector<double> mu;
    for (double a : o.angles) mu.push_back(a == 90.0 ? 0.0 : a == 180.0 ? -1.0 : std::cos(a * deg));
    const mie_result r = solve_mie(*o.m, *o.x, mu);
    const mie_efficiencies& e = r.efficiencies;
    std::printf("sphere x = %s, m = %s (absorption |Im m|), %zu terms\n", number(*o.x).c_str(),
                index_text(*o.m).c_str(), r.terms);
    std::printf("Q_ext = %.9g\nQ_sca = %.9g\nQ_abs = %.9g\nQ_back = %.9g\ng = %.9g\n", e.q_ext,
                e.q_sca, e.q_abs, e.q_back, e.g);
    for (std::size_t j = 0; j < mu.size(); ++j)
        std::printf("theta %s deg: S1 = %.9g %+.9g i, S2 = %.9g %+.9g i, phase = %.9g /sr\n",
                    number(o.angles[j]).c_str(), r.s1[j].real(), r.s1[j].imag(), r.s2[j].real(),
                    r.s2[j].imag(), unpolarized_phase(r.s1[j], r.s2[j], *o.x, e.q_sca));
    return 0;
}

// Creates the missing directories of --out and checks that the file can be written, before
// the computation (the table is written atomically at the end; write_phase_table).
void prepare_output(const std::string& out) {
    if (out.empty()) return;
    const std::filesystem::path parent = std::filesystem::path(out).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (ec) throw io_error("cannot create directory " + parent.string() + ": " + ec.message());
    if (const std::string error = cloudmath::tools::check_output_path(out); !error.empty()) throw io_error(error);
}

int run_distribution(const options& o) {
    prepare_output(o.out);
    const auto start = std::chrono::steady_clock::now();
    modified_gamma dist = o.distribution == "c1"
                              ? deirmendjian_c1()
                              : modified_gamma_from_effective_radius(*o.reff, o.alpha, o.gamma);
    mean_phase_settings s;
    s.wavelength_um = o.wavelength;
    s.refractive_index = *o.m;
    s.size_parameter_step = o.step;
    s.relative_tolerance = o.tolerance;
    s.threads = o.threads != 0 ? o.threads : std::max(1u, std::thread::hardware_concurrency());
    const std::string label =
        o.distribution == "c1" ? "c1" : "gamma r_eff " + number(*o.reff) + " um";
    if (!o.quiet)
        s.progress = [&](double fraction) {
            std::fprintf(stderr, "\rcloudmath_mie: %s at %s um: %3d%%", label.c_str(),
                         number(o.wavelength).c_str(),
                         static_cast<int>(std::floor(100.0 * fraction)));
            std::fflush(stderr);
        };
    mean_phase_result r = compute_mean_phase(dist, s);
    if (!o.quiet) std::fprintf(stderr, "\n");
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    phase_table& t = r.table;
    if (o.distribution == "c1") {
        t.set_meta("distribution", "Deirmendjian cloud C.1");
        t.set_meta("parameters", "n(r) = 2.373 r^6 exp(-1.5 r), r in um");
    } else {
        t.set_meta("distribution", "modified gamma");
        t.set_meta("parameters", "n(r) = a r^alpha exp(-b r^gamma), r in um, one droplet in total");
        t.set_meta("alpha", number(dist.alpha));
        t.set_meta("gamma", number(dist.gamma));
        t.set_meta("b", number(dist.b));
        t.set_meta("a", number(dist.scale));
    }
    t.set_meta("wavelength_um", number(o.wavelength));
    t.set_meta("m", index_text(*o.m) + " (n - i k convention; |Im| is the absorption)");
    t.set_meta("quadrature", "adaptive midpoint in size parameter (see size_distribution.hpp)");
    t.set_meta("size_parameter_step", number(o.step));
    t.set_meta("relative_tolerance", number(o.tolerance));
    t.set_meta("r_min_um", number(r.r_min_um));
    t.set_meta("r_max_um", number(r.r_max_um));
    t.set_meta("r_cells", std::to_string(r.cell_count));
    t.set_meta("mie_evaluations", std::to_string(r.evaluation_count));
    t.set_meta("r_eff_um", number(r.effective_radius_um));
    t.set_meta("asymmetry_g", number(r.asymmetry_g));
    t.set_meta("table_mean_cosine", number(t.mean_cosine()));
    t.set_meta("integral_before_normalisation", number(r.integral_before_normalisation));
    t.set_meta("normalisation", "phase divided by integral_before_normalisation");
    t.set_meta("mean_C_ext_um2", number(r.mean_c_ext_um2));
    t.set_meta("mean_C_sca_um2", number(r.mean_c_sca_um2));
    t.set_meta("single_scattering_albedo", number(r.single_scattering_albedo));
    t.set_meta("angle_convention", "theta = scattering angle, 0 = forward");
    t.set_meta("generator", "cloudmath_mie (tools/reference/optics/mie_main.cpp)");
    t.set_meta("threads", std::to_string(s.threads));
    t.set_meta("elapsed_s", number(elapsed));
    if (!o.out.empty()) {
        try {
            write_phase_table(o.out, t);
        } catch (const std::runtime_error& e) {
            throw io_error(e.what());
        }
    }
    std::printf(
        "%s at %s um, m = %s: g = %.6f, table mean cosine %.6f, integral before "
        "normalisation %.6f, single-scattering albedo %.9f, p(0) = %.6g, p(90) = %.6g, "
        "p(180) = %.6g /sr, %zu Mie evaluations, %.2f s on %u threads%s%s\n",
        label.c_str(), number(o.wavelength).c_str(), index_text(*o.m).c_str(), r.asymmetry_g,
        t.mean_cosine(), r.integral_before_normalisation, r.single_scattering_albedo,
        t.evaluate(1.0), t.evaluate(0.0), t.evaluate(-1.0), r.evaluation_count, elapsed, s.threads,
        o.out.empty() ? "" : " -> ", o.out.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const options o = parse(argc, argv);
        if (o.help) {
            std::fputs(usage_text, stdout);
            return 0;
        }
        return o.sphere ? run_sphere(o) : run_distribution(o);
    } catch (const usage_error& e) {
        std::fprintf(stderr, "cloudmath_mie: %s (see --help)\n", e.what());
        return 2;
    } catch (const io_error& e) {
        std::fprintf(stderr, "cloudmath_mie: %s\n", e.what());
        return 1;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "cloudmath_mie: %s (see --help)\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cloudmath_mie: %s\n", e.what());
        return 1;
    }
}
