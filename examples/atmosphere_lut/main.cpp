// examples/atmosphere_lut: the atmosphere's LUTs generated on the GPU by a GLSL compute
// shader built from cloudmath's twins, timed, read back and compared texel for texel with
// the CPU reference:
//   transmittance         cm_atmosphere_transmittance_lut_altitude_mu, then
//                         cm_atmosphere_transmittance at each texel centre
//                         (cloudmath::atmosphere_transmittance_lut)
//   multiple-scattering   cm_atmosphere_multiple_scattering_lut_altitude_mu, then
//                         cm_atmosphere_multiple_scattering (64 directions, 32 sun steps;
//                         cloudmath::atmosphere_multiple_scattering_lut)
//
//   cloudmath_atmosphere_lut [--lut transmittance|multiple-scattering] [--width W] [--height H]
//                            [--steps N] [--runs R] | --print-shader
//   defaults: transmittance 256 x 64 with 64 steps, multiple scattering 32 x 32 with 20 steps
//   (Hillaire 2020's sizes), 5 timed runs after one warm-up.
// Prints the device, the median time per generation (host clock from the dispatch to the end
// of glFinish: on llvmpipe the GPU timestamps are taken when the work is queued) and the
// largest difference from the CPU LUT. Exit status: 0 when that difference is at most 1e-5,
// 1 when it is larger, 2 for a bad command line; without an OpenGL 4.3 context 77 (skipped),
// or 1 when the environment has CI=true.
#include <cloudmath/atmosphere.hpp>
#include <cloudmath/glsl.hpp>

#include <egl_headless.hpp>
#include <gl_functions.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

const char* const usage =
    "usage: cloudmath_atmosphere_lut [--lut transmittance|multiple-scattering] [--width W] [--height H] [--steps N] [--runs R]\n"
    "                                [--print-shader]\n"
    "  W, H: 2..4096 (default 256 x 64; multiple scattering 32 x 32); N: steps per ray 1..1024 (default 64;\n"
    "  multiple scattering 20); R: timed runs 1..100 (default 5)\n"
    "  --print-shader: print the compute shader and exit\n";

// The multiple-scattering LUT's fixed counts (Hillaire 2020): rays per texel, sun steps.
constexpr int ms_directions = 64, ms_sun_steps = 32;

// The whole number in [lo, hi] that `text` spells, or -1.
int whole(const char* text, int lo, int hi) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi) return -1;
    return static_cast<int>(v);
}

// The compute shader: one invocation per texel, the library's GLSL for the math.
std::string compute_source(bool multiple_scattering) {
    const std::string texel =
        multiple_scattering
            ? "    vec2 am = cm_atmosphere_multiple_scattering_lut_altitude_mu(air, (vec2(texel) + 0.5) / vec2(size), vec2(size));\n"
              "    imageStore(u_lut, texel, vec4(cm_atmosphere_multiple_scattering(air, am.x, am.y, " +
                  std::to_string(ms_directions) + ", u_steps, " + std::to_string(ms_sun_steps) + "), 1.0));\n"
            : "    vec2 am = cm_atmosphere_transmittance_lut_altitude_mu(air, (vec2(texel) + 0.5) / vec2(size), vec2(size));\n"
              "    imageStore(u_lut, texel, vec4(cm_atmosphere_transmittance(air, am.x, am.y, u_steps), 1.0));\n";
    return "#version 430 core\n"
           "layout(local_size_x = 8, local_size_y = 8) in;\n"
           "layout(rgba32f, binding = 0) uniform writeonly image2D u_lut;\n"
           "uniform int u_steps;\n" +
           cloudmath::glsl_source("atmosphere") +
           "\nvoid main() {\n"
           "    ivec2 size = imageSize(u_lut);\n"
           "    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);\n"
           "    if (texel.x >= size.x || texel.y >= size.y) return;\n"
           "    CmAtmosphere air = cm_earth_atmosphere();\n" +
           texel + "}\n";
}

}  // namespace

