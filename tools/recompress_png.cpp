// tools/recompress_png.cpp: cloudmath_recompress_png, rewrites PNG files through the encoder
// every cloudmath tool writes with (png_encode.hpp; zlib level 9, stb_image_write_impl.cpp),
// pixel for pixel: each file is decoded, encoded again, the new bytes decoded and compared
// with the old pixels, and only then written (atomically, atomic_file.hpp). A stored image
// then has the bytes its generator would write today, so a report compared byte for byte
// still matches, and images kept from before the encoder changed shrink without a re-render.
//
//   cloudmath_recompress_png [--check] FILE.png...
//
// Prints one line a file (old and new size) and the total. --check writes nothing and exits 1
// when any file would change (the stored images are what the encoder writes). Exit status:
// 0 done, 1 a file that cannot be read, decoded, re-encoded identically or written (named),
// 2 bad command line.
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "atomic_file.hpp"
#include "gzip_text.hpp"
#include "png_encode.hpp"

namespace {

struct decoded {
    int width = 0, height = 0, channels = 0;
    std::vector<unsigned char> pixels;
};

bool decode(const std::string& bytes, decoded& out) {
    int w = 0, h = 0, n = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> p(
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()), &w, &h, &n, 0),
        stbi_image_free);
    if (!p || stbi_is_16_bit_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size())))
        return false;
    out.width = w;
    out.height = h;
    out.channels = n;
    out.pixels.assign(p.get(), p.get() + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(n));
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    bool check = false;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--check") check = true;
        else if (a == "--help") {
            std::puts("usage: cloudmath_recompress_png [--check] FILE.png...");
            return 0;
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "cloudmath_recompress_png: unknown flag %s\n", a.c_str());
            return 2;
        } else files.push_back(a);
    }
    if (files.empty()) {
        std::fputs("usage: cloudmath_recompress_png [--check] FILE.png...\n", stderr);
        return 2;
    }
    long long before = 0, after = 0;
    int changed = 0;
    for (const std::string& f : files) {
        std::string bytes;
        try {
            bytes = cloudmath::tools::read_data_file(f);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "cloudmath_recompress_png: %s\n", e.what());
            return 1;
        }
        decoded old;
        if (!decode(bytes, old)) {
            std::fprintf(stderr, "cloudmath_recompress_png: %s: not an 8-bit PNG stb can read\n", f.c_str());
            return 1;
        }
        const std::string png =
            cloudmath::tools::encode_png(old.width, old.height, old.channels, old.pixels.data(), old.width * old.channels);
        decoded again;
        if (png.empty() || !decode(png, again) || again.width != old.width || again.height != old.height ||
            again.channels != old.channels || again.pixels != old.pixels) {
            std::fprintf(stderr, "cloudmath_recompress_png: %s: the re-encoded image is not the same pixels\n", f.c_str());
            return 1;
        }
        before += static_cast<long long>(bytes.size());
        after += static_cast<long long>(png.size());
        const bool differs = png != bytes;
        changed += differs ? 1 : 0;
        std::printf("%s: %zu -> %zu bytes%s\n", f.c_str(), bytes.size(), png.size(), differs ? "" : " (unchanged)");
        if (differs && !check) {
            const std::string why = cloudmath::tools::write_file_atomically(f, png);
            if (!why.empty()) {
                std::fprintf(stderr, "cloudmath_recompress_png: %s\n", why.c_str());
                return 1;
            }
        }
    }
    std::printf("%zu files: %lld -> %lld bytes, %d %s\n", files.size(), before, after, changed,
                check ? "would change" : "rewritten");
    return check && changed > 0 ? 1 : 0;
}
