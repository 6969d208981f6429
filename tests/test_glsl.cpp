// Tests of glsl.hpp: the embedded GLSL twins, include resolution (each file once, in
// dependency order), agreement between the embedded copies and the files on disk, and the
// errors for unknown modules and folders.
#include <cloudmath/glsl.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "test_support.hpp"

#ifndef CLOUDMATH_GLSL_DIR
#error "CLOUDMATH_GLSL_DIR must name include/cloudmath/glsl (set by tests/CMakeLists.txt)"
#endif

namespace {
const char* const modules[] = {"core", "phase", "transmittance", "integration", "multiple_scattering",
                               "diffusion_lighting", "diffusion_lighting_models", "cone_sampling",
                               "geometry", "density", "noise", "sun", "reprojection", "shadow_map", "texture_lod", "atmosphere", "cloudmath"};

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Lines that are #include directives (first non-blank characters '#', then "include"); the
// word in a comment does not count.
int include_directives(const std::string& text) {
    int n = 0;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t i = line.find_first_not_of(" \t");
        if (i == std::string::npos || line[i] != '#') continue;
        const std::size_t j = line.find_first_not_of(" \t", i + 1);
        if (j != std::string::npos && line.compare(j, 7, "include") == 0) ++n;
    }
    return n;
}

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}
}  // namespace

TEST_CASE("every GLSL file is embedded, byte for byte") {
    const std::vector<std::string_view> names = cloudmath::glsl_file_names();
    CHECK(names.size() == std::size(modules));
    for (const char* m : modules) {
        const std::string file = std::string(m) + ".glsl";
        INFO(file);
        CHECK(cloudmath::glsl_embedded_file(file) == read_file(std::string(CLOUDMATH_GLSL_DIR) + "/" + file));
    }
    CHECK(cloudmath::glsl_embedded_file("nope.glsl").empty());
}

TEST_CASE("the shipped files do use #include (so resolution is exercised)") {
    CHECK(include_directives(std::string(cloudmath::glsl_embedded_file("phase.glsl"))) >= 1);
    CHECK(include_directives(std::string(cloudmath::glsl_embedded_file("cloudmath.glsl"))) == 15);
    CHECK(include_directives("  #  include \"x.glsl\"\n// #include \"y.glsl\"\n") == 1);
}

TEST_CASE("glsl_source resolves includes once each, dependencies first, no #include left") {
    for (const char* m : modules) {
        std::string error = "unchanged";
        const std::string src = cloudmath::glsl_source(m, &error);
        INFO(m);
        CHECK(!src.empty());
        CHECK(error.empty());
        CHECK(include_directives(src) == 0);
        CHECK(count(src, "#define CM_CORE_GLSL") == 1);  // core once, even when several files include it
        CHECK(src.find("#define CM_CORE_GLSL") < src.find("cm_saturate(float x)"));
    }
    const std::string all = cloudmath::glsl_source("cloudmath");
    for (const char* guard : {"CM_PHASE_GLSL", "CM_TRANSMITTANCE_GLSL", "CM_INTEGRATION_GLSL", "CM_MULTIPLE_SCATTERING_GLSL",
                              "CM_CONE_SAMPLING_GLSL", "CM_GEOMETRY_GLSL", "CM_DENSITY_GLSL", "CM_NOISE_GLSL"})
        CHECK(count(all, std::string("#define ") + guard) == 1);
    // phase needs core before its first use of CM_INV_FOUR_PI.
    const std::string phase = cloudmath::glsl_source("phase");
    CHECK(phase.find("#define CM_INV_FOUR_PI") < phase.find("float cm_phase_hg("));
}

TEST_CASE("glsl_source_from_directory gives the same text as the embedded copies") {
    for (const char* m : modules) {
        std::string error;
        INFO(m);
        CHECK(cloudmath::glsl_source_from_directory(CLOUDMATH_GLSL_DIR, m, &error) == cloudmath::glsl_source(m));
        CHECK(error.empty());
    }
}

TEST_CASE("unknown modules and folders give an empty string and a message, no exception") {
    std::string error;
    CHECK(cloudmath::glsl_source("no_such_module", &error).empty());
    CHECK(error.find("no_such_module.glsl") != std::string::npos);
    CHECK(cloudmath::glsl_source_from_directory("/nonexistent/cloudmath", "phase", &error).empty());
    CHECK(error.find("phase.glsl") != std::string::npos);
    CHECK(cloudmath::glsl_source("no_such_module").empty());  // error pointer optional
}

TEST_CASE("glsl_resolve_includes: a user's shader, its own files and cloudmath's, each once, defines kept") {
    const std::string source =
        "#version 450\n"
        "#define CM_CONE_EXTINCTION my_extinction\n"
        "float my_extinction(vec3 p, int i);\n"
        "#include \"cloudmath/glsl/cone_sampling.glsl\"\n"
        "  #  include \"lighting.glsl\"\n"
        "#include \"phase.glsl\"\n"
        "void main() {}\n";
    const std::vector<std::pair<std::string, std::string>> files = {
        {"shaders/lighting.glsl", "#include \"cloudmath/glsl/phase.glsl\"\nfloat my_light() { return cm_phase_hg(0.5, 0.8); }\n"}};
    std::string error = "stale";
    const std::string out = cloudmath::glsl_resolve_includes(source, files, &error);
    CHECK(error.empty());
    CHECK(include_directives(out) == 0);
    // The user's lines are kept, in order, the define before the code that reads it.
    const std::size_t define = out.find("#define CM_CONE_EXTINCTION my_extinction");
    const std::size_t cone = out.find("cm_cone_optical_depth");
    REQUIRE(define != std::string::npos);
    REQUIRE(cone != std::string::npos);
    CHECK(define < cone);
    CHECK(out.rfind("#version 450\n", 0) == 0);
    CHECK(out.find("void main() {}") != std::string::npos);
    // The user's file by its base name, cloudmath's files once each (phase.glsl is asked for
    // by cone_sampling.glsl's dependencies, by lighting.glsl and by the source).
    CHECK(count(out, "float my_light()") == 1);
    CHECK(count(out, "#ifndef CM_PHASE_GLSL") == 1);
    CHECK(count(out, "#ifndef CM_CORE_GLSL") == 1);
    // Embedded twins resolve the same as glsl_source.
    CHECK(cloudmath::glsl_resolve_includes("#include \"phase.glsl\"\n") == cloudmath::glsl_source("phase"));
    // A missing file: empty, and the message names it.
    const std::string bad = cloudmath::glsl_resolve_includes("#include \"nowhere/missing.glsl\"\n", {}, &error);
    CHECK(bad.empty());
    CHECK(error.find("nowhere/missing.glsl") != std::string::npos);
    // No includes: the text unchanged (plus a final newline).
    CHECK(cloudmath::glsl_resolve_includes("float x;") == "float x;\n");
}
