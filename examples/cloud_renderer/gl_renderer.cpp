#include "gl_renderer.hpp"

#include "far_shadow.hpp"
#include "frame_block.hpp"
#include "physical_sky.hpp"
#include "sky_tables_gl.hpp"

#include "clouds_frag.hpp"

#include <cloudmath/glsl.hpp>
#include <cloudmath/reprojection.hpp>

#include "egl_headless.hpp"
#include "gl_functions.hpp"

#include <GL/glcorearb.h>

#include <chrono>
#include <cstddef>
#include <cstring>
#include <cstdio>
#include <initializer_list>
#include <map>
#include <vector>

namespace cloud_renderer {

// ---------------------------------------------------------------------------------------
// Shader sources.

std::string vertex_shader_source() {
    // One triangle that covers the screen; no vertex buffer.
    return "#version 410 core\n"
           "void main() {\n"
           "    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
           "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
           "}\n";
}

namespace {

// `body` with its line `#include "cloudmath.glsl"` (the line itself, not a comment that names
// it) replaced by the library's GLSL.
std::string with_cloudmath(std::string body) {
    const std::string include_line = "\n#include \"cloudmath.glsl\"\n";
    const std::size_t at = body.find(include_line);
    if (at != std::string::npos) body.replace(at, include_line.size(), "\n" + cloudmath::glsl_source("cloudmath") + "\n");
    return body;
}

// A permutation block: the empty CR_PARAM and `const int name = value;` for each constant (the
// shader's CR_PARAM lines, compiled in as constants).
std::string permutation_block(const std::vector<shader_constant>& constants) {
    std::string block = "#define CR_PARAM(type, name)\n";
    for (const shader_constant& c : constants) block += std::string("const int ") + c.name + " = " + std::to_string(c.value) + ";\n";
    return block;
}

}  // namespace

std::string fragment_shader_source(const variant& v, const scene& sc, clouds_pass pass) {
    std::string head = "#version 410 core\n";
    if (sc.sky == sky_model::physical) head += "#define CR_PHYSICAL_SKY 1\n";
    // The permutation's values under the shader's names (clouds.frag's CR_PARAM lines): the
    // pass, and the variant's and the scene's tables (scene.hpp).
    std::vector<shader_constant> constants = {{"u_pass", static_cast<int>(pass)}};
    for (const shader_constant& c : scene_constants(sc)) constants.push_back(c);
    for (const shader_constant& c : variant_constants(v)) constants.push_back(c);
    return head + permutation_block(constants) + with_cloudmath(clouds_frag_text);
}

std::string temporal_resolve_shader_source() { return "#version 410 core\n" + with_cloudmath(temporal_resolve_frag_text); }

std::string composite_shader_source(const scene& sc) {
    return "#version 410 core\n" + permutation_block(scene_constants(sc, switch_shader::composite)) + with_cloudmath(composite_frag_text);
}

std::string sky_tables_shader_source() { return "#version 410 core\n" + with_cloudmath(sky_tables_frag_text); }

// The GL entry points (tools/egl's table, loaded at run time: no loader library).
using gl_api = cloudmath_egl::gl_functions;

struct gl_renderer::state {
    // Only for the headless context this class created (tools/egl); null on the caller's.
    std::unique_ptr<cloudmath_egl::headless_context> egl;

    gl_api gl;
    GLuint vao = 0, queries[2] = {0, 0};  // GL_TIMESTAMP before and after the draw
    GLuint textures[5] = {0, 0, 0, 0, 0};  // base, detail, weather, weather_wide, curl
    GLuint fbo = 0, target = 0;      // offscreen float target for render()
    gpu_sky_tables sky;              // the physical sky's tables, drawn on the GPU (sky_tables_gl.hpp)
    // ... and its clouds' shadow beyond the light march (far_shadow.hpp): an RGBA32F n_alt x n_mu
    // target that clouds.frag's pass 4 draws (ensure_far_shadow), its framebuffer, a 1 x 1
    // stand-in bound while it is drawn, and what it was drawn for (empty: not yet).
    GLuint far_shadow = 0, far_shadow_fbo = 0, far_shadow_stand_in = 0;
    std::vector<float> far_shadow_key;
    float textures_uploaded = 0.0f;  // upload_textures' count: the far shadow's field changes with them
    // The Beer shadow map (clouds.frag's pass 2): an RGBA32F target and its framebuffer.
    struct shadow_target {
        GLuint fbo = 0, map = 0;
    };
    shadow_target shadow;  // the full frame's, drawn whole every frame
    int target_w = 0, target_h = 0;
    std::map<std::string, GLuint> programs;  // by permutation_key, pass and sky; composite.frag's by its switches

    // The full frame (draw): clouds.frag's pass 3 (what lies behind the layer, the scene's depth)
    // and pass 0 (the layer, its depth) at full resolution, for composite.frag to combine.
    struct frame_targets {
        int width = 0, height = 0;
        GLuint background_fbo = 0, background = 0, scene_depth = 0;
        GLuint layer_fbo = 0, layer = 0, layer_depth = 0;
    } frame;

    // Temporal rendering (render_temporal): the quarter-resolution shading target (linear
    // radiance + opacity, depth), two full-resolution histories (colour, depth + samples)
    // written in turn, and the display image composite.frag writes from the new history.
    struct temporal_targets {
        int width = 0, height = 0;
        GLuint fresh_fbo = 0, fresh[2] = {0, 0};
        GLuint background_fbo = 0, background = 0;  // clouds.frag's pass 3: what lies behind the layer
        GLuint scene_depth = 0;                      // ... and the scene's (the terrain's) depth
        GLuint history_fbo[2] = {0, 0}, history[2][2] = {{0, 0}, {0, 0}}, display_fbo = 0, display = 0;
        GLuint resolve_program = 0;
        // Its own shadow map, a slice a frame: a full frame in between (another variant, another
        // scene) does not make it redraw the whole map.
        shadow_target shadow;
        std::string shadow_map_key;  // what the shadow map was last drawn whole for (empty: redraw it whole)
        int current = 0;          // the history the next resolve reads
        bool has_history = false;
        scene previous;
    } temporal;

    std::string gl_errors(const char* where) const { return gl.errors(where); }

    // Links a vertex and a fragment shader (and deletes them); 0 and the log on failure.
    GLuint link(GLuint vs, GLuint fs, std::string& why) const {
        const GLuint shaders[2] = {vs, fs};
        return gl.link(shaders, 2, "shader program", why);
    }

