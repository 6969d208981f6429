#include "window.hpp"

#include "gl_renderer.hpp"

#include <GLFW/glfw3.h>

#include <cstdio>

namespace cloud_renderer {
namespace {

const char* const key_help =
    "keys: mouse drag or arrows look around; W/S altitude up/down; Q/E sun azimuth; R/F sun elevation;\n"
    "      1-7 presets; M diffusion/octaves; P phase model; O octaves; B powder; L cone/march toward\n"
    "      the sun; K cone/march behind; I integration; [ ] view steps;\n"
    "      T temporal scheme on/off (1 of 16 pixels per frame, reprojected history; on at start);\n"
    "      H this help; Esc quit\n";

struct window_state {
    options o;
    bool drag = false;
    double last_x = 0, last_y = 0;
    bool changed = true;  // print the variant after a change
    bool temporal = true;  // the temporal scheme (gl_renderer::draw_temporal)
};

void on_key(GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    auto& st = *static_cast<window_state*>(glfwGetWindowUserPointer(w));
    scene& s = st.o.sc;
    variant& v = st.o.var;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_LEFT: s.yaw -= 3; break;
    case GLFW_KEY_RIGHT: s.yaw += 3; break;
    case GLFW_KEY_UP: s.pitch = s.pitch + 2 > 89 ? 89.0f : s.pitch + 2; break;
    case GLFW_KEY_DOWN: s.pitch = s.pitch - 2 < -89 ? -89.0f : s.pitch - 2; break;
    case GLFW_KEY_W: s.camera_altitude += s.camera_altitude < 1000 ? 100.0f : 500.0f; break;
    case GLFW_KEY_S: s.camera_altitude = s.camera_altitude > 600 ? s.camera_altitude - 500 : 2.0f; break;
    case GLFW_KEY_Q: s.sun_azimuth -= 5; break;
    case GLFW_KEY_E: s.sun_azimuth += 5; break;
    case GLFW_KEY_R: s.sun_elevation = s.sun_elevation + 2 > 90 ? 90.0f : s.sun_elevation + 2; break;
    case GLFW_KEY_F: s.sun_elevation = s.sun_elevation - 2 < -10 ? -10.0f : s.sun_elevation - 2; break;
    case GLFW_KEY_P: v.phase = static_cast<phase_model>((static_cast<int>(v.phase) + 1) % 4); break;
    case GLFW_KEY_O: v.octaves = v.octaves % 8 + 1; break;
    case GLFW_KEY_B: v.powder = !v.powder; break;
    case GLFW_KEY_L: v.light = v.light == light_mode::cone ? light_mode::march : light_mode::cone; break;
    case GLFW_KEY_K: v.behind = v.behind == light_mode::cone ? light_mode::march : light_mode::cone; break;
    case GLFW_KEY_M:
        v.lighting = v.lighting == lighting_model::diffusion ? lighting_model::octaves : lighting_model::diffusion;
        break;
    case GLFW_KEY_I:
        v.integration = v.integration == integration_mode::analytic ? integration_mode::naive : integration_mode::analytic;
        break;
    case GLFW_KEY_LEFT_BRACKET: v.view_steps = v.view_steps / 2 < 8 ? 8 : v.view_steps / 2; break;
    case GLFW_KEY_RIGHT_BRACKET: v.view_steps = v.view_steps * 2 > 1024 ? 1024 : v.view_steps * 2; break;
    case GLFW_KEY_T: st.temporal = !st.temporal; break;
    case GLFW_KEY_H: std::printf("%s", key_help); break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && static_cast<std::size_t>(key - GLFW_KEY_1) < presets().size())
            s = presets()[static_cast<std::size_t>(key - GLFW_KEY_1)];
        else
            return;
    }
    st.changed = true;
}

