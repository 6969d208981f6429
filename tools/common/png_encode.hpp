// tools/common/png_encode.hpp: a PNG file's bytes in memory, through stb_image_write's
// callback API (stbi_write_png_to_func), so that our code writes them (atomic_file.hpp) and
// checks every step: stbi_write_png itself opens the target with fopen("wb"), truncating
// the old file first, and ignores the errors of fwrite and fclose.
//
// Needs <stb/stb_image_write.h> on the include path and stb's implementation linked (the
// object library cloudmath_stb_image_write of tools/CMakeLists.txt).
#ifndef CLOUDMATH_TOOLS_COMMON_PNG_ENCODE_HPP
#define CLOUDMATH_TOOLS_COMMON_PNG_ENCODE_HPP

#include <stb/stb_image_write.h>

#include <cstddef>
#include <string>

namespace cloudmath::tools {

// The PNG of a width x height image with `channels` interleaved 8-bit channels (1 grey,
// 2 grey-alpha, 3 RGB, 4 RGBA), rows `stride_bytes` apart, top row first. Empty when stb
// fails (bad arguments, out of memory).
[[nodiscard]] inline std::string encode_png(int width, int height, int channels, const void* pixels,
                                            int stride_bytes) {
    std::string png;
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || pixels == nullptr) return png;
    const auto append = [](void* context, void* data, int size) {
        if (size > 0) static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    if (stbi_write_png_to_func(append, &png, width, height, channels, pixels, stride_bytes) == 0) png.clear();
    return png;
}

}  // namespace cloudmath::tools

#endif  // CLOUDMATH_TOOLS_COMMON_PNG_ENCODE_HPP
