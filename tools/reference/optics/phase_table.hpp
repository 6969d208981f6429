// tools/reference/optics/phase_table.hpp: a tabulated phase function, the exchange format between
// the Lorenz-Mie tool (which writes tables), the Monte Carlo path tracer (which samples them)
// and the error reports (which compare cloudmath's analytic phase functions with them).
//
// File format (CSV, written by write_phase_table, read by read_phase_table):
//   # key: value                 metadata lines first (distribution, wavelength_um, ...)
//   theta_deg,mu,phase           header line
//   0,1,123.456                  one row per angle, theta ascending from 0 to 180 inclusive,
//   ...                          mu = cos(theta), phase in 1/sr, integrating to 1 over the
//                                sphere; numbers written with 17 significant digits.
// Convention: theta is the scattering angle, 0 = forward (cloudmath's mu = +1).
// Between rows the function is linear in mu: that is what evaluate() returns, what
// integral() integrates exactly and what sample_mu() samples exactly, so a path tracer that
// samples and evaluates the table is consistent with itself.
#ifndef CLOUDMATH_TOOLS_PHASE_TABLE_HPP
#define CLOUDMATH_TOOLS_PHASE_TABLE_HPP

#include <string>
#include <utility>
#include <vector>

namespace cloudmath::reference {

struct phase_table {
    std::vector<double> theta_deg;  // ascending, first 0, last 180
    std::vector<double> phase;      // 1/sr, same length, >= 0
    std::vector<std::pair<std::string, std::string>> metadata;  // "# key: value" lines, in order

    // Value of the metadata key, or "" when absent.
    [[nodiscard]] std::string meta(const std::string& key) const;
    void set_meta(const std::string& key, const std::string& value);  // replaces or appends

    // Phase at cosine mu (clamped to [-1, 1]), linear in mu between rows. Requires finalize().
    [[nodiscard]] double evaluate(double mu) const;
    // 2 pi times the integral over mu of the piecewise-linear function (exact for it).
    [[nodiscard]] double integral() const;
    // 2 pi times the integral of mu p(mu) (the mean cosine g when integral() is 1).
    [[nodiscard]] double mean_cosine() const;
    // Divides the phase by integral() so that it integrates to 1; returns the old integral.
    double normalize();
    // Builds the cached mu array and CDF. Throws std::invalid_argument on a malformed table
    // (fewer than 2 rows, theta not strictly ascending from 0 to 180, negative or non-finite
    // phase, zero integral). read_phase_table calls it; call it after filling a table by hand.
    void finalize();
    // Cosine mu with density p(mu) 2 pi / integral() for u in [0, 1): exact inversion of the
    // piecewise-quadratic CDF. Requires finalize().
    [[nodiscard]] double sample_mu(double u) const;

    // Cached by finalize(): mu ascending (row order reversed) and the CDF over mu.
    std::vector<double> mu_ascending;
    std::vector<double> phase_ascending;
    std::vector<double> cdf;  // cdf[i] = integral from -1 to mu_ascending[i], cdf.back() = 1
    double total = 0.0;       // 2 pi * integral over mu
};

// Tabulates f(mu) on the given angles (degrees, ascending 0 .. 180) and finalizes the table.
template <class F>
[[nodiscard]] phase_table tabulate_phase(const std::vector<double>& theta_deg, F&& f);

// The default angular grid of the tools: fine near 0 and 180 degrees, where cloud phase
// functions have their forward peak and glory. Steps: 0.01 deg on [0, 1], 0.05 on [1, 5],
// 0.1 on [5, 15], 0.25 on [15, 165], 0.1 on [165, 175], 0.02 on [175, 180]: 1231 angles.
[[nodiscard]] std::vector<double> default_angles_deg();

// A "# key: value" metadata line (the '#' first): key and value with the spaces, tabs and
// carriage returns around them removed; the value is empty when there is no ':'. Every
// reference file of the tools starts with such lines.
[[nodiscard]] std::pair<std::string, std::string> parse_metadata_line(const std::string& line);

// Writes text to a temporary file beside path and renames it over path, checking every
// step, so that no reader ever sees half a file and a failed run leaves the old file and no
// temporary (tools/common/atomic_file.hpp: cloudmath::tools::write_file_atomically). Throws
// std::runtime_error naming the path and the reason. Every output file of the reference
// tools is written through it.
void write_text_file_atomically(const std::string& path, const std::string& text);

// Writes the table (metadata, header, rows) through write_text_file_atomically. Throws
// std::runtime_error when the file cannot be written (the message names the path).
void write_phase_table(const std::string& path, const phase_table& table);
// Reads a table written by write_phase_table (or by hand in that format) and finalizes it.
// Throws std::runtime_error naming the path and line on any malformed content.
[[nodiscard]] phase_table read_phase_table(const std::string& path);

}  // namespace cloudmath::reference

#include <cmath>

template <class F>
cloudmath::reference::phase_table cloudmath::reference::tabulate_phase(
    const std::vector<double>& theta_deg, F&& f) {
    phase_table t;
    t.theta_deg = theta_deg;
    t.phase.reserve(theta_deg.size());
    const double deg = 3.14159265358979323846 / 180.0;
    for (double th : theta_deg) t.phase.push_back(f(th == 90.0 ? 0.0 : std::cos(th * deg)));
    t.finalize();
    return t;
}

#endif  // CLOUDMATH_TOOLS_PHASE_TABLE_HPP
