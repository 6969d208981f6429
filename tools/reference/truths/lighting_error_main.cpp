// tools/reference/truths/lighting_error_main.cpp: cloudmath_lighting_error, the lighting models of
// cloudmath (single scattering, Wrenninge octaves, Beer-Powder, Nubis attenuation) against
// the Monte Carlo reference.
//
//   cloudmath_lighting_error reference [--out docs/data/lighting_reference.csv] [--paths N]
//       [--max-paths N] [--target-error 0.01] [--threads 0] [--seed 1] [--quick]
//       [--holdout] [--phase hg:0.85] [--albedo 1]
//   cloudmath_lighting_error report [--reference docs/data/lighting_reference.csv]
//       [--docs docs] [--images docs/images]
//   cloudmath_lighting_error choice [--reference docs/data/lighting_reference.csv] [--out PATH]
//   cloudmath_lighting_error fit-diffusion [--data docs/data] [--train A.csv,B.csv]
//       [--holdout C.csv,D.csv]
//       [--header include/cloudmath/diffusion_lighting_models.hpp]
//       [--glsl include/cloudmath/glsl/diffusion_lighting_models.glsl] [--smoothing 10]
//       [--ridge 0.001]
//
// `reference` path-traces the sphere and slab rays (lighting_error.hpp) and writes the CSV;
// `report` measures every model on it, fits a, b, c per octave count and form, and writes
// lighting_error.md, lighting_error.csv and lighting_error_*.svg. Exit status: 0 success,
// 2 bad command line, 1 I/O or data failure (the message names the path).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <cloudmath/multiple_scattering.hpp>

#include "atomic_file.hpp"
#include "cli_main.hpp"  // split_list
#include "strict_number.hpp"
#include "lighting_diffusion.hpp"
#include "lighting_error.hpp"
#include "lighting_report.hpp"

namespace lm = cloudmath::reference::lighting;

namespace {

const char* const usage_text =
    "usage: cloudmath_lighting_error <command> [--flag value ...]\n"
    "\n"
    "commands:\n"
    "  reference  path-traces the reference: a sphere seen from 6 directions around the sun\n"
    "             and a slab under 3 sun angles, optical thickness 1 to 100, HG g = 0.85.\n"
    "             flags: --out docs/data/lighting_reference.csv --paths 200000\n"
    "                    --max-paths 3200000 (paths per ray, each at most 1e8)\n"
    "                    --target-error 0.01 --threads 0 --seed 1\n"
    "                    --quick (3 thicknesses, 2 view angles, 1 sun, few paths: a smoke\n"
    "                    test, not a reference)\n"
    "                    --holdout (the held-out split: thicknesses, view and sun angles\n"
    "                    and slab views that the default set does not contain)\n"
    "                    --phase hg:0.85 (any montecarlo.hpp phase spec) --albedo 1\n"
    "  report     measures the lighting models against the reference and fits them:\n"
    "             writes DOCS/lighting_error.md, DOCS/lighting_error.csv and\n"
    "             IMAGES/lighting_error_*.svg.\n"
    "             flags: --reference docs/data/lighting_reference.csv --docs docs\n"
    "                    --images docs/images --choice-header PATH (also writes the data of\n"
    "                    cloudmath/lighting_choice.hpp there)\n"
    "  fit-diffusion  fits the diffusion model (cloudmath/diffusion_lighting.hpp) on the\n"
    "             training references and measures it, beside the octave presets, on them\n"
    "             and on held-out ones; writes the generated model headers when asked.\n"
    "             flags: --data docs/data (where the default sets are: lighting_reference,\n"
    "                    lighting_train_g0.8 and _g0.93 to fit; lighting_holdout_g0.75,\n"
    "                    _g0.85 and _g0.9 held out)\n"
    "                    --train A.csv,B.csv (instead; the first is the reference the\n"
    "                    model's rms_error is measured on) --holdout C.csv,D.csv\n"
    "                    --header PATH.hpp --glsl PATH.glsl\n"
    "                    --smoothing 0.01 --ridge 0.0001\n"
    "                    --clouds DATA/diffusion_clouds.txt (the whole-cloud fit of\n"
    "                    cloudmath_volume_truth fit-clouds, measured beside them and written\n"
    "                    as diffusion_models::clouds; default when the file exists, none: not)\n"
    "                    --cv (instead of fitting: leave-one-set-out cross-validation of\n"
    "                    smoothing and ridge over the training sets alone)\n"
    "  choice     writes the measured-error table of cloudmath/lighting_choice.hpp alone.\n"
    "             flags: --reference docs/data/lighting_reference.csv\n"
    "                    --out include/cloudmath/lighting_choice_data.hpp\n"
    "Exit status: 0 ok, 1 I/O or data failure, 2 bad command line.\n";

struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// "--name value" pairs (and bare switches), checked against what a command accepts.
std::map<std::string, std::string> parse_flags(int argc, char** argv,
                                               const std::set<std::string>& with_value,
                                               const std::set<std::string>& switches) {
    std::map<std::string, std::string> out;
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--", 0) != 0) throw usage_error("unexpected argument '" + arg + "'");
        const std::string key = arg.substr(2);
        if (switches.count(key)) {
            out[key] = "1";
        } else if (with_value.count(key)) {
            if (i + 1 >= argc) throw usage_error("flag '" + arg + "' needs a value");
            out[key] = argv[++i];
        } else {
            throw usage_error("unknown flag '" + arg + "'");
        }
    }
    return out;
}