void on_button(GLFWwindow* w, int button, int action, int) {
    auto& st = *static_cast<window_state*>(glfwGetWindowUserPointer(w));
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    st.drag = action == GLFW_PRESS;
    glfwGetCursorPos(w, &st.last_x, &st.last_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
    auto& st = *static_cast<window_state*>(glfwGetWindowUserPointer(w));
    if (!st.drag) return;
    st.o.sc.yaw += float(x - st.last_x) * 0.2f;
    const float pitch = st.o.sc.pitch - float(y - st.last_y) * 0.2f;
    st.o.sc.pitch = pitch > 89 ? 89.0f : (pitch < -89 ? -89.0f : pitch);
    st.last_x = x;
    st.last_y = y;
}

void* glfw_proc(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

}  // namespace

int run_window(const options& o, const cloud_textures& textures) {
    if (!glfwInit()) {
        const char* desc = nullptr;
        glfwGetError(&desc);
        std::fprintf(stderr,
                     "error: cannot open a window (%s).\n"
                     "       Without a display, use --headless (GPU through EGL) or --cpu.\n",
                     desc ? desc : "glfwInit failed");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow* w = glfwCreateWindow(o.width, o.height, "cloudmath clouds", nullptr, nullptr);
    if (w == nullptr) {
        const char* desc = nullptr;
        glfwGetError(&desc);
        std::fprintf(stderr, "error: no window with an OpenGL 4.1 core context (%s); try --headless or --cpu.\n",
                     desc ? desc : "glfwCreateWindow failed");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(w);
    glfwSwapInterval(0);
    int status = 0;
    {
        std::string why;
        auto gpu = gl_renderer::create_for_current_context(&glfw_proc, why);
        if (!gpu || !gpu->upload_textures(textures, why)) {
            std::fprintf(stderr, "error: %s\n", why.c_str());
            status = 1;
        } else {
            window_state st{o};
            glfwSetWindowUserPointer(w, &st);
            glfwSetKeyCallback(w, on_key);
            glfwSetMouseButtonCallback(w, on_button);
            glfwSetCursorPosCallback(w, on_cursor);
            std::printf("OpenGL: %s\n%s", gpu->device().c_str(), key_help);
            std::fflush(stdout);
            double shown = glfwGetTime(), sum_ms = 0, sum_gl_ms = 0;
            int frames = 0, total_frames = 0;
            while (!glfwWindowShouldClose(w)) {
                int fw = 0, fh = 0;
                glfwGetFramebufferSize(w, &fw, &fh);
                frame_timing ft;
                bool ok = true;
                if (fw > 0 && fh > 0 && st.temporal) {
                    // The live temporal result: frame numbers count up, the history follows
                    // the camera (a new size starts a new history).
                    scene s = st.o.sc;
                    s.frame = static_cast<std::uint32_t>(total_frames);
                    ok = gpu->draw_temporal(s, st.o.var, fw, fh, &ft, why) && gpu->show_temporal(0, why);
                } else if (fw > 0 && fh > 0) {
                    ok = gpu->draw(st.o.sc, st.o.var, 0, fw, fh, &ft, why);
                }
                if (!ok) {
                    std::fprintf(stderr, "error: %s\n", why.c_str());
                    status = 1;
                    break;
                }
                glfwSwapBuffers(w);
                glfwPollEvents();
                sum_ms += ft.wall_ms;
                sum_gl_ms += ft.gpu_ms;
                ++frames;
                // --frames N: close after N frames (scripted runs and the test under Xvfb).
                ++total_frames;
                if (o.frames_given && total_frames >= o.frames) glfwSetWindowShouldClose(w, GLFW_TRUE);
                if (st.changed) {
                    std::printf("variant %s%s\n", variant_spec(st.o.var).c_str(), st.temporal ? " (temporal)" : "");
                    st.changed = false;
                }
                const double now = glfwGetTime();
                if (now - shown >= 1.0 || glfwWindowShouldClose(w)) {
                    // Host clock from the draw to glFinish (see frame_timing), and the GL timestamps.
                    char title[256];
                    std::snprintf(title, sizeof title, "cloudmath clouds: %.1f ms per frame (%d x %d), %s", sum_ms / frames, fw,
                                  fh, variant_spec(st.o.var).c_str());
                    glfwSetWindowTitle(w, title);
                    std::printf("%.1f ms per frame (GL timestamps %.1f ms), %d x %d\n", sum_ms / frames, sum_gl_ms / frames, fw, fh);
                    std::fflush(stdout);  // visible at once when the output is a pipe or a log
                    shown = now;
                    sum_ms = sum_gl_ms = 0;
                    frames = 0;
                }
            }
        }
    }
    glfwDestroyWindow(w);
    glfwTerminate();
    return status;
}

}  // namespace cloud_renderer
