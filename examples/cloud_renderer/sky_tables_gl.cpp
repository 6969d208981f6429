// sky_tables_gl.cpp: see sky_tables_gl.hpp.
#include "sky_tables_gl.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace cloud_renderer {
namespace {

// The stacked table, sky_tables.frag's u_table: physical_air's 32 x 32 refined LUT as
// atmosphere_stacked_table lays it out (part p at rows 32 p .. 32 p + 31; the ground
// irradiance's block 0: the sky's ground reflects the sun alone).
constexpr int table_size = 32, table_parts = cloudmath::atmosphere_stacked_table_parts;

// The RGB of a w x h RGBA32F read-back.
std::vector<glm::vec3> rgb(const std::vector<float>& rgba) {
    std::vector<glm::vec3> out(rgba.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]);
    return out;
}

constexpr int values_width = sun_heights + 12;  // sky_tables.frag's values row

}  // namespace

void float_texture(const cloudmath_egl::gl_functions& gl, GLuint tex, GLenum internal, GLenum format, int w, int h,
                   const void* texels) {
    gl.BindTexture(GL_TEXTURE_2D, tex);
    gl.TexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), w, h, 0, format, GL_FLOAT, texels);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

bool gpu_sky_tables::update(const cloudmath_egl::gl_functions& gl, const std::string& vertex_shader, GLuint vao,
                            const scene& s, std::string& why) {
    const glm::vec3 sun = geometry_constants(s).sun_dir;
    const glm::vec2 band = cloud_band(s);
    const float camera = std::fmax(s.camera_altitude, 0.0f);
    const std::vector<float> key = {camera, s.layer_bottom, s.layer_top, band.x, band.y, sun.x, sun.y, sun.z};
    if (key == key_) return true;
    const auto t0 = std::chrono::steady_clock::now();
    if (program_ == 0) {
        GLuint shaders[2] = {gl.compile(GL_VERTEX_SHADER, vertex_shader, "vertex shader", why), 0};
        if (shaders[0] != 0) shaders[1] = gl.compile(GL_FRAGMENT_SHADER, sky_tables_shader_source(), "sky_tables.frag", why);
        if (shaders[1] == 0) {
            if (shaders[0] != 0) gl.DeleteShader(shaders[0]);
            return false;
        }
        program_ = gl.link(shaders, 2, "the sky tables' program", why);
        if (program_ == 0) return false;
        gl.GenTextures(5, textures_);
        gl.GenFramebuffers(1, &fbo_);
        gl.ActiveTexture(GL_TEXTURE0);
        const std::vector<glm::vec3> table = cloudmath::atmosphere_stacked_table(earth_air().luts);
        float_texture(gl, textures_[0], GL_RGB32F, GL_RGB, table_size, table_size * table_parts, table.data());
        const sky_view_table layout;  // its size
        float_texture(gl, textures_[1], GL_RGBA32F, GL_RGBA, layout.n_az, layout.n_el, nullptr);
        float_texture(gl, textures_[2], GL_RGBA32F, GL_RGBA, layout.n_az, layout.n_el, nullptr);
        float_texture(gl, textures_[3], GL_RGBA32F, GL_RGBA, haze_.n_d * haze_.n_az, haze_.n_el, nullptr);
        float_texture(gl, textures_[4], GL_RGBA32F, GL_RGBA, values_width, 1, nullptr);
    }
    gl.UseProgram(program_);
    const auto loc = [&](const char* name) { return gl.GetUniformLocation(program_, name); };
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, textures_[0]);
    gl.Uniform1i(loc("u_table"), 0);
    gl.Uniform1f(loc("u_max_distance"), haze_.max_distance);
    gl.Uniform1f(loc("u_layer_bottom"), s.layer_bottom);
    gl.Uniform1f(loc("u_layer_top"), s.layer_top);
    gl.Uniform1f(loc("u_cloud_type"), s.cloud_type);
    gl.Uniform1f(loc("u_type_spread"), s.type_spread);
    gl.Uniform1i(loc("u_shape"), s.shape == cloud_shape::detailed ? 1 : 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    const GLenum one = GL_COLOR_ATTACHMENT0;
    gl.DrawBuffers(1, &one);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.BindVertexArray(vao);
    const glm::vec3 sun_at_zero = sun_at_azimuth_zero(sun);
    std::vector<float> back;
    // Draws table `t` (w x h) of `kind` at `altitude`; reads it back into `back` when asked.
    const auto draw = [&](int t, int w, int h, int kind, glm::ivec3 size, float altitude, glm::vec3 toward, bool read) {
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, textures_[t], 0);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            why = "the sky tables' float target is not supported (framebuffer incomplete)";
            return false;
        }
        gl.Viewport(0, 0, w, h);
        gl.Uniform1i(loc("u_kind"), kind);
        gl.Uniform3i(loc("u_size"), size.x, size.y, size.z);
        gl.Uniform1f(loc("u_altitude"), altitude);
        gl.Uniform3f(loc("u_sun"), toward.x, toward.y, toward.z);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        if (read) {
            back.assign(std::size_t(w) * std::size_t(h) * 4, 0.0f);
            gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, back.data());
        }
        return true;
    };
    sky_view_table at_camera, at_top;
    bool ok = draw(1, at_camera.n_az, at_camera.n_el, 0, {at_camera.n_az, at_camera.n_el, 0}, camera, sun_at_zero, true);
    if (ok) at_camera.texels = rgb(back);
    ok = ok && draw(2, at_top.n_az, at_top.n_el, 0, {at_top.n_az, at_top.n_el, 0}, s.layer_top, sun_at_zero, true);
    if (ok) at_top.texels = rgb(back);
    ok = ok && draw(3, haze_.n_d * haze_.n_az, haze_.n_el, 1, {haze_.n_d, haze_.n_az, haze_.n_el}, camera, sun_at_zero, false);
    ok = ok && draw(4, values_width, 1, 2, {0, 0, 0}, camera, sun, true);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (!ok) return false;
    const std::vector<glm::vec3> v = rgb(back);
    for (int i = 0; i < sun_heights; ++i) samples_.sun_by_height[i] = v[std::size_t(i)];
    samples_.sun_band_middle = v[sun_heights];
    samples_.sun_camera = v[sun_heights + 1];
    samples_.zenith = v[sun_heights + 2];
    samples_.horizon = glm::vec3(0.0f);
    for (int i = 0; i < 8; ++i) samples_.horizon += v[std::size_t(sun_heights + 3 + i)];
    samples_.horizon /= 8.0f;
    band_ = glm::vec2(v[std::size_t(sun_heights + 11)]);
    shared_camera_ = std::make_shared<const sky_view_table>(std::move(at_camera));
    shared_top_ = std::make_shared<const sky_view_table>(std::move(at_top));
    gl.Finish();
    why = gl.errors("the sky tables' passes");
    if (!why.empty()) return false;
    build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++builds_;
    key_ = key;
    return true;
}

bool gpu_sky_tables::read_haze(const cloudmath_egl::gl_functions& gl, std::vector<glm::vec3>& out, std::string& why) const {
    if (key_.empty()) {
        why = "the sky tables are not drawn yet";
        return false;
    }
    std::vector<float> back(std::size_t(haze_.n_d * haze_.n_az * haze_.n_el) * 4);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, textures_[3], 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.ReadPixels(0, 0, haze_.n_d * haze_.n_az, haze_.n_el, GL_RGBA, GL_FLOAT, back.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    out = rgb(back);
    why = gl.errors("reading the aerial-perspective table back");
    return why.empty();
}

void gpu_sky_tables::release(const cloudmath_egl::gl_functions& gl) {
    if (program_) gl.DeleteProgram(program_);
    if (textures_[0]) gl.DeleteTextures(5, textures_);
    if (fbo_) gl.DeleteFramebuffers(1, &fbo_);
    program_ = fbo_ = 0;
    for (GLuint& t : textures_) t = 0;
    key_.clear();
}

}  // namespace cloud_renderer
