// tools/reference/truths/lighting_report.hpp: the lighting error report of cloudmath_lighting_error:
// every lighting model and the library's multiple-scattering presets measured against the
// Monte Carlo reference, fits of a, b, c per octave count, form and range of optical
// thickness, and the cheapest model within 10% and 1%. Writes docs/lighting_error.md,
// docs/lighting_error.csv and docs/images/lighting_error_*.svg.
#ifndef CLOUDMATH_TOOLS_LIGHTING_REPORT_HPP
#define CLOUDMATH_TOOLS_LIGHTING_REPORT_HPP

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "lighting_error.hpp"

namespace cloudmath::reference::lighting {

// A named selection of reference rows.
struct row_subset {
    std::string id;     // stable, used in the CSV ("all", "tau_1_2", ...)
    std::string label;  // for the tables
    row_filter select;
};
// The optical-thickness ranges the fits and presets are made for: all (1-100), thin (up to
// 10), thick (10 and more).
[[nodiscard]] const std::vector<row_subset>& fit_ranges();
// The columns of the report's error tables (by thickness, by geometry and sun).
[[nodiscard]] const std::vector<row_subset>& report_subsets();

// Relative cost of a model per sample: the exponentials it evaluates (N for the octaves,
// one more for the powder factor, 2N for Nubis' two-exponential attenuation). The phase
// functions are per ray, not per sample, in a ray marcher with a fixed sun direction.
[[nodiscard]] int model_cost(const model_spec& spec);

// The smallest octave count whose fitted residual is within octave_tolerance of the best
// over 1..max_octaves: more octaves than that buy less than 0.2% of rms error.
inline constexpr double octave_tolerance = 0.002;
inline constexpr int max_octaves = 8;

struct report_options {
    std::string reference_path = "docs/data/lighting_reference.csv";
    std::string docs_dir = "docs";
    std::string images_dir = "docs/images";
    // Where to write the generated data of cloudmath/lighting_choice.hpp (empty: nowhere).
    std::string choice_header;
    std::function<void(const std::string&)> log;  // progress lines, may be empty
};
struct report_summary {
    std::size_t rows = 0, fits = 0, images = 0;
};
// Throws std::runtime_error naming the path on unreadable input or unwritable output.
report_summary write_report(const report_options& options);

// The text of include/cloudmath/lighting_choice_data.hpp: every shipped model (the
// ms_preset octaves, the diffusion models) with its rms error at each optical thickness of
// the reference set, measured with the library functions.
[[nodiscard]] std::string lighting_choice_header(const reference_set& set,
                                                 const std::string& reference_name);

}  // namespace cloudmath::reference::lighting

#endif  // CLOUDMATH_TOOLS_LIGHTING_REPORT_HPP
