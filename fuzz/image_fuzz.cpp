// Fuzzes image decoding from memory, every input as a PNG and a BMP
// (stb_image), as a PFM and as an OpenEXR file (OpenEXR 3, vkray's size
// limits checked before it reads pixels). Any exception other than
// vkray::Error is a bug; a decoded image's size must match its pixel array.
#include <cstddef>
#include <cstdint>
#include <string>

#include "image/image_io.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    for (const char* path : {"fuzz.png", "fuzz.pfm", "fuzz.bmp", "fuzz.exr"}) {
        try {
            const vkray::Image image = vkray::decodeImage(bytes, path);
            if (image.width <= 0 || image.height <= 0 ||
                image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) *
                                           std::size_t(image.channels))
                __builtin_trap();
        } catch (const vkray::Error&) {
        }
    }
    return 0;
}