    // The frame's constants (clouds.frag's CrFrame, frame_block.hpp): one buffer on binding 0,
    // uploaded when its bytes change (a frame's passes share them).
    GLuint frame_ubo = 0;
    frame_block uploaded{};
    bool has_uploaded = false;
    void upload_frame_block(const frame_block& b) {
        if (frame_ubo == 0) {
            gl.GenBuffers(1, &frame_ubo);
            gl.BindBuffer(GL_UNIFORM_BUFFER, frame_ubo);
            gl.BufferData(GL_UNIFORM_BUFFER, sizeof(frame_block), nullptr, GL_DYNAMIC_DRAW);
        }
        gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, frame_ubo);
        if (has_uploaded && std::memcmp(&b, &uploaded, sizeof b) == 0) return;
        gl.BindBuffer(GL_UNIFORM_BUFFER, frame_ubo);
        gl.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof b, &b);
        uploaded = b;
        has_uploaded = true;
    }

    // Binds program p's CrFrame to binding 0 after checking its layout against frame_block's:
    // the block's size and every member's offset (a member on one side alone, or moved, names
    // itself here). False and `why` on a mismatch.
    bool bind_frame_block(GLuint p, std::string& why) const {
        const GLuint index = gl.GetUniformBlockIndex(p, "CrFrame");
        if (index == GL_INVALID_INDEX) {
            why = "clouds.frag has no uniform block CrFrame";
            return false;
        }
        GLint size = 0;
        gl.GetActiveUniformBlockiv(p, index, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
        std::string wrong;
        if (size != GLint(sizeof(frame_block)))
            wrong += " size " + std::to_string(size) + " (frame_block: " + std::to_string(sizeof(frame_block)) + ")";
#define CLOUD_RENDERER_CHECK_MEMBER(member)                                                                        \
        {                                                                                                          \
            const char* name = "u_" #member;                                                                       \
            const std::string array_name = std::string(name) + "[0]";                                              \
            GLuint at = GL_INVALID_INDEX;                                                                          \
            gl.GetUniformIndices(p, 1, &name, &at);                                                                \
            if (at == GL_INVALID_INDEX) {                                                                          \
                const char* first = array_name.c_str();                                                           \
                gl.GetUniformIndices(p, 1, &first, &at);                                                           \
            }                                                                                                      \
            GLint offset = -1;                                                                                     \
            if (at != GL_INVALID_INDEX) gl.GetActiveUniformsiv(p, 1, &at, GL_UNIFORM_OFFSET, &offset);             \
            if (at != GL_INVALID_INDEX && offset != GLint(offsetof(frame_block, member)))                           \
                wrong += std::string(" ") + name + " at " + std::to_string(offset) + " (frame_block: " +           \
                         std::to_string(offsetof(frame_block, member)) + ")";                                      \
        }
        CLOUD_RENDERER_FRAME_BLOCK_MEMBERS(CLOUD_RENDERER_CHECK_MEMBER)
#undef CLOUD_RENDERER_CHECK_MEMBER
        if (!wrong.empty()) {
            why = "clouds.frag's CrFrame does not match frame_block.hpp:" + wrong;
            return false;
        }
        gl.UniformBlockBinding(p, index, 0);
        return true;
    }

    // Compiles and links the full-screen vertex shader with fragment shader `source`; 0 and
    // `why` on failure.
    GLuint full_screen_program(const std::string& source, const char* what, std::string& why) const {
        const GLuint vs = gl.compile(GL_VERTEX_SHADER, vertex_shader_source(), "vertex shader", why);
        if (vs == 0) return 0;
        const GLuint fs = gl.compile(GL_FRAGMENT_SHADER, source, what, why);
        if (fs == 0) {
            gl.DeleteShader(vs);
            return 0;
        }
        return link(vs, fs, why);
    }

    // composite.frag's program for the scene's composite switches (compiled on first use).
    GLuint composite_program(const scene& sc, std::string& why) {
        std::string key = "composite";
        for (const shader_constant& c : scene_constants(sc, switch_shader::composite)) key += std::string("/") + c.name + "=" + std::to_string(c.value);
        const auto found = programs.find(key);
        if (found != programs.end()) return found->second;
        const GLuint p = full_screen_program(composite_shader_source(sc), "composite shader", why);
        if (p != 0) programs[key] = p;
        return p;
    }

    GLuint program_for(const variant& v, const scene& sc, clouds_pass pass, std::string& why) {
        // One program per permutation (the variant, the scene's switches, the pass and the sky).
        const std::string key = permutation_key(v, sc) + "/pass" + std::to_string(static_cast<int>(pass)) +
                                (sc.sky == sky_model::physical ? "/physical" : "");
        const auto found = programs.find(key);
        if (found != programs.end()) return found->second;
        const GLuint p = full_screen_program(fragment_shader_source(v, sc, pass), "fragment shader", why);
        if (p == 0) return 0;
        if (!bind_frame_block(p, why)) {
            gl.DeleteProgram(p);
            return 0;
        }
        programs[key] = p;
        return p;
    }

    void release_gl() {
        if (gl.DeleteProgram == nullptr) return;  // loading failed: nothing was created
        for (auto& [key, p] : programs) gl.DeleteProgram(p);
        programs.clear();
        gl.DeleteTextures(5, textures);
        if (target) gl.DeleteTextures(1, &target);
        release_shadow(shadow);
        sky.release(gl);
        if (far_shadow) gl.DeleteTextures(1, &far_shadow);
        if (far_shadow_stand_in) gl.DeleteTextures(1, &far_shadow_stand_in);
        if (far_shadow_fbo) gl.DeleteFramebuffers(1, &far_shadow_fbo);
        if (fbo) gl.DeleteFramebuffers(1, &fbo);
        if (vao) gl.DeleteVertexArrays(1, &vao);
        if (frame_ubo) gl.DeleteBuffers(1, &frame_ubo);
        if (queries[0]) gl.DeleteQueries(2, queries);
        release_frame();
        release_temporal();
    }

    void release_frame() {
        frame_targets& f = frame;
        const GLuint fbos[2] = {f.background_fbo, f.layer_fbo};
        const GLuint textures_[4] = {f.background, f.scene_depth, f.layer, f.layer_depth};
        if (f.background_fbo) gl.DeleteFramebuffers(2, fbos);
        if (f.background) gl.DeleteTextures(4, textures_);
        f = frame_targets{};
    }

    void release_temporal() {
        temporal_targets& t = temporal;
        if (t.resolve_program) gl.DeleteProgram(t.resolve_program);
        if (t.fresh_fbo) gl.DeleteFramebuffers(1, &t.fresh_fbo);
        if (t.history_fbo[0]) gl.DeleteFramebuffers(2, t.history_fbo);
        if (t.fresh[0]) gl.DeleteTextures(2, t.fresh);
        if (t.background_fbo) gl.DeleteFramebuffers(1, &t.background_fbo);
        if (t.background) gl.DeleteTextures(1, &t.background);
        if (t.scene_depth) gl.DeleteTextures(1, &t.scene_depth);
        for (GLuint* h : t.history)
            if (h[0]) gl.DeleteTextures(2, h);
        if (t.display) gl.DeleteTextures(1, &t.display);
        if (t.display_fbo) gl.DeleteFramebuffers(1, &t.display_fbo);
        release_shadow(t.shadow);
        t = temporal_targets{};
    }

    void release_shadow(shadow_target& t) {
        if (t.map) gl.DeleteTextures(1, &t.map);
        if (t.fbo) gl.DeleteFramebuffers(1, &t.fbo);
        t = shadow_target{};
    }

    // GL objects go while the context is current; `egl` then destroys the context.
    ~state() {
        if (egl && egl->make_current()) release_gl();
    }
};

