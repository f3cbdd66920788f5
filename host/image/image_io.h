// Reading and writing image files, the format chosen by the extension: PNG
// (8-bit sRGB-less, values clamped to [0,1] and rounded) through stb
// (image/stb_codecs.h), PFM (float, lossless: image/pfm.h) and OpenEXR
// (float, lossless, multi-layer: image/exr_io.h). Every write
// goes to a temporary file in the destination folder and is renamed into
// place, so a failed run never leaves a partial file.
#pragma once

#include "image/frame.h"
#include "image/image.h"
#include "util/files.h"

#include <string>

namespace vkray {

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

// writeImage as part of a set of files written together (util/files.h
// StagedFiles).
void stageImage(StagedFiles& files, const std::string& path, const Image& image);
// A frame's colours, as stageImage(colorImage(frame)) writes them; a PNG is
// converted to its bytes straight from the frame, with no float copy of it
// (a quarter of the memory to fault in).
void stageColor(StagedFiles& files, const std::string& path, const Frame& frame);

}  // namespace vkray
