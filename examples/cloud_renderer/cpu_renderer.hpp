// The CPU reference: the scene of shaders/clouds.frag rendered with cloudmath's C++
// functions, line for line, on all cores. The density field and the sky are those of
// cloud_density.hpp, which reproduces OpenGL's GL_LINEAR + GL_REPEAT filtering of the same
// UNORM8 texels.
#ifndef CLOUD_RENDERER_CPU_RENDERER_HPP
#define CLOUD_RENDERER_CPU_RENDERER_HPP

#include "image.hpp"
#include "physical_sky.hpp"
#include "scene.hpp"
#include "textures.hpp"

#include <cloudmath/diffusion_lighting.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace cloud_renderer {

// threads = 0: one per hardware thread. rgb: the display colour (tonemapped), a: opacity.
image render_cpu(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                 unsigned threads = 0);
// The same image before the tonemap: rgb linear radiance (the units of the scene's
// sun_radiance), a: opacity.
// Texture reads of the shader, counted on its CPU twin (same program, same early exits):
// per pixel whose view ray enters the cloud layer, the mean and 95th percentile of all its
// texture() calls, and the share of them made by the light (toward the sun, and away from
// it for the diffusion model).
// shadow_map: the reads of the Beer shadow map's pass (once per frame, whatever the image
// size; not in the per-pixel figures).
struct texture_read_stats {
    int pixels_in_layer = 0;
    double mean = 0.0, p95 = 0.0, light_share = 0.0;
    long shadow_map = 0;
};
texture_read_stats count_texture_reads(const scene& s, const variant& v, const cloud_textures& textures, int width,
                                       int height, unsigned threads = 0);

image render_cpu_linear(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                        unsigned threads = 0);
// render_cpu_linear with the light pass run every `capacity` recorded samples (1..lit_samples)
// instead of every lit_samples: the same image for any capacity (the overflow rule's test).
image render_cpu_lit_capacity(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                              int capacity, unsigned threads = 0);

// The diffusion model's radiance as a linear function of its fitted numbers (the table, then
// the peak weights of diffusion_lighting.hpp), for fitting them to whole-cloud images: per
// pixel, linear radiance = fixed + sun_radiance * sum_i theta_i grad[pixel * count + i]
// (row-major pixels as image), exact but for the model's two max(0, ...) clamps. fixed is
// the image with every fitted number 0. The variant's lighting must be diffusion.
inline constexpr int diffusion_feature_count = cloudmath::diffusion_layout::table_size + cloudmath::diffusion_layout::peak_size;
struct diffusion_features {
    int width = 0, height = 0;
    std::vector<glm::vec3> fixed;
    std::vector<float> grad;
    glm::vec3 sun_radiance{0.0f};
    // The sky light's share (2 per pixel): radiance = ... + ambient_top * sky[2 p] +
    // ambient_bottom * sky[2 p + 1] (already in fixed).
    std::vector<float> sky;
    glm::vec3 ambient_top{0.0f}, ambient_bottom{0.0f};
};
diffusion_features render_cpu_diffusion_features(const scene& s, const variant& v, const cloud_textures& textures,
                                                 int width, int height, unsigned threads = 0);
// render_cpu_linear with another diffusion model than the default's.
image render_cpu_linear_with(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                             const cloudmath::diffusion_model& model, unsigned threads = 0);

// The dither's hash of pixel (x, y) on a frame: another hash of the pixel than the march
// jitter's, new each frame (composite.frag computes the same).
std::uint32_t dither_hash(int x, int y, std::uint32_t frame);
// composite.frag's twin, the last pass of every frame: the cloud layer (rgb premultiplied
// linear radiance, a opacity) over what lies behind it, exposed, tonemapped and, with dither,
// dithered for pixel (x, y) of frame `frame`; a: the layer's opacity.
glm::vec4 composite_display(glm::vec3 behind, glm::vec4 layer, float exposure, bool dither, int x, int y, std::uint32_t frame);

// Temporal rendering, Horizon Zero Dawn's scheme (reprojection.hpp): frame f shades one pixel
// of every 4 x 4 block (temporal_update_offset(f): a quarter-resolution pass, 1/16 of the
// pixels) and takes the other 15 from a full-resolution history, reprojected by the motion
// since the previous frame: the camera's rotation, its change of altitude and the wind's
// offset, at the depth of the block's new sample (the cloud's transmittance-weighted
// distance; 1e7 m where it meets no cloud). A shaded pixel joins its history as a running
// mean of at most max_samples (temporal_blend_weight); its march jitter advances once per
// 16 frames (frame_jitter with frame / 16), so each pixel's samples follow R1. A pixel whose
// point was off the previous screen (disocclusion at the screen edge, or the first frame)
// takes the bilinear interpolation of the new samples until its own turn. The display image is
// the composite (composite_display) of the new history over the background.
// temporal_resolve.frag and composite.frag are the GPU twins.
class cpu_temporal_renderer {
public:
    cpu_temporal_renderer(int width, int height, int max_samples = 8);
    // Frame s.frame of the sequence (frames should count up by one); returns the display image.
    image frame(const scene& s, const variant& v, const cloud_textures& textures, unsigned threads = 0);
    // Forgets the history (the next frame is a first frame).
    void reset() { has_history_ = false; }
    // Texture reads of the last frame per pixel whose ray enters the cloud layer: the shaded
    // pixels' reads over all in-layer pixels of the image.
    texture_read_stats last_reads() const;
    // The physical sky's tables this renderer made and keeps (its own, not the process's:
    // they go with it); make_frame_constants(s, r.sky_tables()) reads the same.
    cpu_sky_tables& sky_tables() { return tables_; }
    const cpu_sky_tables& sky_tables() const { return tables_; }

private:
    int width_, height_, max_samples_;
    bool has_history_ = false;
    scene previous_;
    cpu_sky_tables tables_;
    std::vector<glm::vec4> color_;
    std::vector<glm::vec2> aux_;
    long reads_view_ = 0, reads_light_ = 0, reads_shadow_map_ = 0;  // the last frame's
    // The shadow map, redrawn a slice a frame (temporal_shadow_rows), and the variant and shape
    // it was drawn for (a change redraws the whole of it).
    std::vector<glm::vec3> shadow_map_;
    std::string shadow_map_key_;
};

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_CPU_RENDERER_HPP
