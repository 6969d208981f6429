// Error, compile and link helpers of the peer harness's GL table (peer_gl.hpp): every
// failure comes back as text with the driver's log, so a peer shader that does not compile
// on this driver says why instead of drawing nothing.
#include "peer_gl.hpp"

#include <cstdio>

namespace peer_bench {

std::string gl_api::errors(const char* where) const {
    std::string text;
    for (int i = 0; i < 8; ++i) {  // bounded: a lost context can report errors forever
        const GLenum e = GetError();
        if (e == GL_NO_ERROR) break;
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", e);
        text += (text.empty() ? std::string("GL error after ") + where + ": " : std::string(", ")) + code;
    }
    return text;
}

GLuint gl_api::compile(GLenum kind, const std::string& source, const std::string& label, std::string& why) const {
    const GLuint shader = CreateShader(kind);
    const char* text = source.c_str();
    ShaderSource(shader, 1, &text, nullptr);
    CompileShader(shader);
    GLint ok = 0;
    GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok) return shader;
    GLint length = 0;
    GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
    GetShaderInfoLog(shader, length, nullptr, log.data());
    why = label + " does not compile:\n" + log;
    DeleteShader(shader);
    return 0;
}

GLuint gl_api::link(const GLuint* shaders, int count, const std::string& label, std::string& why) const {
    const GLuint program = CreateProgram();
    for (int i = 0; i < count; ++i) AttachShader(program, shaders[i]);
    LinkProgram(program);
    for (int i = 0; i < count; ++i) DeleteShader(shaders[i]);  // the program keeps them alive
    GLint ok = 0;
    GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok) return program;
    GLint length = 0;
    GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 1 ? length : 1), '\0');
    GetProgramInfoLog(program, length, nullptr, log.data());
    why = label + " does not link:\n" + log;
    DeleteProgram(program);
    return 0;
}

}  // namespace peer_bench
