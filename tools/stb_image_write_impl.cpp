// The one translation unit that compiles stb_image_write's implementation (Debian package
// libstb-dev, header <stb/stb_image_write.h>). It is kept apart and built without our strict
// warning flags, because the third-party code is not written for -Wconversion -Werror.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
