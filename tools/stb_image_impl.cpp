// stb_image's implementation (PNG decoding only), for tools/recompress_png.cpp; kept apart and
// built without our strict warning flags, like stb_image_write_impl.cpp.
#define STBI_ONLY_PNG
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
