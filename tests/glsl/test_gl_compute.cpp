// Self-test of the headless compute runner that the GLSL parity tests stand on: a context
// comes up, a bad shader is refused with a log, and a known shader gives known numbers for
// every element (including the zero padding past a partial last work group, and the u_case
// uniform being present or absent).
// Exit codes: 0 pass, 1 fail, 77 skipped (no GL context and CI is not "true").
#include "gl_compute.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

namespace {

using vec4 = std::array<float, 4>;
using clock_type = std::chrono::steady_clock;

double ms_since(clock_type::time_point start) {
    return std::chrono::duration<double, std::milli>(clock_type::now() - start).count();
}

// local_size_x = 64 with 1000 inputs leaves a partial last group: the runner must pad.
const char* const k_shader = R"(#version 430 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { vec4 v_in[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 v_out[]; };
uniform int u_case;
void main() {
    uint i = gl_GlobalInvocationID.x;
    vec4 a = v_in[i];
    v_out[i] = vec4(a.x * 2.0, a.y + float(u_case), sqrt(a.z), exp(-a.w));
}
)";

// No u_case: run() must not try to set it.
const char* const k_swizzle_shader = R"(#version 430 core
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Inputs { vec4 v_in[]; };
layout(std430, binding = 1) writeonly buffer Outputs { vec4 v_out[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    v_out[i] = v_in[i].wzyx;
}
)";

const char* const k_broken_shader = R"(#version 430 core
layout(local_size_x = 64) in;
void main() { undeclared_name = 1.0; }
)";

// Relative error against a double reference; a zero reference must be matched exactly.
double rel_error(float got, double ref) {
    if (ref == 0.0) return got == 0.f ? 0.0 : INFINITY;
    return std::fabs(static_cast<double>(got) - ref) / std::fabs(ref);
}

// Checks one run of k_shader; prints the first few mismatches. Returns the failure count.
int check_main_shader(const std::vector<vec4>& in, const std::vector<vec4>& out, int case_id) {
    // GLSL 4.30 allows 2.5 ULP for sqrt and (3 + 2|x|) ULP for exp; with |w| <= 2 that is
    // at most 7 ULP < 8.4e-7 relative, so 1e-6 holds on any conforming driver.
    const double tol = 1e-6;
    int failures = 0;
    double worst_sqrt = 0, worst_exp = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const vec4& a = in[i];
        const vec4& r = out[i];
        const double e_sqrt = rel_error(r[2], std::sqrt(static_cast<double>(a[2])));
        const double e_exp = rel_error(r[3], std::exp(-static_cast<double>(a[3])));
        worst_sqrt = std::max(worst_sqrt, e_sqrt);
        worst_exp = std::max(worst_exp, e_exp);
        // x * 2 and y + case are single correctly rounded operations on both sides: exact.
        const bool ok = r[0] == a[0] * 2.f && r[1] == a[1] + static_cast<float>(case_id) &&
                        e_sqrt <= tol && e_exp <= tol;
        if (!ok && ++failures <= 5)
            std::printf("  case %d, element %zu: in (%.9g %.9g %.9g %.9g) out (%.9g %.9g %.9g %.9g)\n",
                        case_id, i, static_cast<double>(a[0]), static_cast<double>(a[1]),
                        static_cast<double>(a[2]), static_cast<double>(a[3]),
                        static_cast<double>(r[0]), static_cast<double>(r[1]),
                        static_cast<double>(r[2]), static_cast<double>(r[3]));
    }
    std::printf("case %d: %zu elements, %d mismatches, worst relative error sqrt %.3g, exp %.3g\n",
                case_id, in.size(), failures, worst_sqrt, worst_exp);
    return failures;
}

}  // namespace

int main() {
    auto t0 = clock_type::now();
    std::string why;
    auto gl = cm_gl::compute_context::create(why);
    if (gl == nullptr) return cm_gl::no_context_exit_code(why);
    std::printf("context: %.1f ms\nGL_RENDERER: %s\nGL_VERSION: %s\n", ms_since(t0),
                gl->renderer().c_str(), gl->version().c_str());
    int failures = 0;

    // A shader that does not compile must be refused with a log, and run() must then fail
    // rather than reuse a previous program.
    std::string log;
    if (gl->compile(k_broken_shader, log) || log.empty()) {
        std::printf("FAIL: broken shader accepted or gave no log\n");
        ++failures;
    }
    if (!gl->run({vec4{1.f, 2.f, 3.f, 4.f}}, 0).empty() || gl->last_error().empty()) {
        std::printf("FAIL: run() without a program did not report an error\n");
        ++failures;
    }

    t0 = clock_type::now();
    if (!gl->compile(k_shader, log)) {
        std::printf("FAIL: compile:\n%s\n", log.c_str());
        return 1;
    }
    std::printf("compile: %.1f ms%s%s\n", ms_since(t0), log.empty() ? "" : ", log:\n",
                log.c_str());

    // Deterministic inputs from exact 24-bit fractions (independent of the standard library's
    // distributions), plus exact zeros for sqrt and exp every 100th element.
    std::mt19937 rng(12345u);
    auto u01 = [&rng] { return static_cast<float>(rng() >> 8) * 0x1p-24f; };
    std::vector<vec4> in(1000);
    for (std::size_t i = 0; i < in.size(); ++i) {
        const bool edge = i % 100 == 0;
        in[i] = {(u01() * 2.f - 1.f) * 1000.f, (u01() * 2.f - 1.f) * 100.f,
                 edge ? 0.f : u01() * 1e4f, edge ? 0.f : u01() * 4.f - 2.f};
    }
    for (int case_id : {0, 7, -3}) {
        t0 = clock_type::now();
        const std::vector<vec4> out = gl->run(in, case_id);
        const double run_ms = ms_since(t0);
        if (out.size() != in.size()) {
            std::printf("FAIL: run(case %d): %s\n", case_id, gl->last_error().c_str());
            return 1;
        }
        std::printf("run(case %d): %.2f ms\n", case_id, run_ms);
        failures += check_main_shader(in, out, case_id);
    }

    // A program without u_case, and a local size that does not divide the count either.
    if (!gl->compile(k_swizzle_shader, log)) {
        std::printf("FAIL: compile (swizzle):\n%s\n", log.c_str());
        return 1;
    }
    const std::vector<vec4> out = gl->run(in, 5);
    if (out.size() != in.size()) {
        std::printf("FAIL: run (swizzle): %s\n", gl->last_error().c_str());
        return 1;
    }
    for (std::size_t i = 0; i < in.size(); ++i) {
        const vec4 want{in[i][3], in[i][2], in[i][1], in[i][0]};
        if (out[i] != want && ++failures <= 5) std::printf("  swizzle mismatch at %zu\n", i);
    }

    std::printf("%s: %d failure(s)\n", failures == 0 ? "PASS" : "FAIL", failures);
    return failures == 0 ? 0 : 1;
}
