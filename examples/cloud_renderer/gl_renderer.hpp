// The GPU renderer: compiles shaders/clouds.frag with the cloudmath GLSL includes, uploads
// the baked textures and draws the full-screen pass, timed (frame_timing).
// It runs on a context it creates itself (headless: EGL, no display needed; Mesa llvmpipe
// on a machine without a GPU) or on one the caller made current (the GLFW window).
#ifndef CLOUD_RENDERER_GL_RENDERER_HPP
#define CLOUD_RENDERER_GL_RENDERER_HPP

#include "image.hpp"
#include "scene.hpp"
#include "textures.hpp"

#include <memory>
#include <string>
#include <vector>

namespace cloud_renderer {

// clouds.frag's passes (its u_pass): the cloud layer at every pixel (the full frame), the
// temporal scheme's shading pass (the layer at one pixel of each 4 x 4 block), the Beer shadow
// map, the background (what lies behind the layer, and the scene's depth), the physical sky's
// far shadow. A frame ends with composite.frag, which lays the layer over the background.
enum class clouds_pass { frame = 0, temporal_shading = 1, shadow_map = 2, background = 3, far_shadow = 4 };

// The fragment shader for a variant, as compiled: #version, `#define CR_PHYSICAL_SKY 1` for the
// physical sky (its tables), the permutation block (the variant, the scene's shape and
// switches, and the pass as constants: one program per permutation, as engines ship them),
// the shader file with cloudmath.glsl resolved in.
std::string fragment_shader_source(const variant& v, const scene& s, clouds_pass pass = clouds_pass::frame);
std::string vertex_shader_source();
// shaders/temporal_resolve.frag as compiled (#version, cloudmath.glsl resolved in).
std::string temporal_resolve_shader_source();
// shaders/composite.frag as compiled for the scene's composite switches (the dither): #version,
// the permutation block, cloudmath.glsl resolved in.
std::string composite_shader_source(const scene& s);
// The running mean's cap of the temporal scheme (temporal_blend_weight), on the CPU and GPU.
inline constexpr int temporal_max_samples = 8;

// Time of one draw: from GL timestamp queries around it (the GPU's own clock; what a real
// GPU's profiler shows), and on the host from before the draw to the end of glFinish()
// (includes driver overhead; the meaningful one on Mesa's llvmpipe, whose timestamps are
// taken when the draw is queued, not when it runs).
struct frame_timing {
    double gpu_ms = 0;
    double wall_ms = 0;
    // The temporal scheme's passes apart, on the host (set split_passes before the call: each
    // pass then ends with glFinish, which adds a little to wall_ms; 0 when not split).
    bool split_passes = false;
    double shadow_ms = 0, shading_ms = 0, background_ms = 0, resolve_ms = 0, composite_ms = 0;
};

class gl_renderer {
public:
    using proc_loader = void* (*)(const char* name);

    // An OpenGL 4.1+ core context without any window: EGL's surfaceless platform (Mesa), then
    // EGL devices (NVIDIA), then the default display. nullptr and the reason on failure.
    static std::unique_ptr<gl_renderer> create_headless(std::string& why);
    // Uses the context current on this thread; `load` returns GL entry points.
    static std::unique_ptr<gl_renderer> create_for_current_context(proc_loader load, std::string& why);
    ~gl_renderer();
    gl_renderer(const gl_renderer&) = delete;
    gl_renderer& operator=(const gl_renderer&) = delete;

    // "renderer name, OpenGL version" of the driver.
    std::string device() const;
    bool upload_textures(const cloud_textures& t, std::string& why);

    // Draws into framebuffer `fbo` (0: the window) over (0, 0, width, height) with the
    // permutation's programs (compiled on first use, cached): the shadow map, the background
    // (clouds.frag's pass 3), the cloud layer (pass 0) into float targets of the renderer's,
    // then composite.frag into `fbo`. timing (optional) receives the time of the draw.
    bool draw(const scene& s, const variant& v, unsigned fbo, int width, int height, frame_timing* timing, std::string& why);
    // Draws offscreen into a float target and reads it back.
    bool render(const scene& s, const variant& v, int width, int height, image& out, frame_timing* timing, std::string& why);
    // What the last full frame (draw, render) gave composite.frag, read back: the layer
    // (clouds.frag's pass 0: rgb premultiplied linear radiance, a opacity) and the cloud's depth
    // (0: none), the background (pass 3: rgb what lies behind the layer, a 1 where the ray
    // meets the band) and the scene's depth (0: none). False and `why` before any full frame.
    struct frame_layers {
        image layer, background;
        std::vector<float> cloud_depth, scene_depth;
    };
    bool read_frame_layers(frame_layers& out, std::string& why);

    // Temporal rendering, the twin of cpu_temporal_renderer (cpu_renderer.hpp): frame s.frame
    // shades one pixel of every 4 x 4 block (clouds.frag's temporal pass), resolves the full
    // layer from the reprojected history (temporal_resolve.frag) and composites it over the
    // background (composite.frag). Frames should count up by one; a new size or
    // reset_temporal() starts a new history. timing covers every pass. draw_temporal keeps the display image on the GPU (show_temporal copies it
    // into framebuffer fbo, 0 the window); render_temporal reads it back.
    bool draw_temporal(const scene& s, const variant& v, int width, int height, frame_timing* timing, std::string& why);
    bool show_temporal(unsigned fbo, std::string& why);
    bool render_temporal(const scene& s, const variant& v, int width, int height, image& out, frame_timing* timing,
                         std::string& why);
    void reset_temporal();

    // The physical sky's far shadow as the frame reads it, drawn on the GPU (clouds.frag's pass
    // 4): the nodes of far_shadow() for the scene and variant (the same range; n_alt x n_mu
    // values, row-major, row: the sun's cosine), in `out`, for a test against the CPU's table.
    // False and `why` without the physical sky or on a GL error.
    bool far_shadow_gpu(const scene& s, const variant& v, std::vector<float>& out, std::string& why);

    // The physical sky's tables as the frame reads them, drawn on the GPU (sky_tables.frag,
    // sky_tables_gl.hpp) for the scene's sun and geometry: the sky-view tables at the camera and
    // at the layer's top and the aerial-perspective table (physical_sky.hpp's layouts), the
    // values row and its band, the last draw's host time and how many draws this renderer made; for a test
    // against the CPU's tables. False and `why` without the physical sky or on a GL error.
    struct gpu_sky_readback {
        std::vector<glm::vec3> sky_view, sky_top, haze;
        physical_sky_samples samples{};
        glm::vec2 band{0.0f};
        double build_ms = 0.0;
        int builds = 0;
    };
    bool sky_tables_gpu(const scene& s, gpu_sky_readback& out, std::string& why);

    struct state;

private:
    explicit gl_renderer(std::unique_ptr<state> s);
    std::unique_ptr<state> s_;
};

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_GL_RENDERER_HPP