namespace {

// Loads the GL functions and creates the objects every draw needs; checks the version.
bool init_gl(gl_renderer::state& s, gl_renderer::proc_loader load, std::string& why) {
    const std::string missing = s.gl.load(load, false);
    if (!missing.empty()) {
        why = "OpenGL function " + missing + " not available";
        return false;
    }
    GLint major = 0, minor = 0;
    s.gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    s.gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 41) {
        why = "OpenGL " + std::to_string(major) + "." + std::to_string(minor) + " context; the renderer needs 4.1 core";
        return false;
    }
    s.gl.GenVertexArrays(1, &s.vao);
    s.gl.GenQueries(2, s.queries);
    s.gl.GenTextures(5, s.textures);
    why = s.gl_errors("context setup");
    return why.empty();
}

}  // namespace

gl_renderer::gl_renderer(std::unique_ptr<state> s) : s_(std::move(s)) {}
gl_renderer::~gl_renderer() {
    if (s_ && !s_->egl) s_->release_gl();  // the caller's context: still current
}

std::unique_ptr<gl_renderer> gl_renderer::create_headless(std::string& why) {
    auto s = std::make_unique<state>();
    s->egl = cloudmath_egl::headless_context::open(4, 1, cloudmath_egl::platform::any, why);
    if (!s->egl) {
        why = "no OpenGL context could be created (" + why + ")";
        return nullptr;
    }
    if (!init_gl(*s, &cloudmath_egl::gl_proc, why)) return nullptr;
    return std::unique_ptr<gl_renderer>(new gl_renderer(std::move(s)));
}

std::unique_ptr<gl_renderer> gl_renderer::create_for_current_context(proc_loader load, std::string& why) {
    auto s = std::make_unique<state>();
    if (!init_gl(*s, load, why)) return nullptr;
    return std::unique_ptr<gl_renderer>(new gl_renderer(std::move(s)));
}

std::string gl_renderer::device() const {
    const auto text = [this](GLenum e) {
        const GLubyte* t = s_->gl.GetString(e);
        return t ? std::string(reinterpret_cast<const char*>(t)) : std::string("?");
    };
    return text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
}

