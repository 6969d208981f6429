// tools/reference/truths/lighting_error.hpp: the lighting models of lighting_models.hpp against the
// Monte Carlo reference (montecarlo.hpp): the reference data set of sphere and slab
// radiances, the error of a model on it, and least-squares fits of Wrenninge's a, b, c per
// octave count. The cloudmath_lighting_error tool (lighting_error_main.cpp) writes
// docs/data/lighting_reference.csv with it and turns that into docs/lighting_error.md.
//
// Use:
//   reference_set ref = read_reference("docs/data/lighting_reference.csv");
//   evaluator ev(ref);
//   model_spec production{attenuation::beer, 0.85, 0.5, 0.5, 0.5, 3};
//   error_summary e = measure(ref, ev.radiance(production), select_all());
//   lighting_fit f = fit_octaves(ev, ref, attenuation::beer, 4, 0.85, select_all());
//
// Error of a model on a set of rows. Each row is one pixel of an "image": the rays of one
// geometry (sphere, slab reflected, slab transmitted), optical thickness and sun angle.
// With L the model, L_ref the reference and Lbar the image's mean reference radiance,
// e = (L - L_ref) / Lbar, the error relative to the image's typical brightness (what a
// viewer compares; a relative error per pixel would let the darkest pixels, where the
// octave models are off by factors of 1e9 in thick media, decide everything):
//   rms  = sqrt(weighted mean of e^2)
//   bias = weighted mean of e                   (< 0: the model is too dark)
//   max  = max |e|
// Weights: every row of a geometry class (sphere, slab) has weight 1 / (rows of its class
// in the selection), so the sphere's many rays and the slab's few views count the same.
#ifndef CLOUDMATH_TOOLS_LIGHTING_ERROR_HPP
#define CLOUDMATH_TOOLS_LIGHTING_ERROR_HPP

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "lighting_models.hpp"
#include "montecarlo.hpp"

