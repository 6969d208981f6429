// cloudmath_lighting_choice: which shipped lighting model a scene needs. For a range of
// optical thickness and an rms error budget, cloudmath::choose_lighting_model returns the
// cheapest model whose error against the Monte Carlo reference (lighting_choice_data.hpp)
// is within the budget, or the most accurate one when none is.
//
//   cloudmath_lighting_choice                       the typical scenes of docs/choosing_a_model.md
//   cloudmath_lighting_choice TAU_MIN TAU_MAX BUDGET   one scene (BUDGET a fraction: 0.5 = 50%)
#include <cloudmath/lighting_choice.hpp>

#include <cstdio>
#include <cstdlib>

namespace {

void print(const char* scene, float tau_min, float tau_max, float budget) {
    const cloudmath::lighting_model_choice c = cloudmath::choose_lighting_model(tau_min, tau_max, budget);
    std::printf("| %s | %g-%g | %.0f%% | %s | %.0f%%%s | %d | %s |\n", scene, double(tau_min), double(tau_max),
                100.0 * double(budget), c.name, 100.0 * double(c.rms_error), c.extrapolated ? " (extrapolated)" : "",
                c.exponentials, c.meets_budget ? (c.extra_inputs ? "yes, needs tau_behind and tau_view" : "yes")
                                               : "no: the most accurate model");
}

bool parse(const char* text, float& out) {
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(v >= 0.0) || v > 1e30) return false;
    out = static_cast<float>(v);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    std::printf("| Scene | Optical thickness | Budget (rms) | Model | Its rms | Exp per sample | Meets the budget |\n"
                "|---|---|---|---|---|---|---|\n");
    if (argc == 4) {
        float lo = 0, hi = 0, budget = 0;
        if (!parse(argv[1], lo) || !parse(argv[2], hi) || !parse(argv[3], budget) || lo > hi) {
            std::fprintf(stderr, "cloudmath_lighting_choice: need TAU_MIN <= TAU_MAX and BUDGET, numbers >= 0\n");
            return 2;
        }
        print("given", lo, hi, budget);
        return 0;
    }
    if (argc != 1) {
        std::fprintf(stderr, "usage: cloudmath_lighting_choice [TAU_MIN TAU_MAX BUDGET]\n");
        return 2;
    }
    // Optical thickness across a cloud: thin stratus a few, fair-weather cumulus tens,
    // storm towers a hundred (Bohren & Clothiaux, "Fundamentals of Atmospheric Radiation",
    // 2006, ch. 5: cloud optical thickness 1 to 100 and beyond).
    print("thin stratus, loose budget", 1.0f, 5.0f, 0.5f);
    print("thin stratus, tight budget", 1.0f, 5.0f, 0.35f);
    print("fair-weather cumulus", 5.0f, 50.0f, 0.5f);
    print("storm tops", 20.0f, 100.0f, 0.5f);
    print("anything, 40% budget", 1.0f, 100.0f, 0.4f);
    return 0;
}
