// Runs the peer's clouds compute shader (peer_clouds.hpp). The setup follows the engine at
// TerrainEngine-OpenGL d08c253: texture formats, sizes, filters and dispatch counts of
// CloudsModel::generateModelTextures / generateWeatherMap, the uniforms of
// VolumetricClouds::draw with CloudsModel::initVariables' values, the sky texture of
// Skybox::draw. Where we differ, a comment says so and why.
#include "peer_clouds.hpp"

#include "gl_functions.hpp"
#include "instrument.hpp"
#include "quality_knobs.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace peer_bench {

using gl_api = cloudmath_egl::gl_functions;  // tools/egl's table of GL entry points

namespace {

// ---------------------------------------------------------------------------------------
// The engine's default values, by where it sets them.

// Main.cpp: the camera starts at (0, 800, 0); glm::perspective(Camera::Zoom, aspect, 5, 1e7).
constexpr float camera_height = 800.0f;
constexpr float near_plane = 5.0f;
constexpr float far_plane = 10000000.0f;
// The engine's weather seed is an uninitialised glm::vec3 in Main.cpp; (0, 0, 0) is its GUI's
// "Use default seed" and CloudsModel's own initial value.
const glm::vec3 weather_seed(0.0f);
// glfwGetTime() in the engine (seconds since start: moves the clouds with the wind). Fixed
// so that every frame, and the instrumented run, draw the same picture.
constexpr float time_seconds = 0.0f;

// CloudsModel::initVariables. VolumetricClouds::draw passes absorption * 0.01.
constexpr float cloud_speed = 450.0f;
constexpr float coverage = 0.45f;
constexpr float crispiness = 40.0f;
constexpr float curliness = 0.1f;
constexpr float density = 0.02f;
constexpr float absorption = 0.35f;
constexpr float earth_radius = 600000.0f;
constexpr float sphere_inner_radius = 5000.0f;
constexpr float sphere_outer_radius = 17000.0f;
constexpr float perlin_frequency = 0.8f;
const glm::vec3 cloud_color_top = glm::vec3(169.0f, 149.0f, 149.0f) * (1.5f / 255.0f);
const glm::vec3 cloud_color_bottom = glm::vec3(65.0f, 70.0f, 80.0f) * (1.5f / 255.0f);

// Skybox: Skybox::update blends its high-sun preset (DefaultPreset, with Main.cpp's light
// colour) and its sunset preset (SunsetPreset1, the last one the constructor stores) by a
// sigmoid of the sun direction's y; done the same way here.
struct sky_preset {
    glm::vec3 sky_top, sky_bottom, light_color;
};
const sky_preset high_sun{glm::vec3(0.5f, 0.7f, 0.8f) * 1.05f, glm::vec3(0.9f, 0.9f, 0.95f),
                          glm::vec3(255.0f, 255.0f, 230.0f) / 255.0f};
const sky_preset sunset{glm::vec3(133.0f, 158.0f, 214.0f) / 255.0f, glm::vec3(241.0f, 161.0f, 161.0f) / 255.0f,
                        glm::vec3(255.0f, 201.0f, 201.0f) / 255.0f};
sky_preset sky_for_sun(float sun_y) {
    const float a = std::clamp(1.0f / (1.0f + std::exp(8.0f - sun_y * 40.0f)), 0.0f, 1.0f);
    return {high_sun.sky_top * a + sunset.sky_top * (1.0f - a), high_sun.sky_bottom * a + sunset.sky_bottom * (1.0f - a),
            high_sun.light_color * a + sunset.light_color * (1.0f - a)};
}

// Texture sizes and the work group sizes the engine divides by (INT_CEIL in CloudsModel.h).
constexpr int perlin_size = 128, perlin_group = 4;
constexpr int worley_size = 32, worley_group = 4;
constexpr int weather_size = 1024, weather_group = 8;  // the shader's groups are 16 x 16: the engine over-dispatches
constexpr int clouds_group = 16;
constexpr int output_images = 4;                       // fragColor, bloom, alphaness, cloudDistance

GLuint ceil_div(int n, int d) { return static_cast<GLuint>((n + d - 1) / d); }

bool read_text(const std::string& path, std::string& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream text;
    text << in.rdbuf();
    out = text.str();
    return static_cast<bool>(in) || in.eof();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

struct peer_clouds::state {
    gl_api gl;
    bool quiet = false;
    std::string sky_vert, sky_frag;                // screen.vert, sky.frag (the sky texture's pass)
    std::string clouds_source;                     // volumetric_clouds.comp as shipped
    std::vector<GLuint> quality;                   // add_quality_program's copies
    peer_view last_view;                           // of the last prepare()
    GLuint clouds = 0, counted = 0, sky = 0;       // programs: as shipped, instrumented, sky
    GLuint perlin = 0, worley = 0, weather = 0;    // the noise textures
    GLuint outputs[output_images] = {0, 0, 0, 0};
    GLuint sky_texture = 0, sky_fbo = 0, depth = 0;
    GLuint quad_vao = 0, quad_vbo = 0, counters = 0;
    int width = 0, height = 0;
    bool light_attributed = false;  // instrument.hpp found the light function
    std::string light_note;

    void note(const char* text) const {
        if (!quiet) std::fprintf(stderr, "peer: %s\n", text);
    }

    GLuint compute_program(const std::string& source, const std::string& label, std::string& why) const {
        const GLuint shader = gl.compile(GL_COMPUTE_SHADER, source, label, why);
        return shader == 0 ? 0 : gl.link(&shader, 1, label, why);
    }

    // generateTexture3D: RGBA8, repeat, trilinear, mipmaps.
    GLuint volume(int size) const {
        GLuint tex = 0;
        gl.GenTextures(1, &tex);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_3D, tex);
        gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl.TexImage3D(GL_TEXTURE_3D, 0, GL_RGBA8, size, size, size, 0, GL_RGBA, GL_FLOAT, nullptr);
        gl.GenerateMipmap(GL_TEXTURE_3D);
        return tex;
    }

    // generateTexture2D: RGBA32F, repeat, bilinear, no mipmaps.
    GLuint plane(int w, int h) const {
        GLuint tex = 0;
        gl.GenTextures(1, &tex);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, tex);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
        return tex;
    }

