// examples/atmosphere_lut: the atmosphere's LUTs generated on the GPU by a GLSL compute
// shader built from cloudmath's twins, timed, read back and compared texel for texel with
// the CPU reference:
//   transmittance         cm_atmosphere_transmittance_lut_altitude_mu, then
//                         cm_atmosphere_transmittance at each texel centre
//                         (cloudmath::atmosphere_transmittance_lut)
//   multiple-scattering   cm_atmosphere_multiple_scattering_lut_altitude_mu, then
//                         cm_atmosphere_multiple_scattering (64 directions, 32 sun steps;
//                         cloudmath::atmosphere_multiple_scattering_lut)
//   sky-view              the sky's radiance seen from one altitude by direction (Hillaire
//                         2020's sky-view LUT over the whole sphere, the renderer's
//                         sky_view_table): cm_atmosphere_sky_radiance (32 view and 32 sun
//                         steps) at each node, reading the refined multiple-scattering table
//                         (atmosphere_make_sky_luts, 32 x 32, every part, and a 64-texel
//                         ground irradiance) through CM_ATMOSPHERE_TABLE from two textures;
//                         the table is made once per atmosphere on the CPU, the sky-view LUT
//                         per sun and altitude on the GPU (cloudmath::atmosphere_sky_radiance)
//
//   cloudmath_atmosphere_lut [--lut transmittance|multiple-scattering|sky-view] [--width W] [--height H]
//                            [--steps N] [--runs R] [--altitude A] [--sun-elevation E] | --print-shader
//   defaults: transmittance 256 x 64 with 64 steps, multiple scattering 32 x 32 with 20 steps
//   (Hillaire 2020's sizes), sky view 64 x 64 (azimuth from the sun 0..180 degrees by the view's
//   zenith cosine, crowded at the horizon) with 32 steps at A = 2 m and E = 6 degrees; 5 timed
//   runs after one warm-up.
// Prints the device, the median time per generation (host clock from the dispatch to the end
// of glFinish: on llvmpipe the GPU timestamps are taken when the work is queued) and the
// largest difference from the CPU LUT (sky view: relative, against max(|CPU|, 1e-3 of the
// LUT's largest value)). Exit status: 0 when that difference is at most 1e-5 (sky view 1e-4),
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
#include <limits>
#include <string>
#include <vector>

namespace {

const char* const usage =
    "usage: cloudmath_atmosphere_lut [--lut transmittance|multiple-scattering|sky-view] [--width W] [--height H] [--steps N]\n"
    "                                [--runs R] [--altitude A] [--sun-elevation E] [--print-shader]\n"
    "  W, H: 2..4096 (default 256 x 64; multiple scattering 32 x 32; sky view 64 x 64); N: steps per ray 1..1024\n"
    "  (default 64; multiple scattering 20; sky view 32); R: timed runs 1..100 (default 5)\n"
    "  A: the sky view's altitude in metres, 0..100000 (default 2); E: its sun's elevation in degrees, -90..90 (default 6)\n"
    "  --print-shader: print the compute shader and exit\n"
    "       cloudmath_atmosphere_lut --write-table FILE | --check-table FILE\n"
    "  the refined table the sky view reads (32 x 32, parts stacked, no GPU needed), written as raw little-endian\n"
    "  float32 RGB (the web demo's web/demo/sky_table.bin), or checked against FILE (exit 1 when it differs)\n";

enum class lut_kind { transmittance, multiple_scattering, sky_view };

// The multiple-scattering LUT's fixed counts (Hillaire 2020): rays per texel, sun steps.
constexpr int ms_directions = 64, ms_sun_steps = 32;
// The sky view's: the sun's transmittance steps, the refined table's size and its ground
// irradiance's texels (atmosphere_make_sky_luts' and atmosphere_ground_irradiance_lut's
// defaults), and the parts of the table stacked in one texture (part p: rows p h .. p h + h - 1;
// the ground irradiance, part CM_ATMOSPHERE_TABLE_GROUND = 3, has its own texture).
constexpr int sky_sun_steps = 32, table_size = 32, ground_size = 64, table_parts = cloudmath::atmosphere_stacked_table_parts;
constexpr float degrees = 3.14159265358979f / 180.0f;

// Whether `text` spells a whole number in [lo, hi]; if so, it is stored in `out`.
bool whole(const char* text, int lo, int hi, int& out) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi) return false;
    out = static_cast<int>(v);
    return true;
}

