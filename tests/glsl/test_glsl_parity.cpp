// GLSL parity: evaluates every cm_ function on a real OpenGL driver (compute shader, headless
// EGL; Mesa llvmpipe here, a GPU driver where one is available) over grids of inputs that
// include the hard cases of the C++ unit tests, and compares each result with the C++ float
// twin. Prints a table per function; fails when an error exceeds its budget or the GPU
// returns NaN/Inf where the C++ does not.
//
// Error: |gpu - cpu| / max(|cpu|, floor), per output component. The floor (absolute error
// scale) is stated per case: outputs that pass through zero by cancellation are compared
// absolutely on the scale of their inputs. Budget 1e-5 unless a case states otherwise.
// Inputs avoid NaN, Inf and denormals: GPUs flush denormals and drivers differ on NaN,
// which the library never relies on (documented in core.hpp).
//
// Usage: test_glsl_parity [--markdown FILE] [--fuzz N]
//        test_glsl_parity --dump-cases FILE
//        test_glsl_parity --program MAIN.comp... --config-program CONFIG.comp... [--language NAME]
// --dump-cases writes every case as JSON (inputs and the C++ outputs; see dump_cases()) for
// the HLSL/WGSL twins' generators, and needs no OpenGL context. --program / --config-program
// run the cases on complete GLSL compute sources made elsewhere (e.g. from the HLSL twins by
// tests/hlsl/hlsl_parity.cmake) instead of the GLSL twins: one file per program of at most
// 64 cases, in the order of the dump's "program" field (main programs, then config ones).
// --language names those twins in the table and the markdown.
// Exit:  0 all within budget (or dumped); 1 failure; 2 usage; 77 no OpenGL context outside
//        CI (skipped), 1 in CI.
#include <cloudmath/cloudmath.hpp>
#include <cloudmath/glsl.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "atomic_file.hpp"
#include "gl_compute.hpp"

namespace cm = cloudmath;
using glm::vec2;
using glm::vec3;
using glm::vec4;

namespace {

struct parity_case {
    std::string function;  // the cm_ name (one row per overload may share it)
    std::string glsl;      // expression of vec4 a, vec4 b returning vec4
    std::function<vec4(vec4, vec4)> cpp;
    std::vector<std::pair<vec4, vec4>> inputs;
    int components = 1;    // output components compared
    float floor = 1e-30f;  // absolute scale below which errors are absolute
    double budget = 1e-5;
};

// --- the user hooks of the generic forms, identical on both sides --------------------------
const char* const glsl_prelude = R"(
float cm_test_phase(float mu, float scale);
float cm_test_extinction(vec3 p, int i);
#define CM_MS_PHASE cm_test_phase
#define CM_DIFFUSION_PHASE cm_test_phase
#define CM_CONE_EXTINCTION cm_test_extinction
vec3 cm_test_atmosphere_table(int part, int x, int y);
#define CM_ATMOSPHERE_TABLE cm_test_atmosphere_table
)";
// The extinction hook uses core.glsl's accurate sin and cos: the built-ins may be 2^-11 off
// (SwiftShader's are), which would test the platform's trigonometry, not the cone sampling.
const char* const glsl_after = R"(
vec3 cm_test_atmosphere_table(int part, int x, int y) {
    float p = float(part), fx = float(x), fy = float(y);
    return vec3(0.3, 0.45, 0.8) * ((1.0 + 0.07 * fx + 0.05 * fy) / (1.0 + 0.1 * p)) + vec3(0.002 * p, 0.001 * fx, 0.0005 * fy);
}
float cm_test_phase(float mu, float scale) { return cm_phase_hg_dual(mu, 0.8 * scale, -0.5 * scale, 0.5); }
float cm_test_extinction(vec3 p, int i) {
    return 0.01 * (1.0 + 0.5 * cmi_sin_cos(0.01 * p.x).x * cmi_sin_cos(0.013 * p.z).y) + 0.001 * float(i);
}
vec4 cm_test_chord_fluence(vec4 a) {
    float flux;
    float U = cm_diffusion_chord_fluence(a.x, a.y, a.z, a.w, flux);
    return vec4(U, flux, 0.0, 0.0);
}
vec4 cm_test_march(vec4 a, vec4 b, bool grey) {
    CmMarchAccumulator acc = cm_march_accumulator();
    for (int i = 0; i < 8; ++i) {
        if (grey) cm_march_add_segment(acc, a.xyz * (1.0 + 0.1 * float(i)), b.x, a.w);
        else cm_march_add_segment(acc, a.xyz * (1.0 + 0.1 * float(i)), b.xyz, a.w);
    }
    return vec4(acc.luminance, acc.transmittance.y);
}
vec4 cm_test_beer_shadow_march(float start, float scale, float depth) {
    CmBeerShadowAccumulator acc = cm_beer_shadow_accumulator();
    for (int i = 0; i < 24; ++i) {
        float t = start + 100.0 * float(i);
        cm_beer_shadow_add_step(acc, t, 100.0, (i % 7 < 3 ? scale : 0.0) * (1.0 + 0.1 * float(i)));
    }
    vec3 texel = cm_beer_shadow_texel(acc);
    return vec4(texel.x, texel.y * 1000.0, cm_beer_shadow_optical_depth(texel, depth), cm_beer_shadow_transmittance(texel, depth));
}
)";
// The multiple-scattering table of the sky's cases: every part smooth in (x, y) and distinct.
vec3 cpp_test_atmosphere_table(int part, int x, int y) {
    const float p = float(part), fx = float(x), fy = float(y);
    return vec3(0.3f, 0.45f, 0.8f) * ((1.0f + 0.07f * fx + 0.05f * fy) / (1.0f + 0.1f * p)) + vec3(0.002f * p, 0.001f * fx, 0.0005f * fy);
}
// The same table as atmosphere_multiple_scattering_table's vectors: width x height texels per
// part, parts 1 (psi), 2 (with vertical moments) or 3 (with the sun-azimuth moments and the
// aerosol field), and the ground irradiance's first ground_width texels (5 or 1; none where 0).
struct cpp_test_sky_table {
    std::vector<vec3> psi, vertical, along, aerosol, ground, ground1;  // ground: 5 texels, ground1: its first
    cm::atmosphere_multiple_scattering_table<float> view(int width, int height, int parts, int ground_width) const {
        cm::atmosphere_multiple_scattering_table<float> t;
        t.width = width;
        t.height = height;
        if (parts >= 1) t.texels = &psi;
        if (parts >= 2) t.vertical_moments = &vertical;
        if (parts >= 3) {
            t.sun_azimuth_moments = &along;
            t.aerosol_field = &aerosol;
        }
        if (ground_width > 0) t.ground_irradiance = ground_width == 1 ? &ground1 : &ground;
        return t;
    }
};
cpp_test_sky_table make_cpp_test_sky_table(int width, int height, int ground_width) {
    cpp_test_sky_table t;
    const auto part = [&](int p) {
        std::vector<vec3> v;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) v.push_back(cpp_test_atmosphere_table(p, x, y));
        return v;
    };
    t.psi = part(0);
    t.vertical = part(1);
    t.along = part(2);
    for (int j = 0; j < cm::atmosphere_aerosol_field_nodes; ++j) {
        const std::vector<vec3> node = part(4 + j);
        t.aerosol.insert(t.aerosol.end(), node.begin(), node.end());
    }
    for (int x = 0; x < ground_width; ++x) t.ground.push_back(cpp_test_atmosphere_table(3, x, 0));
    t.ground1.push_back(cpp_test_atmosphere_table(3, 0, 0));
    return t;
}
float cpp_test_phase(float mu, float scale) { return cm::phase_hg_dual(mu, 0.8f * scale, -0.5f * scale, 0.5f); }
float cpp_test_extinction(const vec3& p, int i) {
    return 0.01f * (1.0f + 0.5f * std::sin(0.01f * p.x) * std::cos(0.013f * p.z)) + 0.001f * float(i);
}
vec4 cpp_test_march(vec4 a, vec4 b, bool grey) {
    vec3 lum, tr;
    if (grey) {
        cm::march_accumulator<vec3, float> acc;
        for (int i = 0; i < 8; ++i) acc.add_segment(vec3(a) * (1.0f + 0.1f * float(i)), b.x, a.w);
        lum = acc.luminance;
        tr = vec3(acc.transmittance);
    } else {
        cm::march_accumulator<vec3> acc;
        for (int i = 0; i < 8; ++i) acc.add_segment(vec3(a) * (1.0f + 0.1f * float(i)), vec3(b), a.w);
        lum = acc.luminance;
        tr = acc.transmittance;
    }
    return vec4(lum, tr.y);
}

// --- input grids ------------------------------------------------------------------------------
std::vector<float> mu_values() {  // dense, with +-1 and values within 1e-k of them
    std::vector<float> v;
    for (int i = -20; i <= 20; ++i) v.push_back(float(i) / 20.0f);
    for (float d : {1e-2f, 1e-3f, 1e-4f, 1e-5f, 1e-6f}) {
        v.push_back(1.0f - d);
        v.push_back(-1.0f + d);
    }
    return v;
}
std::vector<float> g_values() {
    return {-0.9999f, -0.999f, -0.99f, -0.8f, -0.5f, -1e-4f, 0.0f, 1e-4f, 0.3f, 0.5f, 0.8f, 0.85f, 0.9f, 0.99f, 0.995f, 0.999f, 0.9999f, 1.0f, -1.0f};
}
std::vector<float> tau_values() {  // 0, tiny (the sigma_t hard cases), the landmarks, huge
    return {0.0f, 1e-30f, 1e-8f, 1e-6f, 1e-4f, 1e-3f, 0.05f, 0.2f, 0.25f, 0.3466f, 0.4757f, 0.5493f, 1.0f, 2.0f, 5.0f, 10.0f, 30.0f, 80.0f, 1e4f};
}
std::vector<float> unit_values() {
    std::vector<float> v;
    for (int i = -4; i <= 24; ++i) v.push_back(float(i) / 20.0f);
    return v;
}

// Noise sample points: a = (position, period), b.x = seed. Lattice points, cell borders,
// negative coordinates, positions a whole period away, and random interior points.
void cm_test_points(std::vector<std::pair<vec4, vec4>>& pts) {
    std::uint32_t state = 12345U;
    auto unit = [&state]() { state = cm::noise_hash(state + 1U); return float(state >> 8) / 16777216.0f; };
    for (float period : {1.0f, 4.0f, 7.0f})
        for (float seed : {0.0f, 3.0f}) {
            for (vec3 p : {vec3(0.0f), vec3(1.0f, 2.0f, 3.0f), vec3(-1.0f, -2.5f, 0.5f), vec3(3.999f, 0.001f, 2.0f), vec3(-7.25f, 8.5f, 11.75f)})
                pts.push_back({vec4(p, period), vec4(seed, 0.0f, 0.0f, 0.0f)});
            for (int i = 0; i < 40; ++i)
                pts.push_back({vec4(unit() * 16.0f - 8.0f, unit() * 16.0f - 8.0f, unit() * 16.0f - 8.0f, period), vec4(seed, 0.0f, 0.0f, 0.0f)});
        }
}