namespace cloudmath::reference::lighting {

// ---------------------------------------------------------------------------------------
// Reference data set: one row per camera ray, in the frame of lighting_models.hpp.
struct reference_row {
    std::string geometry;  // "sphere", "slab_reflected" or "slab_transmitted"
    double tau = 0.0;      // sphere: optical diameter; slab: optical thickness
    // sphere: angle between the view direction and the direction toward the sun (0 = sun
    // behind the sphere); slab: solar zenith angle.
    double sun_deg = 0.0;
    double view_mu = 0.0, view_phi_deg = 0.0;  // slab: exit cosine, relative azimuth (DISORT)
    double u = 0.0;                            // sphere: image coordinate, > 0 sunward
    glm::dvec3 origin{0.0}, dir{0.0}, sun{0.0};  // camera ray and unit vector toward the sun
    double radiance = 0.0, std_error = 0.0;      // L/F0 (1/sr) and its standard error
    std::uint64_t paths = 0;
    [[nodiscard]] bool is_sphere() const { return geometry == "sphere"; }
    [[nodiscard]] double mu() const;  // dot(dir, sun): cosine of the single-scattering angle
};

struct reference_set {
    std::string phase_spec;  // montecarlo.hpp phase spec, e.g. "hg:0.85"
    double albedo = 1.0;
    std::vector<std::pair<std::string, std::string>> metadata;  // "# key: value" lines
    std::vector<reference_row> rows;
};

struct reference_options {
    std::vector<double> taus{1, 2, 5, 10, 20, 50, 100};
    std::vector<double> sphere_view_angles_deg{30, 60, 90, 120, 150, 170};
    unsigned sphere_points = 9;  // rays along the diameter (make_sphere_camera_line)
    std::vector<double> slab_sun_zenith_deg{0, 60, 80};
    std::string slab_views = "r:1,0;r:0.5,0;r:0.5,180;t:1,0;t:0.5,0;t:0.5,180";
    std::string phase = "hg:0.85";
    double albedo = 1.0;
    // Every ray gets `paths`; rays whose relative standard error is above target_rel_error
    // get more, (se / target)^2 times as many in all, at most max_paths.
    std::uint64_t paths = 200000;
    std::uint64_t max_paths = 3200000;
    double target_rel_error = 0.01;
    std::uint64_t seed = 1;
    unsigned threads = 0;  // 0 = every core
    std::function<void(const std::string&)> log;  // one line per finished job, may be empty
};

// The held-out split: none of its optical thicknesses, sphere view angles, slab sun angles
// or slab views is in the default reference_options (the split models are fitted on), so
// errors measured on it are out of sample. Run it with other phase functions too
// (hg:0.75, hg:0.9) for the error away from the fitted g.
[[nodiscard]] reference_options holdout_reference_options();

// Throws std::invalid_argument for empty lists or values out of range.
[[nodiscard]] reference_set generate_reference(const reference_options& options);
// CSV with "# key: value" metadata lines, written through write_text_file_atomically (a
// temporary beside path, renamed over it). Throws std::runtime_error naming the path on I/O
// failure.
void write_reference(const reference_set& set, const std::string& path);
// Throws std::runtime_error naming the path and line for unreadable or malformed files.
[[nodiscard]] reference_set read_reference(const std::string& path);

// The camera direction of a slab view (montecarlo.hpp's slab_view) in the frame of
// lighting_models.hpp (z up, sun in the x-z plane): (s cos phi, s sin phi, -+mu) with
// s = sqrt(1 - mu^2), minus for a reflected view (camera above, looking down).
[[nodiscard]] glm::dvec3 slab_view_direction(const mc::slab_view& view);

// The model-independent radiance integral of a row (lighting_models.hpp).
[[nodiscard]] ray_quadrature row_quadrature(const reference_row& row, double albedo,
                                            double panel = 0.25);

// ---------------------------------------------------------------------------------------
// A lighting model with HG octaves: form, g of the medium's HG phase, Wrenninge's a, b, c.
struct model_spec {
    attenuation form = attenuation::beer;
    double g = 0.85, a = 0.5, b = 0.5, c = 0.5;
    int octaves = 3;
};
[[nodiscard]] std::string describe(const model_spec& spec);  // "beer N=3 a=0.5 b=0.5 c=0.5"

// Evaluates models on every row of a set, with the quadratures computed once. Its results
// equal radiance(make_model(...), row_quadrature(...)) to rounding (tested).
class evaluator {
public:
    explicit evaluator(const reference_set& set, double panel = 0.25);
    [[nodiscard]] std::vector<double> radiance(const model_spec& spec) const;
    [[nodiscard]] std::size_t nodes() const { return weight_.size(); }

private:
    std::vector<std::size_t> begin_;  // rows + 1 offsets into the node arrays
    std::vector<double> mu_;          // per row
    std::vector<double> weight_, tau_light_, powder_factor_;  // per node
};

// ---------------------------------------------------------------------------------------
using row_filter = std::function<bool(const reference_row&)>;
[[nodiscard]] row_filter select_all();

struct error_summary {
    double rms = 0.0, bias = 0.0, max = 0.0;
    std::size_t max_row = 0;  // index of the row of the maximum
    std::size_t rows = 0;
};
// True when a row counts in the selection's measures and fits: selected, and its reference
// radiance > 0 (the relative errors divide by it).
[[nodiscard]] bool row_counts(const reference_row& row, const row_filter& select);
// Per row: the mean reference radiance of its image (Lbar above).
[[nodiscard]] std::vector<double> image_means(const reference_set& set);
// Rows where the reference is not > 0 are skipped. model has one value per row of set.
[[nodiscard]] error_summary measure(const reference_set& set, const std::vector<double>& model,
                                    const row_filter& select);
// rms of the reference's own standard error / Lbar over the selection (same weights): the
// noise floor of every rms measured on it.
[[nodiscard]] double noise_floor(const reference_set& set, const row_filter& select);

// Least squares: minimises the rms above over a, b, c in (0, 1) (logistic transforms) for the given form, g and octave
// count, by Nelder-Mead from `start` (default a = b = c = 0.5), from (0.8, 0.8, 0.5) and
// from (0.2, 0.3, 0.8), keeping the best. octaves = 1 has nothing to fit (single
// scattering) and returns the model as given.
struct lighting_fit {
    model_spec spec;
    double residual = 0.0;  // the rms at the fitted parameters
    int evaluations = 0;
};
[[nodiscard]] lighting_fit fit_octaves(const evaluator& ev, const reference_set& set,
                                       attenuation form, int octaves, double g,
                                       const row_filter& select,
                                       const model_spec* start = nullptr);

}  // namespace cloudmath::reference::lighting

#endif  // CLOUDMATH_TOOLS_LIGHTING_ERROR_HPP