// The compute shader: one invocation per texel, the library's GLSL for the math.
std::string compute_source(lut_kind kind) {
    std::string head = "#version 430 core\n"
                       "layout(local_size_x = 8, local_size_y = 8) in;\n"
                       "layout(rgba32f, binding = 0) uniform writeonly image2D u_lut;\n"
                       "uniform int u_steps;\n";
    std::string texel;
    if (kind == lut_kind::transmittance) {
        texel = "    vec2 am = cm_atmosphere_transmittance_lut_altitude_mu(air, (vec2(texel) + 0.5) / vec2(size), vec2(size));\n"
                "    imageStore(u_lut, texel, vec4(cm_atmosphere_transmittance(air, am.x, am.y, u_steps), 1.0));\n";
    } else if (kind == lut_kind::multiple_scattering) {
        texel = "    vec2 am = cm_atmosphere_multiple_scattering_lut_altitude_mu(air, (vec2(texel) + 0.5) / vec2(size), vec2(size));\n"
                "    imageStore(u_lut, texel, vec4(cm_atmosphere_multiple_scattering(air, am.x, am.y, " +
                std::to_string(ms_directions) + ", u_steps, " + std::to_string(ms_sun_steps) + "), 1.0));\n";
    } else {
        // The table's texels through the hook: declared before the library, defined after it.
        head += "uniform sampler2D u_table;   // parts stacked: part p at rows p h .. p h + h - 1\n"
                "uniform sampler2D u_ground;  // the ground irradiance, one row\n"
                "uniform float u_altitude;\n"
                "uniform vec3 u_sun_dir;\n"
                "vec3 lut_table(int part, int x, int y);\n"
                "#define CM_ATMOSPHERE_TABLE lut_table\n";
        texel = "    // The node's direction (physical_sky.cpp's node_direction): zenith cosine mu with\n"
                "    // sign(mu) sqrt|mu| even in y, azimuth from the sun's 0..pi in x.\n"
                "    float s = 2.0 * float(texel.y) / float(size.y - 1) - 1.0;\n"
                "    float mu = s < 0.0 ? -s * s : s * s;\n"
                "    float phi = CM_PI * float(texel.x) / float(size.x - 1);\n"
                "    float sin_zenith = sqrt(max(1.0 - mu * mu, 0.0));\n"
                "    vec3 dir = vec3(sin_zenith * cos(phi), mu, sin_zenith * sin(phi));\n"
                "    CmAtmosphereTable table = CmAtmosphereTable(" + std::to_string(table_size) + ", " + std::to_string(table_size) +
                ", 3, " + std::to_string(ground_size) + ");\n"
                "    imageStore(u_lut, texel, vec4(cm_atmosphere_sky_radiance(air, table, u_altitude, dir, u_sun_dir, u_steps, " +
                std::to_string(sky_sun_steps) + "), 1.0));\n";
    }
    std::string after;
    if (kind == lut_kind::sky_view)
        after = "vec3 lut_table(int part, int x, int y) {\n"
                "    if (part == CM_ATMOSPHERE_TABLE_GROUND) return texelFetch(u_ground, ivec2(x, 0), 0).rgb;\n"
                "    return texelFetch(u_table, ivec2(x, y + part * " + std::to_string(table_size) + "), 0).rgb;\n"
                "}\n";
    return head + cloudmath::glsl_source("atmosphere") + "\n" + after +
           "void main() {\n"
           "    ivec2 size = imageSize(u_lut);\n"
           "    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);\n"
           "    if (texel.x >= size.x || texel.y >= size.y) return;\n"
           "    CmAtmosphere air = cm_earth_atmosphere();\n" +
           texel + "}\n";
}

