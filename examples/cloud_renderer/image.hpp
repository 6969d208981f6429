// A float RGBA image (rows bottom-up, as OpenGL reads them), PNG output and comparisons.
#ifndef CLOUD_RENDERER_IMAGE_HPP
#define CLOUD_RENDERER_IMAGE_HPP

#include <glm/vec4.hpp>

#include <string>
#include <vector>

namespace cloud_renderer {

struct image {
    int width = 0, height = 0;
    std::vector<glm::vec4> pixels;  // row 0 is the bottom row; rgb display colour, a opacity
    glm::vec4& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
};

// Writes the rgb channels as an 8-bit sRGB PNG, top row first, atomically: to a temporary
// file beside path, checked, then renamed over it (tools/common/atomic_file.hpp), so that a
// failed write leaves the old file and no temporary. False if writing fails, with the
// reason (naming the path) in *error when given.
bool write_png(const std::string& path, const image& img, std::string* error = nullptr);

struct image_stats {
    int nan_pixels = 0;         // pixels with a NaN or Inf in any channel
    double mean_brightness = 0; // mean of (r + g + b) / 3
    double cloud_fraction = 0;  // fraction of pixels with opacity above 0.1
};
image_stats statistics(const image& img);

struct image_difference {
    double psnr_db = 0;         // over rgb in [0, 1]; +inf for identical images
    double max_abs = 0;         // largest channel difference
    double rms = 0;
};
// Requires images of the same size. With a mask (one flag per pixel), only the flagged
// pixels count; no flagged pixel gives psnr_db NaN.
image_difference compare(const image& a, const image& b);
image_difference compare(const image& a, const image& b, const std::vector<char>& mask);

}  // namespace cloud_renderer

#endif  // CLOUD_RENDERER_IMAGE_HPP
