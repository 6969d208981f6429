// cloudmath/lighting_choice.hpp: model only what a scene needs. Given a scene's range of
// optical thickness and an error budget, the cheapest shipped lighting model that meets the
// budget, with its measured error and cost.
//
// Use:      #include <cloudmath/lighting_choice.hpp>
//           const auto c = cloudmath::choose_lighting_model(1.0f, 10.0f, 0.6f);
//           if (c.kind == cloudmath::lighting_model_kind::octaves)
//               M = cloudmath::multiple_scattering(tau_sun, mu, g, *c.octaves);
//           else
//               M = cloudmath::diffusion_scattering(tau_sun, tau_behind, tau_view, mu, g,
//                                                   *c.diffusion);
// GLSL:     there is nothing to choose at run time in a shader: call this once in C++ (or
//           read the table in docs/lighting_error.md) and use the matching constant,
//           CM_MS_PRESET_<NAME> with cm_multiple_scattering or CM_DIFFUSION_MODEL_<NAME>
//           with cm_diffusion_scattering. c.name says which ("ms_preset::cheap", ...).
// Data:     the error of every shipped model at each optical thickness of the Monte Carlo
//           reference (docs/data/lighting_reference.csv: spheres and slabs, HG g = 0.85,
//           thickness 1, 2, 5, 10, 20, 50, 100), generated into lighting_choice_data.hpp by
//           cloudmath_lighting_error report; never typed by hand.
// Error:    over a range, the rms of the per-thickness rms errors of the thicknesses inside
//           it (the error measure of multiple_scattering_preset). A range with no measured
//           thickness inside takes the measured thickness nearest to it, and says so
//           (extrapolated = true). Bad input: NaN bounds or tau_max < tau_min give
//           kind = none; a negative budget meets nothing.
// Cost:     models are ordered by (extra inputs, exponentials per sample): the octaves need
//           only the optical depth toward the sun, the diffusion models also the optical
//           depth behind the sample (a second light march) and from the camera; so any
//           octave model within budget is preferred to a diffusion model.
// When no model meets the budget: the most accurate one, with meets_budget = false.
#ifndef CLOUDMATH_LIGHTING_CHOICE_HPP
#define CLOUDMATH_LIGHTING_CHOICE_HPP

#include <cmath>
#include <limits>

#include "diffusion_lighting.hpp"
#include "multiple_scattering.hpp"

namespace cloudmath {

enum class lighting_model_kind { none, octaves, diffusion };

// One shipped model with its measured errors (generated: lighting_choice_data.hpp).
struct lighting_model_record {
    const char* name;
    lighting_model_kind kind;
    const multiple_scattering_preset* octaves;  // kind == octaves
    const diffusion_model* diffusion;           // kind == diffusion
    int exponentials;                           // per sample
    int extra_inputs;                           // optical depths beyond tau_sun
};

struct lighting_model_choice {
    const char* name = "none";
    lighting_model_kind kind = lighting_model_kind::none;
    const multiple_scattering_preset* octaves = nullptr;
    const diffusion_model* diffusion = nullptr;
    float rms_error = 0.0f;  // measured over the range (header comment)
    int exponentials = 0;
    int extra_inputs = 0;
    bool meets_budget = false;
    bool extrapolated = false;  // no measured thickness inside the range
};

}  // namespace cloudmath

#include "lighting_choice_data.hpp"

namespace cloudmath {

// The rms error of model `index` of lighting_choice_data over [tau_min, tau_max]; sets
// extrapolated when no measured thickness lies inside. NaN-free for any finite range.
[[nodiscard]] inline float lighting_model_error(int index, float tau_min, float tau_max,
                                                bool& extrapolated) noexcept {
    namespace D = lighting_choice_data;
    float sum = 0.0f;
    int count = 0;
    for (int t = 0; t < D::thickness_count; ++t)
        if (D::thickness[t] >= tau_min && D::thickness[t] <= tau_max) {
            sum += D::rms[index][t] * D::rms[index][t];
            ++count;
        }
    extrapolated = count == 0;
    if (count == 0) {
        // The measured thickness nearest to the range (its middle, in log space). The middle
        // is the mean of the ends' logs, each end clamped to [1e-30, FLT_MAX]: the product
        // tau_min * tau_max overflowed to +Inf for ranges such as (200, +Inf), (200, FLT_MAX)
        // or (1e20, 1e20), and every distance was then equal (the thinnest thickness won).
        const auto log_end = [](float tau) {
            return std::log(detail::min(detail::max(tau, 1e-30f), std::numeric_limits<float>::max()));
        };
        const float log_mid = 0.5f * log_end(tau_min) + 0.5f * log_end(tau_max);
        int best = 0;
        for (int t = 1; t < D::thickness_count; ++t)
            if (std::abs(std::log(D::thickness[t]) - log_mid) < std::abs(std::log(D::thickness[best]) - log_mid))
                best = t;
        return D::rms[index][best];
    }
    return std::sqrt(sum / static_cast<float>(count));
}

// The cheapest model whose error over [tau_min, tau_max] is at most rms_budget (a fraction:
// 0.5 = 50%), or the most accurate one with meets_budget = false.
[[nodiscard]] inline lighting_model_choice choose_lighting_model(float tau_min, float tau_max,
                                                                 float rms_budget) noexcept {
    namespace D = lighting_choice_data;
    lighting_model_choice none;
    if (!(tau_min <= tau_max)) return none;  // also NaN bounds
    int chosen = -1, most_accurate = -1;
    float chosen_error = 0.0f, best_error = 0.0f;
    bool chosen_extrapolated = false, best_extrapolated = false;
    for (int i = 0; i < D::model_count; ++i) {
        bool extrapolated = false;
        const float e = lighting_model_error(i, tau_min, tau_max, extrapolated);
        if (most_accurate < 0 || e < best_error) {
            most_accurate = i;
            best_error = e;
            best_extrapolated = extrapolated;
        }
        if (!(e <= rms_budget)) continue;
        const lighting_model_record& r = D::models[i];
        const bool cheaper =
            chosen < 0 || r.extra_inputs < D::models[chosen].extra_inputs ||
            (r.extra_inputs == D::models[chosen].extra_inputs &&
             (r.exponentials < D::models[chosen].exponentials ||
              (r.exponentials == D::models[chosen].exponentials && e < chosen_error)));
        if (cheaper) {
            chosen = i;
            chosen_error = e;
            chosen_extrapolated = extrapolated;
        }
    }
    const bool meets = chosen >= 0;
    const int i = meets ? chosen : most_accurate;
    const lighting_model_record& r = D::models[i];
    lighting_model_choice c;
    c.name = r.name;
    c.kind = r.kind;
    c.octaves = r.octaves;
    c.diffusion = r.diffusion;
    c.rms_error = meets ? chosen_error : best_error;
    c.exponentials = r.exponentials;
    c.extra_inputs = r.extra_inputs;
    c.meets_budget = meets;
    c.extrapolated = meets ? chosen_extrapolated : best_extrapolated;
    return c;
}

}  // namespace cloudmath

#endif  // CLOUDMATH_LIGHTING_CHOICE_HPP
