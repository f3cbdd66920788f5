// The one translation unit that compiles stb_image and stb_image_write. Only
// the PNG and BMP decoders are built (readImage reads .png, and .bmp for
// Hill's pixmaps); each is reached only through its own extension and
// signature (image_io.cpp), and fuzzed (fuzz/image_fuzz.cpp).
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

// PNGs are deflated by zlib rather than stb's own compressor, several times
// faster on a 1920x1080 frame at the same size or smaller (docs/usage.md,
// render's time line).
#include <zlib.h>

#include <cstdlib>

namespace {

constexpr int kPngDeflateLevel = 6;

unsigned char* zlibDeflate(unsigned char* data, int length, int* outLength, int /*quality*/) {
    uLongf size = compressBound(uLong(length));
    auto* out = static_cast<unsigned char*>(std::malloc(size));
    if (out && compress2(out, &size, data, uLong(length), kPngDeflateLevel) == Z_OK) {
        *outLength = int(size);
        return out;
    }
    std::free(out);
    return nullptr;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS zlibDeflate
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
