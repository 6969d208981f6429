// Smallest real use of an installed cloudmath: the umbrella header compiles and a few
// functions give the documented values, and the GLSL twins are usable: the embedded copies
// (cloudmath/glsl_embedded.hpp, committed and installed) and the .glsl files on disk agree.
// Usage: consumer GLSL_DIR, the directory of the .glsl files that belong to the headers in
// use (<prefix>/include/cloudmath/glsl when installed, the source tree's
// include/cloudmath/glsl under add_subdirectory). Returns non-zero, with a message, on failure.
// The umbrella header brings in the version macros; built with CONSUMER_EXPECTED_VERSION (the
// version find_package reported), the consumer also checks the headers are that version.
#include <cloudmath/cloudmath.hpp>
#include <cloudmath/glsl.hpp>

#include <cmath>
#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s GLSL_DIR\n", argc > 0 ? argv[0] : "consumer");
        return 2;
    }
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

    // Version macros: the string spells the three numbers, the number combines them.
    const std::string version = std::to_string(CLOUDMATH_VERSION_MAJOR) + "." +
                                std::to_string(CLOUDMATH_VERSION_MINOR) + "." +
                                std::to_string(CLOUDMATH_VERSION_PATCH);
    check(version == CLOUDMATH_VERSION_STRING, "CLOUDMATH_VERSION_STRING == MAJOR.MINOR.PATCH");
    check(CLOUDMATH_VERSION == CLOUDMATH_VERSION_MAJOR * 10000 + CLOUDMATH_VERSION_MINOR * 100 +
                                   CLOUDMATH_VERSION_PATCH,
          "CLOUDMATH_VERSION == MAJOR * 10000 + MINOR * 100 + PATCH");
#ifdef CONSUMER_EXPECTED_VERSION
    if (version != CONSUMER_EXPECTED_VERSION)
        std::fprintf(stderr, "consumer: headers say %s, the package says %s\n", version.c_str(),
                     CONSUMER_EXPECTED_VERSION);
    check(version == CONSUMER_EXPECTED_VERSION, "CLOUDMATH_VERSION_STRING == package version");
#endif

    // GLSL: the embedded module, then the same module resolved from the files on disk.
    const std::string phase = cloudmath::glsl_source("phase");
    check(!phase.empty(), "glsl_source(\"phase\") is not empty");
    check(phase.find("cm_phase_hg") != std::string::npos,
          "glsl_source(\"phase\") contains cm_phase_hg");
    std::string error;
    const std::string from_directory =
        cloudmath::glsl_source_from_directory(argv[1], "cloudmath", &error);
    if (from_directory.empty())
        std::fprintf(stderr, "consumer: glsl_source_from_directory(\"%s\"): %s\n", argv[1],
                     error.c_str());
    check(!from_directory.empty(), "glsl_source_from_directory(GLSL_DIR, \"cloudmath\") is not empty");
    check(from_directory == cloudmath::glsl_source("cloudmath"),
          "glsl_source_from_directory(GLSL_DIR, \"cloudmath\") == glsl_source(\"cloudmath\")");

    if (failures == 0) std::printf("consumer: ok\n");
    return failures == 0 ? 0 : 1;
}