// Numbers are read strictly (strict_number.hpp): the whole text, no spaces, nan or inf;
// counts may be written 2e5. strtoull read " -5" as 2^64 - 5.
std::uint64_t to_count(const std::string& flag, const std::string& text, std::uint64_t max) {
    const std::optional<std::uint64_t> v = cloudmath::tools::parse_count(text);
    if (!v) throw usage_error("--" + flag + " needs a non-negative integer, got '" + text + "'");
    if (*v > max)
        throw usage_error("--" + flag + " is at most " + std::to_string(max) + ", got '" + text + "'");
    return *v;
}

double to_positive(const std::string& flag, const std::string& text) {
    const std::optional<double> v = cloudmath::tools::parse_finite(text);
    if (!v || !(*v > 0.0))
        throw usage_error("--" + flag + " needs a positive number, got '" + text + "'");
    return *v;
}

// Paths per ray: the default reference gives each 200000, up to 3200000 where it is noisy;
// the cap, 30 times that, keeps a typo (an extra zero or two) from running for days.
constexpr std::uint64_t max_paths_per_ray = 100000000;

int run_reference(int argc, char** argv) {
    auto f = parse_flags(argc, argv, {"out", "paths", "max-paths", "target-error", "threads",
                                      "seed", "phase", "albedo"},
                         {"quick", "holdout"});
    lm::reference_options o;
    if (f.count("quick") && f.count("holdout"))
        throw usage_error("--quick and --holdout exclude each other");
    if (f.count("holdout")) o = lm::holdout_reference_options();
    if (f.count("phase")) o.phase = f["phase"];
    if (f.count("albedo")) {
        o.albedo = to_positive("albedo", f["albedo"]);
        if (o.albedo > 1.0) throw usage_error("--albedo must be in (0, 1], got '" + f["albedo"] + "'");
    }
    if (f.count("quick")) {
        o.taus = {1, 10, 100};
        o.sphere_view_angles_deg = {30, 120};
        o.sphere_points = 5;
        o.slab_sun_zenith_deg = {60};
        o.paths = 2000;
        o.max_paths = 8000;
    }
    if (f.count("paths")) o.paths = to_count("paths", f["paths"], max_paths_per_ray);
    if (f.count("max-paths")) o.max_paths = to_count("max-paths", f["max-paths"], max_paths_per_ray);
    if (f.count("target-error")) o.target_rel_error = to_positive("target-error", f["target-error"]);
    if (f.count("threads")) o.threads = static_cast<unsigned>(to_count("threads", f["threads"], 1024));
    if (f.count("seed")) o.seed = to_count("seed", f["seed"], std::numeric_limits<std::uint64_t>::max());
    if (o.paths == 0) throw usage_error("--paths must be > 0");
    if (o.max_paths < o.paths) o.max_paths = o.paths;
    const std::string out = f.count("out") ? f["out"] : "docs/data/lighting_reference.csv";
    // Checked now, written atomically when done (write_reference): a bad path fails before
    // hours of path tracing, and an interrupted run leaves the old file as it was.
    if (const std::string error = cloudmath::tools::check_output_path(out); !error.empty())
        throw std::runtime_error(error);
    o.log = [](const std::string& line) { std::cerr << "cloudmath_lighting_error: " << line << '\n'; };

    const auto t0 = std::chrono::steady_clock::now();
    lm::reference_set set = lm::generate_reference(o);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f", seconds);
    set.metadata.emplace_back("elapsed_s", buf);
    lm::write_reference(set, out);
    std::cout << "cloudmath_lighting_error: wrote " << set.rows.size() << " rows to " << out
              << " in " << buf << " s\n";
    return 0;
}