bool gl_renderer::upload_textures(const cloud_textures& t, std::string& why) {
    const gl_api& gl = s_->gl;
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // GL_LINEAR and GL_REPEAT, level 0 only (cloud_density.hpp's linear_texture is its twin).
    const auto upload = [&](GLenum target, GLuint tex, GLint internal, GLenum format, int n, const std::vector<std::uint8_t>& texels) {
        gl.BindTexture(target, tex);
        if (target == GL_TEXTURE_3D)
            gl.TexImage3D(target, 0, internal, n, n, n, 0, format, GL_UNSIGNED_BYTE, texels.data());
        else
            gl.TexImage2D(target, 0, internal, n, n, 0, format, GL_UNSIGNED_BYTE, texels.data());
        gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TexParameteri(target, GL_TEXTURE_MAX_LEVEL, 0);
        gl.TexParameteri(target, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl.TexParameteri(target, GL_TEXTURE_WRAP_T, GL_REPEAT);
        gl.TexParameteri(target, GL_TEXTURE_WRAP_R, GL_REPEAT);
    };
    upload(GL_TEXTURE_3D, s_->textures[0], GL_RGBA8, GL_RGBA, t.base_size, t.base);
    upload(GL_TEXTURE_3D, s_->textures[1], GL_RGB8, GL_RGB, t.detail_size, t.detail);
    upload(GL_TEXTURE_2D, s_->textures[2], GL_RGB8, GL_RGB, t.weather_size, t.weather);
    upload(GL_TEXTURE_2D, s_->textures[3], GL_RGB8, GL_RGB, t.weather_wide_size, t.weather_wide);
    upload(GL_TEXTURE_2D, s_->textures[4], GL_RGB8, GL_RGB, t.curl_size, t.curl);
    s_->textures_uploaded += 1.0f;
    why = s_->gl_errors("texture upload");
    return why.empty();
}

namespace {

// A float render target (sky_tables_gl.hpp's float_texture without texels).
void make_target(const gl_api& gl, GLuint tex, GLenum internal_format, GLenum format, int width, int height) {
    float_texture(gl, tex, internal_format, format, width, height, nullptr);
}

// GL_LINEAR filtering for a make_target texture that a pass reads between texels (texture());
// texelFetch reads ignore it.
void linear_filter(const gl_api& gl, GLuint tex) {
    gl.BindTexture(GL_TEXTURE_2D, tex);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

// New RGBA32F colour and R32F depth targets of width x height on framebuffer fbo's attachments
// 0 and 1 (clouds.frag's two outputs); false if the framebuffer is not complete.
bool colour_and_depth(const gl_api& gl, GLuint fbo, GLuint colour, GLuint depth, int width, int height) {
    make_target(gl, colour, GL_RGBA32F, GL_RGBA, width, height);
    make_target(gl, depth, GL_R32F, GL_RED, width, height);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, depth, 0);
    return gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

// Sets uniforms of one program by name (the location lookups of both passes).
struct uniform_setter {
    const gl_api& gl;
    GLuint program;
    GLint loc(const char* n) const { return gl.GetUniformLocation(program, n); }
    void i1(const char* n, int x) const { gl.Uniform1i(loc(n), x); }
    void f1(const char* n, float x) const { gl.Uniform1f(loc(n), x); }
    void v2(const char* n, glm::vec2 x) const { gl.Uniform2f(loc(n), x.x, x.y); }
    void v3(const char* n, const glm::vec3& x) const { gl.Uniform3f(loc(n), x.x, x.y, x.z); }
    void u2(const char* n, glm::uvec2 x) const { gl.Uniform2ui(loc(n), x.x, x.y); }
};

// The frame's constants: with the physical sky, from its tables drawn on the GPU (drawn first
// when the sun or the geometry changed); false and `why` on a GL error.
bool frame_for(gl_renderer::state& st, const scene& sc, frame_constants& k, std::string& why) {
    if (sc.sky != sky_model::physical) {
        k = make_frame_constants(sc);
        return true;
    }
    if (!st.sky.update(st.gl, vertex_shader_source(), st.vao, sc, why)) return false;
    k = make_frame_constants(sc, st.sky.inputs());
    return true;
}

GLuint bind_clouds(gl_renderer::state& st, const scene& sc, const variant& v, const frame_constants& k, int width, int height,
                   clouds_pass pass, glm::uvec2 offset, std::string& why);

// Draws the physical sky's far shadow for the scene and variant (clouds.frag's pass 4 into
// st.far_shadow, far_shadow_nodes' size and range) unless it holds that table already: what
// far_shadow() keys its CPU table by, the uploaded textures for their bytes. 0.3-0.6 s on
// llvmpipe, once per scene, sun and reach; outside the frame's timing. The CPU renderer keeps
// its own table (far_shadow()), which this one matches to test_cloud_renderer's bounds.
// `frame`: the frame's constants (frame_for's), which pass 4 reads as every pass does.
bool ensure_far_shadow(gl_renderer::state& st, const scene& sc, const variant& v, const frame_constants& frame, std::string& why) {
    const gl_api& gl = st.gl;
    const frame_constants k = geometry_constants(sc);
    const float reach = light_reach(v, k);
    std::vector<float> key = far_shadow_scene_key(sc, k.sun_dir, reach);
    key.push_back(st.textures_uploaded);
    if (st.far_shadow != 0 && key == st.far_shadow_key) return true;
    const far_shadow_table f = far_shadow_nodes(sc, reach);
    if (st.far_shadow == 0) {
        gl.ActiveTexture(GL_TEXTURE7);  // make_target binds to the active unit: the table's own
        gl.GenTextures(1, &st.far_shadow_stand_in);
        make_target(gl, st.far_shadow_stand_in, GL_RGBA32F, GL_RGBA, 1, 1);
        gl.GenTextures(1, &st.far_shadow);
        make_target(gl, st.far_shadow, GL_RGBA32F, GL_RGBA, f.n_alt, f.n_mu);
        gl.GenFramebuffers(1, &st.far_shadow_fbo);
        gl.BindFramebuffer(GL_FRAMEBUFFER, st.far_shadow_fbo);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, st.far_shadow, 0);
        const bool complete = gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        if (!complete) {
            why = "the far shadow's float target is not supported (framebuffer incomplete)";
            return false;
        }
    }
    const GLuint program = bind_clouds(st, sc, v, frame, f.n_alt, f.n_mu, clouds_pass::far_shadow, glm::uvec2(0), why);
    if (program == 0) return false;
    const GLenum one = GL_COLOR_ATTACHMENT0;
    gl.BindFramebuffer(GL_FRAMEBUFFER, st.far_shadow_fbo);
    gl.DrawBuffers(1, &one);
    gl.Viewport(0, 0, f.n_alt, f.n_mu);
    gl.UseProgram(program);
    gl.BindVertexArray(st.vao);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    why = st.gl_errors("the far shadow's pass");
    if (!why.empty()) return false;
    st.far_shadow_key = key;
    return true;
}

// Makes the clouds program of the variant's pass current with every uniform of the scene set
// and the cloud textures bound; 0 on failure. clouds_pass::temporal_shading shades pixel
// 4 (i, j) + offset. k: the frame's constants, frame_for's for the scene, made once per frame by
// the caller before any pass is bound (drawing the sky tables binds their own program and target).
GLuint bind_clouds(gl_renderer::state& st, const scene& sc, const variant& v, const frame_constants& k, int width, int height,
                   clouds_pass pass, glm::uvec2 offset, std::string& why) {
    // scene::light splits the truth tool's light by source: the sky alone is drawn (its frame
    // only lacks the sun), the sun alone is for the CPU reference only: without the sky its
    // frame has no sky-view table to bind.
    if (sc.light == light_sources::sun) {
        why = "scene::light sun is the truth tool's split by source for the CPU reference; the GL renderer draws all "
              "the light or the sky's alone";
        return 0;
    }
    const gl_api& gl = st.gl;
    // The physical sky's far shadow, drawn on the GPU when what it depends on changes (pass 4
    // binds its own program through this function: it draws no far shadow itself).
    if (sc.sky == sky_model::physical && pass != clouds_pass::far_shadow && !ensure_far_shadow(st, sc, v, k, why)) return 0;
    const GLuint program = st.program_for(v, sc, pass, why);
    if (program == 0) return 0;
    gl.UseProgram(program);
    const uniform_setter u{gl, program};
    // The frame's constants: one block (CrFrame), filled here and uploaded when it changed.
    frame_block b{};
    b.forward = k.forward;
    b.tan_half_fov = k.tan_half_fov;
    b.right = k.right;
    b.cam_altitude = sc.camera_altitude;
    b.up = k.up;
    b.planet_radius = sc.planet_radius;
    b.sun_dir = k.sun_dir;
    b.layer_bottom = sc.layer_bottom;
    b.sun_radiance = k.sun_radiance;
    b.layer_top = sc.layer_top;
    b.ambient_top = k.ambient_top;
    b.sun_angular_radius = k.sun_angular_radius;
    b.ambient_bottom = k.ambient_bottom;
    b.aureole = k.aureole;
    b.sky_zenith = k.sky_zenith;
    b.coverage = sc.coverage;
    b.sky_horizon = k.sky_horizon;
    b.cloud_type = sc.cloud_type;
    b.ground = k.ground;
    b.extinction = sc.extinction;
    b.shadow_origin = k.shadow_origin;
    b.albedo = sc.albedo;
    b.shadow_right = k.shadow_right;
    b.max_distance = sc.max_distance;
    b.shadow_up = k.shadow_up;
    b.shadow_half_extent = k.shadow_half_extent;
    for (int i = 0; i < 4; ++i) b.terrain_boxes[i] = glm::vec4(terrain_boxes[i].x, terrain_boxes[i].z, terrain_boxes[i].half_width, terrain_boxes[i].top);
    for (int i = 0; i < sun_heights; ++i) b.sun_by_height[i] = glm::vec4(k.sun_by_height[i], 0.0f);
    b.resolution = glm::vec2(float(width), float(height));
    b.band = k.band;
    b.wind = sc.wind;
    b.update_offset = offset;
    b.frame = sc.frame;
    b.exposure = k.exposure;
    b.base_tile = sc.base_tile;
    b.detail_tile = sc.detail_tile;
    b.weather_tile = sc.weather_tile;
    b.weather_wide_tile = sc.weather_wide_tile;
    b.curl_tile = sc.curl_tile;
    b.curl_strength = sc.curl_strength;
    b.type_spread = sc.type_spread;
    b.top_rounding = sc.top_rounding;
    b.density_scale = sc.density_scale;
    b.phase_g = k.phase_g;
    b.phase_g_back = k.phase_g_back;
    b.phase_w = k.phase_w;
    b.droplet_diameter = k.droplet_diameter;
    b.ms_a = k.ms_a;
    b.ms_b = k.ms_b;
    b.ms_c = k.ms_c;
    b.phase_mean_cosine = phase_mean_cosine(k, v.phase);
    b.cone_step = k.cone_step;
    b.cone_spread = k.cone_spread;
    b.cone_far_distance = k.cone_far_distance;
    b.cone_far_length = k.cone_far_length;
    b.light_march_max = k.light_march_max;
    b.min_transmittance = k.min_transmittance;
    b.march_near_distance = k.march_near_distance;
    // Units 0-2 and 4-5 (3 is the shadow map's, bound by shadow_pass).
    struct unit {
        const char* sampler;
        GLenum kind;
        int texture, index;
    };
    const unit units[5] = {{"u_base", GL_TEXTURE_3D, 0, 0},
                           {"u_detail", GL_TEXTURE_3D, 1, 1},
                           {"u_weather", GL_TEXTURE_2D, 2, 2},
                           {"u_weather_wide", GL_TEXTURE_2D, 3, 4},
                           {"u_curl", GL_TEXTURE_2D, 4, 5}};
    for (const unit& t : units) {
        gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + t.index));
        gl.BindTexture(t.kind, st.textures[t.texture]);
        u.i1(t.sampler, t.index);
    }
    u.i1("u_shadow_map", 3);
    if (sc.sky == sky_model::physical) {
        // The aerial-perspective table on unit 6 (drawn on the GPU by frame_for; no filtering:
        // clouds.frag interpolates it as haze_lookup does).
        const haze_table& t = st.sky.haze_layout();
        gl.ActiveTexture(GL_TEXTURE6);
        gl.BindTexture(GL_TEXTURE_2D, st.sky.haze_texture());
        u.i1("u_haze_table", 6);
        b.haze_table_size = glm::vec3(float(t.n_d), float(t.n_az), float(t.n_el));
        b.haze_table_distance = t.max_distance;
        // The far shadow on unit 7 (drawn by pass 4, ensure_far_shadow; while pass 4 draws it, a
        // stand-in) and the sky-view table on unit 8, read as the haze table is.
        const far_shadow_table f = far_shadow_nodes(sc, light_reach(v, k));
        gl.ActiveTexture(GL_TEXTURE7);
        gl.BindTexture(GL_TEXTURE_2D, pass == clouds_pass::far_shadow ? st.far_shadow_stand_in : st.far_shadow);
        u.i1("u_far_shadow", 7);
        b.far_shadow_size = glm::vec2(float(f.n_alt), float(f.n_mu));
        b.far_shadow_range = glm::vec4(f.alt_lo, f.alt_hi, f.mu_lo, f.mu_hi);
        // What pass 4 (the table on the GPU) needs beyond its range: the march's end and the
        // field's period (far_shadow.cpp's make_table).
        b.far_shadow_reach = f.reach;
        b.far_shadow_period = sc.shape == cloud_shape::classic ? sc.weather_tile : sc.weather_wide_tile;
        gl.ActiveTexture(GL_TEXTURE8);
        gl.BindTexture(GL_TEXTURE_2D, st.sky.sky_view_texture());
        u.i1("u_sky_view", 8);
    }
    st.upload_frame_block(b);
    return program;
}