    // One noise volume: the peer's compute shader writes level 0 through a layered RGBA8
    // image, then mipmaps. The engine has the barrier before glGenerateMipmap commented out;
    // it is needed for defined results (image stores are incoherent), so we issue it.
    bool bake_volume(const std::string& source, const char* label, int size, int group, GLuint& tex, std::string& why) const {
        const auto start = std::chrono::steady_clock::now();
        const GLuint program = compute_program(source, label, why);
        if (program == 0) return false;
        tex = volume(size);
        gl.UseProgram(program);
        const GLint resolution = gl.GetUniformLocation(program, "u_resolution");  // set by the engine, unused by the shaders
        if (resolution >= 0) gl.Uniform3f(resolution, float(size), float(size), float(size));
        gl.BindImageTexture(0, tex, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA8);
        gl.DispatchCompute(ceil_div(size, group), ceil_div(size, group), ceil_div(size, group));
        gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl.BindTexture(GL_TEXTURE_3D, tex);
        gl.GenerateMipmap(GL_TEXTURE_3D);
        gl.Finish();
        gl.DeleteProgram(program);
        why = gl.errors(label);
        char text[128];
        std::snprintf(text, sizeof text, "%s: %d^3 generated in %.1f s", label, size, seconds_since(start));
        note(text);
        return why.empty();
    }

