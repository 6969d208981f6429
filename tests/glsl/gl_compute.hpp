// Headless OpenGL compute runner for the GLSL parity tests: one EGL context with no window,
// one compute program at a time, vec4 in / vec4 out through two shader storage buffers.
// No GL or EGL header leaks out of here (and no GLM), so test files include only this.
//
// The context comes from tools/egl/egl_headless.hpp: Mesa's surfaceless platform, then each
// EGL device (NVIDIA), then the default display; the first with OpenGL 4.3+ core wins.
// The environment variable CLOUDMATH_GL_PLATFORM=surfaceless|device|default restricts the
// choice to that one (e.g. `device` to run on the GPU of a machine that also has Mesa). Any
// other non-empty value makes create() fail with a reason, which is how the skip/fail exit
// codes are tested by hand.
#ifndef CLOUDMATH_TESTS_GL_COMPUTE_HPP
#define CLOUDMATH_TESTS_GL_COMPUTE_HPP

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace cm_gl {

// One instance owns one EGL display reference, one context and its GL objects. Use it from
// one thread; several instances may coexist (each makes itself current when used).
class compute_context {
public:
    // Headless OpenGL 4.3+ core context (compute shaders + SSBOs). Returns nullptr and a
    // one-line reason in `why` on failure; never crashes or exits.
    static std::unique_ptr<compute_context> create(std::string& why);
    ~compute_context();
    compute_context(const compute_context&) = delete;
    compute_context& operator=(const compute_context&) = delete;

    std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version() const;   // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"

    // Compiles and links a compute shader from complete source text (the caller writes
    // #version and layout(local_size_x = N) in;). On failure `log` says which step failed,
    // with the driver's info log; on success it is empty. On success the program becomes current; on failure
    // there is no current program, so a later run() fails instead of running a stale one.
    bool compile(const std::string& source, std::string& log);

    // Runs the current program over inputs.size() invocations:
    //   binding 0: std430 buffer of vec4 inputs, binding 1: std430 buffer of vec4 outputs,
    //   uniform int u_case = case_id (set only if the program declares and uses it).
    // Dispatches ceil(n / local_size_x) groups. Both buffers are padded with zeros to the
    // dispatched count, so shaders need no bounds check (and .length() is that padded count).
    // Returns the first n outputs; on failure returns an empty vector and last_error() says
    // why (last_error() is empty after a successful run, including one with no inputs).
    std::vector<std::array<float, 4>> run(const std::vector<std::array<float, 4>>& inputs,
                                          int case_id);
    const std::string& last_error() const { return error_; }

private:
    struct state;
    explicit compute_context(std::unique_ptr<state> s);
    std::unique_ptr<state> s_;
    std::string error_;
};

// The rule every GL test follows when create() fails: outside CI the test is skipped (prints
// "SKIPPED: <why>", returns 77, ctest's SKIP_RETURN_CODE); when the environment variable CI
// is "true" the GL tests must really run, so it prints the reason and returns 1.
int no_context_exit_code(const std::string& why);

}  // namespace cm_gl

#endif
