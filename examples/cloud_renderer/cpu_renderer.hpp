// The CPU reference: the scene of shaders/clouds.frag rendered with cloudmath's C++
// functions, line for line, on all cores. The density field and the sky are those of
// cloud_density.hpp, which reproduces OpenGL's GL_LINEAR + GL_REPEAT filtering of the same
// UNORM8 texels.
#ifndef CLOUD_RENDERER_CPU_RENDERER_HPP
#define CLOUD_RENDERER_CPU_RENDERER_HPP

#include "image.hpp"
#include "scene.hpp"
#include "textures.hpp"

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
struct texture_read_stats {
    int pixels_in_layer = 0;
    double mean = 0.0, p95 = 0.0, light_share = 0.0;
};
texture_read_stats count_texture_reads(const scene& s, const variant& v, const cloud_textures& textures, int width,
                                       int height, unsigned threads = 0);

image render_cpu_linear(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                        unsigned threads = 0);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_CPU_RENDERER_HPP
