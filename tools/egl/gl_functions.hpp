// The OpenGL entry points that the cloud renderer (examples/cloud_renderer/gl_renderer.cpp),
// the GLSL parity harness (tests/glsl/gl_compute.cpp) and the peer bench (bench/peer) call,
// loaded at run time from any context (tools/egl's headless one through gl_proc, or a
// window's through glfwGetProcAddress): no loader library and no link-time GL symbols. One
// table, so a function is declared and loaded in one place, with the error, compile and link
// helpers every consumer needs.
#ifndef CLOUDMATH_TOOLS_EGL_GL_FUNCTIONS_HPP
#define CLOUDMATH_TOOLS_EGL_GL_FUNCTIONS_HPP

#include <GL/glcorearb.h>

#include <string>

namespace cloudmath_egl {

// OpenGL 4.1 core: what the renderer needs (4.1 is the newest that macOS offers).
#define CLOUDMATH_GL_CORE_FUNCTIONS(X)                          \
    X(PFNGLGETERRORPROC, GetError)                              \
    X(PFNGLGETSTRINGPROC, GetString)                            \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                        \
    X(PFNGLGETINTEGER64VPROC, GetInteger64v)                    \
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
    X(PFNGLUNIFORM2IPROC, Uniform2i)                            \
    X(PFNGLUNIFORM3IPROC, Uniform3i)                            \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui)                          \
    X(PFNGLUNIFORM2UIPROC, Uniform2ui)                          \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                            \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                            \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                            \
    X(PFNGLUNIFORM4FPROC, Uniform4f)                            \
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
    X(PFNGLGENBUFFERSPROC, GenBuffers)                          \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                    \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                          \
    X(PFNGLBUFFERDATAPROC, BufferData)                          \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                  \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                    \
    X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex)      \
    X(PFNGLUNIFORMBLOCKBINDINGPROC, UniformBlockBinding)        \
    X(PFNGLGETACTIVEUNIFORMBLOCKIVPROC, GetActiveUniformBlockiv) \
    X(PFNGLGETUNIFORMINDICESPROC, GetUniformIndices)            \
    X(PFNGLGETACTIVEUNIFORMSIVPROC, GetActiveUniformsiv)        \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)              \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)          \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)      \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)  \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                        \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                          \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)          \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)        \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                          \
    X(PFNGLVIEWPORTPROC, Viewport)                              \
    X(PFNGLDISABLEPROC, Disable)                                \
    X(PFNGLENABLEPROC, Enable)                                  \
    X(PFNGLSCISSORPROC, Scissor)                                \
    X(PFNGLREADPIXELSPROC, ReadPixels)                          \
    X(PFNGLFINISHPROC, Finish)                                  \
    X(PFNGLGENQUERIESPROC, GenQueries)                          \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                    \
    X(PFNGLQUERYCOUNTERPROC, QueryCounter)                      \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

// OpenGL 4.3 core: compute shaders and image units (the parity harness, the peer bench).
#define CLOUDMATH_GL_COMPUTE_FUNCTIONS(X)                       \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                    \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                    \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)

struct gl_functions {
#define CLOUDMATH_GL_DECLARE(type, name) type name = nullptr;
    CLOUDMATH_GL_CORE_FUNCTIONS(CLOUDMATH_GL_DECLARE)
    CLOUDMATH_GL_COMPUTE_FUNCTIONS(CLOUDMATH_GL_DECLARE)
#undef CLOUDMATH_GL_DECLARE

    using proc_loader = void* (*)(const char* name);

    // Loads the 4.1 table, and the 4.3 one when `compute` is true (a 4.1 context lacks it).
    // Empty on success, else the name of the first entry point the driver lacks.
    std::string load(proc_loader get, bool compute);

    // "GL error after <where>: GL_INVALID_VALUE, ..." for every pending error (at most 8: a
    // lost context can report errors forever), empty when there is none.
    std::string errors(const char* where) const;

    // One shader from its source; 0 on failure, with `why` = "<label> does not compile:" and
    // the driver's log.
    GLuint compile(GLenum kind, const std::string& source, const std::string& label, std::string& why) const;

    // A program of `count` shaders, which it deletes (the program keeps them alive); 0 on
    // failure, with `why` = "<label> does not link:" and the driver's log.
    GLuint link(const GLuint* shaders, int count, const std::string& label, std::string& why) const;
};

}  // namespace cloudmath_egl

#endif  // CLOUDMATH_TOOLS_EGL_GL_FUNCTIONS_HPP