// The shadow-map pass's program (bind_clouds with clouds_pass::shadow_map) when the variant
// draws the map (needs_shadow_map), else 0 with `why` empty; 0 and `why` on failure.
GLuint bind_shadow_map(gl_renderer::state& st, const scene& sc, const variant& v, const frame_constants& k, int width, int height,
                       std::string& why) {
    if (!needs_shadow_map(v, sc)) return 0;
    return bind_clouds(st, sc, v, k, width, height, clouds_pass::shadow_map, glm::uvec2(0), why);
}

// Draws rows [rows.x, rows.y) of the Beer shadow map (all: a full frame; a slice: the
// temporal scheme, temporal_shadow_rows) with `shadow_program` (bind_shadow_map's; 0: the
// variant has no map), then binds the map to unit 3 for the passes that read it. Unit 3 holds
// no texture while the map is drawn (no feedback loop). The caller makes its own pass current
// afterwards.
bool shadow_pass(gl_renderer::state& st, gl_renderer::state::shadow_target& target, GLuint shadow_program,
                 std::string& why, glm::ivec2 rows = glm::ivec2(0, shadow_map_size)) {
    const gl_api& gl = st.gl;
    gl.ActiveTexture(GL_TEXTURE3);  // make_target binds to the active unit: not the clouds' 0-2
    if (target.fbo == 0) {
        gl.GenFramebuffers(1, &target.fbo);
        gl.GenTextures(1, &target.map);
        make_target(gl, target.map, GL_RGBA32F, GL_RGBA, shadow_map_size, shadow_map_size);
        gl.BindFramebuffer(GL_FRAMEBUFFER, target.fbo);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.map, 0);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            why = "the shadow map's float target is not supported (framebuffer incomplete)";
            return false;
        }
    }
    gl.ActiveTexture(GL_TEXTURE3);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    if (shadow_program != 0) {
        const GLenum one = GL_COLOR_ATTACHMENT0;
        gl.BindFramebuffer(GL_FRAMEBUFFER, target.fbo);
        gl.DrawBuffers(1, &one);
        gl.Viewport(0, 0, shadow_map_size, shadow_map_size);
        gl.UseProgram(shadow_program);
        const bool slice = rows.x > 0 || rows.y < shadow_map_size;
        if (slice) {
            gl.Enable(GL_SCISSOR_TEST);
            gl.Scissor(0, rows.x, shadow_map_size, rows.y - rows.x);
        }
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        if (slice) gl.Disable(GL_SCISSOR_TEST);
    }
    gl.ActiveTexture(GL_TEXTURE3);
    gl.BindTexture(GL_TEXTURE_2D, target.map);
    return true;
}

