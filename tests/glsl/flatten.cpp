// cloudmath_glsl_flatten MODULE [DIRECTORY]: prints a GLSL module with its includes resolved
// (from the embedded copies, or from .glsl files in DIRECTORY). Used by the GLSL tests to
// build what a raw-OpenGL user would compile.
#include <cloudmath/glsl.hpp>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: %s MODULE [DIRECTORY]\n", argv[0]);
        return 2;
    }
    std::string error;
    const std::string src = argc == 3 ? cloudmath::glsl_source_from_directory(argv[2], argv[1], &error)
                                      : cloudmath::glsl_source(argv[1], &error);
    if (src.empty()) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    std::fputs(src.c_str(), stdout);
    return 0;
}
