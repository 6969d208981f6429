// Implementation notes: the context comes from tools/egl (egl_headless.hpp, shared with the
// cloud renderer): EGL with no window system, so the same code runs on a headless CI box (Mesa
// llvmpipe) and on a GPU server (NVIDIA through EGL devices). GL entry points are tools/egl's
// table (gl_functions.hpp, shared with the renderer and the peer bench), loaded with
// cloudmath_egl::gl_proc (eglGetProcAddress), so no loader library and no link-time GL symbols
// are needed.
#include "gl_compute.hpp"

#include "egl_headless.hpp"
#include "gl_functions.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace cm_gl {

using gl_api = cloudmath_egl::gl_functions;  // tools/egl's table of GL entry points

struct compute_context::state {
    std::unique_ptr<cloudmath_egl::headless_context> egl;  // display reference, context
    gl_api gl;
    GLuint program = 0;
    GLint local_x = 0;  // GL_COMPUTE_WORK_GROUP_SIZE.x of `program`
    GLuint buffers[2] = {0, 0};
    GLint max_groups_x = 0;
    GLint64 max_ssbo_bytes = 0;

    // Creates the context (on the one platform `only`, unless any) and checks that it can do
    // what run() needs. Returns nullptr with the reason in `why`; partial state is released
    // by ~state.
    static std::unique_ptr<state> open(cloudmath_egl::platform only, std::string& why);

    state() = default;
    state(const state&) = delete;
    state& operator=(const state&) = delete;

    // Several instances may live on one thread, so every public call re-selects its own
    // context (cheap when it is already current).
    bool make_current() const { return egl->make_current(); }

    // All pending GL errors as text, empty when there are none. Bounded because a lost
    // context may report the same error forever.
    std::string gl_errors(const char* phase) const { return gl.errors(phase); }

    void drop_program() {
        if (program != 0) {
            gl.UseProgram(0);
            gl.DeleteProgram(program);
        }
        program = 0;
        local_x = 0;
    }

    // GL objects go while the context is current; `egl` then destroys the context.
    ~state() {
        // No context or no functions (loading failed): no GL objects either.
        if (egl != nullptr && gl.DeleteBuffers != nullptr && make_current()) {
            drop_program();
            gl.DeleteBuffers(2, buffers);
        }
    }
};

std::unique_ptr<compute_context::state> compute_context::state::open(
    cloudmath_egl::platform only, std::string& why) {
    auto s = std::make_unique<state>();
    // 4.3 core is the first version with compute shaders and SSBOs; drivers return the
    // newest version compatible with it (4.5 or 4.6 in practice).
    s->egl = cloudmath_egl::headless_context::open(4, 3, only, why);
    if (s->egl == nullptr) return nullptr;
    const std::string missing = s->gl.load(cloudmath_egl::gl_proc, true);
    if (!missing.empty()) {
        why = "GL entry point " + missing + " not found";
        return nullptr;
    }
    s->gl.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &s->max_groups_x);
    s->gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &s->max_ssbo_bytes);
    s->gl.GenBuffers(2, s->buffers);
    why = s->gl_errors("context setup");
    if (!why.empty()) return nullptr;
    return s;
}

compute_context::compute_context(std::unique_ptr<state> s) : s_(std::move(s)) {}
compute_context::~compute_context() = default;

std::unique_ptr<compute_context> compute_context::create(std::string& why) {
    why.clear();
    const char* env = std::getenv("CLOUDMATH_GL_PLATFORM");
    const std::string name = env != nullptr ? env : "";
    using cloudmath_egl::platform;
    platform only = platform::any;
    if (name == "surfaceless") only = platform::surfaceless;
    else if (name == "device") only = platform::device;
    else if (name == "default") only = platform::default_display;
    else if (!name.empty()) {
        why = "CLOUDMATH_GL_PLATFORM=" + name + " is not surfaceless, device or default";
        return nullptr;
    }
    auto s = state::open(only, why);
    if (s == nullptr) {
        why = "no headless OpenGL 4.3 context: " + why;
        return nullptr;
    }
    return std::unique_ptr<compute_context>(new compute_context(std::move(s)));
}

