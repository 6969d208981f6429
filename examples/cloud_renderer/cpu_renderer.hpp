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
image render_cpu_linear(const scene& s, const variant& v, const cloud_textures& textures, int width, int height,
                        unsigned threads = 0);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_CPU_RENDERER_HPP
