// tools/reference/optics/phase_error.hpp: measures how far cloudmath's analytic phase functions are
// from a tabulated (Lorenz-Mie) phase function, fits their parameters to the table, and
// draws both as small SVG plots. The cloudmath_phase_error tool (phase_error_main.cpp) turns
// this into docs/phase_error.md and docs/phase_error.csv.
//
// Use:
//   const phase_table mie = read_phase_table("docs/data/mie_c1_0.55um.csv");
//   const phase_comparison c = compare(mie, [](double mu) { return phase_hg(mu, 0.85); });
//   const fit_result hg = fit_hg(make_fit_target(mie));       // hg.parameters = {g}
//   for (const phase_variant& v : phase_variants(mie, 6.0)) ...  // every model of the report
//
// Convention: mu = cos(scattering angle), mu = +1 forward (as cloudmath and phase_table).
// Models: Henyey & Greenstein 1941, dual-lobe HG (Hillaire 2016, Frostbite), Cornette & Shanks
// 1992, Draine 2003, Jendersie & d'Eon 2023 (all in cloudmath/phase.hpp). Minimiser:
// Nelder & Mead, Computer Journal 7:308 (1965), with the usual coefficients (reflection 1,
// expansion 2, contraction 1/2, shrink 1/2; Lagarias et al., SIAM J. Optim. 9:112, 1998).
#ifndef CLOUDMATH_TOOLS_PHASE_ERROR_HPP
#define CLOUDMATH_TOOLS_PHASE_ERROR_HPP

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "phase_table.hpp"