// Runs `draws` (which issues the draw calls) between two GPU timestamps and glFinish calls.
// Two timestamps rather than a GL_TIME_ELAPSED query: Mesa 22's llvmpipe returns a
// timestamp, not a duration, for the latter.
template <class Draws>
bool timed(gl_renderer::state& st, frame_timing* timing, std::string& why, Draws draws) {
    const gl_api& gl = st.gl;
    gl.BindVertexArray(st.vao);
    gl.Finish();  // nothing earlier in the wall time
    const auto wall_start = std::chrono::steady_clock::now();
    gl.QueryCounter(st.queries[0], GL_TIMESTAMP);
    draws();
    gl.QueryCounter(st.queries[1], GL_TIMESTAMP);
    gl.Finish();
    const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall_start).count();
    GLuint64 start = 0, end = 0;
    gl.GetQueryObjectui64v(st.queries[0], GL_QUERY_RESULT, &start);
    gl.GetQueryObjectui64v(st.queries[1], GL_QUERY_RESULT, &end);
    if (timing != nullptr) {
        timing->gpu_ms = end > start ? double(end - start) * 1e-6 : 0.0;
        timing->wall_ms = wall_ms;
    }
    why = st.gl_errors("draw");
    return why.empty();
}

// The temporal targets for a width x height image (a new history when the size changes).
bool ensure_temporal_targets(gl_renderer::state& st, int width, int height, std::string& why) {
    auto& t = st.temporal;
    const gl_api& gl = st.gl;
    if (t.resolve_program == 0) {
        t.resolve_program = st.full_screen_program(temporal_resolve_shader_source(), "temporal resolve shader", why);
        if (t.resolve_program == 0) return false;
    }
    if (t.width == width && t.height == height) return true;
    if (t.fresh_fbo == 0) {
        gl.GenFramebuffers(1, &t.fresh_fbo);
        gl.GenFramebuffers(2, t.history_fbo);
        gl.GenTextures(2, t.fresh);
        gl.GenTextures(2, t.history[0]);
        gl.GenTextures(2, t.history[1]);
        gl.GenTextures(1, &t.display);
        gl.GenFramebuffers(1, &t.display_fbo);
        gl.GenFramebuffers(1, &t.background_fbo);
        gl.GenTextures(1, &t.background);
        gl.GenTextures(1, &t.scene_depth);
    }
    const int lw = (width + 3) / 4, lh = (height + 3) / 4;
    bool complete = colour_and_depth(gl, t.fresh_fbo, t.fresh[0], t.fresh[1], lw, lh);
    linear_filter(gl, t.fresh[0]);  // the resolve's Catmull-Rom reads between texels
    complete = colour_and_depth(gl, t.background_fbo, t.background, t.scene_depth, width, height) && complete;
    make_target(gl, t.display, GL_RGBA32F, GL_RGBA, width, height);
    gl.BindFramebuffer(GL_FRAMEBUFFER, t.display_fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.display, 0);
    complete = complete && gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    for (int i = 0; i < 2; ++i) {
        make_target(gl, t.history[i][0], GL_RGBA32F, GL_RGBA, width, height);
        linear_filter(gl, t.history[i][0]);
        make_target(gl, t.history[i][1], GL_RG32F, GL_RG, width, height);
        gl.BindFramebuffer(GL_FRAMEBUFFER, t.history_fbo[i]);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.history[i][0], 0);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, t.history[i][1], 0);
        complete = complete && gl.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
    if (!complete) {
        why = "the temporal float targets are not supported (framebuffer incomplete)";
        return false;
    }
    t.width = width;
    t.height = height;
    t.has_history = false;
    why = st.gl_errors("temporal targets");
    return why.empty();
}

// The full frame's targets for a width x height image.
bool ensure_frame_targets(gl_renderer::state& st, int width, int height, std::string& why) {
    auto& f = st.frame;
    if (f.width == width && f.height == height) return true;
    const gl_api& gl = st.gl;
    gl.ActiveTexture(GL_TEXTURE9);  // make_target binds to the active unit: the composite's, not the clouds' 0-8
    if (f.background_fbo == 0) {
        gl.GenFramebuffers(1, &f.background_fbo);
        gl.GenFramebuffers(1, &f.layer_fbo);
        GLuint t[4];
        gl.GenTextures(4, t);
        f.background = t[0];
        f.scene_depth = t[1];
        f.layer = t[2];
        f.layer_depth = t[3];
    }
    if (!colour_and_depth(gl, f.background_fbo, f.background, f.scene_depth, width, height) ||
        !colour_and_depth(gl, f.layer_fbo, f.layer, f.layer_depth, width, height)) {
        why = "the frame's float targets are not supported (framebuffer incomplete)";
        return false;
    }
    f.width = width;
    f.height = height;
    why = st.gl_errors("frame targets");
    return why.empty();
}