// The sky view on the CPU: the same nodes, cloudmath::atmosphere_sky_radiance.
std::vector<glm::vec3> cpu_sky_view(const cloudmath::atmosphere_parameters<float>& air,
                                    const cloudmath::atmosphere_multiple_scattering_table<float>& table, int width, int height,
                                    int steps, float altitude, const glm::vec3& sun) {
    std::vector<glm::vec3> out;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float s = 2.0f * float(y) / float(height - 1) - 1.0f;
            const float mu = s < 0.0f ? -s * s : s * s;
            const float phi = 3.14159265358979f * float(x) / float(width - 1);
            const float sin_zenith = std::sqrt(std::max(1.0f - mu * mu, 0.0f));
            out.push_back(cloudmath::atmosphere_sky_radiance(air, table, altitude,
                                                             glm::vec3(sin_zenith * std::cos(phi), mu, sin_zenith * std::sin(phi)), sun,
                                                             steps, sky_sun_steps));
        }
    return out;
}

// --write-table / --check-table: the stacked table of Earth's air (the renderer's physical_air:
// atmosphere_make_sky_luts' defaults at 32 x 32) as raw little-endian float32 RGB. Exit status
// 0 written or equal (within 1e-5 of each part's largest value: another compiler may round
// otherwise), 1 when it differs or cannot be read or written.
int table_file(const std::string& path, bool check) {
    const auto air = cloudmath::earth_atmosphere<float>();
    const std::vector<glm::vec3> table = cloudmath::atmosphere_stacked_table(cloudmath::atmosphere_make_sky_luts(air, table_size, table_size));
    std::vector<float> values;
    for (const glm::vec3& v : table) values.insert(values.end(), {v.x, v.y, v.z});
    static_assert(sizeof(float) == 4, "float32 expected");
    const std::size_t bytes = values.size() * sizeof(float);
    if (!check) {
        const std::string temporary = path + ".tmp";
        std::FILE* f = std::fopen(temporary.c_str(), "wb");
        const bool ok = f != nullptr && std::fwrite(values.data(), 1, bytes, f) == bytes;
        if (f != nullptr && std::fclose(f) != 0) f = nullptr;
        if (!ok || f == nullptr || std::rename(temporary.c_str(), path.c_str()) != 0) {
            std::remove(temporary.c_str());
            std::fprintf(stderr, "cloudmath_atmosphere_lut: cannot write %s\n", path.c_str());
            return 1;
        }
        std::printf("wrote %s: %zu bytes, %d parts of %d x %d RGB float32 texels\n", path.c_str(), bytes, table_parts, table_size, table_size);
        return 0;
    }
    std::vector<float> stored(values.size() + 1);
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: cannot read %s\n", path.c_str());
        return 1;
    }
    const std::size_t got = std::fread(stored.data(), 1, stored.size() * sizeof(float), f);
    std::fclose(f);
    if (got != bytes) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %s holds %zu bytes, not the table's %zu; regenerate it with --write-table\n",
                     path.c_str(), got, bytes);
        return 1;
    }
    const std::size_t per_part = values.size() / std::size_t(table_parts);
    double worst = 0.0;
    for (std::size_t p = 0; p < std::size_t(table_parts); ++p) {
        float peak = 0.0f;
        for (std::size_t i = p * per_part; i < (p + 1) * per_part; ++i) peak = std::max(peak, std::fabs(values[i]));
        for (std::size_t i = p * per_part; i < (p + 1) * per_part; ++i) {
            const double d = std::fabs(double(stored[i]) - double(values[i])) / std::max(double(peak), 1e-30);
            worst = std::isfinite(stored[i]) ? std::max(worst, d) : std::numeric_limits<double>::infinity();
        }
    }
    std::printf("%s against the table: largest difference %.3g of a part's largest value\n", path.c_str(), worst);
    if (worst > 1e-5) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %s is stale; regenerate it with --write-table\n", path.c_str());
        return 1;
    }
    return 0;
}