namespace cloudmath::reference {

// A phase function of mu in 1/sr.
using phase_function = std::function<double(double mu)>;

// ---------------------------------------------------------------------------------------
// Angular regions. Each covers [theta_min_deg, theta_max_deg) of scattering angle; the last
// one also includes 180 degrees.
struct angular_region {
    const char* name;
    double theta_min_deg;
    double theta_max_deg;
    const char* why;  // one line for the report
};

// forward [0, 5): the diffraction peak of 5-10 um droplets, about lambda/d rad wide
//                 (0.55 um / 12 um = 2.6 deg), with its first rings;
// side [5, 160):  the smooth side scattering, its minimum near 100-120 deg and the cloud bow
//                 near 140 deg;
// backward [160, 180]: the rise to backscatter and the glory within a few degrees of 180.
[[nodiscard]] const std::vector<angular_region>& phase_error_regions();

// ---------------------------------------------------------------------------------------
// Comparison of a model with a table.
//
// Quadrature: the table's angles plus the region boundaries, each interval cut into
// compare_subdivisions equal steps of theta. At every node the table is evaluated with its
// own linear-in-mu interpolation (phase_table::evaluate) and the model directly; integrals
// over the sphere are 2 pi times trapezoids in mu over the nodes (exact for the table itself;
// |p_model - p_table| is integrated exactly for a difference linear between nodes, crossings
// included).
inline constexpr int compare_subdivisions = 8;

struct region_error {
    angular_region region{};
    // exp(rms) - 1, rms = sqrt(mean over the region's solid angle of ln^2(p_model/p_table)):
    // a typical relative factor (0.1 = typically 10% off in either direction).
    double rms_factor = 0.0;
    double max_rel_error = 0.0;  // max over the nodes of |p_model/p_table - 1|
    double max_at_deg = 0.0;     // scattering angle of that maximum
    // This region's share of the misdirected energy, 0.5 * integral of |p_model - p_table|.
    double misdirected = 0.0;
    double table_energy = 0.0;  // integral of p_table over the region (fraction of the light)
};

struct phase_comparison {
    std::vector<region_error> regions;  // in the order of phase_error_regions()
    // 0.5 * integral over the sphere of |p_model - p_table| dOmega: 0 identical, 1 disjoint;
    // the fraction of the scattered light the model sends in the wrong directions.
    double misdirected_energy = 0.0;
    double model_integral = 0.0;     // integral of p_model dOmega (1 when normalised)
    double table_integral = 0.0;     // phase_table::integral()
    double model_mean_cosine = 0.0;  // integral of mu p_model / integral of p_model
    double table_mean_cosine = 0.0;  // mean_cosine() / integral() of the table
};

// Requires a finalized table. Model values <= 0 where the table is > 0 give an infinite ln
// ratio (reported as such); nodes where both are 0 count as equal.
[[nodiscard]] phase_comparison compare(const phase_table& table, const phase_function& model);

// ---------------------------------------------------------------------------------------
// Least-squares fits in log space over the table's angles:
//   minimise sum_i w_i (ln p_model(mu_i) - ln p_table(mu_i))^2,
// with w_i the angular width of row i in degrees (half the distance between its
// neighbours). Uniform weight per degree of scattering angle: the table's rows are 25 times
// denser near 0 and 180 deg than in between, so equal row weights would fit mostly the
// peaks; solid-angle weights (sin theta) would give the forward peak, which holds about half
// of the scattered light and makes the silver lining, almost no weight. Per degree, every
// direction of a view sweeping around the sun counts the same. Rows where the table is 0
// are skipped.
struct log_fit_target {
    std::vector<double> mu;
    std::vector<double> log_phase;  // ln p_table
    std::vector<double> weight;     // degrees
    double weight_sum = 0.0;
    double mean_cosine = 0.0;  // of the table, for moment-matched starting points
};
[[nodiscard]] log_fit_target make_fit_target(const phase_table& table);

// sqrt(sum w_i r_i^2 / sum w_i), r_i = ln(p_model/p_table): the RMS ln error per degree, the
// residual every fit minimises (squared). Infinite when the model is <= 0 at some row.
[[nodiscard]] double log_residual(const log_fit_target& target, const phase_function& model);

// Nelder-Mead simplex minimiser. Starts from x0 with a simplex of edge `step`, stops when the
// spread of values is below f_tolerance (absolute) and the simplex diameter below
// x_tolerance, or after max_evaluations; then restarts from the best point with a fresh
// simplex (it can collapse early in narrow valleys) until a restart no longer improves by
// more than f_tolerance, at most `restarts` times.
struct nelder_mead_options {
    double step = 0.5;
    double f_tolerance = 1e-13;
    double x_tolerance = 1e-9;
    int max_evaluations = 4000;  // per start and per restart
    int restarts = 3;
};
struct nelder_mead_result {
    std::vector<double> x;
    double value = 0.0;
    int evaluations = 0;
};
[[nodiscard]] nelder_mead_result nelder_mead(
    const std::function<double(const std::vector<double>&)>& f, std::vector<double> x0,
    const nelder_mead_options& options = {});

// Each fit runs Nelder-Mead from several starting points on transformed parameters
// (g = phase_g_max tanh(x), so every g the minimiser tries is one the phase function uses
// unclamped; weights = logistic(x) in (0, 1); alpha, d = exp(x) > 0) and keeps the best.
struct fit_result {
    std::vector<double> parameters;  // natural units, order given per function below
    double residual = 0.0;           // log_residual at the parameters
    int evaluations = 0;             // objective evaluations, all starts together
};
[[nodiscard]] fit_result fit_hg(const log_fit_target& t);                   // {g}
[[nodiscard]] fit_result fit_hg_dual(const log_fit_target& t);              // {g0, g1, w}, g0 >= g1
[[nodiscard]] fit_result fit_cornette_shanks(const log_fit_target& t);      // {g}
[[nodiscard]] fit_result fit_draine(const log_fit_target& t);               // {g, alpha}
[[nodiscard]] fit_result fit_mie_approx_diameter(const log_fit_target& t);  // {d_um}
// {g_hg, g_draine, alpha, w_draine} of phase_mie_approx(mu, mie_approx_parameters).
[[nodiscard]] fit_result fit_mie_approx_parameters(const log_fit_target& t);

// Cornette-Shanks mean cosine 3 g (4 + g^2) / (5 (2 + g^2)) (Cornette & Shanks 1992) and its
// inverse: the g in (-1, 1) whose CS mean cosine is the given value (|value| < 1), the root
// of 3 g^3 - 5 G g^2 + 12 g - 10 G = 0 (increasing in g, one real root).
[[nodiscard]] double cornette_shanks_mean_cosine(double g);
[[nodiscard]] double cornette_shanks_g_for_mean_cosine(double mean_cosine);

// ---------------------------------------------------------------------------------------
// The model variants of the report, in report order:
//   hg_moment           phase_hg, g = table mean cosine
//   hg_fit              phase_hg, g fitted
//   dual_frostbite      phase_hg_dual, Frostbite example (0.8, -0.5, 0.5)
//   dual_fit            phase_hg_dual, (g0, g1, w) fitted
//   schlick_moment      phase_hg_schlick, g = table mean cosine (Schlick's k(g))
//   cs_moment           phase_cornette_shanks, CS mean cosine = table mean cosine
//   cs_fit              phase_cornette_shanks, g fitted
//   draine_fit          phase_draine, (g, alpha) fitted (alpha = 1 moment matched is cs_moment)
//   mie_approx_d2reff   phase_mie_approx, d = 2 r_eff (omitted when r_eff_um is not > 0)
//   mie_approx_dfit     phase_mie_approx, d fitted
//   mie_approx_fit      phase_mie_approx(mu, mie_approx_parameters), all four fitted
struct phase_variant {
    std::string id;        // as above; stable, used in the CSV
    std::string function;  // cloudmath function it evaluates
    std::string label;     // short human-readable name
    std::string method;    // "moment matched", "published example", "size = 2 r_eff", "fitted"
    std::vector<std::pair<std::string, double>> parameters;
    double residual = 0.0;  // log_residual against the table
    phase_function model;
};
// progress(fraction in [0, 1]) is called between fits when given.
[[nodiscard]] std::vector<phase_variant> phase_variants(
    const phase_table& table, double r_eff_um,
    const std::function<void(double)>& progress = nullptr);

// ---------------------------------------------------------------------------------------
// SVG plots (self-contained SVG 1.1 text). Curves are decimated in screen space (points
// that stay within a fraction of a pixel of the line through their neighbours are dropped)
// to at most svg_max_points_per_curve points each; every curve is one <polyline>.
inline constexpr std::size_t svg_max_points_per_curve = 600;

struct plot_curve {
    std::string label;
    std::string colour;             // SVG colour, e.g. "#1f77b4"
    std::string dash;               // stroke-dasharray, "" for solid
    double width = 1.5;             // stroke width in px
    std::vector<double> theta_deg;  // ascending scattering angles
    std::vector<double> phase;      // 1/sr, same length
};

// Titles may hold several lines separated by '\n' (the first is drawn larger).
// x = scattering angle from 0 to theta_max_deg (linear), y = log10 phase, whole decades
// spanning the curves' values in that range (at most 9 decades below the largest value).
[[nodiscard]] std::string svg_phase_cartesian(const std::vector<plot_curve>& curves,
                                              const std::string& title,
                                              double theta_max_deg = 180.0);
// Polar plot: angle = scattering angle, forward to the right, upper half mirrored into the
// lower half; radius = log10(p) from floor_per_sr (centre) to the decade above the maximum.
[[nodiscard]] std::string svg_phase_polar(const std::vector<plot_curve>& curves,
                                          const std::string& title, double floor_per_sr = 1e-3);

// Escapes & < > " ' for XML text and attribute values.
[[nodiscard]] std::string xml_escape(const std::string& text);

}  // namespace cloudmath::reference

#endif  // CLOUDMATH_TOOLS_PHASE_ERROR_HPP
