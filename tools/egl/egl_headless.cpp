// Implementation notes: EGL gives a context with no window system, so the same code runs on
// a headless CI box (Mesa llvmpipe) and on a GPU server (NVIDIA through EGL devices). GL is
// reached only through eglGetProcAddress, so nothing here links libGL or libOpenGL;
// GL/glcorearb.h gives the types and enums of the one GL call made here (the version check).
#include "egl_headless.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <utility>

namespace cloudmath_egl {

bool has_extension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t len = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += len) {
        const bool starts = p == list || p[-1] == ' ';
        const bool ends = p[len] == ' ' || p[len] == '\0';
        if (starts && ends) return true;
    }
    return false;
}

std::string egl_error() {
    static const char* const names[] = {
        "EGL_SUCCESS", "EGL_NOT_INITIALIZED", "EGL_BAD_ACCESS", "EGL_BAD_ALLOC",
        "EGL_BAD_ATTRIBUTE", "EGL_BAD_CONFIG", "EGL_BAD_CONTEXT", "EGL_BAD_CURRENT_SURFACE",
        "EGL_BAD_DISPLAY", "EGL_BAD_MATCH", "EGL_BAD_NATIVE_PIXMAP", "EGL_BAD_NATIVE_WINDOW",
        "EGL_BAD_PARAMETER", "EGL_BAD_SURFACE", "EGL_CONTEXT_LOST"};
    const EGLint e = eglGetError();
    if (e >= EGL_SUCCESS && e <= EGL_CONTEXT_LOST) return names[e - EGL_SUCCESS];
    char buf[32];
    std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(e));
    return buf;
}

void* gl_proc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

namespace {

// eglTerminate is not reference counted (EGL returns the same EGLDisplay for the same
// platform and device), so terminating when one context dies would break any other live
// context on that display. Count the users and terminate with the last one.
std::mutex& display_mutex() {
    static std::mutex m;
    return m;
}
std::map<EGLDisplay, int>& display_users() {
    static std::map<EGLDisplay, int> users;
    return users;
}
bool acquire_display(EGLDisplay dpy, std::string& why) {
    std::lock_guard<std::mutex> lock(display_mutex());
    // eglInitialize is a no-op on an initialized display, so calling it every time is fine.
    if (eglInitialize(dpy, nullptr, nullptr) != EGL_TRUE) {
        why = "eglInitialize failed (" + egl_error() + ")";
        return false;
    }
    ++display_users()[dpy];
    return true;
}
void release_display(EGLDisplay dpy) {
    std::lock_guard<std::mutex> lock(display_mutex());
    auto it = display_users().find(dpy);
    if (it != display_users().end() && --it->second == 0) {
        display_users().erase(it);
        eglTerminate(dpy);
    }
}

std::string version_text(int major, int minor) { return std::to_string(major) + "." + std::to_string(minor); }

}  // namespace

struct headless_context::handles {
    EGLDisplay dpy = EGL_NO_DISPLAY;  // set only once acquire_display succeeded
    EGLContext ctx = EGL_NO_CONTEXT;
    EGLSurface surf = EGL_NO_SURFACE;  // a 1x1 pbuffer, only without EGL_KHR_surfaceless_context

    handles() = default;
    handles(const handles&) = delete;
    handles& operator=(const handles&) = delete;

    bool make_current() const {
        if (eglGetCurrentContext() == ctx) return true;
        return eglBindAPI(EGL_OPENGL_API) == EGL_TRUE && eglMakeCurrent(dpy, surf, surf, ctx) == EGL_TRUE;
    }

    ~handles() {
        if (ctx != EGL_NO_CONTEXT) {
            if (eglGetCurrentContext() == ctx) eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(dpy, ctx);
        }
        if (surf != EGL_NO_SURFACE) eglDestroySurface(dpy, surf);
        if (dpy != EGL_NO_DISPLAY) release_display(dpy);
    }
};

