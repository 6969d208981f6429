// Smallest real use of an installed cloudmath: the umbrella header compiles and a few
// functions give the documented values. Returns non-zero, with a message, on failure.
#include <cloudmath/cloudmath.hpp>

#include <cmath>
#include <cstdio>

int main() {
    int failures = 0;
    auto check = [&failures](bool ok, const char* what) {
        if (!ok) {
            std::fprintf(stderr, "consumer: FAILED %s\n", what);
            ++failures;
        }
    };
    check(cloudmath::saturate(1.5f) == 1.0f, "saturate(1.5f) == 1.0f");
    check(cloudmath::remap(0.5, 0.0, 1.0, 10.0, 20.0) == 15.0,
          "remap(0.5, 0, 1, 10, 20) == 15");
    const double inv_four_pi = 1.0 / (4.0 * std::acos(-1.0));
    check(std::abs(cloudmath::phase_isotropic<double>() - inv_four_pi) < 1e-15,
          "phase_isotropic<double>() == 1/(4 pi)");
    if (failures == 0) std::printf("consumer: ok\n");
    return failures == 0 ? 0 : 1;
}
