// Loading and the error, compile and link helpers of the shared GL table (gl_functions.hpp).
#include "gl_functions.hpp"

#include <cstddef>
#include <cstdio>

namespace cloudmath_egl {
namespace {

const char* error_name(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: return nullptr;
    }
}

// A shader's or program's info log through the matching pair of getters.
template <class GetIv, class GetLog>
std::string info_log(GLuint object, GetIv get_iv, GetLog get_log) {
    GLint length = 0;
    get_iv(object, GL_INFO_LOG_LENGTH, &length);
    if (length <= 1) return "(empty log)";
    std::string text(static_cast<std::size_t>(length), '\0');
    GLsizei written = 0;
    get_log(object, length, &written, text.data());
    text.resize(static_cast<std::size_t>(written > 0 ? written : 0));
    return text;
}

}  // namespace

std::string gl_functions::load(proc_loader get, bool compute) {
#define CLOUDMATH_GL_LOAD(type, name)                         \
    name = reinterpret_cast<type>(get("gl" #name));            \
    if (name == nullptr) return "gl" #name;
    CLOUDMATH_GL_CORE_FUNCTIONS(CLOUDMATH_GL_LOAD)
    if (compute) {
        CLOUDMATH_GL_COMPUTE_FUNCTIONS(CLOUDMATH_GL_LOAD)
    }
#undef CLOUDMATH_GL_LOAD
    return {};
}

std::string gl_functions::errors(const char* where) const {
    std::string text;
    for (int i = 0; i < 8; ++i) {
        const GLenum e = GetError();
        if (e == GL_NO_ERROR) break;
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", e);
        const char* name = error_name(e);
        text += (text.empty() ? std::string("GL error after ") + where + ": " : std::string(", ")) + (name ? name : code);
    }
    return text;
}

GLuint gl_functions::compile(GLenum kind, const std::string& source, const std::string& label, std::string& why) const {
    const GLuint shader = CreateShader(kind);
    const char* text = source.c_str();
    ShaderSource(shader, 1, &text, nullptr);
    CompileShader(shader);
    GLint ok = GL_FALSE;
    GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok == GL_TRUE) return shader;
    why = label + " does not compile:\n" + info_log(shader, GetShaderiv, GetShaderInfoLog);
    DeleteShader(shader);
    return 0;
}

GLuint gl_functions::link(const GLuint* shaders, int count, const std::string& label, std::string& why) const {
    const GLuint program = CreateProgram();
    for (int i = 0; i < count; ++i) AttachShader(program, shaders[i]);
    LinkProgram(program);
    for (int i = 0; i < count; ++i) DeleteShader(shaders[i]);  // only flagged while attached
    GLint ok = GL_FALSE;
    GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok == GL_TRUE) return program;
    why = label + " does not link:\n" + info_log(program, GetProgramiv, GetProgramInfoLog);
    DeleteProgram(program);
    return 0;
}

}  // namespace cloudmath_egl
