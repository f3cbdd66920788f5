// PNG (written and read) and BMP (read: Hill's pixmaps) through stb, with
// vkray's size limits checked before stb allocates anything.
#pragma once

#include <string>
#include <vector>

#include "image/image.h"

namespace vkray {

// A colour channel as a PNG stores it: clamped to [0,1], times 255, rounded
// (NaN: 0). `vkray view` converts on the device to these very bytes.
unsigned char pngByte(float value);

// An image of 1 or 3 channels as PNG file bytes (grey or RGB8). Throws Error
// naming `path` when encoding fails.
std::string encodePng(const std::string& path, const Image& image);
// The same from bytes already converted (pngByte), `channels` (1 or 3) a pixel.
std::string encodePng(const std::string& path, int width, int height, int channels,
                      const std::vector<unsigned char>& bytes);

// PNG or BMP file bytes (any channel count) as 3 channels in [0,1]. Throws
// Error naming `path`.
Image decodePng(const std::string& path, const std::string& bytes);
Image decodeBmp(const std::string& path, const std::string& bytes);

}  // namespace vkray
