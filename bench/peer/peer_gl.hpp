// The OpenGL 4.3+ entry points the peer harness calls itself (compute dispatch, image units,
// buffers), loaded at run time from the headless context (tools/egl, gl_proc) like
// examples/cloud_renderer/gl_renderer.cpp does: no loader library, one X-macro table.
#ifndef CLOUDMATH_PEER_BENCH_PEER_GL_HPP
#define CLOUDMATH_PEER_BENCH_PEER_GL_HPP

#include <GL/glcorearb.h>

#include <string>

namespace peer_bench {

#define PEER_GL_FUNCTIONS(X)                                    \
    X(PFNGLGETERRORPROC, GetError)                              \
    X(PFNGLGETSTRINGPROC, GetString)                            \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                        \
    X(PFNGLCREATESHADERPROC, CreateShader)                      \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                      \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                    \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                        \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)              \
    X(PFNGLDELETESHADERPROC, DeleteShader)                      \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                    \
    X(PFNGLATTACHSHADERPROC, AttachShader)                      \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                        \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                      \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)            \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                    \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                          \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)          \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                            \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                            \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                            \
    X(PFNGLUNIFORM2IPROC, Uniform2i)                            \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                            \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)              \
    X(PFNGLGENTEXTURESPROC, GenTextures)                        \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                  \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                        \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                    \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                          \
    X(PFNGLTEXIMAGE3DPROC, TexImage3D)                          \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                    \
    X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                  \
    X(PFNGLGETTEXIMAGEPROC, GetTexImage)                        \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                        \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)              \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                    \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                          \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                    \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                          \
    X(PFNGLBUFFERDATAPROC, BufferData)                          \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                  \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)              \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)          \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)      \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)  \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                        \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)          \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)        \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                          \
    X(PFNGLVIEWPORTPROC, Viewport)                              \
    X(PFNGLDISABLEPROC, Disable)                                \
    X(PFNGLFINISHPROC, Finish)

struct gl_api {
#define PEER_GL_DECLARE(type, name) type name = nullptr;
    PEER_GL_FUNCTIONS(PEER_GL_DECLARE)
#undef PEER_GL_DECLARE

    // Empty on success, else the name of the first entry point the driver lacks.
    std::string load(void* (*get)(const char* name)) {
#define PEER_GL_LOAD(type, name)                                  \
    name = reinterpret_cast<type>(get("gl" #name));                \
    if (name == nullptr) return "gl" #name;
        PEER_GL_FUNCTIONS(PEER_GL_LOAD)
#undef PEER_GL_LOAD
        return {};
    }

    // "GL error after <where>: 0x0502, ..." for every pending error, empty when none.
    std::string errors(const char* where) const;
    // Compiles one shader; 0 and the driver's log in `why` (prefixed with `label`) on failure.
    GLuint compile(GLenum kind, const std::string& source, const std::string& label, std::string& why) const;
    // Links the given shaders (deleting them) into a program; 0 and the log on failure.
    GLuint link(const GLuint* shaders, int count, const std::string& label, std::string& why) const;
};

}  // namespace peer_bench

#endif  // CLOUDMATH_PEER_BENCH_PEER_GL_HPP
