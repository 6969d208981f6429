// Tests of lighting_choice.hpp: the choice follows the generated error table (budget met,
// cheapest first: fewer extra inputs, then fewer exponentials), the error over a range is
// the rms of the per-thickness errors, ranges outside the measurements are flagged, and
// bad input (NaN, reversed range, negative budget) gives defined answers. That the table is
// what the Monte Carlo data gives is checked by tools/reference (reference.lighting_presets).
#include <cloudmath/lighting_choice.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "test_support.hpp"

using namespace cloudmath;
namespace D = cloudmath::lighting_choice_data;

TEST_CASE("lighting_model_error: rms of the per-thickness errors inside the range") {
    for (int i = 0; i < D::model_count; ++i) {
        bool extrapolated = true;
        // The whole measured range.
        double sum = 0;
        for (int t = 0; t < D::thickness_count; ++t) sum += double(D::rms[i][t]) * double(D::rms[i][t]);
        CHECK(lighting_model_error(i, 0.0f, 1e9f, extrapolated) == doctest::Approx(std::sqrt(sum / D::thickness_count)).epsilon(1e-6));
        CHECK_FALSE(extrapolated);
        // One thickness.
        CHECK(lighting_model_error(i, D::thickness[2], D::thickness[2], extrapolated) == D::rms[i][2]);
        CHECK_FALSE(extrapolated);
        // Between two measured thicknesses, none inside: the nearest, flagged.
        const float a = D::thickness[0] * 1.01f, b = D::thickness[0] * 1.02f;
        CHECK(lighting_model_error(i, a, b, extrapolated) == D::rms[i][0]);
        CHECK(extrapolated);
        CHECK(lighting_model_error(i, 1e5f, 1e6f, extrapolated) == D::rms[i][D::thickness_count - 1]);
        CHECK(extrapolated);
    }
}

TEST_CASE("choose_lighting_model: the cheapest model within the budget") {
    for (float lo : {1.0f, 5.0f, 20.0f})
        for (float hi : {10.0f, 100.0f})
            for (float budget : {0.2f, 0.4f, 0.6f, 0.8f, 1.2f, 5.0f}) {
                if (lo > hi) continue;
                const lighting_model_choice c = choose_lighting_model(lo, hi, budget);
                REQUIRE(c.kind != lighting_model_kind::none);
                // Brute force over the table: cheapest by (extra inputs, exponentials, error).
                int best = -1;
                float best_error = 0;
                for (int i = 0; i < D::model_count; ++i) {
                    bool x = false;
                    const float e = lighting_model_error(i, lo, hi, x);
                    if (e > budget) continue;
                    const auto& r = D::models[i];
                    if (best < 0 || r.extra_inputs < D::models[best].extra_inputs ||
                        (r.extra_inputs == D::models[best].extra_inputs &&
                         (r.exponentials < D::models[best].exponentials ||
                          (r.exponentials == D::models[best].exponentials && e < best_error)))) {
                        best = i;
                        best_error = e;
                    }
                }
                CAPTURE(lo);
                CAPTURE(hi);
                CAPTURE(budget);
                if (best >= 0) {
                    CHECK(c.meets_budget);
                    CHECK(std::strcmp(c.name, D::models[best].name) == 0);
                    CHECK(c.rms_error == best_error);
                    CHECK(c.rms_error <= budget);
                } else {
                    CHECK_FALSE(c.meets_budget);
                    CHECK(c.rms_error > budget);
                }
                // The pointers match the kind.
                CHECK((c.kind == lighting_model_kind::octaves) == (c.octaves != nullptr));
                CHECK((c.kind == lighting_model_kind::diffusion) == (c.diffusion != nullptr));
            }
}

TEST_CASE("choose_lighting_model: a budget nothing meets gives the most accurate model") {
    const lighting_model_choice c = choose_lighting_model(1.0f, 100.0f, 0.0f);
    CHECK_FALSE(c.meets_budget);
    for (int i = 0; i < D::model_count; ++i) {
        bool x = false;
        CHECK(c.rms_error <= lighting_model_error(i, 1.0f, 100.0f, x));
    }
    CHECK_FALSE(choose_lighting_model(1.0f, 100.0f, -1.0f).meets_budget);
}

TEST_CASE("choose_lighting_model: bad ranges") {
    CHECK(choose_lighting_model(10.0f, 1.0f, 1.0f).kind == lighting_model_kind::none);
    if (cm_test::ieee_build) {
        const float nan = cm_test::make_nan<float>();
        CHECK(choose_lighting_model(nan, 1.0f, 1.0f).kind == lighting_model_kind::none);
        CHECK(choose_lighting_model(1.0f, nan, 1.0f).kind == lighting_model_kind::none);
        CHECK(choose_lighting_model(1.0f, cm_test::make_inf<float>(), 1.0f).kind != lighting_model_kind::none);
    }
    // Zero or negative thickness: the thinnest measurement, flagged.
    const lighting_model_choice c = choose_lighting_model(0.0f, 0.0f, 10.0f);
    CHECK(c.meets_budget);
    CHECK(c.extrapolated);
}

// Hardening round 2, A2: tau_min * tau_max overflowed to +Inf, every log distance to the
// measurements was then equal, and the thinnest one (where `thin` looks good) was taken.
TEST_CASE("lighting_model_error: ranges whose product overflows take the nearest measurement in log space") {
    const float ranges[3][2] = {{200.0f, std::numeric_limits<float>::max()}, {1e20f, 1e20f}, {200.0f, 1e30f}};
    for (int i = 0; i < D::model_count; ++i) {
        bool extrapolated = false;
        for (const auto& r : ranges) {
            CHECK(lighting_model_error(i, r[0], r[1], extrapolated) == D::rms[i][D::thickness_count - 1]);
            CHECK(extrapolated);
        }
        if (cm_test::ieee_build) {
            CHECK(lighting_model_error(i, 200.0f, cm_test::make_inf<float>(), extrapolated) == D::rms[i][D::thickness_count - 1]);
            CHECK(extrapolated);
        }
    }
    // The choice is the one of a finite range beyond the measurements (no overflow there).
    const lighting_model_choice finite = choose_lighting_model(200.0f, 300.0f, 0.5f);
    for (const auto& r : ranges) {
        const lighting_model_choice c = choose_lighting_model(r[0], r[1], 0.5f);
        CHECK(std::strcmp(c.name, finite.name) == 0);
        CHECK(c.rms_error == finite.rms_error);
        CHECK(c.meets_budget == finite.meets_budget);
        CHECK(std::strcmp(c.name, "thin") != 0);
    }
    if (cm_test::ieee_build)
        CHECK(std::strcmp(choose_lighting_model(200.0f, cm_test::make_inf<float>(), 0.5f).name, finite.name) == 0);
}