// Draws the current program's full-screen triangle into framebuffer fbo's first `buffers`
// attachments (0: the default framebuffer) over width x height.
void full_screen(const gl_api& gl, GLuint program, GLuint fbo, int buffers, int width, int height) {
    const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl.UseProgram(program);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (fbo != 0) gl.DrawBuffers(buffers, attachments);
    gl.Viewport(0, 0, width, height);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

// composite.frag (program: composite_program's): the layer over the background, the frame's
// exposure, tonemap and dither, into framebuffer fbo. Both inputs on units 9 and 10, which no
// clouds.frag sampler uses.
void composite_pass(const gl_api& gl, GLuint program, float exposure, std::uint32_t frame, GLuint layer, GLuint background,
                    GLuint fbo, int width, int height) {
    gl.UseProgram(program);
    const uniform_setter u{gl, program};
    u.f1("u_exposure", exposure);
    gl.Uniform1ui(u.loc("u_frame"), frame);
    gl.ActiveTexture(GL_TEXTURE9);
    gl.BindTexture(GL_TEXTURE_2D, layer);
    u.i1("u_layer", 9);
    gl.ActiveTexture(GL_TEXTURE10);
    gl.BindTexture(GL_TEXTURE_2D, background);
    u.i1("u_background", 10);
    full_screen(gl, program, fbo, 1, width, height);
}

}  // namespace

bool gl_renderer::draw(const scene& sc, const variant& v, unsigned fbo, int width, int height,
                       frame_timing* timing, std::string& why) {
    if (!ensure_frame_targets(*s_, width, height, why)) return false;
    // The frame's constants once, then every program bound (compiled the first time) and its
    // uniforms set before the timing.
    frame_constants k;
    if (!frame_for(*s_, sc, k, why)) return false;
    const GLuint shadow = bind_shadow_map(*s_, sc, v, k, width, height, why);
    if (shadow == 0 && !why.empty()) return false;
    const GLuint background = bind_clouds(*s_, sc, v, k, width, height, clouds_pass::background, glm::uvec2(0), why);
    if (background == 0) return false;
    const GLuint clouds = bind_clouds(*s_, sc, v, k, width, height, clouds_pass::frame, glm::uvec2(0), why);
    if (clouds == 0) return false;
    const GLuint composite = s_->composite_program(sc, why);
    if (composite == 0) return false;
    const gl_api& gl = s_->gl;
    const auto& f = s_->frame;
    bool shadow_ok = true;
    const bool ok = timed(*s_, timing, why, [&] {
        shadow_ok = shadow_pass(*s_, s_->shadow, shadow, why);
        full_screen(gl, background, f.background_fbo, 2, width, height);  // what lies behind the layer
        full_screen(gl, clouds, f.layer_fbo, 2, width, height);            // the layer
        composite_pass(gl, composite, k.exposure, sc.frame, f.layer, f.background, fbo, width, height);
    });
    return shadow_ok && ok;
}

void gl_renderer::reset_temporal() { s_->temporal.has_history = false; }

bool gl_renderer::draw_temporal(const scene& sc, const variant& v, int width, int height,
                                frame_timing* timing, std::string& why) {
    if (!ensure_temporal_targets(*s_, width, height, why)) return false;
    auto& t = s_->temporal;
    const gl_api& gl = s_->gl;
    const glm::uvec2 offset = cloudmath::temporal_update_offset(sc.frame);
    // The frame's constants once (the frame number is not among them: the shading pass's
    // are the same). The shading pass: one pixel of every 4 x 4 block, the jitter of frame / 16.
    // Every program bound (compiled the first time) and its uniforms set before the timing.
    frame_constants k;
    if (!frame_for(*s_, sc, k, why)) return false;
    scene shading = sc;
    shading.frame = sc.frame >> 4U;
    const GLuint shadow = bind_shadow_map(*s_, shading, v, k, width, height, why);
    if (shadow == 0 && !why.empty()) return false;
    // The shadow map a slice a frame (temporal_shadow_rows): the whole of it on a first frame,
    // or when the variant, the shape or the shader form changed.
    const std::string map_key = permutation_key(v, sc);
    const bool whole_map = !t.has_history || map_key != t.shadow_map_key;
    t.shadow_map_key = map_key;
    const GLuint background = bind_clouds(*s_, shading, v, k, width, height, clouds_pass::background, offset, why);
    if (background == 0) return false;
    const GLuint clouds = bind_clouds(*s_, shading, v, k, width, height, clouds_pass::temporal_shading, offset, why);
    if (clouds == 0) return false;
    const GLuint composite = s_->composite_program(sc, why);
    if (composite == 0) return false;
    const int lw = (width + 3) / 4, lh = (height + 3) / 4;

    // The resolve pass's uniforms (temporal_resolve.frag).
    const GLuint r = t.resolve_program;
    gl.UseProgram(r);
    const uniform_setter u{gl, r};
    const scene& prev = t.has_history ? t.previous : sc;
    const frame_constants pk = geometry_constants(prev);  // its camera
    u.v2("u_resolution", glm::vec2(float(width), float(height)));
    u.v3("u_forward", k.forward);
    u.v3("u_right", k.right);
    u.v3("u_up", k.up);
    u.v3("u_prev_forward", pk.forward);
    u.v3("u_prev_right", pk.right);
    u.v3("u_prev_up", pk.up);
    u.f1("u_tan_half_fov", k.tan_half_fov);
    u.f1("u_prev_tan_half_fov", pk.tan_half_fov);
    u.v3("u_motion", glm::vec3(sc.wind.x - prev.wind.x, sc.camera_altitude - prev.camera_altitude, sc.wind.y - prev.wind.y));
    u.u2("u_update_offset", offset);
    u.i1("u_has_history", t.has_history ? 1 : 0);
    u.f1("u_max_samples", float(temporal_max_samples));
    u.f1("u_tolerance", temporal_reprojection_tolerance);
    u.f1("u_fill_blend", temporal_fill_blend);
    const char* samplers[6] = {"u_fresh", "u_fresh_depth", "u_history", "u_history_aux", "u_background", "u_scene_depth"};
    const GLuint inputs[6] = {t.fresh[0], t.fresh[1], t.history[t.current][0], t.history[t.current][1], t.background, t.scene_depth};
    const int out = 1 - t.current;

    bool shadow_ok = true;
    // With split_passes, each pass's host time (glFinish after it).
    const bool split = timing != nullptr && timing->split_passes;
    auto mark = std::chrono::steady_clock::now();
    const auto lap = [&](double* ms) {
        if (!split) return;
        gl.Finish();
        const auto now = std::chrono::steady_clock::now();
        *ms = std::chrono::duration<double, std::milli>(now - mark).count();
        mark = now;
    };
    double shadow_ms = 0, shading_ms = 0, background_ms = 0, resolve_ms = 0, composite_ms = 0;
    const bool ok = timed(*s_, timing, why, [&] {
        mark = std::chrono::steady_clock::now();
        shadow_ok = shadow_pass(*s_, t.shadow, shadow, why, temporal_shadow_rows(sc.frame, whole_map));
        lap(&shadow_ms);
        full_screen(gl, clouds, t.fresh_fbo, 2, lw, lh);
        lap(&shading_ms);
        // The background pass (clouds.frag's pass 3) at full resolution.
        full_screen(gl, background, t.background_fbo, 2, width, height);
        lap(&background_ms);
        gl.UseProgram(r);
        for (int i = 0; i < 6; ++i) {
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
            gl.BindTexture(GL_TEXTURE_2D, inputs[i]);
            u.i1(samplers[i], i);
        }
        full_screen(gl, r, t.history_fbo[out], 2, width, height);
        lap(&resolve_ms);
        // The new history (the layer) over the background, into the display image.
        composite_pass(gl, composite, k.exposure, sc.frame, t.history[out][0], t.background, t.display_fbo, width, height);
        lap(&composite_ms);
    });
    if (timing != nullptr) {
        timing->shadow_ms = shadow_ms;
        timing->shading_ms = shading_ms;
        timing->background_ms = background_ms;
        timing->resolve_ms = resolve_ms;
        timing->composite_ms = composite_ms;
    }
    if (!ok || !shadow_ok) return false;
    t.current = out;
    t.previous = sc;
    t.has_history = true;
    return true;
}

