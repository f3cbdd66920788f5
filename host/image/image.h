// A float image in memory, as the image files hold it, and the limits on what
// vkray reads.
#pragma once

#include <string>
#include <vector>

namespace vkray {

// A float image with 1 or 3 channels, row 0 at the top.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;  // width * height * channels, interleaved
};

// Limits for images read (PNG, BMP and PFM alike): they keep a corrupt or hostile
// header from asking for gigabytes. Renders are at most 16384 per side and 64
// Mpixels, so everything vkray writes reads back.
inline constexpr long kMaxImageSide = 1 << 16;
inline constexpr long long kMaxImagePixels = 64ll << 20;

// The message for an image whose header asks for more pixels than vkray reads.
inline std::string tooManyPixels(const std::string& path, long long width, long long height) {
    return path + ": the image is " + std::to_string(width) + "x" + std::to_string(height) +
           ", above vkray's limit of " + std::to_string(kMaxImagePixels) + " pixels (" +
           std::to_string(kMaxImageSide) + " per side)";
}

}  // namespace vkray