// A float RGB texture of width x height texels, sampled with texelFetch only.
GLuint upload(cloudmath_egl::gl_functions& gl, const std::vector<glm::vec3>& texels, int width, int height) {
    GLuint t = 0;
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_2D, t);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, texels.data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    int width = -1, height = -1, steps = -1, runs = 5, altitude_m = 2, sun_elevation_deg = 6;
    lut_kind kind = lut_kind::transmittance;
    bool print_shader = false, check_table = false;
    std::string table_path;  // --write-table / --check-table
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
        if ((a == "--write-table" || a == "--check-table") && i + 1 < argc && table_path.empty()) {
            table_path = argv[++i];
            check_table = a == "--check-table";
            continue;
        }
        if (a == "--lut" && i + 1 < argc) {
            const std::string k = argv[i + 1];
            if (k == "transmittance" || k == "multiple-scattering" || k == "sky-view") {
                kind = k == "transmittance" ? lut_kind::transmittance : k == "sky-view" ? lut_kind::sky_view : lut_kind::multiple_scattering;
                ++i;
                continue;
            }
        }
        int* target = a == "--width" ? &width : a == "--height" ? &height : a == "--steps" ? &steps : a == "--runs" ? &runs
                      : a == "--altitude" ? &altitude_m : a == "--sun-elevation" ? &sun_elevation_deg : nullptr;
        const int hi = a == "--steps" ? 1024 : a == "--runs" ? 100 : a == "--altitude" ? 100000 : a == "--sun-elevation" ? 90 : 4096;
        const int lo = a == "--width" || a == "--height" ? 2 : a == "--altitude" ? 0 : a == "--sun-elevation" ? -90 : 1;
        if (target == nullptr || i + 1 >= argc || !whole(argv[i + 1], lo, hi, *target)) {
            std::fprintf(stderr, "cloudmath_atmosphere_lut: bad argument '%s'\n%s", a.c_str(), usage);
            return 2;
        }
        ++i;
    }
    if (!table_path.empty()) {
        if (argc != 3) {
            std::fprintf(stderr, "cloudmath_atmosphere_lut: --write-table and --check-table take no other argument\n%s", usage);
            return 2;
        }
        return table_file(table_path, check_table);
    }
    if (width < 0) width = kind == lut_kind::multiple_scattering ? 32 : kind == lut_kind::sky_view ? 64 : 256;
    if (height < 0) height = kind == lut_kind::multiple_scattering ? 32 : 64;
    if (steps < 0) steps = kind == lut_kind::multiple_scattering ? 20 : kind == lut_kind::sky_view ? 32 : 64;
    if (print_shader) {
        std::fputs(compute_source(kind).c_str(), stdout);
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
    const GLuint shader = gl.compile(GL_COMPUTE_SHADER, compute_source(kind), "the LUT compute shader", why);
    const GLuint program = shader != 0 ? gl.link(&shader, 1, "the LUT compute program", why) : 0;
    if (program == 0) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %s\n", why.c_str());
        return 1;
    }
    const auto air = cloudmath::earth_atmosphere<float>();
    const float altitude = float(altitude_m);
    const glm::vec3 sun(std::cos(float(sun_elevation_deg) * degrees), std::sin(float(sun_elevation_deg) * degrees), 0.0f);
    // The sky view's table, made once per atmosphere on the CPU (timed apart) and uploaded.
    cloudmath::atmosphere_sky_luts<float> luts;
    double table_ms = 0.0;
    GLuint table_texture = 0, ground_texture = 0;
    gl.UseProgram(program);
    if (kind == lut_kind::sky_view) {
        const auto start = std::chrono::steady_clock::now();
        luts = cloudmath::atmosphere_make_sky_luts(air, table_size, table_size);
        luts.ground_irradiance = cloudmath::atmosphere_ground_irradiance_lut(air, luts.table(), ground_size);
        table_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        const std::vector<glm::vec3> stacked = cloudmath::atmosphere_stacked_table(luts);
        gl.ActiveTexture(GL_TEXTURE1);
        table_texture = upload(gl, stacked, table_size, table_size * table_parts);
        gl.ActiveTexture(GL_TEXTURE2);
        ground_texture = upload(gl, luts.ground_irradiance, ground_size, 1);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.Uniform1i(gl.GetUniformLocation(program, "u_table"), 1);
        gl.Uniform1i(gl.GetUniformLocation(program, "u_ground"), 2);
        gl.Uniform1f(gl.GetUniformLocation(program, "u_altitude"), altitude);
        gl.Uniform3f(gl.GetUniformLocation(program, "u_sun_dir"), sun.x, sun.y, sun.z);
    }
    GLuint texture = 0;
    gl.GenTextures(1, &texture);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
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
    if (table_texture != 0) gl.DeleteTextures(1, &table_texture);
    if (ground_texture != 0) gl.DeleteTextures(1, &ground_texture);
    gl.DeleteProgram(program);
    if (!why.empty()) {
        std::fprintf(stderr, "cloudmath_atmosphere_lut: %s\n", why.c_str());
        return 1;
    }
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2];

    const auto start = std::chrono::steady_clock::now();
    const std::vector<glm::vec3> cpu =
        kind == lut_kind::multiple_scattering ? cloudmath::atmosphere_multiple_scattering_lut(air, width, height, ms_directions, steps, ms_sun_steps)
        : kind == lut_kind::sky_view         ? cpu_sky_view(air, luts.table(), width, height, steps, altitude, sun)
                                             : cloudmath::atmosphere_transmittance_lut(air, width, height, steps);
    const double cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // The transmittance and Psi_ms are of order 1: absolute differences. The sky's radiance
    // spans decades (the night side, the ground): relative, with a floor of 1e-3 of its peak.
    double peak = 0.0;
    if (kind == lut_kind::sky_view)
        for (const glm::vec3& v : cpu) peak = std::max({peak, double(v.x), double(v.y), double(v.z)});
    double worst = 0.0;
    for (std::size_t i = 0; i < cpu.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = std::fabs(double(texels[4 * i + std::size_t(c)]) - double(cpu[i][c]));
            worst = std::max(worst, kind == lut_kind::sky_view ? d / std::max(std::fabs(double(cpu[i][c])), 1e-3 * peak) : d);
            // A NaN on either side fails (std::max would keep the old worst).
            if (!std::isfinite(texels[4 * i + std::size_t(c)]) || !std::isfinite(cpu[i][c])) worst = std::numeric_limits<double>::infinity();
        }

    const char* renderer = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    std::printf("device: %s\n", renderer != nullptr ? renderer : "unknown");
    if (kind == lut_kind::sky_view) {
        std::printf("sky-view LUT %d x %d at %d m, sun %d degrees, %d view and %d sun steps: GPU %.2f ms (median of %d; min %.2f, "
                    "max %.2f), CPU %.1f ms (one thread); the refined table it reads (32 x 32, every part, 64 ground texels) %.0f ms "
                    "on the CPU, once per atmosphere; largest relative difference from the CPU LUT %.3g\n",
                    width, height, altitude_m, sun_elevation_deg, steps, sky_sun_steps, median, runs, ms.front(), ms.back(), cpu_ms,
                    table_ms, worst);
        return worst <= 1e-4 ? 0 : 1;
    }
    std::printf("%s LUT %d x %d, %d steps: GPU %.2f ms (median of %d; min %.2f, max %.2f), CPU %.1f ms (one thread); "
                "largest difference from the CPU LUT %.3g\n",
                kind == lut_kind::multiple_scattering ? "multiple-scattering" : "transmittance", width, height, steps, median, runs,
                ms.front(), ms.back(), cpu_ms, worst);
    return worst <= 1e-5 ? 0 : 1;
}
