// PFM, the float image format of the AOVs: a three-line text header ("PF"
// colour or "Pf" grey, width and height, a scale whose sign is the byte
// order), then the rows of 32-bit floats, bottom row first.
#pragma once

#include <string>

#include "image/image.h"

namespace vkray {

// 1 or 3 channels, little-endian.
std::string encodePfm(const Image& image);

// Either byte order. Every header field, the image limits and the amount of
// pixel data are checked before anything is allocated; throws Error naming
// `path` and what is wrong.
Image decodePfm(const std::string& path, const std::string& bytes);

}  // namespace vkray