std::string compute_context::renderer() const {
    if (!s_->make_current()) return {};
    const GLubyte* text = s_->gl.GetString(GL_RENDERER);
    return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

std::string compute_context::version() const {
    if (!s_->make_current()) return {};
    const GLubyte* text = s_->gl.GetString(GL_VERSION);
    return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

bool compute_context::compile(const std::string& source, std::string& log) {
    log.clear();
    state& s = *s_;
    if (!s.make_current()) {
        log = "eglMakeCurrent failed (" + cloudmath_egl::egl_error() + ")";
        return false;
    }
    const gl_api& gl = s.gl;
    s.gl_errors("");  // errors from earlier calls must not be blamed on this compile
    s.drop_program();

    const GLuint shader = gl.compile(GL_COMPUTE_SHADER, source, "compute shader", log);
    if (shader == 0) return false;
    const GLuint program = gl.link(&shader, 1, "compute program", log);
    if (program == 0) return false;

    // run() maps invocation i to element i along x only, so a 2D/3D local size would
    // silently run extra invocations on the same elements: refuse it.
    GLint size[3] = {0, 0, 0};
    gl.GetProgramiv(program, GL_COMPUTE_WORK_GROUP_SIZE, size);
    if (size[0] < 1 || size[1] != 1 || size[2] != 1) {
        gl.DeleteProgram(program);
        log += "local size must be (N, 1, 1); write layout(local_size_x = N) in;";
        return false;
    }
    gl.UseProgram(program);
    s.program = program;
    s.local_x = size[0];
    const std::string errors = s.gl_errors("compile/link");
    if (!errors.empty()) {
        s.drop_program();
        log += errors;
        return false;
    }
    return true;
}

std::vector<std::array<float, 4>> compute_context::run(
    const std::vector<std::array<float, 4>>& inputs, int case_id) {
    using vec4 = std::array<float, 4>;
    static_assert(sizeof(vec4) == 4 * sizeof(float), "vec4 must match std430 vec4 layout");
    error_.clear();
    state& s = *s_;
    const gl_api& gl = s.gl;
    auto fail = [&](std::string message) {
        error_ = std::move(message);
        return std::vector<vec4>();
    };
    if (!s.make_current())
        return fail("eglMakeCurrent failed (" + cloudmath_egl::egl_error() + ")");
    if (s.program == 0) return fail("no program: compile() failed or was not called");
    if (inputs.empty()) return {};
    std::string errors = s.gl_errors("earlier calls (before run)");
    if (!errors.empty()) return fail(errors);

    const std::size_t n = inputs.size();
    const std::size_t local = static_cast<std::size_t>(s.local_x);
    const std::size_t groups = (n + local - 1) / local;
    const std::size_t padded = groups * local;
    const std::size_t bytes = padded * sizeof(vec4);
    if (groups > static_cast<std::size_t>(s.max_groups_x))
        return fail(std::to_string(n) + " inputs need " + std::to_string(groups) +
                    " work groups, driver maximum is " + std::to_string(s.max_groups_x));
    if (bytes > static_cast<std::size_t>(s.max_ssbo_bytes))
        return fail(std::to_string(bytes) + " bytes per buffer, driver maximum is " +
                    std::to_string(s.max_ssbo_bytes));

    // Inputs padded with zeros, then the same staging storage zeroed for the outputs, so
    // a shader that writes nothing for some element is seen as 0, not as stale memory.
    std::vector<vec4> staging(padded, vec4{0.f, 0.f, 0.f, 0.f});
    std::copy(inputs.begin(), inputs.end(), staging.begin());
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, s.buffers[0]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), staging.data(),
                  GL_STATIC_DRAW);
    std::fill(staging.begin(), staging.end(), vec4{0.f, 0.f, 0.f, 0.f});
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, s.buffers[1]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), staging.data(),
                  GL_STREAM_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, s.buffers[0]);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, s.buffers[1]);
    if (!(errors = s.gl_errors("buffer upload")).empty()) return fail(errors);

    // -1 when the program does not declare u_case or the compiler removed it as unused.
    const GLint where = gl.GetUniformLocation(s.program, "u_case");
    if (where >= 0) gl.Uniform1i(where, case_id);
    if (!(errors = s.gl_errors("setting u_case")).empty()) return fail(errors);

    gl.DispatchCompute(static_cast<GLuint>(groups), 1, 1);
    // Shader writes must be visible to glGetBufferSubData, which is a buffer update.
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!(errors = s.gl_errors("dispatch")).empty()) return fail(errors);

    std::vector<vec4> out(n);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, s.buffers[1]);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(n * sizeof(vec4)),
                        out.data());  // waits for the dispatch to finish
    if (!(errors = s.gl_errors("readback")).empty()) return fail(errors);
    return out;
}

int no_context_exit_code(const std::string& why) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::strcmp(ci, "true") == 0) {
        std::fprintf(stderr, "FAILED: no OpenGL context, and CI=true requires the GL tests: %s\n",
                     why.c_str());
        return 1;
    }
    std::printf("SKIPPED: %s\n", why.c_str());
    std::fflush(stdout);
    return 77;
}

}  // namespace cm_gl