bool gl_renderer::show_temporal(unsigned fbo, std::string& why) {
    auto& t = s_->temporal;
    const gl_api& gl = s_->gl;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, t.display_fbo);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    gl.BlitFramebuffer(0, 0, t.width, t.height, 0, 0, t.width, t.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    why = s_->gl_errors("temporal display");
    return why.empty();
}

bool gl_renderer::render_temporal(const scene& sc, const variant& v, int width, int height, image& out,
                                  frame_timing* timing, std::string& why) {
    if (!draw_temporal(sc, v, width, height, timing, why)) return false;
    const gl_api& gl = s_->gl;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, s_->temporal.display_fbo);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    out.width = width;
    out.height = height;
    out.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec4(0.0f));
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, out.pixels.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    why = s_->gl_errors("temporal read back");
    return why.empty();
}

bool gl_renderer::read_frame_layers(frame_layers& out, std::string& why) {
    const auto& f = s_->frame;
    if (f.width == 0) {
        why = "no full frame was drawn yet";
        return false;
    }
    const gl_api& gl = s_->gl;
    const std::size_t n = static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height);
    const auto read = [&](GLuint fbo, GLenum attachment, GLenum format, void* to) {
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        gl.ReadBuffer(attachment);
        gl.ReadPixels(0, 0, f.width, f.height, format, GL_FLOAT, to);
    };
    for (image* i : {&out.layer, &out.background}) {
        i->width = f.width;
        i->height = f.height;
        i->pixels.assign(n, glm::vec4(0.0f));
    }
    out.cloud_depth.assign(n, 0.0f);
    out.scene_depth.assign(n, 0.0f);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    read(f.layer_fbo, GL_COLOR_ATTACHMENT0, GL_RGBA, out.layer.pixels.data());
    read(f.layer_fbo, GL_COLOR_ATTACHMENT1, GL_RED, out.cloud_depth.data());
    read(f.background_fbo, GL_COLOR_ATTACHMENT0, GL_RGBA, out.background.pixels.data());
    read(f.background_fbo, GL_COLOR_ATTACHMENT1, GL_RED, out.scene_depth.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    why = s_->gl_errors("reading the frame's layers back");
    return why.empty();
}

bool gl_renderer::far_shadow_gpu(const scene& sc, const variant& v, std::vector<float>& out, std::string& why) {
    if (sc.sky != sky_model::physical) {
        why = "the far shadow is the physical sky's";
        return false;
    }
    state& st = *s_;
    frame_constants k;
    if (!frame_for(st, sc, k, why) || !ensure_far_shadow(st, sc, v, k, why)) return false;
    const far_shadow_table f = far_shadow_nodes(sc, light_reach(v, geometry_constants(sc)));
    std::vector<float> rgba(static_cast<std::size_t>(f.n_alt * f.n_mu) * 4u);
    st.gl.BindFramebuffer(GL_FRAMEBUFFER, st.far_shadow_fbo);
    st.gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    st.gl.ReadPixels(0, 0, f.n_alt, f.n_mu, GL_RGBA, GL_FLOAT, rgba.data());
    st.gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    why = st.gl_errors("reading the far shadow back");
    if (!why.empty()) return false;
    out.resize(static_cast<std::size_t>(f.n_alt * f.n_mu));
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = rgba[4 * i];
    return true;
}

bool gl_renderer::sky_tables_gpu(const scene& sc, gpu_sky_readback& out, std::string& why) {
    if (sc.sky != sky_model::physical) {
        why = "the sky tables are the physical sky's";
        return false;
    }
    state& st = *s_;
    if (!st.sky.update(st.gl, vertex_shader_source(), st.vao, sc, why)) return false;
    const physical_sky_inputs in = st.sky.inputs();
    out.sky_view = in.at_camera->texels;
    out.sky_top = in.at_top->texels;
    out.samples = in.samples;
    out.band = st.sky.band();
    out.build_ms = st.sky.last_build_ms();
    out.builds = st.sky.builds();
    return st.sky.read_haze(st.gl, out.haze, why);
}

bool gl_renderer::render(const scene& sc, const variant& v, int width, int height, image& out,
                         frame_timing* timing, std::string& why) {
    const gl_api& gl = s_->gl;
    if (s_->fbo == 0 || s_->target_w != width || s_->target_h != height) {
        if (s_->fbo == 0) gl.GenFramebuffers(1, &s_->fbo);
        if (s_->target == 0) gl.GenTextures(1, &s_->target);
        gl.BindTexture(GL_TEXTURE_2D, s_->target);
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.BindFramebuffer(GL_FRAMEBUFFER, s_->fbo);
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s_->target, 0);
        if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            why = "the float render target is not supported (framebuffer incomplete)";
            return false;
        }
        s_->target_w = width;
        s_->target_h = height;
    }
    if (!draw(sc, v, s_->fbo, width, height, timing, why)) return false;
    out.width = width;
    out.height = height;
    out.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec4(0.0f));
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, out.pixels.data());
    why = s_->gl_errors("read back");
    return why.empty();
}

}  // namespace cloud_renderer