// --- the cases --------------------------------------------------------------------------------
std::vector<parity_case> make_cases() {
    std::vector<parity_case> cs;
    auto add = [&cs](parity_case c) { cs.push_back(std::move(c)); };
    const float R = 6371e3f;

    // core
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float x : {-1e4f, -2.0f, -1e-3f, 0.0f, 1e-6f, 0.3f, 0.999f, 1.0f, 1.5f, 1e4f}) in.push_back({vec4(x, -x, x * 0.5f, 1.0f - x), vec4(0)});
        add({"cm_saturate", "vec4(cm_saturate(a.x), cm_saturate(a.yz), 0.0)", [](vec4 a, vec4) { return vec4(cm::saturate(a.x), cm::saturate(vec2(a.y, a.z)), 0.0f); }, in, 3});
        add({"cm_saturate", "vec4(cm_saturate(a.xyz), cm_saturate(a).w)", [](vec4 a, vec4) { return vec4(cm::saturate(vec3(a)), cm::saturate(a).w); }, in, 4});
    }
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float x : unit_values())
            for (vec2 r : {vec2(0.0f, 1.0f), vec2(0.3f, 1.0f), vec2(1.0f, 0.0f), vec2(0.5f, 0.5f), vec2(0.2f, 0.2000001f), vec2(-3.0f, 7.0f)})
                in.push_back({vec4(x, r.x, r.y, 0.0f), vec4(0.1f, 0.7f, 0.0f, 0.0f)});
        add({"cm_remap", "vec4(cm_remap(a.x, a.y, a.z, b.x, b.y))", [](vec4 a, vec4 b) { return vec4(cm::remap(a.x, a.y, a.z, b.x, b.y)); }, in, 1, 1.0f, 1e-5});
        add({"cm_remap_clamped", "vec4(cm_remap_clamped(a.x, a.y, a.z, b.x, b.y))", [](vec4 a, vec4 b) { return vec4(cm::remap_clamped(a.x, a.y, a.z, b.x, b.y)); }, in, 1, 1.0f});
        add({"cm_smoothstep_safe", "vec4(cm_smoothstep_safe(a.y, a.z, a.x))", [](vec4 a, vec4) { return vec4(cm::smoothstep_safe(a.y, a.z, a.x)); }, in, 1, 1.0f});
    }
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (int e = -30; e <= 4; ++e)
            for (float m : {1.0f, 2.5f, 6.0f}) {
                const float x = m * std::pow(10.0f, float(e));
                in.push_back({vec4(x, x * 0.5f, x * 2.0f, -x), vec4(0)});
            }
        for (float x : {0.0f, 0.2499f, 0.25f, 0.2501f, -0.2f, -10.0f}) in.push_back({vec4(x, x, x, -x), vec4(0)});
        add({"cm_one_minus_exp_neg_over_x", "vec4(cm_one_minus_exp_neg_over_x(a.x), cm_one_minus_exp_neg_over_x(a.yzw))", [](vec4 a, vec4) {
                 const vec3 v = cm::one_minus_exp_neg_over_x(vec3(a.y, a.z, a.w));
                 return vec4(cm::one_minus_exp_neg_over_x(a.x), v); }, in, 4});
        add({"cm_one_minus_exp_neg", "vec4(cm_one_minus_exp_neg(a.x), cm_one_minus_exp_neg(a.yzw))", [](vec4 a, vec4) {
                 const vec3 v = cm::one_minus_exp_neg(vec3(a.y, a.z, a.w));
                 return vec4(cm::one_minus_exp_neg(a.x), v); }, in, 4});
        // Huge x (regression): x * cm_one_minus_exp_neg_over_x(x) was Inf * 0 = NaN; 1 - exp(-x) = 1.
        std::vector<std::pair<vec4, vec4>> huge;
        for (float x : {17.0f, 88.0f, 100.0f, 1e4f, 1e30f, 1e38f, 1.7e38f, 3.4028235e38f})
            huge.push_back({vec4(x, x * 0.5f, x * 1e-10f, std::min(x * 2.0f, 3.4028235e38f)), vec4(0)});
        add({"cm_one_minus_exp_neg", "vec4(cm_one_minus_exp_neg(a.x), cm_one_minus_exp_neg(a.yzw))", [](vec4 a, vec4) {
                 const vec3 v = cm::one_minus_exp_neg(vec3(a.y, a.z, a.w));
                 return vec4(cm::one_minus_exp_neg(a.x), v); }, huge, 4});
    }
    {
        // remap_clamped with huge finite inputs (regression: Inf / Inf = NaN) and equal new
        // ends (the blend rounded an ulp outside them); compared on the new range's scale.
        std::vector<std::pair<vec4, vec4>> in;
        const float big = 3.4028235e38f;
        for (float x : {big, -big, 3e38f, -3e38f, 1e38f, 2.5e38f, 1.0f, 0.0f})
            for (vec2 r : {vec2(-big, big), vec2(big, -big), vec2(-3e38f, 3e38f), vec2(0.0f, big), vec2(-1.0f, 3e38f)}) {
                in.push_back({vec4(x, r.x, r.y, 0.0f), vec4(0.0f, 1.0f, 0.0f, 0.0f)});
                in.push_back({vec4(x, r.x, r.y, 0.0f), vec4(0.920364857f, 0.920364857f, 0.0f, 0.0f)});
                in.push_back({vec4(x, r.x, r.y, 0.0f), vec4(5.0f, -5.0f, 0.0f, 0.0f)});
            }
        in.push_back({vec4(-0.125486612f, -0.0317127705f, -1.16267025f, 0.0f), vec4(0.920364857f, 0.920364857f, 0.0f, 0.0f)});
        in.push_back({vec4(0.285094023f, -0.252416611f, 1.121454f, 0.0f), vec4(-1.56015718f, -1.56015718f, 0.0f, 0.0f)});
        add({"cm_remap_clamped", "vec4(cm_remap_clamped(a.x, a.y, a.z, b.x, b.y))", [](vec4 a, vec4 b) { return vec4(cm::remap_clamped(a.x, a.y, a.z, b.x, b.y)); }, in, 1, 1.0f});
    }

    // cmi_sin_cos (internal, core.glsl): the accurate sin and cos behind the Sun, cone and Mie
    // twins, against double std::sin / std::cos of the same float. Small angles relatively
    // (the Sun's disc), then |x| up to its 8192 domain absolutely (values in [-1, 1]).
    {
        std::vector<std::pair<vec4, vec4>> small, wide;
        for (float x : {0.0f, 1e-30f, 1e-8f, 2.3262e-3f, 4.6524e-3f, 0.0349f, 0.1f, 0.5f, 0.785f, 0.7854f, 1.0f})
            small.push_back({vec4(x, -x, 0.0f, 0.0f), vec4(0)});
        for (int i = -39; i <= 39; ++i) {  // |x| < 8192
            const float x = float(i) * 204.8f + 0.37f * float(i % 7);
            wide.push_back({vec4(x, x * 0.001f, 1.5707964f * float(i), 3.1415927f * float(i) + 1e-3f), vec4(0)});
        }
        const auto sc = [](float x) { return vec2(float(std::sin(double(x))), float(std::cos(double(x)))); };
        add({"cmi_sin_cos [internal]", "vec4(cmi_sin_cos(a.x), cmi_sin_cos(a.y).x, 0.0)",
             [sc](vec4 a, vec4) { return vec4(sc(a.x), sc(a.y).x, 0.0f); }, small, 3, 1e-30f, 1e-6});
        add({"cmi_sin_cos [internal]", "vec4(cmi_sin_cos(a.x), cmi_sin_cos(a.z).x, cmi_sin_cos(a.w).y)",
             [sc](vec4 a, vec4) { return vec4(sc(a.x), sc(a.z).x, sc(a.w).y); }, wide, 4, 1.0f, 1e-6});
    }

    // phase
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float mu : mu_values())
            for (float g : g_values()) in.push_back({vec4(mu, g, 0.5f, 0.0f), vec4(0)});
        add({"cm_phase_isotropic", "vec4(cm_phase_isotropic())", [](vec4, vec4) { return vec4(cm::phase_isotropic<float>()); }, {in.front()}});
        add({"cm_phase_rayleigh", "vec4(cm_phase_rayleigh(a.x))", [](vec4 a, vec4) { return vec4(cm::phase_rayleigh(a.x)); }, in});
        add({"cm_phase_hg", "vec4(cm_phase_hg(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::phase_hg(a.x, a.y)); }, in});
        add({"cm_phase_hg_dual", "vec4(cm_phase_hg_dual(a.x, a.y, -0.5 * a.y, a.z))", [](vec4 a, vec4) { return vec4(cm::phase_hg_dual(a.x, a.y, -0.5f * a.y, a.z)); }, in});
        add({"cm_phase_cornette_shanks", "vec4(cm_phase_cornette_shanks(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::phase_cornette_shanks(a.x, a.y)); }, in});
        add({"cm_phase_draine", "vec4(cm_phase_draine(a.x, a.y, 21.996), cm_phase_draine(a.x, a.y, 250.0), cm_phase_draine(a.x, a.y, 1.0), 0.0)",
             [](vec4 a, vec4) { return vec4(cm::phase_draine(a.x, a.y, 21.996f), cm::phase_draine(a.x, a.y, 250.0f), cm::phase_draine(a.x, a.y, 1.0f), 0.0f); }, in, 3});
        add({"cm_phase_schlick", "vec4(cm_phase_schlick(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::phase_schlick(a.x, a.y)); }, in});
        add({"cm_schlick_k_from_hg_g", "vec4(cm_schlick_k_from_hg_g(a.y))", [](vec4 a, vec4) { return vec4(cm::schlick_k_from_hg_g(a.y)); }, in, 1, 1e-3f});
        add({"cm_phase_hg_schlick", "vec4(cm_phase_hg_schlick(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::phase_hg_schlick(a.x, a.y)); }, in});
    }
    {
        std::vector<std::pair<vec4, vec4>> in;
        std::vector<float> ds = {0.0f, 0.01f, 0.05f, 0.1f, 0.1001f, 0.2f, 0.5f, 1.0f, 1.4999f, 1.5f, 2.0f, 3.0f, 4.0f, 4.81f, 4.9999f, 5.0f, 7.5f, 10.0f, 20.0f, 30.0f, 50.0f, 80.0f};
        for (float d : ds)
            for (float mu : mu_values()) in.push_back({vec4(mu, d, 0.0f, 0.0f), vec4(0)});
        add({"cm_mie_approx_params", "vec4(cm_mie_approx_params(a.y).g_hg, cm_mie_approx_params(a.y).g_draine, cm_mie_approx_params(a.y).alpha, cm_mie_approx_params(a.y).w_draine)",
             [](vec4 a, vec4) { const auto p = cm::mie_approx_params(a.y); return vec4(p.g_hg, p.g_draine, p.alpha, p.w_draine); }, in, 4, 1e-2f});
        // Budget 1e-4: the forward peak scales as 1/(1 - g_HG)^2 with 1 - g_HG = 2e-3 at
        // d = 50 um, so one float ulp of g_HG (the driver's exp may differ from the C++ one
        // by an ulp) moves the peak by 2 * 6e-8 / 2e-3 = 6e-5. Storing g_HG in float carries
        // the same uncertainty in the C++ itself.
        add({"cm_phase_mie_approx", "vec4(cm_phase_mie_approx(a.x, a.y), cm_phase_mie_approx(a.x, cm_mie_approx_params(a.y)), 0.0, 0.0)",
             [](vec4 a, vec4) { return vec4(cm::phase_mie_approx(a.x, a.y), cm::phase_mie_approx(a.x, cm::mie_approx_params(a.y)), 0.0f, 0.0f); }, in, 2, 1e-30f, 1e-4});
    }
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float g : g_values()) {
            for (int i = 0; i <= 64; ++i) in.push_back({vec4(g, float(i) / 64.0f, 0.0f, 0.0f), vec4(0)});
            for (float u : {1e-7f, 1e-4f, 0.9999f, 0.99999994f, -0.5f, 1.5f}) in.push_back({vec4(g, u, 0.0f, 0.0f), vec4(0)});
        }
        // Sampled mu is compared absolutely (it lives in [-1, 1] and crosses 0).
        add({"cm_sample_phase_hg", "vec4(cm_sample_phase_hg(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::sample_phase_hg(a.x, a.y)); }, in, 1, 1.0f});
    }

    // transmittance
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float t : tau_values()) in.push_back({vec4(t, t * 0.5f, t * 2.0f, -t), vec4(0)});
        // Values that underflow (exp(-1e4)) compare absolutely at 1e-30.
        add({"cm_beer_lambert", "vec4(cm_beer_lambert(a.x), cm_beer_lambert(a.yzw))", [](vec4 a, vec4) { return vec4(cm::beer_lambert(a.x), cm::beer_lambert(vec3(a.y, a.z, a.w))); }, in, 4, 1e-30f});
        add({"cm_powder", "vec4(cm_powder(a.x, 2.0), cm_powder(a.yzw, 2.0))", [](vec4 a, vec4) { return vec4(cm::powder(a.x, 2.0f), cm::powder(vec3(a.y, a.z, a.w), 2.0f)); }, in, 4});
        add({"cm_beer_powder", "vec4(cm_beer_powder(a.x), cm_beer_powder(a.yzw))", [](vec4 a, vec4) { return vec4(cm::beer_powder(a.x), cm::beer_powder(vec3(a.y, a.z, a.w))); }, in, 4});
        add({"cm_nubis_attenuation", "vec4(cm_nubis_attenuation(a.x), cm_nubis_attenuation(a.yzw))", [](vec4 a, vec4) { return vec4(cm::nubis_attenuation(a.x), cm::nubis_attenuation(vec3(a.y, a.z, a.w))); }, in, 4});
        for (float g : {0.0f, 0.8f, 0.99f, 1.0f, -1.0f})
            add({"cm_diffuse_transmittance", "vec4(cm_diffuse_transmittance(a.x, " + std::to_string(g) + "), cm_diffuse_transmittance(a.yzw, " + std::to_string(g) + "))",
                 [g](vec4 a, vec4) { return vec4(cm::diffuse_transmittance(a.x, g), cm::diffuse_transmittance(vec3(a.y, a.z, a.w), g)); }, in, 4});
        // Huge optical depths (regression: cm_beer_powder was NaN from tau = 1.7e38, where 2 tau
        // overflows, and cm_powder(1e30, 1e10) where k tau does): the limits 0 and 1.
        std::vector<std::pair<vec4, vec4>> huge;
        for (float t : {1e10f, 1e30f, 1e38f, 1.7e38f, 2e38f, 3.4028235e38f}) huge.push_back({vec4(t, t * 0.5f, t * 0.9f, t), vec4(0)});
        add({"cm_beer_lambert", "vec4(cm_beer_lambert(a.x), cm_beer_lambert(a.yzw))", [](vec4 a, vec4) { return vec4(cm::beer_lambert(a.x), cm::beer_lambert(vec3(a.y, a.z, a.w))); }, huge, 4, 1e-30f});
        add({"cm_powder", "vec4(cm_powder(a.x, 1e10), cm_powder(a.yzw, 1e10))", [](vec4 a, vec4) { return vec4(cm::powder(a.x, 1e10f), cm::powder(vec3(a.y, a.z, a.w), 1e10f)); }, huge, 4});
        add({"cm_powder", "vec4(cm_powder(a.x, 2.0), cm_powder(a.yzw, 2.0))", [](vec4 a, vec4) { return vec4(cm::powder(a.x, 2.0f), cm::powder(vec3(a.y, a.z, a.w), 2.0f)); }, huge, 4});
        add({"cm_beer_powder", "vec4(cm_beer_powder(a.x), cm_beer_powder(a.yzw))", [](vec4 a, vec4) { return vec4(cm::beer_powder(a.x), cm::beer_powder(vec3(a.y, a.z, a.w))); }, huge, 4, 1e-30f});
        add({"cm_nubis_attenuation", "vec4(cm_nubis_attenuation(a.x), cm_nubis_attenuation(a.yzw))", [](vec4 a, vec4) { return vec4(cm::nubis_attenuation(a.x), cm::nubis_attenuation(vec3(a.y, a.z, a.w))); }, huge, 4, 1e-30f});
    }

    // integration
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float s : {0.0f, 1e-30f, 1e-20f, 1e-8f, 1e-6f, 1e-3f, 0.05f, 0.3f, 1.0f, 10.0f, 100.0f, 1e4f})
            for (float ds : {0.01f, 1.0f, 7.3f}) in.push_back({vec4(0.37f, 1.0f, 2.0f, ds), vec4(s, s * 3.0f, s * 0.1f, 0.0f)});
        add({"cm_integrate_scattering", "vec4(cm_integrate_scattering(a.x, b.x, a.w), cm_integrate_scattering(a.xyz, b.xyz, a.w))",
             [](vec4 a, vec4 b) { return vec4(cm::integrate_scattering(a.x, b.x, a.w), cm::integrate_scattering(vec3(a), vec3(b), a.w)); }, in, 4});
        add({"cm_integrate_scattering", "vec4(cm_integrate_scattering(a.xyz, b.x, a.w), 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::integrate_scattering(vec3(a), b.x, a.w), 0.0f); }, in, 3});
        std::vector<std::pair<vec4, vec4>> march;
        for (float s : {0.0f, 1e-9f, 1e-3f, 0.05f, 0.5f, 3.0f})
            for (float ds : {0.1f, 1.0f, 10.0f}) march.push_back({vec4(0.2f, 0.5f, 1.0f, ds), vec4(s, s * 2.0f, s * 0.5f, 0.0f)});
        add({"cm_march_add_segment", "cm_test_march(a, b, false)", [](vec4 a, vec4 b) { return cpp_test_march(a, b, false); }, march, 4, 1e-30f});
        add({"cm_march_accumulator", "cm_test_march(a, b, true)", [](vec4 a, vec4 b) { return cpp_test_march(a, b, true); }, march, 4, 1e-30f});
        add({"cm_march_is_opaque",
             "vec4(cm_march_is_opaque(CmMarchAccumulator(vec3(0.0), a.xyz), b.x) ? 1.0 : 0.0, cm_march_opacity(CmMarchAccumulator(vec3(0.0), a.xyz)))",
             [](vec4 a, vec4 b) {
                 cm::march_accumulator<vec3> acc;
                 acc.transmittance = vec3(a);
                 return vec4(acc.is_opaque(b.x) ? 1.0f : 0.0f, acc.opacity()); },
             {{vec4(0.005f, 0.002f, 0.009f, 0), vec4(0.01f)}, {vec4(0.005f, 0.2f, 0.009f, 0), vec4(0.01f)}, {vec4(1.0f), vec4(0.01f)}, {vec4(0.5f, 0.25f, 0.125f, 0), vec4(0.6f)}}, 4, 1.0f});
        add({"cm_march_opacity", "vec4(cm_march_opacity(CmMarchAccumulator(vec3(1.0), a.xyz)), 0.0)",
             [](vec4 a, vec4) { cm::march_accumulator<vec3> acc; acc.transmittance = vec3(a); return vec4(acc.opacity(), 0.0f); },
             {{vec4(0.0f, 0.5f, 1.0f, 0), vec4(0)}, {vec4(0.25f, 0.75f, 1e-6f, 0), vec4(0)}}, 3, 1.0f});
        // Step schedules: camera at the layer, inside it, a nearly uniform one (huge
        // near_distance), an empty range and a 1000 km ray with near_distance 1 m.
        std::vector<std::pair<vec4, vec4>> schedule;
        for (vec3 r : {vec3(0.0f, 35000.0f, 1000.0f), vec3(1500.0f, 4000.0f, 500.0f), vec3(0.0f, 35000.0f, 1e9f),
                       vec3(100.0f, 100.0f, 10.0f), vec3(0.0f, 1e6f, 1.0f)})
            for (float u : {-0.5f, 0.0f, 0.01f, 0.1f, 0.37f, 0.5f, 0.9f, 0.999f, 1.0f, 2.0f}) schedule.push_back({vec4(u, r), vec4(0)});
        // Hardening round 2, A6: ends whose difference rounds, u just below 1, a near_distance
        // tiny against the range (the ends' ratio overflows float).
        for (vec3 r : {vec3(0.21875f, 841061.688f, 7.086f), vec3(1.0f, 16777218.0f, 1.0f), vec3(0.0f, 1e6f, 1e-33f)})
            for (float u : {0.5f, 0.99999994f, 1.0f}) schedule.push_back({vec4(u, r), vec4(0)});
        add({"cm_march_schedule_distance", "vec4(cm_march_schedule_distance(a.x, a.y, a.z, a.w))",
             [](vec4 a, vec4) { return vec4(cm::march_schedule_distance(a.x, a.y, a.z, a.w)); }, schedule, 1, 1e-3f});
        // Light steps (u clamped, lengths 0 to 30 km) and sub-step counts (below, at and
        // above the cap, NaN-free edges: 0, 1, just above 1, huge).
        std::vector<std::pair<vec4, vec4>> light_steps;
        for (float length : {0.0f, 1.0f, 3300.0f, 30000.0f})
            for (float u : {-0.5f, 0.0f, 0.01f, 1.0f / 6.0f, 0.5f, 0.999f, 1.0f, 2.0f}) light_steps.push_back({vec4(u, length, 0, 0), vec4(0)});
        add({"cm_light_march_distance", "vec4(cm_light_march_distance(a.x, a.y))",
             [](vec4 a, vec4) { return vec4(cm::light_march_distance(a.x, a.y)); }, light_steps, 1, 1e-6f});
        std::vector<std::pair<vec4, vec4>> taus;
        for (float tau : {-1.0f, 0.0f, 0.5f, 1.0f, 1.0000001f, 1.5f, 2.0f, 7.3f, 15.99f, 16.0f, 100.0f, 1e30f})
            for (float most : {-2.0f, 1.0f, 4.0f, 16.0f}) taus.push_back({vec4(tau, most, 0, 0), vec4(0)});
        add({"cm_refine_substeps", "vec4(float(cm_refine_substeps(a.x, int(a.y))))",
             [](vec4 a, vec4) { return vec4(float(cm::refine_substeps(a.x, int(a.y)))); }, taus, 1, 1.0f, 0.0});
    }

    // diffusion lighting: optical depths from 0 to 1e4 (past the 1e6 clamp is C++-tested),
    // every mu, g from isotropic to the clamp. The sun term's floor is 1e-3 (1/sr): the
    // diffusion's fluence cancels near a chord's back end to an absolute error of about
    // e^z eps L, so results far below the diffusion's scale (~0.1) compare absolutely.
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float ts : {0.0f, 0.3f, 2.0f, 10.0f, 60.0f, 1e4f})
            for (float tb : {0.0f, 1.0f, 20.0f, 1e4f})
                for (float tv : {0.0f, 0.5f, 8.0f})
                    for (float mu : {-1.0f, -0.2f, 0.6f, 1.0f})
                        for (float g : {0.0f, 0.75f, 0.85f, 0.999f})
                            for (float albedo : {1.0f, 0.99f, 0.5f}) in.push_back({vec4(ts, tb, tv, mu), vec4(g, albedo, 0.0f, 0.0f)});
        add({"cm_diffusion_scattering", "vec4(cm_diffusion_scattering(a.x, a.y, a.z, a.w, b.x, b.y, CM_DIFFUSION_MODEL_FITTED), cm_diffusion_scattering(a.x, a.y, a.z, a.w, b.x, b.y, CM_DIFFUSION_MODEL_PHYSICAL), cm_diffusion_scattering(a.x, a.y, a.z, a.w, b.x, b.y, CM_DIFFUSION_MODEL_CLOUDS), 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::diffusion_scattering(a.x, a.y, a.z, a.w, b.x, b.y, cm::diffusion_models::fitted),
                                              cm::diffusion_scattering(a.x, a.y, a.z, a.w, b.x, b.y, cm::diffusion_models::physical),
                                              cm::diffusion_scattering(a.x, a.y, a.z, a.w, b.x, b.y, cm::diffusion_models::clouds), 0.0f); }, in, 3, 1e-3f, 1e-4});
        add({"cm_diffusion_scattering_with", "vec4(cm_diffusion_scattering_with(a.x, a.y, a.z, a.w, b.x, b.y, CM_DIFFUSION_MODEL_FITTED), 0.0, 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::diffusion_scattering_with(a.x, a.y, a.z, a.w, b.x, b.y, cm::diffusion_models::fitted, cpp_test_phase), 0.0f, 0.0f, 0.0f); }, in, 1, 1e-3f, 1e-4});
        add({"cm_diffusion_table_coordinates", "cm_diffusion_table_coordinates(a.x, a.y, a.z, a.w, b.x, b.y)",
             [](vec4 a, vec4 b) { const auto u = cm::diffusion_table_coordinates(a.x, a.y, a.z, a.w, b.x, b.y); return vec4(u.u_sun, u.u_behind, u.u_mu, u.u_surface); }, in, 4, 1e-6f});
        std::vector<std::pair<vec4, vec4>> fluence;
        for (float x : {0.0f, 0.01f, 0.5f, 3.0f, 40.0f, 1e3f})
            for (float y : {0.0f, 0.01f, 0.5f, 3.0f, 40.0f, 1e3f})
                for (float kappa : {0.0f, 1e-6f, 0.02f, 0.3f, 0.9f}) fluence.push_back({vec4(x, y, std::exp(-x), kappa), vec4(0.0f)});
        add({"cm_diffusion_chord_fluence", "cm_test_chord_fluence(a)",
             [](vec4 a, vec4) { float flux = 0.0f; const float U = cm::diffusion_chord_fluence(a.x, a.y, a.z, a.w, flux); return vec4(U, flux, 0.0f, 0.0f); }, fluence, 2, 1e-5f, 1e-4});
        std::vector<std::pair<vec4, vec4>> media;
        for (float g : {-1.0f, -0.3f, 0.0f, 0.85f, 0.999f, 1.0f})
            for (float albedo : {0.0f, 0.5f, 0.9f, 0.99f, 0.9999f, 1.0f}) media.push_back({vec4(g, albedo, 0.0f, 0.0f), vec4(0.0f)});
        add({"cm_diffusion_similarity", "vec4(cm_diffusion_similarity(a.x, a.y), 0.0, 0.0)",
             [](vec4 a, vec4) { const auto m = cm::diffusion_similarity(a.x, a.y); return vec4(m.s, m.kappa, 0.0f, 0.0f); }, media, 2, 1e-6f});
        std::vector<std::pair<vec4, vec4>> coords;
        for (float u : {0.0f, 0.13f, 0.5f, 0.77f, 1.0f})
            for (float v : {0.0f, 0.4f, 1.0f})
                for (float m : {0.0f, 0.25f, 0.5f, 0.9f, 1.0f})
                    for (float d : {0.0f, 0.6f, 1.0f}) coords.push_back({vec4(u, v, m, d), vec4(0.0f)});
        add({"cm_diffusion_table_lookup", "vec4(cm_diffusion_table_lookup(CM_DIFFUSION_MODEL_FITTED, a), cm_diffusion_table_lookup(CM_DIFFUSION_MODEL_CLOUDS, a), 0.0, 0.0)",
             [](vec4 a, vec4) { const cm::diffusion_coordinates<float> u{a.x, a.y, a.z, a.w};
                                return vec4(cm::diffusion_table_lookup(cm::diffusion_models::fitted, u),
                                            cm::diffusion_table_lookup(cm::diffusion_models::clouds, u), 0.0f, 0.0f); }, coords, 2, 1e-5f});
    }

    // multiple scattering
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float t : {0.0f, 0.1f, 1.0f, 5.0f, 30.0f, 1e4f})
            for (float mu : {-1.0f, -0.3f, 0.0f, 0.7f, 0.999f, 1.0f})
                for (float g : {0.0f, 0.8f, 0.9999f, -0.5f})
                    for (float n : {0.0f, 1.0f, 3.0f, 8.0f}) in.push_back({vec4(t, mu, g, n), vec4(0.5f, 0.5f, 0.5f, 0.0f)});
        add({"cm_multiple_scattering", "vec4(cm_multiple_scattering(a.x, a.y, a.z, b.x, b.y, b.z, int(a.w)), cm_multiple_scattering(a.x, a.y, a.z, 0.3, 0.75, 0.5, int(a.w)), cm_multiple_scattering(a.x, a.y, a.z, b.x, b.y, b.z), 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::multiple_scattering(a.x, a.y, a.z, b.x, b.y, b.z, int(a.w)), cm::multiple_scattering(a.x, a.y, a.z, 0.3f, 0.75f, 0.5f, int(a.w)),
                                              cm::multiple_scattering<3>(a.x, a.y, a.z, b.x, b.y, b.z), 0.0f); }, in, 3, 1e-30f});
        add({"cm_multiple_scattering [presets]", "vec4(cm_multiple_scattering(a.x, a.y, a.z, CM_MS_PRESET_PRODUCTION), cm_multiple_scattering(a.x, a.y, a.z, CM_MS_PRESET_FITTED), cm_multiple_scattering(a.x, a.y, a.z, CM_MS_PRESET_THIN), cm_multiple_scattering(a.x, a.y, a.z, CM_MS_PRESET_THICK) + cm_multiple_scattering(a.x, a.y, a.z, CM_MS_PRESET_CHEAP))",
             [](vec4 a, vec4) { return vec4(cm::multiple_scattering(a.x, a.y, a.z, cm::ms_preset::production), cm::multiple_scattering(a.x, a.y, a.z, cm::ms_preset::fitted),
                                            cm::multiple_scattering(a.x, a.y, a.z, cm::ms_preset::thin), cm::multiple_scattering(a.x, a.y, a.z, cm::ms_preset::thick) + cm::multiple_scattering(a.x, a.y, a.z, cm::ms_preset::cheap)); }, in, 4, 1e-30f});
        add({"cm_multiple_scattering_with", "vec4(cm_multiple_scattering_with(a.x, a.y, b.x, b.y, b.z, int(a.w)), cm_multiple_scattering_with(a.x, a.y, b.x, b.y, b.z), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::multiple_scattering_with(a.x, a.y, b.x, b.y, b.z, int(a.w), cpp_test_phase),
                                              cm::multiple_scattering_with<3>(a.x, a.y, b.x, b.y, b.z, cpp_test_phase), 0.0f, 0.0f); }, in, 2, 1e-30f});
    }

    // cone sampling (config: 6 samples, 50 m steps, spread 0.4, far sample at 800 m for 100 m)
    {
        const std::string cfg = "CmConeLightConfig(int(b.w), 50.0, 0.4, b.z, 100.0)";
        auto cfg_of = [](vec4 b) { return cm::cone_light_config<float>{int(b.w), 50.0f, 0.4f, b.z, 100.0f}; };
        // a = origin and sample index; b = (direction index, -, far_distance, sample_count).
        const vec3 dirs[] = {vec3(0, 1, 0), vec3(0, 0, -1), glm::normalize(vec3(1, 2, 3)), glm::normalize(vec3(-0.3f, 0.1f, -0.9f))};
        std::vector<std::pair<vec4, vec4>> in2;
        for (int di = 0; di < 4; ++di)
            for (int i = -2; i <= 7; ++i)
                for (float far : {800.0f, 0.0f})
                    for (float n : {6.0f, 1.0f}) in2.push_back({vec4(10.0f, -4.0f, 7.0f, float(i)), vec4(float(di), 0.0f, far, n)});
        const std::string dir_glsl = "cm_test_dir(int(b.x))";
        auto dir_cpp = [dirs](vec4 b) { return dirs[int(b.x)]; };
        add({"cm_cone_kernel_offset", "vec4(cm_cone_kernel_offset(int(a.w), int(b.w)), cm_cone_kernel_offset(int(a.w), 5))",
             [](vec4 a, vec4 b) { return vec4(cm::cone_kernel_offset<float>(int(a.w), int(b.w)), cm::cone_kernel_offset<float>(int(a.w), 5)); }, in2, 4, 1.0f});
        // Large counts (regression: the C++ wrap overflowed int for n > INT_MAX / 2); small
        // indices, whose angles both sides round alike.
        std::vector<std::pair<vec4, vec4>> big_n;
        for (float n : {1073741824.0f, 2147483520.0f, 8388608.0f})
            for (int i = 0; i <= 7; ++i) big_n.push_back({vec4(0.0f, 0.0f, 0.0f, float(i)), vec4(0.0f, 0.0f, 0.0f, n)});
        add({"cm_cone_kernel_offset", "vec4(cm_cone_kernel_offset(int(a.w), int(b.w)), cm_cone_kernel_offset(int(a.w) - int(b.w), int(b.w)))",
             [](vec4 a, vec4 b) { return vec4(cm::cone_kernel_offset<float>(int(a.w), int(b.w)), cm::cone_kernel_offset<float>(int(a.w) - int(b.w), int(b.w))); }, big_n, 4, 1.0f});
        add({"cm_cone_sample_distance", "vec4(cm_cone_sample_distance(" + cfg + ", int(a.w)), cm_cone_sample_length(" + cfg + ", int(a.w)), 0.0, 0.0)",
             [cfg_of](vec4 a, vec4 b) { return vec4(cm::cone_sample_distance(cfg_of(b), int(a.w)), cm::cone_sample_length(cfg_of(b), int(a.w)), 0.0f, 0.0f); }, in2, 2, 1.0f});
        add({"cm_cone_sample_length", "vec4(cm_cone_sample_length(" + cfg + ", int(a.w)))",
             [cfg_of](vec4 a, vec4 b) { return vec4(cm::cone_sample_length(cfg_of(b), int(a.w))); }, in2, 1, 1.0f});
        // Positions are compared on the scale of the distances involved (metres).
        add({"cm_cone_sample_position", "vec4(cm_cone_sample_position(a.xyz, " + dir_glsl + ", " + cfg + ", int(a.w)), 0.0)",
             [cfg_of, dir_cpp](vec4 a, vec4 b) { return vec4(cm::cone_sample_position(vec3(a), dir_cpp(b), cfg_of(b), int(a.w)), 0.0f); }, in2, 3, 100.0f});
        add({"cm_cone_optical_depth", "vec4(cm_cone_optical_depth(a.xyz, " + dir_glsl + ", " + cfg + "))",
             [cfg_of, dir_cpp](vec4 a, vec4 b) { return vec4(cm::cone_optical_depth(vec3(a), dir_cpp(b), cfg_of(b), cpp_test_extinction)); }, in2, 1, 1e-3f});
    }

    // geometry
    {
        std::vector<std::pair<vec4, vec4>> in;
        const vec3 dirs[] = {vec3(0, 0, 1), glm::normalize(vec3(0.3f, 0.2f, 1.0f)), glm::normalize(vec3(1, -2, 0.5f))};
        for (const vec3& d : dirs)
            for (vec4 o : {vec4(0, 0, -5, 1), vec4(0, 0, 0, 2), vec4(0, 0, 5, 1), vec4(0, 2, -5, 1), vec4(0.3f, 0.2f, -1e5f, 1), vec4(3, -1, 2, 10)})
                in.push_back({o, vec4(d, 0.0f)});
        // A camera 1.8 m above a 6371 km sphere, the sphere 1500 m above it, rays from the
        // zenith to the horizon in a slanted plane (the compensated c and discriminant).
        for (int i = 0; i <= 12; ++i) {
            const float elevation = 1.5707963f * float(i) / 12.0f;
            const vec3 up = glm::normalize(vec3(0.3f, 0.9f, -0.2f)), side = glm::normalize(glm::cross(up, vec3(0, 0, 1)));
            in.push_back({vec4(up * 6371001.8f, 6372500.0f), vec4(up * std::sin(elevation) + side * std::cos(elevation), 0.0f)});
        }
        add({"cm_ray_sphere_intersect", "vec4(cm_ray_sphere_intersect(a.xyz, b.xyz, vec3(0.0), a.w), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::ray_sphere_intersect(vec3(a), vec3(b), vec3(0.0f), a.w), 0.0f, 0.0f); }, in, 2, 1.0f});
    }
    {
        // Cameras of the C++ tests (1.8 m, 1000 m, 2000 m inside, 10 km, 400 km), on the layer's
        // boundaries and on the ground; rays across the horizon, tangent ones included.
        std::vector<std::pair<vec4, vec4>> in;
        std::vector<float> mus;
        for (int i = -40; i <= 40; ++i) mus.push_back(float(i) / 40.0f);
        for (float m : {1e-4f, -1e-4f, 1e-3f, -1e-3f, 0.01f, -0.01f, -0.0318f, -0.0177f, -0.0331f}) mus.push_back(m);
        for (float h : {0.0f, 1.8f, 1000.0f, 1500.0f, 2000.0f, 4000.0f, 5000.0f, 10000.0f, 400e3f})
            for (float mu : mus) in.push_back({vec4(h, mu, 1500.0f, 4000.0f), vec4(0)});
        // Distances up to ~1e6 m: compared relative to 1 m at the low end (float rounding
        // of a 1e5 m root is ~1e-2 m, so the relative criterion dominates).
        add({"cm_ray_sphere_intersect_altitude", "vec4(cm_ray_sphere_intersect_altitude(a.x, a.y, 6371e3, a.z), cm_ray_sphere_intersect_altitude(a.x, a.y, 6371e3, a.w))",
             [R](vec4 a, vec4) { return vec4(cm::ray_sphere_intersect_altitude(a.x, a.y, R, a.z), cm::ray_sphere_intersect_altitude(a.x, a.y, R, a.w)); }, in, 4, 1.0f});
        add({"cm_cloud_layer_segment", "vec4(cm_cloud_layer_segment(a.x, a.y, 6371e3, a.z, a.w), cm_cloud_layer_segment(a.x, a.y, 6371e3, a.w, a.z))",
             [R](vec4 a, vec4) { return vec4(cm::cloud_layer_segment(a.x, a.y, R, a.z, a.w), cm::cloud_layer_segment(a.x, a.y, R, a.w, a.z)); }, in, 4, 1.0f});
        std::vector<std::pair<vec4, vec4>> along;
        for (float h : {1.8f, 1000.0f, 3000.0f})
            for (float mu : {-0.001f, 0.0f, 0.01f, 0.2f, 1.0f})
                for (float t : {0.0f, 10.0f, 1000.0f, 20000.0f, 100000.0f}) along.push_back({vec4(h, mu, t, 0.0f), vec4(0)});
        add({"cm_altitude_along_ray", "vec4(cm_altitude_along_ray(a.x, a.y, 6371e3, a.z))",
             [R](vec4 a, vec4) { return vec4(cm::altitude_along_ray(a.x, a.y, R, a.z)); }, along, 1, 1.0f});
        std::vector<std::pair<vec4, vec4>> points;
        for (float cam : {1.8f, 2700.0f, 7000.0f})
            for (vec3 p : {vec3(0.0f), vec3(0, 1500, 0), vec3(100000, 0, 0), vec3(-3000, 1200, 40000), vec3(5, -2, -7)})
                points.push_back({vec4(p, cam), vec4(0)});
        add({"cm_point_altitude", "vec4(cm_point_altitude(a.xyz, a.w, 6371e3))",
             [R](vec4 a, vec4) { return vec4(cm::point_altitude(vec3(a), a.w, R)); }, points, 1, 1.0f});
        std::vector<std::pair<vec4, vec4>> hf;
        for (float alt : {-100.0f, 0.0f, 1499.0f, 1500.0f, 2000.0f, 2750.0f, 3999.0f, 4000.0f, 1e9f})
            for (vec2 l : {vec2(1500, 4000), vec2(2000, 2000), vec2(4000, 1500)}) hf.push_back({vec4(alt, l.x, l.y, 0.0f), vec4(0)});
        add({"cm_height_fraction", "vec4(cm_height_fraction(a.x, a.y, a.z))", [](vec4 a, vec4) { return vec4(cm::height_fraction(a.x, a.y, a.z)); }, hf, 1, 1.0f});
    }

    // density
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (int i = -5; i <= 105; ++i)
            for (float t : {-1.0f, 0.0f, 0.25f, 0.5f, 0.8f, 1.0f, 2.0f}) in.push_back({vec4(float(i) / 100.0f, t, 0.0f, 0.0f), vec4(0.1f, 0.3f, 0.6f, 0.9f)});
        add({"cm_height_gradient", "vec4(cm_height_gradient(a.x, b), cm_height_gradient(a.x, vec4(0.2, 0.2, 0.7, 0.7)), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::height_gradient(a.x, b), cm::height_gradient(a.x, vec4(0.2f, 0.2f, 0.7f, 0.7f)), 0.0f, 0.0f); }, in, 2, 1.0f});
        add({"cm_height_profile_stratus", "vec4(cm_height_gradient(a.x, cm_height_profile_stratus()), cm_height_profile_stratus().yzw)",
             [](vec4 a, vec4) { const vec4 p = cm::height_profile_stratus<float>(); return vec4(cm::height_gradient(a.x, p), p.y, p.z, p.w); }, in, 4, 1.0f});
        add({"cm_height_profile_stratocumulus", "vec4(cm_height_gradient(a.x, cm_height_profile_stratocumulus()), cm_height_profile_stratocumulus().yzw)",
             [](vec4 a, vec4) { const vec4 p = cm::height_profile_stratocumulus<float>(); return vec4(cm::height_gradient(a.x, p), p.y, p.z, p.w); }, in, 4, 1.0f});
        add({"cm_height_profile_cumulus", "vec4(cm_height_gradient(a.x, cm_height_profile_cumulus()), cm_height_profile_cumulus().yzw)",
             [](vec4 a, vec4) { const vec4 p = cm::height_profile_cumulus<float>(); return vec4(cm::height_gradient(a.x, p), p.y, p.z, p.w); }, in, 4, 1.0f});
        add({"cm_height_profile_for_type", "cm_height_profile_for_type(a.y)", [](vec4 a, vec4) { return cm::height_profile_for_type(a.y); }, in, 4, 1.0f});
        add({"cm_height_range_for_type", "vec4(cm_height_range_for_type(a.y), 0.0, 0.0)", [](vec4 a, vec4) { return vec4(cm::height_range_for_type(a.y), 0.0f, 0.0f); }, in, 2, 1.0f});
        add({"cm_height_gradient_for_type", "vec4(cm_height_gradient_for_type(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::height_gradient_for_type(a.x, a.y)); }, in, 1, 1.0f});
        add({"cm_height_gradient_exponential", "vec4(cm_height_gradient_exponential(a.x, 50.0, 4.0), cm_height_gradient_exponential(a.x * 1e-6, 50.0, 4.0), 0.0, 0.0)",
             [](vec4 a, vec4) { return vec4(cm::height_gradient_exponential(a.x, 50.0f, 4.0f), cm::height_gradient_exponential(a.x * 1e-6f, 50.0f, 4.0f), 0.0f, 0.0f); }, in, 2, 1e-30f});
        // Below the layer and far above it (regression: 0 * exp(92) = NaN at h = -23, and
        // Inf * 0 from cm_one_minus_exp_neg at h = FLT_MAX); negative a and b act as 0.
        std::vector<std::pair<vec4, vec4>> far;
        for (float h : {-3.4028235e38f, -1e30f, -177.5f, -23.0f, -22.2f, -1.0f, 0.0f, 0.05f, 30.0f, 1e30f, 3.4028235e38f})
            far.push_back({vec4(h, 0.0f, 0.0f, 0.0f), vec4(0)});
        add({"cm_height_gradient_exponential", "vec4(cm_height_gradient_exponential(a.x, 50.0, 4.0), cm_height_gradient_exponential(a.x, -50.0, 4.0), cm_height_gradient_exponential(a.x, 50.0, -4.0), cm_height_gradient_exponential(a.x, 1e30, 1e30))",
             [](vec4 a, vec4) { return vec4(cm::height_gradient_exponential(a.x, 50.0f, 4.0f), cm::height_gradient_exponential(a.x, -50.0f, 4.0f),
                                            cm::height_gradient_exponential(a.x, 50.0f, -4.0f), cm::height_gradient_exponential(a.x, 1e30f, 1e30f)); }, far, 4, 1e-30f});
        std::vector<std::pair<vec4, vec4>> cov;
        for (int b = 0; b <= 20; ++b)
            for (int c = -2; c <= 22; ++c) cov.push_back({vec4(float(b) / 20.0f, float(c) / 20.0f, 0.0f, 0.0f), vec4(0)});
        add({"cm_apply_coverage", "vec4(cm_apply_coverage(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::apply_coverage(a.x, a.y)); }, cov, 1, 1.0f});
        add({"cm_erode", "vec4(cm_erode(a.x, a.y))", [](vec4 a, vec4) { return vec4(cm::erode(a.x, a.y)); }, cov, 1, 1.0f});
        std::vector<std::pair<vec4, vec4>> fog;
        for (float h : {0.0f, 10.0f, 500.0f, 3000.0f})
            for (float mu : {-1.0f, -0.5f, -1e-6f, 0.0f, 1e-9f, 0.01f, 0.3f, 1.0f})
                for (float L : {1.0f, 100.0f, 3000.0f}) fog.push_back({vec4(h, mu, L, 0.0f), vec4(0.02f, 0.002f, 0.05f, 0.0f)});
        add({"cm_height_fog_density", "vec4(cm_height_fog_density(a.x, b.x, b.y))", [](vec4 a, vec4 b) { return vec4(cm::height_fog_density(a.x, b.x, b.y)); }, fog});
        add({"cm_height_fog_optical_depth", "vec4(cm_height_fog_optical_depth(a.x, a.y, a.z, b.x, b.y), cm_height_fog_optical_depth(a.x, a.y, a.z, b.x, b.z), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::height_fog_optical_depth(a.x, a.y, a.z, b.x, b.y), cm::height_fog_optical_depth(a.x, a.y, a.z, b.x, b.z), 0.0f, 0.0f); }, fog, 2});
        // Air: cameras on the ground and above the clouds, rays up, level and down, 1 m to 300 km.
        std::vector<std::pair<vec4, vec4>> air;
        for (float h : {0.0f, 2.0f, 2700.0f, 7000.0f})
            for (float mu : {-1.0f, -0.3f, -0.01f, 0.0f, 0.02f, 0.5f, 1.0f})
                for (float L : {1.0f, 1000.0f, 35000.0f, 300000.0f})
                    if (h + mu * L >= 0.0f) air.push_back({vec4(h, mu, L, 0.0f), vec4(0)});  // above the ground
        add({"cm_air_optical_depth", "vec4(cm_air_optical_depth(a.x, a.y, a.z), 0.0)",
             [](vec4 a, vec4) { return vec4(cm::air_optical_depth(a.x, a.y, a.z), 0.0f); }, air, 3});
        std::vector<std::pair<vec4, vec4>> seen;
        for (float tau : {0.0f, 1e-8f, 1e-3f, 0.5f, 3.0f, 40.0f, 1e4f})
            for (float L : {0.0f, 0.3f, 2.5f}) seen.push_back({vec4(L, 0.7f, tau, tau * 0.5f), vec4(L * 2.0f, 1.1f, 0.0f, 0.0f)});
        // Hardening round 2, A3: L far above L_air (the difference form lost L_air).
        seen.push_back({vec4(1.5e6f, 0.2f, 30.0f, 60.0f), vec4(1e13f, 3.0f, 0.0f, 0.0f)});
        seen.push_back({vec4(1e13f, 3.0f, 1e4f, 40.0f), vec4(2.0f, 1e6f, 0.0f, 0.0f)});
        add({"cm_aerial_perspective", "vec4(cm_aerial_perspective(a.x, a.y, a.z), cm_aerial_perspective(vec3(a.x, b.x, b.y), vec3(a.y), vec3(a.z, a.w, 2.0 * a.z)))",
             [](vec4 a, vec4 b) { return vec4(cm::aerial_perspective(a.x, a.y, a.z),
                                              cm::aerial_perspective(vec3(a.x, b.x, b.y), vec3(a.y), vec3(a.z, a.w, 2.0f * a.z))); }, seen, 4, 1.0f});
    }
    // Nubis density composition over a grid of texture values, types, coverage and heights.
    {
        std::vector<std::pair<vec4, vec4>> in;
        std::uint32_t state = 99U;
        auto unit = [&state]() { state = cm::noise_hash(state + 1U); return float(state >> 8) / 16777216.0f; };
        for (int i = 0; i < 400; ++i)
            in.push_back({vec4(unit(), unit(), unit(), unit()), vec4(unit(), unit(), unit() * 1.2f - 0.1f, unit() * 1.2f - 0.1f)});
        for (float h : {0.0f, 0.05f, 0.1f, 0.5f, 1.0f}) in.push_back({vec4(1.0f, 0.0f, 0.0f, 0.0f), vec4(0.5f, 0.5f, 1.0f, h)});
        add({"cm_nubis_low_frequency_fbm", "vec4(cm_nubis_low_frequency_fbm(a), cm_nubis_base_cloud(a), cm_nubis_high_frequency_fbm(b.xyz), cm_nubis_detail_erosion(b.xyz, b.w))",
             [](vec4 a, vec4 b) { return vec4(cm::nubis_low_frequency_fbm(a), cm::nubis_base_cloud(a), cm::nubis_high_frequency_fbm(vec3(b)), cm::nubis_detail_erosion(vec3(b), b.w)); },
             in, 4, 1.0f});
        add({"cm_nubis_base_cloud", "vec4(cm_nubis_base_cloud(a))", [](vec4 a, vec4) { return vec4(cm::nubis_base_cloud(a)); }, in, 1, 1.0f});
        add({"cm_nubis_high_frequency_fbm", "vec4(cm_nubis_high_frequency_fbm(a.xyz))", [](vec4 a, vec4) { return vec4(cm::nubis_high_frequency_fbm(vec3(a))); }, in, 1, 1.0f});
        add({"cm_nubis_detail_erosion", "vec4(cm_nubis_detail_erosion(a.xyz, b.w))", [](vec4 a, vec4 b) { return vec4(cm::nubis_detail_erosion(vec3(a), b.w)); }, in, 1, 1.0f});
        add({"cm_nubis_density", "vec4(cm_nubis_density(a, b.xyz, b.z, a.w, b.w), cm_nubis_density(a, b.xyz, 1.0, 1.0, b.w), cm_nubis_density(a, b.xyz, 0.6, 0.0, b.w * 0.2), 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::nubis_density(a, vec3(b), b.z, a.w, b.w), cm::nubis_density(a, vec3(b), 1.0f, 1.0f, b.w),
                                              cm::nubis_density(a, vec3(b), 0.6f, 0.0f, b.w * 0.2f), 0.0f); }, in, 3, 1.0f});
        add({"cm_cloud_shape_density",
             "vec4(cm_cloud_shape_density(a, b.xyz, b.w, 0.4, a.w, 0.5, 0.6), cm_cloud_shape_density(a, b.zyx, b.w * 0.5, 0.7, 1.0, 0.8, 0.0), "
             "cm_cloud_top_fraction(b.z), cm_cloud_top_fraction(a.x * 2.0 - 0.5))",
             [](vec4 a, vec4 b) {
                 return vec4(cm::cloud_shape_density(a, vec3(b), b.w, 0.4f, a.w, 0.5f, 0.6f),
                             cm::cloud_shape_density(a, vec3(b.z, b.y, b.x), b.w * 0.5f, 0.7f, 1.0f, 0.8f, 0.0f),
                             cm::cloud_top_fraction(b.z), cm::cloud_top_fraction(a.x * 2.0f - 0.5f)); },
             in, 4, 1.0f});
    }
    // noise: the hashes must agree bit for bit (compared as two exact 16-bit halves);
    // the noise values within 1e-5 of their range (floor 1).
    {
        std::vector<std::pair<vec4, vec4>> hashes;
        for (std::uint32_t i = 0; i < 64; ++i) {
            const std::uint32_t x = cm::noise_hash(i * 2654435761U);  // spread over all 32 bits
            hashes.push_back({vec4(float(x >> 16), float(x & 0xffffU), float(i), float(i % 5)), vec4(float(i * 7 % 13), 0.0f, 0.0f, 0.0f)});
        }
        add({"cm_noise_hash",
             "vec4(float(cm_noise_hash((uint(a.x) << 16u) | uint(a.y)) >> 16u), float(cm_noise_hash((uint(a.x) << 16u) | uint(a.y)) & 0xffffu), "
             "float(cm_noise_hash(uint(a.z), uint(a.w), uint(b.x), 7u) >> 16u), float(cm_noise_hash(uint(a.z), uint(a.w), uint(b.x), 7u) & 0xffffu))",
             [](vec4 a, vec4 b) {
                 const std::uint32_t h = cm::noise_hash((std::uint32_t(a.x) << 16) | std::uint32_t(a.y));
                 const std::uint32_t g = cm::noise_hash(std::uint32_t(a.z), std::uint32_t(a.w), std::uint32_t(b.x), 7U);
                 return vec4(float(h >> 16), float(h & 0xffffU), float(g >> 16), float(g & 0xffffU)); },
             hashes, 4, 1.0f, 0.0});
        // The sequences: bit-identical (uint arithmetic), for small and wrapping indices.
        std::vector<std::pair<vec4, vec4>> indices;
        for (std::uint32_t i = 0; i < 48; ++i) {
            const std::uint32_t n = i < 16 ? i : cm::noise_hash(i);
            const std::uint32_t frame = i < 8 ? i : cm::noise_hash(i + 1000U);
            indices.push_back({vec4(float(n >> 16), float(n & 0xffffU), float(frame >> 16), float(frame & 0xffffU)), vec4(0.0f)});
        }
        const auto index = [](float hi, float lo) { return (std::uint32_t(hi) << 16) | std::uint32_t(lo); };
        add({"cm_low_discrepancy_r1",
             "vec4(cm_low_discrepancy_r1((uint(a.x) << 16u) | uint(a.y)), cm_low_discrepancy_r2((uint(a.x) << 16u) | uint(a.y)), "
             "cm_frame_jitter((uint(a.x) << 16u) | uint(a.y), (uint(a.z) << 16u) | uint(a.w)))",
             [index](vec4 a, vec4) {
                 const std::uint32_t n = index(a.x, a.y), frame = index(a.z, a.w);
                 return vec4(cm::low_discrepancy_r1(n), cm::low_discrepancy_r2(n), cm::frame_jitter(n, frame)); },
             indices, 4, 1.0f, 0.0});
        add({"cm_hash_to_unit", "vec4(cm_hash_to_unit((uint(a.x) << 16u) | uint(a.y)), cm_hash_to_unit((uint(a.z) << 16u) | uint(a.w)), 0.0, 0.0)",
             [index](vec4 a, vec4) { return vec4(cm::hash_to_unit<float>(index(a.x, a.y)), cm::hash_to_unit<float>(index(a.z, a.w)), 0.0f, 0.0f); },
             indices, 2, 1.0f, 0.0});
        add({"cm_sample_jitter",
             "vec4(cm_sample_jitter((uint(a.x) << 16u) | uint(a.y), (uint(a.z) << 16u) | uint(a.w), (uint(a.y) << 16u) | uint(a.z)), 0.0, 0.0, 0.0)",
             [index](vec4 a, vec4) {
                 return vec4(cm::sample_jitter(index(a.x, a.y), index(a.z, a.w), index(a.y, a.z)), 0.0f, 0.0f, 0.0f); },
             indices, 1, 1.0f, 0.0});
        add({"cm_triangular_dither", "vec4(cm_triangular_dither((uint(a.x) << 16u) | uint(a.y)), cm_triangular_dither((uint(a.z) << 16u) | uint(a.w)), 0.0, 0.0)",
             [index](vec4 a, vec4) { return vec4(cm::triangular_dither(index(a.x, a.y)), cm::triangular_dither(index(a.z, a.w)), 0.0f, 0.0f); },
             indices, 2, 1.0f, 0.0});
        std::vector<std::pair<vec4, vec4>> pts;
        cm_test_points(pts);
        add({"cm_perlin_noise_derivatives", "cm_perlin_noise_derivatives(a.xyz, int(a.w), uint(b.x))",
             [](vec4 a, vec4 b) { return cm::perlin_noise_derivatives(vec3(a), int(a.w), std::uint32_t(b.x)); }, pts, 4, 1.0f});
        add({"cm_perlin_noise_derivatives", "cm_perlin_noise_derivatives(a.xyz, int(a.w))",
             [](vec4 a, vec4) { return cm::perlin_noise_derivatives(vec3(a), int(a.w)); }, pts, 4, 1.0f});
        add({"cm_perlin_noise", "vec4(cm_perlin_noise(a.xyz, int(a.w), uint(b.x)), cm_perlin_noise(a.xyz, int(a.w)), cm_perlin_noise(a.xy, int(a.w), uint(b.x)), cm_perlin_noise(a.xy, int(a.w)))",
             [](vec4 a, vec4 b) { return vec4(cm::perlin_noise(vec3(a), int(a.w), std::uint32_t(b.x)), cm::perlin_noise(vec3(a), int(a.w)),
                                              cm::perlin_noise(vec2(a), int(a.w), std::uint32_t(b.x)), cm::perlin_noise(vec2(a), int(a.w))); }, pts, 4, 1.0f});
        add({"cm_worley_f1", "vec4(cm_worley_f1(a.xyz, int(a.w), uint(b.x)), cm_worley_f1(a.xyz, int(a.w)), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::worley_f1(vec3(a), int(a.w), std::uint32_t(b.x)), cm::worley_f1(vec3(a), int(a.w)), 0.0f, 0.0f); }, pts, 2, 1.0f});
        add({"cm_worley_noise", "vec4(cm_worley_noise(a.xyz, int(a.w), uint(b.x)), cm_worley_noise(a.xyz, int(a.w)), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::worley_noise(vec3(a), int(a.w), std::uint32_t(b.x)), cm::worley_noise(vec3(a), int(a.w)), 0.0f, 0.0f); }, pts, 2, 1.0f});
        add({"cm_perlin_fbm", "vec4(cm_perlin_fbm(a.xyz, int(a.w), 4, 3, 0.6, uint(b.x)), cm_perlin_fbm(a.xyz, int(a.w), 4), cm_perlin_fbm(a.xy, int(a.w), 5, 2, 0.5, uint(b.x)), cm_perlin_fbm(a.xy, int(a.w), 3))",
             [](vec4 a, vec4 b) { return vec4(cm::perlin_fbm(vec3(a), int(a.w), 4, 3, 0.6f, std::uint32_t(b.x)), cm::perlin_fbm(vec3(a), int(a.w), 4),
                                              cm::perlin_fbm(vec2(a), int(a.w), 5, 2, 0.5f, std::uint32_t(b.x)), cm::perlin_fbm(vec2(a), int(a.w), 3)); }, pts, 4, 1.0f});
        add({"cm_worley_fbm", "vec4(cm_worley_fbm(a.xyz, int(a.w), 3, 2, 0.5, uint(b.x)), cm_worley_fbm(a.xyz, int(a.w), 3), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::worley_fbm(vec3(a), int(a.w), 3, 2, 0.5f, std::uint32_t(b.x)), cm::worley_fbm(vec3(a), int(a.w), 3), 0.0f, 0.0f); }, pts, 2, 1.0f});
        // gain outside [0, 1] is clamped (regression: gain -1 with 4 octaves divided by 0).
        add({"cm_perlin_fbm", "vec4(cm_perlin_fbm(a.xyz, int(a.w), 4, 2, -1.0, uint(b.x)), cm_perlin_fbm(a.xyz, int(a.w), 3, 2, 2.5, uint(b.x)), cm_perlin_fbm(a.xy, int(a.w), 4, 2, -0.5, uint(b.x)), cm_perlin_fbm(a.xy, int(a.w), 4, 2, 1e30, uint(b.x)))",
             [](vec4 a, vec4 b) { return vec4(cm::perlin_fbm(vec3(a), int(a.w), 4, 2, -1.0f, std::uint32_t(b.x)), cm::perlin_fbm(vec3(a), int(a.w), 3, 2, 2.5f, std::uint32_t(b.x)),
                                              cm::perlin_fbm(vec2(a), int(a.w), 4, 2, -0.5f, std::uint32_t(b.x)), cm::perlin_fbm(vec2(a), int(a.w), 4, 2, 1e30f, std::uint32_t(b.x))); }, pts, 4, 1.0f});
        add({"cm_worley_fbm", "vec4(cm_worley_fbm(a.xyz, int(a.w), 4, 2, -1.0, uint(b.x)), cm_worley_fbm(a.xyz, int(a.w), 3, 2, 0.0, uint(b.x)), cm_worley_fbm(a.xyz, int(a.w), 3, 2, 3.0, uint(b.x)), 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::worley_fbm(vec3(a), int(a.w), 4, 2, -1.0f, std::uint32_t(b.x)), cm::worley_fbm(vec3(a), int(a.w), 3, 2, 0.0f, std::uint32_t(b.x)),
                                              cm::worley_fbm(vec3(a), int(a.w), 3, 2, 3.0f, std::uint32_t(b.x)), 0.0f); }, pts, 3, 1.0f});
        add({"cm_worley_fbm_nubis", "vec4(cm_worley_fbm_nubis(a.xyz, int(a.w), uint(b.x)), cm_worley_fbm_nubis(a.xyz, int(a.w)), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::worley_fbm_nubis(vec3(a), int(a.w), std::uint32_t(b.x)), cm::worley_fbm_nubis(vec3(a), int(a.w)), 0.0f, 0.0f); }, pts, 2, 1.0f});
        add({"cm_perlin_worley", "vec4(cm_perlin_worley(a.xyz, int(a.w), uint(b.x)), cm_perlin_worley(a.xyz, int(a.w)), 0.0, 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::perlin_worley(vec3(a), int(a.w), std::uint32_t(b.x)), cm::perlin_worley(vec3(a), int(a.w)), 0.0f, 0.0f); }, pts, 2, 1.0f});
        // Curl components reach about +-3.6; compared on that scale.
        add({"cm_curl_noise", "vec4(cm_curl_noise(a.xyz, int(a.w), uint(b.x)), 0.0)",
             [](vec4 a, vec4 b) { return vec4(cm::curl_noise(vec3(a), int(a.w), std::uint32_t(b.x)), 0.0f); }, pts, 3, 4.0f});
        add({"cm_curl_noise", "vec4(cm_curl_noise(a.xyz, int(a.w)), 0.0)",
             [](vec4 a, vec4) { return vec4(cm::curl_noise(vec3(a), int(a.w)), 0.0f); }, pts, 3, 4.0f});
        add({"cm_curl_noise", "vec4(cm_curl_noise(a.xy, int(a.w), uint(b.x)), cm_curl_noise(a.xy, int(a.w)))",
             [](vec4 a, vec4 b) { return vec4(cm::curl_noise(vec2(a), int(a.w), std::uint32_t(b.x)), cm::curl_noise(vec2(a), int(a.w))); }, pts, 4, 4.0f});
    }
    // sun: solid angles from the Sun's size to a hemisphere; the disc's radiance inside,
    // at the limb and outside, for the real Sun and a 2-degree artistic one.
    {
        std::vector<std::pair<vec4, vec4>> cones;
        for (float r : {1e-4f, 4.6524e-3f, 0.01f, 0.3f, 1.0f, 1.5707963f}) cones.push_back({vec4(r, 0.0f, 0.0f, 0.0f), vec4(0)});
        add({"cm_cone_solid_angle", "vec4(cm_cone_solid_angle(a.x), CM_SUN_ANGULAR_RADIUS, 0.0, 0.0)",
             [](vec4 a, vec4) { return vec4(cm::cone_solid_angle(a.x), cm::sun_angular_radius<float>(), 0.0f, 0.0f); }, cones, 2, 1.0f});
        std::vector<std::pair<vec4, vec4>> disc;
        for (float r : {4.6524e-3f, 0.0349f})
            for (float f : {0.0f, 0.3f, 0.7f, 0.95f, 0.999f, 1.05f, 3.0f})
                for (float u : {0.0f, 0.6f, 1.0f}) disc.push_back({vec4(1.0f, std::cos(f * r), r, u), vec4(0)});
        // Near the limb sqrt(1 - x^2) magnifies the rounding of cos_angle; compared on the
        // centre's scale (floor: the peak radiance, about 1.5e4 for the Sun).
        add({"cm_sun_disc_radiance", "vec4(cm_sun_disc_radiance(a.x, a.y, a.z, a.w))",
             [](vec4 a, vec4) { return vec4(cm::sun_disc_radiance(a.x, a.y, a.z, a.w)); }, disc, 1, 1.5e4f, 1e-4});
    }
    // reprojection: the Bayer order (bit-identical), projections of points in front of,
    // beside and behind a tilted camera, footprints at and between texel centres, and the
    // blend weight across its cap, with NaN and negative counts.
    {
        std::vector<std::pair<vec4, vec4>> pixels;
        for (int i = 0; i < 40; ++i)
            pixels.push_back({vec4(float(i * 7 % 23), float(i * 5 % 17), float(i), float(i * 977 + 65519)), vec4(0)});
        add({"cm_bayer_index_4x4",
             "vec4(float(cm_bayer_index_4x4(uint(a.x), uint(a.y))), vec2(cm_temporal_update_offset(uint(a.z))), "
             "float(cm_temporal_update_offset(uint(a.w)).x + 4u * cm_temporal_update_offset(uint(a.w)).y))",
             [](vec4 a, vec4) {
                 const glm::uvec2 o = cm::temporal_update_offset(std::uint32_t(a.z)), w = cm::temporal_update_offset(std::uint32_t(a.w));
                 return vec4(float(cm::bayer_index_4x4(std::uint32_t(a.x), std::uint32_t(a.y))), float(o.x), float(o.y), float(w.x + 4U * w.y)); },
             pixels, 4, 1.0f, 0.0});
        const vec3 f = glm::normalize(vec3(0.4f, 0.17f, -0.9f));
        std::vector<std::pair<vec4, vec4>> points;
        for (float x : {-3000.0f, -20.0f, 0.0f, 450.0f, 30000.0f})
            for (float y : {-500.0f, 0.0f, 1500.0f, 4000.0f})
                for (float z : {-35000.0f, -800.0f, 0.0f, 2000.0f}) points.push_back({vec4(x, y, z, 0.57735f), vec4(1.7778f)});
        const std::string basis = "vec3(" + std::to_string(f.x) + ", " + std::to_string(f.y) + ", " + std::to_string(f.z) + ")";
        const vec3 fq(std::stof(std::to_string(f.x)), std::stof(std::to_string(f.y)), std::stof(std::to_string(f.z)));
        const std::string right = "normalize(cross(" + basis + ", vec3(0.0, 1.0, 0.0)))";
        add({"cm_camera_project",
             "vec4(cm_camera_project(a.xyz, " + basis + ", " + right + ", cross(" + right + ", " + basis + "), a.w, b.x), 0.0)",
             [fq](vec4 a, vec4 b) {
                 const vec3 rq = glm::normalize(glm::cross(fq, vec3(0.0f, 1.0f, 0.0f)));
                 return vec4(cm::camera_project(vec3(a), fq, rq, glm::cross(rq, fq), a.w, b.x), 0.0f); },
             points, 3, 1.0f, 1e-4});
        std::vector<std::pair<vec4, vec4>> uvs;
        for (float u : {0.0f, 0.5f / 320.0f, 0.1f, 0.5f, 0.73f, 1.0f - 0.5f / 320.0f, 1.2f})
            for (float v : {-0.1f, 0.5f / 180.0f, 0.33f, 0.999f}) uvs.push_back({vec4(u, v, 0.0f, 0.0f), vec4(320.0f, 180.0f, 0.0f, 0.0f)});
        // Hardening round 2, A8: texel centres where uv * size - 1/2 rounds below i (column 0
        // of width 214, and others): (i, 0) exactly on both sides.
        for (int width : {214, 7, 99, 333, 517})
            for (int i : {0, 1, width / 2, width - 1})
                uvs.push_back({vec4((float(i) + 0.5f) / float(width), (float(i) + 0.5f) / float(width), 0.0f, 0.0f),
                               vec4(float(width), float(width), 0.0f, 0.0f)});
        add({"cm_texel_bilinear", "cm_texel_bilinear(a.xy, b.xy)",
             [](vec4 a, vec4 b) { return cm::texel_bilinear(vec2(a), vec2(b)); }, uvs, 4, 1.0f, 1e-4});
        std::vector<std::pair<vec4, vec4>> counts;
        for (float n : {-1.0f, 0.0f, 1.0f, 3.0f, 7.0f, 8.0f, 100.0f})
            for (float m : {0.0f, 1.0f, 8.0f, 16.0f}) counts.push_back({vec4(n, m, 0.0f, 0.0f), vec4(0)});
        add({"cm_temporal_blend_weight", "vec4(cm_temporal_blend_weight(a.x, a.y))",
             [](vec4 a, vec4) { return vec4(cm::temporal_blend_weight(a.x, a.y)); }, counts, 1, 1.0f, 1e-6});
    }
    // texture_lod: footprints near and far, levels across magnification and minification.
    {
        std::vector<std::pair<vec4, vec4>> in;
        for (float d : {-10.0f, 0.0f, 1.0f, 500.0f, 35000.0f, 2e5f})
            for (float texel : {10.0f, 46.875f, 234.375f})
                in.push_back({vec4(d, 0.57735f, 270.0f, texel), vec4(0)});
        add({"cm_pixel_footprint",
             "vec4(cm_pixel_footprint(a.x, a.y, a.z), cm_texture_lod(cm_pixel_footprint(a.x, a.y, a.z), a.w), cm_texture_lod(a.x, a.w), 0.0)",
             [](vec4 a, vec4) {
                 const float w = cm::pixel_footprint(a.x, a.y, a.z);
                 return vec4(w, cm::texture_lod(w, a.w), cm::texture_lod(a.x, a.w), 0.0f); },
             in, 3, 1.0f, 1e-5});
    }
    // shadow_map: a texel built by a march over clouds with gaps (the accumulator and its
    // steps), looked up at depths in front of, inside and behind the column; projections.
    {
        std::vector<std::pair<vec4, vec4>> marches;
        for (float start : {0.0f, 300.0f, 2500.0f})
            for (float scale : {0.0f, 0.004f, 0.05f})
                for (float depth : {-10.0f, 400.0f, 1200.0f, 2600.0f, 9000.0f})
                    marches.push_back({vec4(start, scale, depth, 0.0f), vec4(0)});
        add({"cm_beer_shadow_add_step",
             "cm_test_beer_shadow_march(a.x, a.y, a.z)",
             [](vec4 a, vec4) {
                 cm::beer_shadow_accumulator<float> acc;
                 for (int i = 0; i < 24; ++i) {
                     const float t = a.x + 100.0f * float(i);
                     acc.add_step(t, 100.0f, (i % 7 < 3 ? a.y : 0.0f) * (1.0f + 0.1f * float(i)));
                 }
                 const vec3 texel = acc.texel();
                 return vec4(texel.x, texel.y * 1000.0f, cm::beer_shadow_optical_depth(texel, a.z), cm::beer_shadow_transmittance(texel, a.z)); },
             marches, 4, 1.0f, 1e-5});
        std::vector<std::pair<vec4, vec4>> projections;
        for (float x : {-30000.0f, 0.0f, 4000.0f})
            for (float y : {0.0f, 2000.0f, 9000.0f})
                for (float z : {-20000.0f, 100.0f}) projections.push_back({vec4(x, y, z, 24000.0f), vec4(500.0f, 6000.0f, -800.0f, 0.0f)});
        add({"cm_shadow_map_project",
             "vec4(cm_shadow_map_project(a.xyz, b.xyz, vec3(0.6, 0.0, 0.8), vec3(-0.48, 0.6, 0.64), vec3(0.64, 0.8, -0.48), a.w), 0.0)",
             [](vec4 a, vec4 b) {
                 return vec4(cm::shadow_map_project(vec3(a), vec3(b), vec3(0.6f, 0.0f, 0.8f), vec3(-0.48f, 0.6f, 0.64f),
                                                    vec3(0.64f, 0.8f, -0.48f), a.w), 0.0f); },
             projections, 3, 1.0f, 1e-5});
    }
    // atmosphere: Earth's air at the ground, in the ozone layer and at the top; zenith angles
    // from straight down through the horizon to straight up; the LUT mapping both ways; EV100.
    {
        std::vector<std::pair<vec4, vec4>> rays;
        for (float h : {0.0f, 1.0f, 1500.0f, 8000.0f, 25000.0f, 59000.0f, 60000.0f})
            for (float mu : {-1.0f, -0.2f, -0.05f, -0.01f, 0.0f, 0.01f, 0.1f, 0.5f, 1.0f})
                rays.push_back({vec4(h, mu, 3000.0f, 0.0f), vec4(0)});
        const auto earth = cm::earth_atmosphere<float>();
        add({"cm_earth_atmosphere",
             "vec4(cm_earth_atmosphere().bottom_radius * 1e-6, cm_earth_atmosphere().rayleigh_scattering.z * 1e6, cm_earth_atmosphere().ozone_absorption.y * 1e6, cm_earth_atmosphere().mie_g)",
             [earth](vec4, vec4) { return vec4(earth.bottom_radius * 1e-6f, earth.rayleigh_scattering.z * 1e6f, earth.ozone_absorption.y * 1e6f, earth.mie_g); },
             {{vec4(0), vec4(0)}}, 4, 1.0f, 1e-6});
        add({"cm_atmosphere_extinction", "vec4(cm_atmosphere_extinction(cm_earth_atmosphere(), a.x) * 1e6, 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_extinction(earth, a.x) * 1e6f, 0.0f); }, rays, 3, 1.0f, 1e-5});
        add({"cm_atmosphere_distance_to_top",
             "vec4(cm_atmosphere_distance_to_top(cm_earth_atmosphere(), a.x, a.y) * 1e-3, cm_atmosphere_ray_hits_ground(cm_earth_atmosphere(), a.x, a.y) ? 1.0 : 0.0, 0.0, 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_distance_to_top(earth, a.x, a.y) * 1e-3f,
                                                 cm::atmosphere_ray_hits_ground(earth, a.x, a.y) ? 1.0f : 0.0f, 0.0f, 0.0f); },
             rays, 2, 1.0f, 1e-5});
        add({"cm_atmosphere_ray_hits_ground", "vec4(cm_atmosphere_ray_hits_ground(cm_earth_atmosphere(), a.x, a.y) ? 1.0 : 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_ray_hits_ground(earth, a.x, a.y) ? 1.0f : 0.0f); }, rays, 1, 1.0f, 0.0});
        add({"cm_atmosphere_optical_depth", "vec4(cm_atmosphere_optical_depth(cm_earth_atmosphere(), a.x, a.y, a.z, 16), 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_optical_depth(earth, a.x, a.y, a.z, 16), 0.0f); }, rays, 3, 1e-3f, 1e-5});
        add({"cm_atmosphere_transmittance", "vec4(cm_atmosphere_transmittance(cm_earth_atmosphere(), a.x, a.y, 64), 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_transmittance(earth, a.x, a.y, 64), 0.0f); }, rays, 3, 1.0f, 1e-5});
        // The whole default LUT (256 x 64) generated in the compute shader, texel for texel
        // against the CPU reference atmosphere_transmittance_lut: a = (i, j), b = (256, 64, 64
        // steps). The step count goes through int(), so --fuzz keeps these inputs as they are
        // (16384 texels, not 20 times as many) and the texel indices stay in the LUT.
        std::vector<std::pair<vec4, vec4>> lut_texels;
        for (int j = 0; j < 64; ++j)
            for (int i = 0; i < 256; ++i) lut_texels.push_back({vec4(float(i), float(j), 0.0f, 0.0f), vec4(256.0f, 64.0f, 64.0f, 0.0f)});
        const std::vector<vec3> lut = cm::atmosphere_transmittance_lut(earth, 256, 64, 64);
        add({"cm_atmosphere_transmittance",
             "vec4(cm_atmosphere_transmittance(cm_earth_atmosphere(), cm_atmosphere_transmittance_lut_altitude_mu(cm_earth_atmosphere(), (a.xy + 0.5) / b.xy, b.xy).x, "
             "cm_atmosphere_transmittance_lut_altitude_mu(cm_earth_atmosphere(), (a.xy + 0.5) / b.xy, b.xy).y, int(b.z)), 0.0)",
             [lut](vec4 a, vec4) {
                 const std::size_t i = std::size_t(std::clamp(a.x, 0.0f, 255.0f)), j = std::size_t(std::clamp(a.y, 0.0f, 63.0f));
                 return vec4(lut[j * 256u + i], 0.0f); },
             lut_texels, 3, 1.0f, 1e-5});
        add({"cm_atmosphere_transmittance_lut_uv", "vec4(cm_atmosphere_transmittance_lut_uv(cm_earth_atmosphere(), a.x, a.y, vec2(256.0, 64.0)), 0.0, 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_transmittance_lut_uv(earth, a.x, a.y, vec2(256.0f, 64.0f)), 0.0f, 0.0f); },
             rays, 2, 1.0f, 1e-5});
        std::vector<std::pair<vec4, vec4>> texels;
        for (float u : {0.0f, 0.5f / 256.0f, 0.1f, 0.5f, 0.9f, 1.0f - 0.5f / 256.0f, 1.0f})
            for (float v : {0.0f, 0.5f / 64.0f, 0.3f, 0.7f, 1.0f - 0.5f / 64.0f, 1.0f}) texels.push_back({vec4(u, v, 0.0f, 0.0f), vec4(256.0f, 64.0f, 0.0f, 0.0f)});
        add({"cm_atmosphere_transmittance_lut_altitude_mu",
             "vec4(cm_atmosphere_transmittance_lut_altitude_mu(cm_earth_atmosphere(), a.xy, b.xy) * vec2(1e-4, 1.0), 0.0, 0.0)",
             [earth](vec4 a, vec4 b) { return vec4(cm::atmosphere_transmittance_lut_altitude_mu(earth, vec2(a), vec2(b)) * vec2(1e-4f, 1.0f), 0.0f, 0.0f); },
             texels, 2, 1.0f, 1e-4});
        // Scattering with its phase: altitudes as above, scattering cosines from back to forward.
        std::vector<std::pair<vec4, vec4>> scatterings;
        for (float h : {0.0f, 1500.0f, 25000.0f, 60000.0f})
            for (float nu : {-1.0f, -0.3f, 0.0f, 0.7f, 0.99f, 1.0f}) scatterings.push_back({vec4(h, nu, 0.0f, 0.0f), vec4(0)});
        add({"cm_atmosphere_scattering_coefficient", "vec4(cm_atmosphere_scattering_coefficient(cm_earth_atmosphere(), a.x) * 1e6, 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_scattering_coefficient(earth, a.x) * 1e6f, 0.0f); }, scatterings, 3, 1.0f, 1e-5});
        add({"cm_atmosphere_scattering", "vec4(cm_atmosphere_scattering(cm_earth_atmosphere(), a.x, a.y) * 1e6, 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_scattering(earth, a.x, a.y) * 1e6f, 0.0f); }, scatterings, 3, 1.0f, 1e-5});
        add({"cm_atmosphere_sun_illuminance", "vec4(cm_atmosphere_sun_illuminance(cm_earth_atmosphere(), a.x, a.y, vec3(1.0, 2.0, 3.0)), 0.0)",
             [earth](vec4 a, vec4) { return vec4(cm::atmosphere_sun_illuminance(earth, a.x, a.y, vec3(1.0f, 2.0f, 3.0f)), 0.0f); },
             rays, 3, 1.0f, 1e-5});
        // Multiple scattering at a few points with small counts (b: directions, steps, sun
        // steps, through int() so --fuzz keeps them), then the whole default 32 x 32 LUT (64
        // directions, 20 steps, 32 sun steps) texel for texel against the CPU reference.
        std::vector<std::pair<vec4, vec4>> ms_points;
        for (float h : {0.0f, 2000.0f, 30000.0f, 60000.0f})
            for (float mu_s : {-1.0f, -0.1f, 0.0f, 0.2f, 1.0f}) ms_points.push_back({vec4(h, mu_s, 0.0f, 0.0f), vec4(16.0f, 8.0f, 8.0f, 0.0f)});
        add({"cm_atmosphere_multiple_scattering",
             "vec4(cm_atmosphere_multiple_scattering(cm_earth_atmosphere(), a.x, a.y, int(b.x), int(b.y), int(b.z)) * 100.0, 0.0)",
             [earth](vec4 a, vec4 b) {
                 return vec4(cm::atmosphere_multiple_scattering(earth, a.x, a.y, int(b.x), int(b.y), int(b.z)) * 100.0f, 0.0f); },
             ms_points, 3, 1.0f, 1e-4});
        std::vector<std::pair<vec4, vec4>> ms_texels;
        for (int j = 0; j < 32; ++j)
            for (int i = 0; i < 32; ++i) ms_texels.push_back({vec4(float(i), float(j), 0.0f, 0.0f), vec4(32.0f, 32.0f, 64.0f, 20.0f)});
        const std::vector<vec3> ms_lut = cm::atmosphere_multiple_scattering_lut(earth, 32, 32, 64, 20, 32);
        add({"cm_atmosphere_multiple_scattering",
             "vec4(cm_atmosphere_multiple_scattering(cm_earth_atmosphere(), cm_atmosphere_multiple_scattering_lut_altitude_mu(cm_earth_atmosphere(), (a.xy + 0.5) / b.xy, b.xy).x, "
             "cm_atmosphere_multiple_scattering_lut_altitude_mu(cm_earth_atmosphere(), (a.xy + 0.5) / b.xy, b.xy).y, int(b.z), int(b.w), 32) * 100.0, 0.0)",
             [ms_lut](vec4 a, vec4) {
                 const std::size_t i = std::size_t(std::clamp(a.x, 0.0f, 31.0f)), j = std::size_t(std::clamp(a.y, 0.0f, 31.0f));
                 return vec4(ms_lut[j * 32u + i] * 100.0f, 0.0f); },
             ms_texels, 3, 1.0f, 1e-4});
        // The field's source: altitudes and view cosines with psi = b.xyz and the vertical
        // moment a.z psi (0: all from the horizon; 1/3: isotropic; 1: all from the vertical).
        std::vector<std::pair<vec4, vec4>> sources;
        for (float h : {0.0f, 1500.0f, 60000.0f})
            for (float mu : {-1.0f, -0.2f, 0.0f, 0.6f, 1.0f})
                for (float share : {0.0f, 1.0f / 3.0f, 1.0f}) sources.push_back({vec4(h, mu, share, 0.0f), vec4(0.02f, 0.03f, 0.05f, 0.0f)});
        add({"cm_atmosphere_multiple_scattering_source",
             "vec4(cm_atmosphere_multiple_scattering_source(cm_earth_atmosphere(), a.x, b.xyz, b.xyz * a.z, a.y) * 1e6, 0.0)",
             [earth](vec4 a, vec4 b) {
                 return vec4(cm::atmosphere_multiple_scattering_source(earth, a.x, vec3(b), vec3(b) * a.z, a.y) * 1e6f, 0.0f); },
             sources, 3, 1.0f, 1e-5});
        std::vector<std::pair<vec4, vec4>> ms_uv;
        for (float h : {-10.0f, 0.0f, 1000.0f, 30000.0f, 60000.0f, 70000.0f})
            for (float mu_s : {-1.0f, -0.5f, 0.0f, 0.3f, 1.0f}) ms_uv.push_back({vec4(h, mu_s, 0.0f, 0.0f), vec4(32.0f, 32.0f, 0.0f, 0.0f)});
        add({"cm_atmosphere_multiple_scattering_lut_uv",
             "vec4(cm_atmosphere_multiple_scattering_lut_uv(cm_earth_atmosphere(), a.x, a.y, b.xy), 0.0, 0.0)",
             [earth](vec4 a, vec4 b) { return vec4(cm::atmosphere_multiple_scattering_lut_uv(earth, a.x, a.y, vec2(b)), 0.0f, 0.0f); },
             ms_uv, 2, 1.0f, 1e-5});
        add({"cm_atmosphere_multiple_scattering_lut_altitude_mu",
             "vec4(cm_atmosphere_multiple_scattering_lut_altitude_mu(cm_earth_atmosphere(), a.xy, b.xy) * vec2(1e-4, 1.0), 0.0, 0.0)",
             [earth](vec4 a, vec4 b) { return vec4(cm::atmosphere_multiple_scattering_lut_altitude_mu(earth, vec2(a), vec2(b)) * vec2(1e-4f, 1.0f), 0.0f, 0.0f); },
             texels, 2, 1.0f, 1e-4});
        // The sky and the aerial perspective with the test's table (cm_test_atmosphere_table,
        // 8 x 6 texels, 5 ground texels): a = (view direction, camera altitude), b = (sun
        // direction, distance). Views up, down (the ground), along the horizon toward and away
        // from the sun and a few degrees off it; suns at the zenith, low, at the horizon and
        // below it (twilight, night); cameras on the ground, in the air, at the top of the air
        // and above it; distances from none to beyond the air. 12 view and 12 sun steps. The sun
        // on the horizon is off the horizontal views' plane: seen from the ground along a level
        // view exactly away from it, every step's sun ray grazes the ground at the camera (its
        // transmittance jumps between 0 and 1 by one rounding; HLSL's compiler rounds otherwise).
        const auto unit = [](float x, float y, float z) { return glm::normalize(vec3(x, y, z)); };
        const std::vector<vec3> sky_views = {unit(0, 1, 0), unit(0, -1, 0), unit(1, 0, 0), unit(-1, 0, 0), unit(0.3f, 0.035f, 0.95f),
                                             unit(0.9f, -0.09f, 0.4f), unit(-0.5f, 0.17f, -0.85f)};
        const std::vector<vec3> sky_suns = {unit(0, 1, 0), unit(0.87f, 0.5f, 0), unit(1, 0.035f, 0), unit(0.8f, 0, 0.6f), unit(1, -0.035f, 0),
                                            unit(0, -1, 0)};
        const std::shared_ptr<const cpp_test_sky_table> sky_table = std::make_shared<cpp_test_sky_table>(make_cpp_test_sky_table(8, 6, 5));
        std::vector<std::pair<vec4, vec4>> sky_rays, segments;
        for (const vec3& v : sky_views)
            for (const vec3& sun : sky_suns)
                for (float h : {0.0f, 1500.0f, 60000.0f, 70000.0f}) {
                    sky_rays.push_back({vec4(v, h), vec4(sun, 0.0f)});
                    if (h != 70000.0f)
                        for (float d : {0.0f, 2000.0f, 1e9f}) segments.push_back({vec4(v, h), vec4(sun, d)});
                }
        for (int parts : {0, 1, 2, 3}) {
            const std::string table = "CmAtmosphereTable(8, 6, " + std::to_string(parts) + ", 5)";
            add({"cm_atmosphere_inscatter",
                 "vec4(cm_atmosphere_inscatter(cm_earth_atmosphere(), " + table + ", a.w, a.xyz, b.xyz, b.w, 12, 12).radiance * 100.0, "
                 "cm_atmosphere_inscatter(cm_earth_atmosphere(), " + table + ", a.w, a.xyz, b.xyz, b.w, 12, 12).transmittance.z)",
                 [earth, sky_table, parts](vec4 a, vec4 b) {
                     const cm::atmosphere_segment<float> s =
                         cm::atmosphere_inscatter(earth, sky_table->view(8, 6, parts, 5), a.w, vec3(a), vec3(b), b.w, 12, 12);
                     return vec4(s.radiance * 100.0f, s.transmittance.z); },
                 segments, 4, 1e-2f, 1e-4});
        }
        for (const auto& [parts, ground] : std::vector<std::pair<int, int>>{{3, 5}, {3, 0}, {2, 1}, {0, 5}}) {
            const std::string table = "CmAtmosphereTable(8, 6, " + std::to_string(parts) + ", " + std::to_string(ground) + ")";
            add({"cm_atmosphere_sky_radiance",
                 "vec4(cm_atmosphere_sky_radiance(cm_earth_atmosphere(), " + table + ", a.w, a.xyz, b.xyz, 12, 12) * 100.0, 0.0)",
                 [earth, sky_table, parts = parts, ground = ground](vec4 a, vec4 b) {
                     return vec4(cm::atmosphere_sky_radiance(earth, sky_table->view(8, 6, parts, ground), a.w, vec3(a), vec3(b), 12, 12) * 100.0f,
                                 0.0f); },
                 sky_rays, 3, 1e-2f, 1e-4});
        }
        std::vector<std::pair<vec4, vec4>> cameras;
        for (float n : {1.4f, 2.8f, 16.0f})
            for (float t : {1.0f / 1000.0f, 1.0f / 100.0f, 1.0f})
                for (float iso : {100.0f, 800.0f}) cameras.push_back({vec4(n, t, iso, n * 1000.0f), vec4(0)});
        add({"cm_ev100_from_camera",
             "vec4(cm_ev100_from_camera(a.x, a.y, a.z), cm_ev100_from_luminance(a.w), cm_exposure_from_ev100(cm_ev100_from_camera(a.x, a.y, a.z)) * 1e4, 0.0)",
             [](vec4 a, vec4) { return vec4(cm::ev100_from_camera(a.x, a.y, a.z), cm::ev100_from_luminance(a.w),
                                            cm::exposure_from_ev100(cm::ev100_from_camera(a.x, a.y, a.z)) * 1e4f, 0.0f); },
             cameras, 3, 1.0f, 1e-5});
        add({"cm_ev100_from_luminance", "vec4(cm_ev100_from_luminance(a.w))",
             [](vec4 a, vec4) { return vec4(cm::ev100_from_luminance(a.w)); }, cameras, 1, 1.0f, 1e-5});
        add({"cm_exposure_from_ev100", "vec4(cm_exposure_from_ev100(a.x))",
             [](vec4 a, vec4) { return vec4(cm::exposure_from_ev100(a.x)); }, cameras, 1, 1e-3f, 1e-5});
    }
    return cs;
}

// Cases compiled with configuration macros set (not their defaults): the compile-time
// octave count and cone sample count against the C++ forms they stand for.
const char* const config_defines = "#define CM_MS_OCTAVES 5\n#define CM_CONE_SAMPLES 4\n";
std::vector<parity_case> make_config_cases() {
    std::vector<parity_case> cs;
    std::vector<std::pair<vec4, vec4>> in;
    for (float t : {0.0f, 0.1f, 1.0f, 5.0f, 30.0f})
        for (float mu : {-1.0f, 0.0f, 0.7f, 1.0f})
            for (float g : {0.0f, 0.8f, 0.9999f}) in.push_back({vec4(t, mu, g, 0.0f), vec4(0.5f, 0.5f, 0.5f, 0.0f)});
    cs.push_back({"cm_multiple_scattering [CM_MS_OCTAVES 5]", "vec4(cm_multiple_scattering(a.x, a.y, a.z, b.x, b.y, b.z), cm_multiple_scattering_with(a.x, a.y, b.x, b.y, b.z), 0.0, 0.0)",
                  [](vec4 a, vec4 b) { return vec4(cm::multiple_scattering<5>(a.x, a.y, a.z, b.x, b.y, b.z), cm::multiple_scattering_with<5>(a.x, a.y, b.x, b.y, b.z, cpp_test_phase), 0.0f, 0.0f); },
                  in, 2, 1e-30f});
    // CM_CONE_SAMPLES 4 replaces the config's sample_count (6 here) everywhere.
    std::vector<std::pair<vec4, vec4>> cone;
    for (int di = 0; di < 4; ++di)
        for (float far : {800.0f, 0.0f}) cone.push_back({vec4(10.0f, -4.0f, 7.0f, 0.0f), vec4(float(di), 0.0f, far, 6.0f)});
    cs.push_back({"cm_cone_optical_depth [CM_CONE_SAMPLES 4]", "vec4(cm_cone_optical_depth(a.xyz, cm_test_dir(int(b.x)), CmConeLightConfig(int(b.w), 50.0, 0.4, b.z, 100.0)))",
                  [](vec4 a, vec4 b) {
                      const vec3 dirs[] = {vec3(0, 1, 0), vec3(0, 0, -1), glm::normalize(vec3(1, 2, 3)), glm::normalize(vec3(-0.3f, 0.1f, -0.9f))};
                      return vec4(cm::cone_optical_depth(vec3(a), dirs[int(b.x)], cm::cone_light_config<float>{4, 50.0f, 0.4f, b.z, 100.0f}, cpp_test_extinction)); },
                  cone, 1, 1e-3f});
    return cs;
}

const char* const glsl_directions = R"(
vec3 cm_test_dir(int k) {
    if (k == 0) return vec3(0.0, 1.0, 0.0);
    if (k == 1) return vec3(0.0, 0.0, -1.0);
    if (k == 2) return normalize(vec3(1.0, 2.0, 3.0));
    return normalize(vec3(-0.3, 0.1, -0.9));
}
)";

std::string shader_source(const std::string& defines, const std::vector<parity_case>& cases) {
    std::string error;
    const std::string lib = cm::glsl_source("cloudmath", &error);
    std::ostringstream s;
    s << "#version 430 core\nlayout(local_size_x = 64) in;\n"
      << "layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };\n"
      << "layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };\n"
      << "uniform int u_case;\n"
      << defines << glsl_prelude << lib << glsl_after << glsl_directions << "vec4 cm_test_case(int c, vec4 a, vec4 b) {\n";
    for (std::size_t i = 0; i < cases.size(); ++i) s << "    if (c == " << i << ") return " << cases[i].glsl << ";\n";
    s << "    return vec4(0.0);\n}\n"
      << "void main() {\n    uint i = gl_GlobalInvocationID.x;\n    uint n = uint(inputs.length()) / 2u;\n"
      << "    if (i >= n) return;\n    outputs[i] = cm_test_case(u_case, inputs[2u * i], inputs[2u * i + 1u]);\n}\n";
    return s.str();
}

bool finite(float x) { return std::isfinite(x); }

bool fuzz_mode = false;  // --fuzz: only finiteness is compared (see fuzzed())
std::string language = "GLSL";  // --language: whose twins the programs hold (for the messages)

struct row {
    std::string function;
    std::size_t evaluations = 0;
    double worst = 0;
    std::string worst_at;
    int nonfinite = 0;
    double budget = 1e-5;
};

// Runs one case on the current program and folds its errors into the row of its function.
bool evaluate(cm_gl::compute_context& gl, const parity_case& pc, int case_id, std::vector<row>& rows) {
    std::vector<std::array<float, 4>> in;
    for (const auto& ab : pc.inputs) {
        in.push_back({ab.first.x, ab.first.y, ab.first.z, ab.first.w});
        in.push_back({ab.second.x, ab.second.y, ab.second.z, ab.second.w});
    }
    const std::vector<std::array<float, 4>> out = gl.run(in, case_id);
    if (out.size() < pc.inputs.size()) {
        std::printf("FAILED: running case %d (%s): %s\n", case_id, pc.function.c_str(), gl.last_error().c_str());
        return false;
    }
    auto it = std::find_if(rows.begin(), rows.end(), [&](const row& r) { return r.function == pc.function; });
    if (it == rows.end()) {
        rows.push_back(row{pc.function, 0, 0.0, "", 0, pc.budget});
        it = rows.end() - 1;
    }
    it->budget = std::max(it->budget, pc.budget);
    for (std::size_t k = 0; k < pc.inputs.size(); ++k) {
        const vec4 want = pc.cpp(pc.inputs[k].first, pc.inputs[k].second);
        for (int j = 0; j < pc.components; ++j) {
            const float got = out[k][std::size_t(j)];
            ++it->evaluations;
            if (finite(want[j]) && !finite(got)) {
                if (it->nonfinite++ == 0) {
                    char buf[256];
                    std::snprintf(buf, sizeof buf, "a=(%g,%g,%g,%g) b=(%g,%g,%g,%g) [%d]: %s %g, C++ %.9g", pc.inputs[k].first.x,
                                  pc.inputs[k].first.y, pc.inputs[k].first.z, pc.inputs[k].first.w, pc.inputs[k].second.x,
                                  pc.inputs[k].second.y, pc.inputs[k].second.z, pc.inputs[k].second.w, j, language.c_str(), double(got),
                                  double(want[j]));
                    it->worst_at = buf;
                }
                continue;
            }
            if (fuzz_mode) continue;
            const double err = std::fabs(double(got) - double(want[j])) / std::max(std::fabs(double(want[j])), double(pc.floor));
            if (err > it->worst) {
                it->worst = err;
                char buf[256];
                std::snprintf(buf, sizeof buf, "a=(%g,%g,%g,%g) b=(%g,%g,%g,%g) [%d]: %.9g vs %.9g", pc.inputs[k].first.x, pc.inputs[k].first.y,
                              pc.inputs[k].first.z, pc.inputs[k].first.w, pc.inputs[k].second.x, pc.inputs[k].second.y, pc.inputs[k].second.z,
                              pc.inputs[k].second.w, j, double(got), double(want[j]));
                it->worst_at = buf;
            }
        }
    }
    return true;
}

// --fuzz N: each case's inputs, N times over with every component scaled by 10^U(-3, 3) or
// 10^U(-38, 38) (signs flipped at random) or replaced by 0, -0, +-FLT_MIN, +-denormal or
// +-FLT_MAX: finite inputs inside and far outside each function's domain. A failure is a
// GLSL result that is NaN or Inf where the C++ twin's is finite (the values are not
// compared: outside the domain only finiteness is promised). Cases that pass an input
// through int() or uint() (sample counts, octaves, hashes) keep their inputs: a fuzzed loop
// count would only measure the driver's patience.
std::vector<parity_case> fuzzed(const std::vector<parity_case>& cases, int n, std::uint32_t seed) {
    std::vector<parity_case> out;
    std::uint32_t state = seed;
    const auto next = [&state]() {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) * (1.0f / 16777216.0f);
    };
    const float specials[] = {0.0f, -0.0f, std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(),
                              std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                              std::numeric_limits<float>::max(), -std::numeric_limits<float>::max()};
    const auto fuzz = [&](float x) {
        const float r = next();
        if (r < 0.1f) return specials[std::min(7, int(next() * 8.0f))];
        const float sign = next() < 0.25f ? -1.0f : 1.0f;
        const float base = x != 0.0f ? x : 1.0f;
        const float exponent = r < 0.55f ? next() * 6.0f - 3.0f : next() * 76.0f - 38.0f;
        const float v = base * sign * std::pow(10.0f, exponent);
        return std::isfinite(v) ? v : std::copysign(std::numeric_limits<float>::max(), v);
    };
    for (const parity_case& pc : cases) {
        parity_case f = pc;
        if (pc.glsl.find("int(") == std::string::npos) {
            f.inputs.clear();
            for (int k = 0; k < n; ++k)
                for (const auto& ab : pc.inputs) {
                    vec4 a = ab.first, b = ab.second;
                    for (int j = 0; j < 4; ++j) {
                        a[j] = fuzz(a[j]);
                        b[j] = fuzz(b[j]);
                    }
                    f.inputs.push_back({a, b});
                }
        }
        out.push_back(std::move(f));
    }
    return out;
}

// The shaders that run the cases: the main cases, then the config cases (compiled with
// config_defines), each split into programs of at most 64 cases. Each case is one
// `if (c == i) return` of cm_test_case, and Mesa's llvmpipe nests those ifs and mis-runs
// control flow nested past 80 levels (gallivm's LP_MAX_TGSI_NESTING): the 81st case
// returned 0 for every input.
struct program {
    std::string defines;
    bool config = false;
    std::vector<parity_case> cases;
};
constexpr std::size_t max_cases_per_shader = 64;
std::vector<program> make_programs(int fuzz_rounds) {
    const auto prepare = [fuzz_rounds](std::vector<parity_case> cases) {
        return fuzz_rounds > 0 ? fuzzed(cases, fuzz_rounds, 12345u) : cases;
    };
    std::vector<program> programs;
    for (const program& all : {program{"", false, prepare(make_cases())}, program{config_defines, true, prepare(make_config_cases())}})
        for (std::size_t first = 0; first < all.cases.size(); first += max_cases_per_shader) {
            const std::size_t last = std::min(all.cases.size(), first + max_cases_per_shader);
            programs.push_back({all.defines, all.config, std::vector<parity_case>(all.cases.begin() + std::ptrdiff_t(first),
                                                                                  all.cases.begin() + std::ptrdiff_t(last))});
        }
    return programs;
}

void json_string(std::ostream& o, const std::string& text) {
    o << '"';
    for (const char ch : text) {
        const auto u = static_cast<unsigned char>(ch);
        if (ch == '"' || ch == '\\') o << '\\' << ch;
        else if (ch == '\n') o << "\\n";
        else if (ch == '\t') o << "\\t";
        else if (u < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(u));
            o << buf;
        } else o << ch;
    }
    o << '"';
}
void json_number(std::ostream& o, double x) {  // %.9g round-trips a float; JSON has no Inf/NaN
    if (!std::isfinite(x)) {
        o << "null";
        return;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    o << buf;
}

// --dump-cases: everything a generator of twins in another language needs to build the
// programs that --program runs, and the C++ results to check them by itself. "program" is
// the index into make_programs() (main programs first), "index" the case's u_case there.
std::string dump_cases(const std::vector<program>& programs) {
    std::ostringstream o;
    o << "{\n  \"prelude\": ";
    json_string(o, glsl_prelude);
    o << ",\n  \"after\": ";
    json_string(o, std::string(glsl_after) + glsl_directions);
    o << ",\n  \"config_defines\": ";
    json_string(o, config_defines);
    o << ",\n  \"max_cases_per_program\": " << max_cases_per_shader << ",\n  \"programs\": [";
    for (std::size_t p = 0; p < programs.size(); ++p)
        o << (p == 0 ? "" : ", ") << "{\"config\": " << (programs[p].config ? "true" : "false") << ", \"cases\": " << programs[p].cases.size() << "}";
    o << "],\n  \"cases\": [";
    const char* case_separator = "\n";
    for (std::size_t p = 0; p < programs.size(); ++p)
        for (std::size_t c = 0; c < programs[p].cases.size(); ++c) {
            const parity_case& pc = programs[p].cases[c];
            o << case_separator << "    {\"function\": ";
            json_string(o, pc.function);
            o << ", \"glsl\": ";
            json_string(o, pc.glsl);
            o << ", \"components\": " << pc.components << ", \"floor\": ";
            json_number(o, double(pc.floor));
            o << ", \"budget\": ";
            json_number(o, pc.budget);
            o << ", \"config\": " << (programs[p].config ? "true" : "false") << ", \"program\": " << p << ", \"index\": " << c
              << ",\n     \"inputs\": [";
            for (std::size_t k = 0; k < pc.inputs.size(); ++k) {
                o << (k == 0 ? "[" : ", [");
                for (int j = 0; j < 8; ++j) {
                    if (j > 0) o << ',';
                    json_number(o, double(j < 4 ? pc.inputs[k].first[j] : pc.inputs[k].second[j - 4]));
                }
                o << ']';
            }
            o << "],\n     \"expected\": [";
            for (std::size_t k = 0; k < pc.inputs.size(); ++k) {
                const vec4 want = pc.cpp(pc.inputs[k].first, pc.inputs[k].second);
                o << (k == 0 ? "[" : ", [");
                for (int j = 0; j < 4; ++j) {
                    if (j > 0) o << ',';
                    json_number(o, double(want[j]));
                }
                o << ']';
            }
            o << "]}";
            case_separator = ",\n";
        }
    o << "\n  ]\n}\n";
    return o.str();
}

bool read_file(const std::string& path, std::string& text) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) return false;
    char buf[65536];
    std::size_t n = 0;
    text.clear();
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
    const bool ok = std::ferror(f) == 0;
    std::fclose(f);
    return ok;
}

// How the programs were made, for the markdown: the GLSL twins' own text is unchanged.
std::string measured_how(const std::string& renderer, const std::string& version) {
    if (language == "GLSL")
        return "Measured by `test_glsl_parity --markdown` (ctest `glsl.parity`; regenerate with `bash scripts/glsl-parity.sh`) on **" +
               renderer + "**, OpenGL " + version + ".";
    if (language == "HLSL")
        return "Measured by `test_glsl_parity --language HLSL --markdown` on programs made by tests/hlsl/hlsl_parity.cmake (ctest "
               "`hlsl.parity`; regenerate with `bash scripts/hlsl-parity.sh`): the shipped HLSL twins (include/cloudmath/hlsl, with "
               "the test's own code translated by tests/shader_parity/make_parity_shader.mjs) compiled by glslang's HLSL front "
               "end to SPIR-V, validated with spirv-val, converted to GLSL 4.30 by spirv-cross and run on **" +
               renderer + "**, OpenGL " + version + ".";
    return "Measured by `test_glsl_parity --language " + language + " --markdown` on GLSL compute programs made from the " +
           language + " twins, run on **" + renderer + "**, OpenGL " + version + ".";
}

}  // namespace

int main(int argc, char** argv) {
    std::string markdown, dump;
    std::vector<std::string> program_files[2];  // [0] --program, [1] --config-program
    int fuzz_rounds = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--markdown") == 0 && i + 1 < argc) markdown = argv[++i];
        else if (std::strcmp(argv[i], "--fuzz") == 0 && i + 1 < argc) {
            fuzz_rounds = std::max(1, std::atoi(argv[++i]));
            fuzz_mode = true;
        }
        else if (std::strcmp(argv[i], "--dump-cases") == 0 && i + 1 < argc) dump = argv[++i];
        else if (std::strcmp(argv[i], "--program") == 0 && i + 1 < argc) program_files[0].push_back(argv[++i]);
        else if (std::strcmp(argv[i], "--config-program") == 0 && i + 1 < argc) program_files[1].push_back(argv[++i]);
        else if (std::strcmp(argv[i], "--language") == 0 && i + 1 < argc) language = argv[++i];
        else {
            std::fprintf(stderr,
                         "usage: %s [--markdown FILE] [--fuzz N] [--dump-cases FILE]\n"
                         "       [--program MAIN.comp]... [--config-program CONFIG.comp]... [--language NAME]\n",
                         argv[0]);
            return 2;
        }
    }
    const std::vector<program> programs = make_programs(fuzz_rounds);
    if (!dump.empty()) {
        const std::string error = cloudmath::tools::write_file_atomically(dump, dump_cases(programs));
        if (!error.empty()) {
            std::fprintf(stderr, "test_glsl_parity: %s\n", error.c_str());
            return 1;
        }
        std::printf("wrote %zu programs of cases to %s\n", programs.size(), dump.c_str());
        return 0;
    }
    // Given programs replace the GLSL twins' shaders one for one: both kinds, all of them.
    std::vector<std::string> sources, source_names;
    const bool external = !program_files[0].empty() || !program_files[1].empty();
    if (external) {
        std::size_t used[2] = {0, 0};
        for (const program& prog : programs) {
            const std::vector<std::string>& files = program_files[prog.config ? 1 : 0];
            std::size_t& next = used[prog.config ? 1 : 0];
            sources.emplace_back();
            source_names.push_back(next < files.size() ? files[next] : "");
            if (next < files.size() && !read_file(files[next], sources.back())) {
                std::fprintf(stderr, "test_glsl_parity: cannot read '%s'\n", files[next].c_str());
                return 2;
            }
            ++next;
        }
        for (int k = 0; k < 2; ++k)
            if (used[k] != program_files[k].size()) {
                std::fprintf(stderr, "test_glsl_parity: %zu %s given, but the cases make %zu programs (at most %zu cases each; "
                             "see the \"program\" field of --dump-cases)\n", program_files[k].size(),
                             k == 0 ? "--program files" : "--config-program files", used[k], max_cases_per_shader);
                return 2;
            }
    }

    std::string why;
    std::unique_ptr<cm_gl::compute_context> gl = cm_gl::compute_context::create(why);
    if (!gl) return cm_gl::no_context_exit_code(why);
    std::printf("%s parity on %s, OpenGL %s\n", language.c_str(), gl->renderer().c_str(), gl->version().c_str());

    std::vector<row> rows;
    std::size_t case_count = 0;
    bool ok = true;
    for (std::size_t p = 0; p < programs.size(); ++p) {
        const program& prog = programs[p];
        std::string log;
        if (!gl->compile(external ? sources[p] : shader_source(prog.defines, prog.cases), log)) {
            if (external)
                std::printf("FAILED: the parity shader '%s' does not compile:\n%s\n", source_names[p].c_str(), log.c_str());
            else
                std::printf("FAILED: the parity shader does not compile:\n%s\n", log.c_str());
            return 1;
        }
        for (std::size_t c = 0; c < prog.cases.size(); ++c) {
            if (!evaluate(*gl, prog.cases[c], int(c), rows)) return 1;
            ++case_count;
        }
    }

    if (fuzz_mode) std::printf("Fuzz: %d rounds of each case's inputs, scaled over 76 decades and signs, and special values; "
                               "a failure is a NaN/Inf where C++ is finite (max error not compared)\n", fuzz_rounds);
    const std::string worst_heading = "worst case (" + language + " vs C++)";
    std::printf("%-42s %8s %12s %9s %5s  %s\n", "function", "values", "max error", "budget", "NaN", worst_heading.c_str());
    for (const row& r : rows) {
        const bool pass = (fuzz_mode || r.worst <= r.budget) && r.nonfinite == 0;
        ok = ok && pass;
        std::printf("%-42s %8zu %12.3g %9.0e %5d  %s%s\n", r.function.c_str(), r.evaluations, r.worst, r.budget, r.nonfinite,
                    pass ? "" : "FAIL ", r.worst_at.c_str());
    }
    if (!markdown.empty()) {
        std::ostringstream md;
        md << "# " << language << " parity: " << language << " twins against the C++ float functions\n\n"
           << measured_how(gl->renderer(), gl->version()) << "\n\n"
           << "Error: |" << language << " - C++| / max(|C++|, floor) per output component, over grids that include the hard cases of the C++ tests "
              "(|g| -> 1, mu = +-1, sigma_t = 0 to 1e4, Earth-radius cameras at 1.8 m to 400 km, tangent rays, degenerate ranges).\n\n"
           << "| function | values | max error | budget | NaN/Inf |\n|---|---|---|---|---|\n";
        for (const row& r : rows) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.2g", r.worst);
            md << "| `" << r.function << "` | " << r.evaluations << " | " << buf << " | " << r.budget << " | " << r.nonfinite << " |\n";
        }
        // Atomically (tools/common/atomic_file.hpp): a failed write leaves the old table.
        const std::string error = cloudmath::tools::write_file_atomically(markdown, md.str());
        if (!error.empty()) {
            std::fprintf(stderr, "test_glsl_parity: %s\n", error.c_str());
            return 1;
        }
    }
    std::printf("%s: %zu functions, %zu cases\n", ok ? "PASSED" : "FAILED", rows.size(), case_count);
    return ok ? 0 : 1;
}
