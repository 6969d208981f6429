// reference.lighting_presets: every cloudmath::ms_preset reproduces, on the Monte Carlo
// reference (docs/data/lighting_reference.csv), the rms and max error documented in
// include/cloudmath/multiple_scattering.hpp, evaluated through the library function itself.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <cloudmath/multiple_scattering.hpp>

#include <fstream>
#include <iterator>

#include "lighting_error.hpp"
#include "lighting_report.hpp"

namespace lm = cloudmath::reference::lighting;

TEST_CASE("the presets' documented error is what the reference measures") {
    const lm::reference_set set =
        lm::read_reference(std::string(CLOUDMATH_SOURCE_DIR) + "/docs/data/lighting_reference.csv");
    REQUIRE(set.phase_spec == "hg:0.85");
    const double g = 0.85;
    for (const cloudmath::multiple_scattering_preset& p : cloudmath::ms_preset::all) {
        // The model's radiance with the library's own multiple_scattering (double) as the
        // sun term, on the exact quadrature of every reference ray.
        std::vector<double> L;
        for (const lm::reference_row& r : set.rows) {
            const lm::ray_quadrature q = lm::row_quadrature(r, set.albedo, 1.0);
            double sum = 0.0;
            for (std::size_t k = 0; k < q.weight.size(); ++k)
                sum += q.weight[k] * cloudmath::multiple_scattering(q.tau_light[k], q.mu, g, p);
            L.push_back(sum);
        }
        const double lo = double(p.tau_min), hi = double(p.tau_max);
        const lm::error_summary e =
            lm::measure(set, L, [lo, hi](const lm::reference_row& r) { return r.tau >= lo && r.tau <= hi; });
        CAPTURE(p.name);
        CHECK(e.rows > 100);
        // Documented to 4 significant digits.
        CHECK(std::abs(e.rms - double(p.rms_error)) <= 6e-4 * std::max(1.0, double(p.rms_error)));
        CHECK(std::abs(e.max - double(p.max_error)) <= 6e-4 * std::max(1.0, double(p.max_error)));
        // The same through the tools' evaluator (a second implementation of the octave sum).
        const lm::evaluator ev(set, 1.0);
        const lm::error_summary e2 = lm::measure(
            set, ev.radiance({lm::attenuation::beer, g, double(p.a), double(p.b), double(p.c), p.octaves}),
            [lo, hi](const lm::reference_row& r) { return r.tau >= lo && r.tau <= hi; });
        CHECK(e2.rms == doctest::Approx(e.rms).epsilon(1e-9));
    }
}

TEST_CASE("the data of choose_lighting_model is what the reference measures") {
    const lm::reference_set set =
        lm::read_reference(std::string(CLOUDMATH_SOURCE_DIR) + "/docs/data/lighting_reference.csv");
    std::ifstream in(std::string(CLOUDMATH_SOURCE_DIR) + "/include/cloudmath/lighting_choice_data.hpp",
                     std::ios::binary);
    REQUIRE(in.good());
    const std::string stored{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    CHECK(lm::lighting_choice_header(set, "lighting_reference.csv") == stored);
}
