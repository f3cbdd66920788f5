// Reading and writing images: PNG (8-bit sRGB-less, values clamped to [0,1]
// and rounded) through stb, and PFM (float, lossless) for AOVs. Every write
// goes to a temporary file in the destination folder and is renamed into
// place, so a failed run never leaves a partial file.
#pragma once

#include "image/frame.h"

#include <csignal>
#include <string>
#include <utility>
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

// By extension: .png (3 channels written as RGB8; 1 channel as grey) or .pfm
// (PF for 3 channels, Pf for 1; little-endian, bottom-to-top rows as the
// format requires). Throws Error naming the path on any failure; the
// destination is then untouched.
void writeImage(const std::string& path, const Image& image);

// Reads .png or .bmp (any channel count; converted to 3 channels in [0,1])
// or .pfm (either endianness). Throws Error naming the path.
Image readImage(const std::string& path);

// The same from bytes already in memory (the format chosen by `path`'s
// extension; `path` is used only for that and in messages). Refuses images
// above kMaxImageSide per side or kMaxImagePixels before decoding them.
Image decodeImage(const std::string& bytes, const std::string& path);

// Limits for images read (PNG, BMP and PFM alike): they keep a corrupt or hostile
// header from asking for gigabytes. Renders are at most 16384 per side and 64
// Mpixels, so everything vkray writes reads back.
inline constexpr long kMaxImageSide = 1 << 16;
inline constexpr long long kMaxImagePixels = 64ll << 20;

// Writes `bytes` to `path` atomically (temporary file in the same folder,
// fsync, rename). Throws Error naming the path.
void writeFileAtomically(const std::string& path, const std::string& bytes);

// --aov PREFIX: PREFIX.depth.pfm, PREFIX.normal.pfm, PREFIX.id.pfm.
void writeAovs(const std::string& prefix, const Frame& frame);

// Files that appear together or not at all (an image, its AOVs, a diff):
// stage() writes each in full to a temporary file beside its destination
// (fsync'd), commit() renames them all into place. Destroyed before
// commit(), it removes its temporaries, so a failed or interrupted run
// leaves every destination as it was. From the first stage() to the end,
// SIGINT, SIGTERM and SIGHUP are held back in the calling thread, so that a
// single-threaded command is not killed with a temporary on disk (render
// installs handlers of its own, which every thread obeys).
class StagedFiles {
public:
    StagedFiles() = default;
    ~StagedFiles();
    StagedFiles(const StagedFiles&) = delete;
    StagedFiles& operator=(const StagedFiles&) = delete;

    void stage(const std::string& path, const std::string& bytes);  // throws Error naming path
    void stageImage(const std::string& path, const Image& image);    // as writeImage
    void stageAovs(const std::string& prefix, const Frame& frame);   // as writeAovs
    void commit();

private:
    void release();
    std::vector<std::pair<std::string, std::string>> staged_;  // temporary, destination
    bool holding_ = false;
    sigset_t previousMask_{};
};

}  // namespace vkray
