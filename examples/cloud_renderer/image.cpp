#include "image.hpp"

#include "atomic_file.hpp"
#include "png_encode.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace cloud_renderer {

bool write_png(const std::string& path, const image& img, std::string* error) {
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec4& p = img.pixels[static_cast<std::size_t>(img.height - 1 - y) * static_cast<std::size_t>(img.width) +
                                            static_cast<std::size_t>(x)];
            for (int c = 0; c < 3; ++c) {
                const float v = std::isfinite(p[c]) ? (p[c] < 0 ? 0.0f : (p[c] > 1 ? 1.0f : p[c])) : 1.0f;
                rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(x)) * 3 +
                    static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(v * 255.0f + 0.5f);
            }
        }
    // Encoded in memory, then written by our own checked code: stbi_write_png would truncate
    // the old file first and ignore the errors of fwrite and fclose.
    const std::string png = cloudmath::tools::encode_png(img.width, img.height, 3, rgb.data(), img.width * 3);
    std::string why = png.empty() ? "cannot encode '" + path + "' as PNG" : cloudmath::tools::write_file_atomically(path, png);
    if (error != nullptr) *error = why;
    return why.empty();
}

image_stats statistics(const image& img) {
    image_stats s;
    double sum = 0;
    std::size_t clouds = 0, finite = 0;
    for (const glm::vec4& p : img.pixels) {
        if (!(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && std::isfinite(p.a))) {
            ++s.nan_pixels;
            continue;
        }
        ++finite;
        sum += (double(p.r) + double(p.g) + double(p.b)) / 3.0;
        if (p.a > 0.1f) ++clouds;
    }
    if (!img.pixels.empty()) {
        s.mean_brightness = finite ? sum / double(finite) : 0.0;
        s.cloud_fraction = double(clouds) / double(img.pixels.size());
    }
    return s;
}

image_difference compare(const image& a, const image& b) { return compare(a, b, std::vector<char>(a.pixels.size(), 1)); }

image_difference compare(const image& a, const image& b, const std::vector<char>& mask) {
    image_difference d;
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size() && i < mask.size(); ++i)
        for (int c = 0; c < 3 && mask[i]; ++c) {
            double e = double(a.pixels[i][c]) - double(b.pixels[i][c]);
            if (!std::isfinite(e)) e = 1.0;  // a NaN pixel counts as the largest error
            e = std::fabs(e);
            sum += e * e;
            d.max_abs = e > d.max_abs ? e : d.max_abs;
            ++n;
        }
    d.rms = n ? std::sqrt(sum / double(n)) : 0.0;
    d.psnr_db = n == 0 ? std::numeric_limits<double>::quiet_NaN()
                       : (d.rms > 0 ? 20.0 * std::log10(1.0 / d.rms) : std::numeric_limits<double>::infinity());
    return d;
}

}  // namespace cloud_renderer
