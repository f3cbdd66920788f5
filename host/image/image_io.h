// Reading and writing images: PNG (8-bit sRGB-less, values clamped to [0,1]
// and rounded) through stb, PFM (float, lossless) and OpenEXR (float,
// lossless, multi-layer: image/exr_io.h) for AOVs. Every write
// goes to a temporary file in the destination folder and is renamed into
// place, so a failed run never leaves a partial file.
#pragma once

#include "image/frame.h"
#include "util/files.h"

#include <glm/vec3.hpp>

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

Image colorImage(const Frame& frame);   // 3 channels: the colour, unclamped
Image depthImage(const Frame& frame);   // 1 channel: depth (+inf on a miss)
Image normalImage(const Frame& frame);  // 3 channels: world normal
Image idImage(const Frame& frame);      // 1 channel: object id as float (-1 = background)

// A colour channel as a PNG stores it: clamped to [0,1], times 255, rounded
// (NaN: 0). `vkray view` converts on the device to these very bytes.
unsigned char pngByte(float value);

// By extension: .png (3 channels written as RGB8; 1 channel as grey), .pfm
// (PF for 3 channels, Pf for 1; little-endian, bottom-to-top rows as the
// format requires) or .exr (float channels R, G, B, or Y for 1 channel;
// unclamped). Throws Error naming the path on any failure; the destination
// is then untouched.
void writeImage(const std::string& path, const Image& image);

// The PNG file writeImage writes, as bytes (for pages that embed images).
std::string pngBytes(const Image& image);

// Reads .png or .bmp (any channel count; converted to 3 channels in [0,1]),
// .pfm (either endianness) or .exr (its R, G, B channels, else its Y).
// Throws Error naming the path.
Image readImage(const std::string& path);

// Object ids as a 1-channel image: an .exr file's id channel (exr_io.h
// kExrIdChannel), any other file as readImage reads it (PREFIX.id.pfm).
Image readIds(const std::string& path);

// Whether `path` is an .exr file with an id channel (false for other
// extensions). Throws Error when the .exr cannot be read.
bool hasIdChannel(const std::string& path);

// Whether the path ends in .exr (any case).
bool isExrPath(const std::string& path);

// The same from bytes already in memory (the format chosen by `path`'s
// extension; `path` is used only for that and in messages). Refuses images
// above kMaxImageSide per side or kMaxImagePixels before decoding them.
Image decodeImage(const std::string& bytes, const std::string& path);

// Limits for images read (PNG, BMP and PFM alike): they keep a corrupt or hostile
// header from asking for gigabytes. Renders are at most 16384 per side and 64
// Mpixels, so everything vkray writes reads back.
inline constexpr long kMaxImageSide = 1 << 16;
inline constexpr long long kMaxImagePixels = 64ll << 20;

// --aov TARGET. TARGET ending in .exr: one OpenEXR file with every layer
// (exr_io.h aovExr(): the colour, depth, normal, id and the world hit
// points `hitPoints`, one per pixel). Otherwise TARGET is a prefix:
// TARGET.depth.pfm, TARGET.normal.pfm, TARGET.id.pfm (no hit points).
void writeAovs(const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints);

// The files writeAovs writes for `target`, for a "wrote ..." line.
std::string aovFilesText(const std::string& target);

// writeImage and writeAovs as part of a set of files written together
// (util/files.h StagedFiles).
void stageImage(StagedFiles& files, const std::string& path, const Image& image);
void stageAovs(StagedFiles& files, const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints);

}  // namespace vkray