namespace {

using handles = headless_context::handles;

// Creates the context on one display, makes it current and checks its version. nullptr
// with the reason in `why`; whatever was made before the failure is released by ~handles.
std::unique_ptr<handles> open_display(EGLDisplay dpy, int major, int minor, std::string& why) {
    if (dpy == EGL_NO_DISPLAY) {
        why = "no display (" + egl_error() + ")";
        return nullptr;
    }
    if (!acquire_display(dpy, why)) return nullptr;
    auto h = std::make_unique<handles>();
    h->dpy = dpy;
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
        why = "desktop OpenGL not supported (eglBindAPI: " + egl_error() + ")";
        return nullptr;
    }
    // Mesa and recent NVIDIA drivers need neither a config nor a surface; older drivers get
    // a config and a 1x1 pbuffer, which costs nothing and is never drawn to.
    const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
    const bool surfaceless = has_extension(exts, "EGL_KHR_surfaceless_context");
    const bool no_config = has_extension(exts, "EGL_KHR_no_config_context");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!no_config || !surfaceless) {
        const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                               surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_NONE};
        EGLint count = 0;
        if (eglChooseConfig(dpy, want, &config, 1, &count) != EGL_TRUE || count < 1) {
            why = "no OpenGL EGL config (" + egl_error() + ")";
            return nullptr;
        }
    }
    // Drivers return the newest version compatible with the one asked for (4.5 or 4.6).
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    h->ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attribs);
    if (h->ctx == EGL_NO_CONTEXT) {
        why = "no OpenGL " + version_text(major, minor) + " core context (eglCreateContext: " + egl_error() + ")";
        return nullptr;
    }
    if (!surfaceless) {
        const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        h->surf = eglCreatePbufferSurface(dpy, config, size);
        if (h->surf == EGL_NO_SURFACE) {
            why = "eglCreatePbufferSurface failed (" + egl_error() + ")";
            return nullptr;
        }
    }
    if (!h->make_current()) {
        why = "eglMakeCurrent failed (" + egl_error() + ")";
        return nullptr;
    }
    // A driver may hand out an older context than asked for: then the next display may do.
    const auto get_integer = reinterpret_cast<PFNGLGETINTEGERVPROC>(eglGetProcAddress("glGetIntegerv"));
    if (get_integer == nullptr) {
        why = "GL entry point glGetIntegerv not found";
        return nullptr;
    }
    GLint got_major = 0, got_minor = 0;
    get_integer(GL_MAJOR_VERSION, &got_major);
    get_integer(GL_MINOR_VERSION, &got_minor);
    if (got_major < major || (got_major == major && got_minor < minor)) {
        why = "OpenGL " + version_text(got_major, got_minor) + " context, " + version_text(major, minor) +
              " core needed";
        return nullptr;
    }
    return h;
}

}  // namespace

headless_context::headless_context(std::unique_ptr<handles> h) : h_(std::move(h)) {}
headless_context::~headless_context() = default;

bool headless_context::make_current() const { return h_->make_current(); }

std::unique_ptr<headless_context> headless_context::open(int major, int minor, platform only, std::string& why) {
    why.clear();
    // Client extensions say which platforms exist; NULL from an EGL 1.4 library means none.
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    std::string tried;  // one "platform: reason" per failed attempt
    const auto note = [&tried](const std::string& name, const std::string& reason) {
        tried += (tried.empty() ? "" : "; ") + name + ": " + reason;
    };
    std::unique_ptr<handles> h;
    const auto attempt = [&](const std::string& name, EGLDisplay dpy) {
        std::string reason;
        h = open_display(dpy, major, minor, reason);
        if (h == nullptr) note(name, reason);
    };
    const auto allowed = [only](platform p) { return only == platform::any || only == p; };

    if (allowed(platform::surfaceless)) {
        if (has_extension(client, "EGL_MESA_platform_surfaceless"))
            attempt("surfaceless", eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
        else
            note("surfaceless", "not available");
    }
    if (h == nullptr && allowed(platform::device)) {
        const auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (has_extension(client, "EGL_EXT_platform_device") && query != nullptr &&
            query(16, devices, &count) == EGL_TRUE && count > 0) {
            for (EGLint i = 0; i < count && h == nullptr; ++i)
                attempt("device " + std::to_string(i),
                        eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
        } else {
            note("device", "no EGL devices");
        }
    }
    if (h == nullptr && allowed(platform::default_display)) attempt("default", eglGetDisplay(EGL_DEFAULT_DISPLAY));

    if (h == nullptr) {
        why = tried;
        return nullptr;
    }
    return std::unique_ptr<headless_context>(new headless_context(std::move(h)));
}

}  // namespace cloudmath_egl