int run_report(int argc, char** argv) {
    auto f = parse_flags(argc, argv, {"reference", "docs", "images", "choice-header"}, {});
    lm::report_options o;
    if (f.count("choice-header")) o.choice_header = f["choice-header"];
    if (f.count("reference")) o.reference_path = f["reference"];
    if (f.count("docs")) o.docs_dir = f["docs"];
    o.images_dir = f.count("images") ? f["images"] : o.docs_dir + "/images";
    o.log = [](const std::string& line) { std::cerr << "cloudmath_lighting_error: " << line << '\n'; };
    const lm::report_summary s = lm::write_report(o);
    std::cout << "cloudmath_lighting_error: " << s.rows << " reference rows, " << s.fits
              << " fits; wrote " << o.docs_dir << "/lighting_error.md, lighting_error.csv and "
              << s.images << " SVGs in " << o.images_dir << '\n';
    return 0;
}

// Writes the data of cloudmath/lighting_choice.hpp alone (the report writes it too).
int run_choice(int argc, char** argv) {
    auto f = parse_flags(argc, argv, {"reference", "out"}, {});
    const std::string ref = f.count("reference") ? f["reference"] : "docs/data/lighting_reference.csv";
    const std::string out = f.count("out") ? f["out"] : "include/cloudmath/lighting_choice_data.hpp";
    const std::size_t slash = ref.find_last_of('/');
    cloudmath::reference::write_text_file_atomically(out, lm::lighting_choice_header(lm::read_reference(ref), ref.substr(slash + 1)));
    std::cout << "cloudmath_lighting_error: wrote " << out << '\n';
    return 0;
}

// Fits the diffusion model (lighting_diffusion.hpp: run_diffusion_fit), prints the report
// and writes the generated headers when asked.
int run_fit_diffusion(int argc, char** argv) {
    auto f = parse_flags(argc, argv, {"data", "train", "holdout", "header", "glsl", "smoothing", "ridge", "clouds"}, {"cv"});
    const std::string data = f.count("data") ? f["data"] : "docs/data";
    lm::diffusion_fit_options o;
    if (f.count("smoothing")) o.smoothing = to_positive("smoothing", f["smoothing"]);
    if (f.count("ridge")) o.ridge = to_positive("ridge", f["ridge"]);
    const std::vector<std::string> train =
        f.count("train") ? cloudmath::reference::split_list(f["train"]) : lm::diffusion_training_paths(data);
    const std::vector<std::string> holdout =
        f.count("holdout") ? cloudmath::reference::split_list(f["holdout"]) : lm::diffusion_holdout_paths(data);
    if (train.empty()) throw usage_error("--train needs at least one reference CSV");
    if (f.count("cv")) {
        std::cout << lm::diffusion_cross_validation(train);
        return 0;
    }
    // The whole-cloud fit (diffusion_models::clouds): --clouds PATH, default DATA/diffusion_clouds.txt
    // when it exists; "none" leaves it out.
    std::string clouds = f.count("clouds") ? f["clouds"] : lm::diffusion_clouds_path(data);
    if (clouds == "none" || (!f.count("clouds") && !std::ifstream(clouds).good())) clouds.clear();
    const lm::diffusion_run run = lm::run_diffusion_fit(train, holdout, o, clouds);
    std::cout << run.report;
    if (f.count("header"))
        cloudmath::reference::write_text_file_atomically(f["header"], lm::diffusion_models_cpp(run.models, run.provenance, run.homogeneous));
    if (f.count("glsl"))
        cloudmath::reference::write_text_file_atomically(f["glsl"], lm::diffusion_models_glsl(run.models, run.provenance));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const std::string command = argc > 1 ? argv[1] : "";
        if (command == "--help" || command == "-h" || command == "help") {
            std::cout << usage_text;
            return 0;
        }
        if (command == "reference") return run_reference(argc, argv);
        if (command == "report") return run_report(argc, argv);
        if (command == "fit-diffusion") return run_fit_diffusion(argc, argv);
        if (command == "choice") return run_choice(argc, argv);
        throw usage_error(command.empty() ? "no command" : "unknown command '" + command + "'");
    } catch (const usage_error& e) {
        std::cerr << "cloudmath_lighting_error: " << e.what() << " (--help for usage)\n";
        return 2;
    } catch (const std::invalid_argument& e) {
        std::cerr << "cloudmath_lighting_error: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "cloudmath_lighting_error: " << e.what() << '\n';
        return 1;
    }
}
