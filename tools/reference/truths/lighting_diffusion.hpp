// tools/reference/truths/lighting_diffusion.hpp: fitting and measuring the chord-diffusion lighting
// model of cloudmath/diffusion_lighting.hpp against the Monte Carlo reference.
//
// The model is linear in its fitted numbers (the table C and the peak weights w), so its
// radiance along a reference ray is a dot product of those numbers with the ray's
// integrated features (plus the exact single scattering), and the fit is a linear least
// squares problem, solved in closed form with a smoothness penalty on the table. Every
// error reported is then measured with the library function itself (float table, double
// arithmetic), not with the features.
//
// Use:
//   std::vector<reference_set> train = {read_reference(...), ...};
//   diffusion_fit_result f = fit_diffusion_model(train, {});
//   diffusion_evaluator ev(holdout_set);
//   error_summary e = measure(holdout_set, ev.radiance(f.model), select_all());
#ifndef CLOUDMATH_TOOLS_LIGHTING_DIFFUSION_HPP
#define CLOUDMATH_TOOLS_LIGHTING_DIFFUSION_HPP

#include <cstddef>
#include <string>
#include <vector>

#include <cloudmath/diffusion_lighting.hpp>

#include "lighting_error.hpp"

namespace cloudmath::reference::lighting {

// A reference set's phase function as a mixture of two HG lobes, (1 - w) HG(g0) + w HG(g1):
// "hg:G" is (G, 0, 0), "dual_hg:G0,G1,W" is (G0, G1, W), "isotropic" (0, 0, 0).
struct hg_mixture {
    double g0 = 0.0, g1 = 0.0, w = 0.0;
    // Its mean cosine, the model's g: (1 - w) g0 + w g1.
    [[nodiscard]] double mean_cosine() const;
    // With its eccentricities scaled by `scale`: the model's phase(mu, scale) callback.
    [[nodiscard]] double phase(double mu, double scale) const;
};
// Throws std::invalid_argument naming the spec for any other spec or a malformed number.
[[nodiscard]] hg_mixture parse_hg_mixture(const std::string& spec);
// parse_hg_mixture(spec).mean_cosine().
[[nodiscard]] double phase_spec_mean_cosine(const std::string& spec);

// Number of fitted numbers: the table, then the peak weights.
inline constexpr std::size_t diffusion_unknowns =
    static_cast<std::size_t>(diffusion_layout::table_size + diffusion_layout::peak_size);

// The model's features at one sample (HG phase of asymmetry g, single-scattering albedo):
// M = single + sum_k coefficient_k feature_k, with the table's max(C, 0) left out (the fit
// is linear).
[[nodiscard]] std::vector<double> diffusion_features(double tau_sun, double tau_behind,
                                                     double tau_view, double mu, double g,
                                                     double albedo, double& single);

// Evaluates models on every row of a set (its phase function, g its mean cosine), the
// quadratures computed once; radiance() calls cloudmath::diffusion_scattering_with at every
// node.
class diffusion_evaluator {
public:
    explicit diffusion_evaluator(const reference_set& set, double panel = 0.25);
    [[nodiscard]] std::vector<double> radiance(const diffusion_model& m) const;
    [[nodiscard]] double g() const { return g_; }
    // Per row: the integrated features (diffusion_unknowns) and the single scattering.
    [[nodiscard]] std::vector<std::vector<double>> row_features(std::vector<double>& single) const;

private:
    hg_mixture phase_;
    double g_ = 0.0, albedo_ = 1.0;
    std::vector<std::size_t> begin_;
    std::vector<double> mu_;
    std::vector<double> weight_, tau_light_, tau_behind_, tau_view_;
};

struct diffusion_fit_options {
    // Penalty on the table's second differences along every axis with 3 or more nodes and
    // on its differences from 1 (the uncorrected diffusion), relative to the mean diagonal
    // of the normal equations. Larger: smoother, closer to plain diffusion.
    // Chosen by leave-one-set-out cross-validation on the training sets (--cv).
    double smoothing = 0.01;
    double ridge = 1e-4;
    double panel = 0.25;  // quadrature panel, optical units
};

struct diffusion_fit_result {
    diffusion_model model{};  // name "fitted", errors left 0
    std::vector<double> coefficients;  // in double, as solved
    double residual = 0.0;  // mean over the sets of the rms of the linear model
};

// The least-squares rows of one set: per reference row, the features and the target (the
// reference minus the single scattering) over the image mean, and the row's weight (within
// a set the sphere and the slab halves as in measure()). They do not depend on the fit's
// options, so cross-validation builds them once.
struct diffusion_fit_rows {
    std::vector<std::vector<double>> features;
    std::vector<double> target, weight;
};
[[nodiscard]] diffusion_fit_rows prepare_diffusion_fit(const reference_set& set, double panel);

// Least squares over all rows of the sets (each set's rms counts equally). Throws
// std::invalid_argument for no set.
[[nodiscard]] diffusion_fit_result fit_diffusion_model(const std::vector<const diffusion_fit_rows*>& sets,
                                                       const diffusion_fit_options& options);
// The same from the reference sets (prepare_diffusion_fit with options.panel).
[[nodiscard]] diffusion_fit_result fit_diffusion_model(const std::vector<reference_set>& sets,
                                                       const diffusion_fit_options& options);

// The plain diffusion model: table 1 everywhere, forward peak e^(-x) - e^(-tau) with c = 4/5.
[[nodiscard]] diffusion_model physical_diffusion_model();

// The data of the shipped fit, in directory `data_dir` (docs/data): the training sets (the
// report's reference, g = 0.85, then g = 0.8 and 0.93 over the same geometry) and the
// held-out split (holdout_reference_options() at g = 0.75, 0.85 and 0.9, and at g = 0.85
// with albedo 0.99: the model's absorption, never fitted, since every fitted set has albedo 1;
// and the example renderer's medium, dual-lobe HG 0.8 / -0.25 / 0.2 with albedo 0.99).
[[nodiscard]] std::vector<std::string> diffusion_training_paths(const std::string& data_dir);
[[nodiscard]] std::vector<std::string> diffusion_holdout_paths(const std::string& data_dir);

// The whole fit as scripts/reference.sh runs it: fits on the training sets (the first is the
// report's reference, whose "all" row gives the model's rms_error and max_error), measures
// the fitted and the plain model with the library function on every set (holdout_rms_error:
// the worst held-out rms), beside the octave presets, and returns both models with a text
// report and the provenance line of the generated headers (file names only, so that the
// headers do not depend on where the tool ran).
// With clouds_path (docs/data/diffusion_clouds.txt, cloudmath_volume_truth fit-clouds), the
// whole-cloud fit joins them as a third model, "clouds", measured on the same sets; it is
// not in the generated all[] (the models of homogeneous media that lighting_choice ranks).
struct diffusion_run {
    std::vector<diffusion_model> models;  // fitted, physical[, clouds]
    std::size_t homogeneous = 2;          // the first models, those of all[]
    std::string report;
    std::string provenance;
};
[[nodiscard]] diffusion_run run_diffusion_fit(const std::vector<std::string>& train_paths,
                                              const std::vector<std::string>& holdout_paths,
                                              const diffusion_fit_options& options,
                                              const std::string& clouds_path = "");
// The whole-cloud fit's file: lines "table,I,V" (I from 0 to table_size - 1) and "peak,I,V",
// '#' comments and the header "kind,index,value". The model named "clouds", its errors 0.
// Throws std::runtime_error naming the path and line for anything else, a missing number
// or a repeated one.
[[nodiscard]] diffusion_model read_clouds_model(const std::string& path);
// The stored whole-cloud fit in directory `data_dir`: data_dir/diffusion_clouds.txt.
[[nodiscard]] std::string diffusion_clouds_path(const std::string& data_dir);

// Leave-one-set-out cross-validation over the training sets alone (the held-out split is
// never looked at): for each smoothing and ridge of a small grid, the fit on all sets but
// one measured on that one (the library function), averaged. Chooses the options the
// shipped fit uses, without tuning on what is reported as out of sample. A text table.
[[nodiscard]] std::string diffusion_cross_validation(const std::vector<std::string>& train_paths);

// C++ and GLSL source of the generated models header (diffusion_lighting_models.hpp and
// glsl/diffusion_lighting_models.glsl); `models` in order, the first is the default, the
// first `in_all` of them listed in the C++ all[].
[[nodiscard]] std::string diffusion_models_cpp(const std::vector<diffusion_model>& models,
                                               const std::string& provenance,
                                               std::size_t in_all = static_cast<std::size_t>(-1));
[[nodiscard]] std::string diffusion_models_glsl(const std::vector<diffusion_model>& models,
                                                const std::string& provenance);

}  // namespace cloudmath::reference::lighting

#endif  // CLOUDMATH_TOOLS_LIGHTING_DIFFUSION_HPP