int main(int argc, char** argv) {
    int width = -1, height = -1, steps = -1, runs = 5;
    bool multiple_scattering = false, print_shader = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(usage, stdout);
            return 0;
        }
        if (a == "--print-shader") {  // the compute shader as compiled (for static cost counts)
            print_shader = true;
            continue;
        }
        if (a == "--lut" && i + 1 < argc &&
            (std::strcmp(argv[i + 1], "transmittance") == 0 || std::strcmp(argv[i + 1], "multiple-scattering") == 0)) {
            multiple_scattering = std::strcmp(argv[++i], "multiple-scattering") == 0;
            continue;
        }
        int* target = a == "--width" ? &width : a == "--height" ? &height : a == "--steps" ? &steps : a == "--runs" ? &runs : nullptr;
        const int hi = a == "--steps" ? 1024 : a == "--runs" ? 100 : 4096;
        const int lo = a == "--width" || a == "--height" ? 2 : 1;
        if (target == nullptr || i + 1 >= argc || (*target = whole(argv[i + 1], lo, hi)) < 0) {
            std::fprintf(stderr, "cloudmath_atmosphere_lut: bad argument '%s'\n%s", a.c_str(), usage);
            return 2;
        }
        ++i;
    }
    if (width < 0) width = multiple_scattering ? 32 : 256;
    if (height < 0) height = multiple_scattering ? 32 : 64;
    if (steps < 0) steps = multiple_scattering ? 20 : 64;
    if (print_shader) {
        std::fputs(compute_source(multiple_scattering).c_str(), stdout);
        return 0;
    }

    std::string why;
    auto context = cloudmath_egl::headless_context::open(4, 3, cloudmath_egl::platform::any, why);
    if (!context) {
        // The GL tests' rule: skipped (77) without a context, failed when CI=true.
        const char* ci = std::getenv("CI");
        const bool in_ci = ci != nullptr && std::strcmp(ci, "true") == 0;
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %sno OpenGL 4.3 context: %s\n", in_ci ? "" : "SKIPPED: ", why.c_str());
        return in_ci ? 1 : 77;
    }
    cloudmath_egl::gl_functions gl;
    const std::string missing = gl.load(&cloudmath_egl::gl_proc, true);
    if (!missing.empty()) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: the driver lacks %s\n", missing.c_str());
        return 1;
    }
    const GLuint shader = gl.compile(GL_COMPUTE_SHADER, compute_source(multiple_scattering), "the LUT compute shader", why);
    const GLuint program = shader != 0 ? gl.link(&shader, 1, "the LUT compute program", why) : 0;
    if (program == 0) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %s\n", why.c_str());
        return 1;
    }
    GLuint texture = 0;
    gl.GenTextures(1, &texture);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.UseProgram(program);
    gl.Uniform1i(gl.GetUniformLocation(program, "u_steps"), steps);
    gl.BindImageTexture(0, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);

    // One warm-up generation (the driver may compile at the first dispatch), then the runs.
    std::vector<double> ms;
    for (int run = 0; run <= runs; ++run) {
        gl.Finish();
        const auto start = std::chrono::steady_clock::now();
        gl.DispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
        gl.MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        gl.Finish();
        if (run > 0) ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::vector<float> texels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4u);
    gl.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, texels.data());
    why = gl.errors("the LUT generation");
    gl.DeleteTextures(1, &texture);
    gl.DeleteProgram(program);
    if (!why.empty()) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %s\n", why.c_str());
        return 1;
    }
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2];

    const auto air = cloudmath::earth_atmosphere<float>();
    const auto start = std::chrono::steady_clock::now();
    const std::vector<glm::vec3> cpu =
        multiple_scattering ? cloudmath::atmosphere_multiple_scattering_lut(air, width, height, ms_directions, steps, ms_sun_steps)
                            : cloudmath::atmosphere_transmittance_lut(air, width, height, steps);
    const double cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    double worst = 0.0;
    for (std::size_t i = 0; i < cpu.size(); ++i)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(double(texels[4 * i + std::size_t(c)]) - double(cpu[i][c])));

    const char* renderer = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    std::printf("device: %s\n", renderer != nullptr ? renderer : "unknown");
    std::printf("%s LUT %d x %d, %d steps: GPU %.2f ms (median of %d; min %.2f, max %.2f), CPU %.1f ms (one thread); "
                "largest difference from the CPU LUT %.3g\n",
                multiple_scattering ? "multiple-scattering" : "transmittance", width, height, steps, median, runs, ms.front(), ms.back(), cpu_ms, worst);
    return worst <= 1e-5 ? 0 : 1;
}