    // generateWeatherMap: RGBA32F texture bound as an RGBA32F image (the shader declares
    // rgba8; the engine binds it so), seed and frequency uniforms.
    bool bake_weather(const std::string& source, std::string& why) {
        const auto start = std::chrono::steady_clock::now();
        const GLuint program = compute_program(source, "weather.comp", why);
        if (program == 0) return false;
        weather = plane(weather_size, weather_size);
        gl.BindImageTexture(0, weather, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        gl.UseProgram(program);
        gl.Uniform3f(gl.GetUniformLocation(program, "seed"), weather_seed.x, weather_seed.y, weather_seed.z);
        gl.Uniform1f(gl.GetUniformLocation(program, "perlinFrequency"), perlin_frequency);
        gl.DispatchCompute(ceil_div(weather_size, weather_group), ceil_div(weather_size, weather_group), 1);
        gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl.Finish();
        gl.DeleteProgram(program);
        why = gl.errors("weather.comp");
        char text[128];
        std::snprintf(text, sizeof text, "weather.comp: %d^2 generated in %.1f s", weather_size, seconds_since(start));
        note(text);
        return why.empty();
    }

    // The uniforms VolumetricClouds::draw sets (those the program keeps; the rest are -1 and
    // ignored by GL, as in the engine).
    void set_clouds_uniforms(GLuint program, const peer_view& v) const {
        const auto loc = [&](const char* name) { return gl.GetUniformLocation(program, name); };
        const auto vec3 = [&](const char* name, const glm::vec3& x) { gl.Uniform3f(loc(name), x.x, x.y, x.z); };
        const auto mat4 = [&](const char* name, const glm::mat4& m) { gl.UniformMatrix4fv(loc(name), 1, GL_FALSE, glm::value_ptr(m)); };

        // Camera (Include/camera.h): yaw -90 looks along -z, our heading 0; lookAt with the
        // Up vector it derives from the world up.
        const float yaw = glm::radians(v.yaw_deg - 90.0f), pitch = glm::radians(v.pitch_deg);
        const glm::vec3 position(0.0f, camera_height, 0.0f);
        const glm::vec3 front = glm::normalize(glm::vec3(std::cos(yaw) * std::cos(pitch), std::sin(pitch), std::sin(yaw) * std::cos(pitch)));
        const glm::vec3 right = glm::normalize(glm::cross(front, glm::vec3(0.0f, 1.0f, 0.0f)));
        const glm::vec3 up = glm::normalize(glm::cross(right, front));
        const glm::mat4 view = glm::lookAt(position, position + front, up);
        const glm::mat4 proj = glm::perspective(glm::radians(v.fov_y_deg), float(width) / float(height), near_plane, far_plane);
        const glm::vec3 sun = glm::normalize(v.sun_dir);  // normalize(lightPos - camera) with lightPos = dir * 1e6 + camera
        const sky_preset sky_colors = sky_for_sun(sun.y);

        gl.UseProgram(program);
        gl.Uniform2f(loc("iResolution"), float(width), float(height));
        gl.Uniform1f(loc("iTime"), time_seconds);
        mat4("inv_proj", glm::inverse(proj));
        mat4("inv_view", glm::inverse(view));
        vec3("cameraPosition", position);
        gl.Uniform1f(loc("FOV"), v.fov_y_deg);
        vec3("lightDirection", sun);
        vec3("lightColor", sky_colors.light_color);
        gl.Uniform1f(loc("coverage_multiplier"), coverage);
        gl.Uniform1f(loc("cloudSpeed"), cloud_speed);
        gl.Uniform1f(loc("crispiness"), crispiness);
        gl.Uniform1f(loc("curliness"), curliness);
        gl.Uniform1f(loc("absorption"), absorption * 0.01f);
        gl.Uniform1f(loc("densityFactor"), density);
        gl.Uniform1f(loc("earthRadius"), earth_radius);
        gl.Uniform1f(loc("sphereInnerRadius"), sphere_inner_radius);
        gl.Uniform1f(loc("sphereOuterRadius"), sphere_outer_radius);
        vec3("cloudColorTop", cloud_color_top);
        vec3("cloudColorBottom", cloud_color_bottom);
        vec3("skyColorTop", sky_colors.sky_top);
        vec3("skyColorBottom", sky_colors.sky_bottom);
        mat4("invViewProj", glm::inverse(proj * view));
        mat4("gVP", proj * view);
        gl.Uniform1i(loc("cloud"), 0);
        gl.Uniform1i(loc("worley32"), 1);
        gl.Uniform1i(loc("weatherTex"), 2);
        gl.Uniform1i(loc("depthMap"), 3);
        gl.Uniform1i(loc("sky"), 4);
        gl.Uniform2i(loc(counter_size_uniform), width, height);  // the instrumented copy only
    }

    // Skybox::draw: the peer's sky.frag over a full-screen quad (ScreenSpaceShader's six
    // vertices, position and texcoord) into an RGBA32F target of the clouds' size; the
    // clouds shader samples it at the pixel. The engine's target also sets an invalid mag
    // filter (GL_LINEAR_MIPMAP_LINEAR), which GL rejects, leaving the default: we skip it.
    bool draw_sky(const peer_view& v, std::string& why) {
        if (quad_vao == 0) {
            const float quad[] = {-1, -1, 0, 0, 1, -1, 1, 0, -1, 1, 0, 1, 1, 1, 1, 1, -1, 1, 0, 1, 1, -1, 1, 0};
            gl.GenVertexArrays(1, &quad_vao);
            gl.GenBuffers(1, &quad_vbo);
            gl.BindVertexArray(quad_vao);
            gl.BindBuffer(GL_ARRAY_BUFFER, quad_vbo);
            gl.BufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
            gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
            gl.EnableVertexAttribArray(0);
            gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), reinterpret_cast<const void*>(2 * sizeof(float)));
            gl.EnableVertexAttribArray(1);
        }
        if (sky == 0) {
            GLuint shaders[2] = {gl.compile(GL_VERTEX_SHADER, sky_vert, "screen.vert", why), 0};
            if (shaders[0] == 0) return false;
            shaders[1] = gl.compile(GL_FRAGMENT_SHADER, sky_frag, "sky.frag", why);
            if (shaders[1] == 0) return false;
            sky = gl.link(shaders, 2, "screen.vert + sky.frag", why);
            if (sky == 0) return false;
        }
        if (sky_fbo == 0) gl.GenFramebuffers(1, &sky_fbo);
        gl.BindFramebuffer(GL_FRAMEBUFFER, sky_fbo);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, sky_texture, 0);
        const GLenum attachment = GL_COLOR_ATTACHMENT0;
        gl.DrawBuffers(1, &attachment);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            why = "the sky texture's framebuffer is incomplete";
            return false;
        }
        gl.Disable(GL_DEPTH_TEST);  // ScreenSpaceShader::disableTests
        gl.Disable(GL_CULL_FACE);
        gl.Viewport(0, 0, width, height);
        set_clouds_uniforms(sky, v);  // the same names: resolution aside, what Skybox::draw sets
        gl.Uniform2f(gl.GetUniformLocation(sky, "resolution"), float(width), float(height));
        gl.BindVertexArray(quad_vao);
        gl.DrawArrays(GL_TRIANGLES, 0, 6);
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.Finish();
        why = gl.errors("sky.frag");
        return why.empty();
    }

    // Binds what VolumetricClouds::draw binds: the four images, then samplers 0..4.
    void bind_clouds_inputs() const {
        for (int i = 0; i < output_images; ++i)
            gl.BindImageTexture(static_cast<GLuint>(i), outputs[i], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const GLuint textures[5] = {perlin, worley, weather, depth, sky_texture};
        const GLenum kinds[5] = {GL_TEXTURE_3D, GL_TEXTURE_3D, GL_TEXTURE_2D, GL_TEXTURE_2D, GL_TEXTURE_2D};
        for (int i = 0; i < 5; ++i) {
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
            gl.BindTexture(kinds[i], textures[i]);
        }
        gl.ActiveTexture(GL_TEXTURE0);
    }

    void dispatch_clouds(GLuint program) const {
        gl.UseProgram(program);
        gl.DispatchCompute(ceil_div(width, clouds_group), ceil_div(height, clouds_group), 1);
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }

    // One timed frame of a clouds program: the dispatch (and the engine's image barrier)
    // between glFinish calls; wall_ms the host time from before the dispatch to the end of
    // glFinish().
    bool timed_dispatch(GLuint program, const char* label, double& wall_ms, std::string& why) const {
        bind_clouds_inputs();
        gl.Finish();  // nothing earlier in the measured time
        const auto start = std::chrono::steady_clock::now();
        dispatch_clouds(program);
        gl.Finish();
        wall_ms = 1000.0 * seconds_since(start);
        why = gl.errors(label);
        return why.empty();
    }

    // Output image `index` (outputs[]: fragColor, bloom, alphaness, cloudDistance) of the last
    // dispatch, rows bottom-up.
    bool read_output(int index, std::vector<glm::vec4>& out, const char* label, std::string& why) const {
        out.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec4(0.0f));
        gl.MemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
        gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl.BindTexture(GL_TEXTURE_2D, outputs[index]);
        gl.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, out.data());
        why = gl.errors(label);
        return why.empty();
    }

    void release() {
        const GLuint programs[3] = {clouds, counted, sky};
        for (GLuint p : programs)
            if (p != 0) gl.DeleteProgram(p);
        for (GLuint p : quality) gl.DeleteProgram(p);
        const GLuint textures[9] = {perlin, worley, weather, outputs[0], outputs[1], outputs[2], outputs[3], sky_texture, depth};
        for (GLuint t : textures)
            if (t != 0) gl.DeleteTextures(1, &t);
        if (sky_fbo != 0) gl.DeleteFramebuffers(1, &sky_fbo);
        if (quad_vao != 0) gl.DeleteVertexArrays(1, &quad_vao);
        if (quad_vbo != 0) gl.DeleteBuffers(1, &quad_vbo);
        if (counters != 0) gl.DeleteBuffers(1, &counters);
    }
};

