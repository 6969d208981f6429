// tools/reference/truths/atmosphere_truth.hpp: the sky's ground truth set and its comparison with
// the library's model (issue 26). The set: for each sun elevation (90, 30, 10, 2, -2
// degrees, sun at azimuth 0, camera at sea level) a table of 7 directions (the zenith; the
// horizon at 1 degree elevation towards the sun, across and away from it; 5 and 15 degrees
// above the sun, or below it for the sun at zenith; 20 degrees beside it) and a panorama of
// the half sky on the sun's side of symmetry (36 azimuths 0-180 x 24 elevations 0-90, cell
// centres). The held-out set: the same directions for the sun at 60, 20, 5, 0 and -1 degrees.
// The model: atmosphere_sky_radiance in float with the 32 x 32 multiple-scattering LUT of
// atmosphere_multiple_scattering_refined_lut (64 directions, 20 steps, 3 passes) with its
// moments and aerosol field (atmosphere_make_sky_luts), 32 view and 32 sun steps: the defaults
// docs/atmosphere.md documents.
#ifndef CLOUDMATH_TOOLS_ATMOSPHERE_TRUTH_HPP
#define CLOUDMATH_TOOLS_ATMOSPHERE_TRUTH_HPP

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "atmosphere_tracer.hpp"

namespace cloudmath::reference::atmo {

inline constexpr std::array<double, 5> truth_sun_elevations{90.0, 30.0, 10.0, 2.0, -2.0};
// The held-out set: the same directions for sun elevations between and beside the truth's,
// traced once the model's design was chosen on the set above and never used to choose it.
inline constexpr std::array<double, 5> holdout_sun_elevations{60.0, 20.0, 5.0, 0.0, -1.0};
inline constexpr int panorama_azimuths = 36, panorama_elevations = 24;

// One row of the truth file.
struct truth_row {
    std::string set;  // "table" or "panorama"
    std::string name;  // table: zenith, horizon_sun, horizon_side, horizon_away, sun_5, sun_15, sun_side; panorama: az_el
    double sun_elevation = 0, view_elevation = 0, view_azimuth = 0;
    double radiance[3] = {0, 0, 0}, std_error[3] = {0, 0, 0};
};

// The sun elevations of a set by its name ("truth" or "holdout"); throws std::invalid_argument
// for any other name.
std::vector<double> set_sun_elevations(const std::string& set_name);

// The rows of the set with their directions (radiance not filled in), for the sun elevations
// given (the truth's by default).
std::vector<truth_row> truth_set(const std::vector<double>& sun_elevations = set_sun_elevations("truth"));

// Reads a truth CSV (as `cloudmath_atmosphere_truth render` writes it); throws
// std::runtime_error naming the path (and the line) if it is missing, malformed, or not the
// set truth_set(sun_elevations) gives.
std::vector<truth_row> read_truth(const std::string& path,
                                  const std::vector<double>& sun_elevations = set_sun_elevations("truth"));

// The sky near the horizon (issue 37): views 2 and 10 degrees up, toward the sun's azimuth and
// away from it (up2_sun, up2_away, up10_sun, up10_away), for the sun at 2, 6, 20 and 60
// degrees; set "horizon". Its truth (docs/data/atmosphere_horizon.csv) is traced by
// `cloudmath_atmosphere_truth horizon --out`.
inline constexpr std::array<double, 4> horizon_sun_elevations{2.0, 6.0, 20.0, 60.0};
std::vector<truth_row> horizon_set();
// Reads a truth CSV whose rows must be `want`'s (set, name and directions), as read_truth.
std::vector<truth_row> read_rows(const std::string& path, const std::vector<truth_row>& want);

// The model's radiance (per unit sun illuminance, 1/sr) for each row, float, as documented.
std::vector<std::array<double, 3>> model_radiance(const std::vector<truth_row>& rows);

// The ground below the horizon: views down from sea level (straight down) and from 1 km
// (90, 30 and 5 degrees down, away from the sun's azimuth), for each sun elevation, traced
// with `paths` paths per channel, against atmosphere_sky_radiance (float, as model_radiance)
// with a ground lit by the sun only and by the sun and the sky
// (atmosphere_multiple_scattering_table::ground_irradiance, atmosphere_ground_irradiance_lut).
struct ground_row {
    double sun_elevation = 0, altitude = 0, view_elevation = 0;
    double truth[3] = {0, 0, 0}, std_error[3] = {0, 0, 0};
    double sun_only[3] = {0, 0, 0}, sky_lit[3] = {0, 0, 0};  // the model's radiance
};
std::vector<ground_row> ground_check(const std::vector<double>& sun_elevations, std::uint64_t paths,
                                     const mc::run_options& options);

// Relative errors (model / truth - 1) over the channels of the rows selected: rms and worst
// (the largest magnitude, with its sign), and the rms of the truth's relative standard errors.
struct error_summary {
    double rms = 0, worst = 0, noise = 0;
    int count = 0;
};
error_summary summarise(const std::vector<truth_row>& rows, const std::vector<std::array<double, 3>>& model,
                        const std::string& set, double sun_elevation);

}  // namespace cloudmath::reference::atmo

#endif  // CLOUDMATH_TOOLS_ATMOSPHERE_TRUTH_HPP
