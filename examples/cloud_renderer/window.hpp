// The interactive mode: a GLFW window, camera and variant keys, frame time on screen.
#ifndef CLOUD_RENDERER_WINDOW_HPP
#define CLOUD_RENDERER_WINDOW_HPP

#include "options.hpp"
#include "textures.hpp"

namespace cloud_renderer {

// Runs until the window closes; returns the process exit status (1 with a message when no
// window or OpenGL 4.1 context can be created).
int run_window(const options& o, const cloud_textures& textures);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_WINDOW_HPP