peer_clouds::peer_clouds(std::unique_ptr<state> s) : s_(std::move(s)) {}
peer_clouds::~peer_clouds() {
    if (s_) s_->release();
}

std::unique_ptr<peer_clouds> peer_clouds::create(const std::string& peer_dir, proc_loader load, bool quiet, std::string& why) {
    // Every file first, so a wrong --peer fails before any slow work.
    const char* names[6] = {"volumetric_clouds.comp", "perlinworley.comp", "worley.comp", "weather.comp", "sky.frag", "screen.vert"};
    std::string sources[6];
    for (int i = 0; i < 6; ++i) {
        const std::string path = peer_dir + "/shaders/" + names[i];
        if (!read_text(path, sources[i]) || sources[i].empty()) {
            why = "cannot read " + path + " (--peer must name a checkout of fede-vaccaro/TerrainEngine-OpenGL)";
            return nullptr;
        }
    }
    auto s = std::make_unique<state>();
    s->quiet = quiet;
    const std::string missing = s->gl.load(load, true);
    if (!missing.empty()) {
        why = "OpenGL function " + missing + " not available";
        return nullptr;
    }
    GLint major = 0, minor = 0;
    s->gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    s->gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 43) {
        why = "OpenGL " + std::to_string(major) + "." + std::to_string(minor) + " context; the peer's compute shaders need 4.3";
        return nullptr;
    }
    std::unique_ptr<peer_clouds> peer(new peer_clouds(std::move(s)));
    state& st = *peer->s_;
    st.sky_vert = sources[5];
    st.sky_frag = sources[4];
    st.clouds_source = sources[0];

    const instrumented_shader counted = instrument_texture_reads(sources[0], why);
    if (counted.source.empty()) return nullptr;
    st.light_attributed = counted.light_attributed;
    st.light_note = counted.light_note;
    st.clouds = st.compute_program(sources[0], "volumetric_clouds.comp", why);
    if (st.clouds == 0) return nullptr;
    st.counted = st.compute_program(counted.source, "volumetric_clouds.comp (instrumented copy)", why);
    if (st.counted == 0) return nullptr;
    st.note("volumetric_clouds.comp compiled (as shipped and instrumented)");

    if (!st.bake_volume(sources[1], "perlinworley.comp", perlin_size, perlin_group, st.perlin, why) ||
        !st.bake_volume(sources[2], "worley.comp", worley_size, worley_group, st.worley, why) ||
        !st.bake_weather(sources[3], why))
        return nullptr;
    return peer;
}

