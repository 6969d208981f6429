// sky_tables_gl.hpp: the physical sky's tables built on the GPU (shaders/sky_tables.frag), as
// Hillaire 2020 builds them: the sky-view tables at the camera and at the layer's top, the
// aerial-perspective table and the sky's values row, drawn whenever the sun, the camera's
// altitude or the layer changes; the two sky-view tables and the values are read back (64 KB;
// the frame's sky light and exposure are their means, physical_sky_inputs), the
// aerial-perspective table stays on the GPU. One set, owned by its gl_renderer: no cache to
// grow. The CPU renderer keeps physical_sky.hpp's CPU tables, which these match
// (test_cloud_renderer).
#ifndef CLOUD_RENDERER_SKY_TABLES_GL_HPP
#define CLOUD_RENDERER_SKY_TABLES_GL_HPP

#include "physical_sky.hpp"
#include "scene.hpp"

#include "gl_functions.hpp"

#include <memory>
#include <string>
#include <vector>

namespace cloud_renderer {

// A 2D float texture (`texels` may be null: a render target) with nearest filtering and clamp
// to edge, bound to the active unit: the renderer's tables and targets, read with texelFetch.
void float_texture(const cloudmath_egl::gl_functions& gl, GLuint tex, GLenum internal, GLenum format, int w, int h,
                   const void* texels);

// shaders/sky_tables.frag as compiled (#version, cloudmath.glsl resolved in).
std::string sky_tables_shader_source();

class gpu_sky_tables {
public:
    // Draws the tables for the scene's sun and geometry unless they are drawn already (true
    // then at no cost). `vertex_shader`: the full-screen triangle's; `vao` an empty vertex
    // array. Leaves framebuffer 0 bound. False and `why` on a GL error.
    bool update(const cloudmath_egl::gl_functions& gl, const std::string& vertex_shader, GLuint vao, const scene& s,
                std::string& why);
    // The physical sky for make_frame_constants (valid after a successful update).
    physical_sky_inputs inputs() const { return {samples_, shared_camera_, shared_top_}; }
    glm::vec2 band() const { return band_; }  // the values row's band (sky_tables.frag's cr_cloud_band)
    const haze_table& haze_layout() const { return haze_; }  // the aerial-perspective table's size (no texels)
    GLuint sky_view_texture() const { return textures_[1]; }  // RGBA32F n_az x n_el, at the camera
    GLuint haze_texture() const { return textures_[3]; }      // RGBA32F (n_d n_az) x n_el
    // The aerial-perspective table, read back (a test's comparison with the CPU's).
    bool read_haze(const cloudmath_egl::gl_functions& gl, std::vector<glm::vec3>& out, std::string& why) const;
    int builds() const { return builds_; }           // how many times update drew the tables
    double last_build_ms() const { return build_ms_; }  // the last one's host time (to glFinish and the read-backs)
    void release(const cloudmath_egl::gl_functions& gl);

private:
    GLuint program_ = 0, fbo_ = 0;
    GLuint textures_[5] = {0, 0, 0, 0, 0};  // the atmosphere's table, sky view at the camera, at the top, haze, values
    std::vector<float> key_;                // what the tables were drawn for (empty: not yet)
    physical_sky_samples samples_{};
    // The last build's sky views, read back, shared with the frame constants made from them (a
    // frame's keep theirs when the sun moves and the tables are drawn again).
    std::shared_ptr<const sky_view_table> shared_camera_, shared_top_;
    haze_table haze_;
    glm::vec2 band_{0.0f};
    int builds_ = 0;
    double build_ms_ = 0.0;
};

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_SKY_TABLES_GL_HPP
