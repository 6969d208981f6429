// A headless OpenGL core context through EGL: no window, no display server, no loader
// library. The GLSL parity tests (tests/glsl/gl_compute.cpp) and the cloud renderer
// (examples/cloud_renderer/gl_renderer.cpp) both open their context here, so the display
// choice, the config/pbuffer fallbacks and the eglTerminate counting exist once.
//
// Display choice, first that gives a context of the asked version wins:
//   1. EGL_PLATFORM_SURFACELESS_MESA   (Mesa; llvmpipe when there is no GPU)
//   2. EGL_PLATFORM_DEVICE_EXT         (each device from eglQueryDevicesEXT; NVIDIA's driver)
//   3. eglGetDisplay(EGL_DEFAULT_DISPLAY)
// No EGL or GL header leaks out of here; GL entry points come from gl_proc().
#ifndef CLOUDMATH_TOOLS_EGL_HEADLESS_HPP
#define CLOUDMATH_TOOLS_EGL_HEADLESS_HPP

#include <memory>
#include <string>

namespace cloudmath_egl {

// Whole-token search of a space-separated extension list (NULL: no extensions); strstr
// alone would find EGL_EXT_foo inside EGL_EXT_foo_bar.
bool has_extension(const char* list, const char* name);

// eglGetError() by name ("EGL_BAD_MATCH"), or "EGL error 0x...." for a code EGL 1.5 lacks.
std::string egl_error();

// Any GL or EGL entry point, core functions included (EGL 1.5 and
// EGL_KHR_get_all_proc_addresses); nullptr when the driver has none of that name.
void* gl_proc(const char* name);

enum class platform { any, surfaceless, device, default_display };

// One display reference (eglTerminate happens with the last context on that display), one
// OpenGL core context and, only without EGL_KHR_surfaceless_context, a 1x1 pbuffer that is
// never drawn to. Use it from one thread; several may coexist.
class headless_context {
public:
    // A context of OpenGL major.minor core or newer (checked with glGetIntegerv, not only
    // asked for), current on this thread. `only` restricts the choice to one platform.
    // nullptr on failure, with every attempt on one line in `why`:
    // "surfaceless: <reason>; device 0: <reason>; default: <reason>".
    static std::unique_ptr<headless_context> open(int major, int minor, platform only, std::string& why);

    // Releases the context from this thread if it is current, then destroys it and the
    // pbuffer. Delete the GL objects first, with make_current().
    ~headless_context();
    headless_context(const headless_context&) = delete;
    headless_context& operator=(const headless_context&) = delete;

    // Makes this context current on this thread (cheap when it already is); eglBindAPI is
    // per-thread state, so it is selected again too. False on failure, egl_error() says why.
    bool make_current() const;

    struct handles;  // EGLDisplay, EGLContext, EGLSurface (egl_headless.cpp)

private:
    explicit headless_context(std::unique_ptr<handles> h);
    std::unique_ptr<handles> h_;
};

}  // namespace cloudmath_egl

#endif  // CLOUDMATH_TOOLS_EGL_HEADLESS_HPP