bool peer_clouds::prepare(int width, int height, const peer_view& view, std::string& why) {
    state& st = *s_;
    const gl_api& gl = st.gl;
    if (width != st.width || height != st.height) {
        st.width = width;
        st.height = height;
        for (GLuint& t : st.outputs) {
            if (t != 0) gl.DeleteTextures(1, &t);
            t = st.plane(width, height);  // TextureSet: generateTexture2D each
        }
        if (st.sky_texture != 0) gl.DeleteTextures(1, &st.sky_texture);
        st.sky_texture = st.plane(width, height);  // FrameBufferObject's colour texture: RGBA32F, bilinear
        if (st.depth == 0) {
            // The scene's depth: all far (1.0), "no terrain". The shipped shader does not read
            // it (its only use is commented out), but the engine binds it, so we do.
            gl.GenTextures(1, &st.depth);
            gl.BindTexture(GL_TEXTURE_2D, st.depth);
            const float far_depth = 1.0f;
            gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, 1, 1, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &far_depth);
            gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        }
    }
    if (!st.draw_sky(view, why)) return false;
    st.last_view = view;
    st.set_clouds_uniforms(st.clouds, view);
    st.set_clouds_uniforms(st.counted, view);
    for (GLuint p : st.quality) st.set_clouds_uniforms(p, view);
    why = gl.errors("setting the peer's uniforms");
    return why.empty();
}

