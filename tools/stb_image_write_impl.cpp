// The one translation unit that compiles stb_image_write's implementation (Debian package
// libstb-dev, header <stb/stb_image_write.h>). It is kept apart and built without our strict
// warning flags, because the third-party code is not written for -Wconversion -Werror.
//
// Its PNGs are deflated by zlib at level 9 (STBIW_ZLIB_COMPRESS, stb's documented hook)
// instead of stb's own small deflate: the same pixels, files about a third smaller (measured
// on docs/images by tools/recompress_png.cpp; issue 39). zlib is deterministic for one
// version, so the same image gives the same bytes (the stored reports are compared byte for
// byte).
#include <cstdlib>

#include <zlib.h>

static unsigned char* cloudmath_zlib_compress(unsigned char* data, int data_len, int* out_len, int /*quality*/) {
    if (data_len < 0) return nullptr;
    uLongf size = compressBound(static_cast<uLong>(data_len));
    auto* out = static_cast<unsigned char*>(std::malloc(size));  // stb frees it with STBIW_FREE (free)
    if (out == nullptr) return nullptr;
    if (compress2(out, &size, data, static_cast<uLong>(data_len), Z_BEST_COMPRESSION) != Z_OK) {
        std::free(out);
        return nullptr;
    }
    *out_len = static_cast<int>(size);
    return out;
}

#define STBIW_ZLIB_COMPRESS cloudmath_zlib_compress
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