bool peer_clouds::dispatch(double& wall_ms, std::string& why) {
    return s_->timed_dispatch(s_->clouds, "the clouds dispatch", wall_ms, why);
}

int peer_clouds::add_quality_program(int view_steps, int light_steps, std::string& why) {
    state& st = *s_;
    const std::string source = with_quality_knobs(st.clouds_source, view_steps, light_steps, why);
    if (source.empty()) return -1;
    const std::string label = "volumetric_clouds.comp (" + std::to_string(view_steps) + " view steps, " +
                              std::to_string(light_steps) + " light samples)";
    const GLuint program = st.compute_program(source, label, why);
    if (program == 0) return -1;
    st.quality.push_back(program);
    st.set_clouds_uniforms(program, st.last_view);
    why = st.gl.errors(label.c_str());
    return why.empty() ? static_cast<int>(st.quality.size()) - 1 : -1;
}

bool peer_clouds::dispatch_quality(int program, float jitter, double& wall_ms, std::string& why) {
    state& st = *s_;
    if (program < 0 || static_cast<std::size_t>(program) >= st.quality.size()) {
        why = "dispatch_quality: no such program";
        return false;
    }
    const GLuint p = st.quality[static_cast<std::size_t>(program)];
    st.gl.UseProgram(p);
    st.gl.Uniform1f(st.gl.GetUniformLocation(p, jitter_uniform), jitter);
    return st.timed_dispatch(p, "the clouds dispatch (quality knobs)", wall_ms, why);
}

bool peer_clouds::read_marched(std::vector<char>& mask, std::string& why) {
    std::vector<glm::vec4> distance;  // cloudDistance: -1 where the fog test skipped the march
    if (!s_->read_output(3, distance, "reading cloudDistance", why)) return false;
    mask.assign(distance.size(), 0);
    for (std::size_t i = 0; i < distance.size(); ++i) mask[i] = distance[i].x == -1.0f ? 0 : 1;
    return true;
}

bool peer_clouds::count_reads(peer_reads& out, std::string& why) {
    state& st = *s_;
    const gl_api& gl = st.gl;
    const std::size_t pixels = static_cast<std::size_t>(st.width) * static_cast<std::size_t>(st.height);
    std::vector<std::uint32_t> counts(pixels * counters_per_pixel, 0u);
    const auto bytes = static_cast<GLsizeiptr>(counts.size() * sizeof(std::uint32_t));
    if (st.counters == 0) gl.GenBuffers(1, &st.counters);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, st.counters);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, bytes, counts.data(), GL_DYNAMIC_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, counter_binding, st.counters);
    st.bind_clouds_inputs();
    st.dispatch_clouds(st.counted);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, counts.data());
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    why = gl.errors("the instrumented dispatch");
    if (!why.empty()) return false;

    out = peer_reads{};
    out.pixels = static_cast<int>(pixels);
    out.light_attributed = st.light_attributed;
    out.light_note = st.light_note;
    std::vector<std::uint32_t> marched;
    double all = 0, light = 0, marched_sum = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint32_t* c = &counts[i * counters_per_pixel];
        all += c[0];
        if (c[2] == 0) continue;
        marched.push_back(c[0]);
        marched_sum += c[0];
        light += c[1];
    }
    out.mean_all = pixels ? all / double(pixels) : 0.0;
    out.marched = static_cast<int>(marched.size());
    if (!marched.empty()) {
        out.mean = marched_sum / double(marched.size());
        const std::size_t k = std::min(marched.size() - 1, static_cast<std::size_t>(0.95 * double(marched.size())));
        std::nth_element(marched.begin(), marched.begin() + static_cast<std::ptrdiff_t>(k), marched.end());
        out.p95 = marched[k];
        out.light_share = marched_sum > 0 ? light / marched_sum : 0.0;
    }
    return true;
}

bool peer_clouds::read_image(cloud_renderer::image& out, std::string& why) {
    out.width = s_->width;
    out.height = s_->height;
    return s_->read_output(0, out.pixels, "reading fragColor", why);
}

}  // namespace peer_bench
