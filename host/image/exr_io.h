// OpenEXR files (OpenEXR 3): one part, scan lines, 32-bit float channels,
// lossless ZIP compression. Channel names follow the convention pbrt-v4 and
// Mitsuba 3 use (R, G, B; Z; N.X, N.Y, N.Z; P.X, P.Y, P.Z), so that
// OpenImageIO, tev, Blender and Nuke show the layers by name.
#pragma once

#include "image/frame.h"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace vkray {

struct Image;

struct ExrChannel {
    std::string name;
    std::vector<float> values;  // width * height, row 0 at the top
};

struct ExrImage {
    int width = 0;
    int height = 0;
    std::vector<ExrChannel> channels;

    const ExrChannel* find(const std::string& name) const;  // null when absent
};

// The object id channel of an AOV file: float, the object's index in scene
// order, -1 where the ray hits nothing (as in PREFIX.id.pfm).
inline constexpr const char* kExrIdChannel = "id";

// The file's bytes. Throws Error naming `path` when a channel's size does not
// match the image's or two channels share a name.
std::string encodeExr(const ExrImage& image, const std::string& path);

// The names of the file's channels (its header only). Throws Error as
// decodeExr does.
std::vector<std::string> exrChannelNames(const std::string& bytes, const std::string& path);

// Reads the named channels of an OpenEXR file's data window (any pixel
// type, converted to float); all of them when `wanted` is empty. Throws
// Error naming `path` (and the channels the file has) when the bytes are no
// readable OpenEXR file, a wanted channel is missing, or the image is above
// image_io.h's size limits.
ExrImage decodeExr(const std::string& bytes, const std::string& path,
                   const std::vector<std::string>& wanted);

// An Image as EXR channels: R, G, B for 3 channels, Y for 1.
ExrImage exrFromImage(const Image& image);

// Every AOV of a frame in one image: R, G, B (linear, unclamped), Z (the
// distance along the pixel's ray, +inf on a miss), N.X, N.Y, N.Z (the world
// normal, 0 on a miss), id (kExrIdChannel) and P.X, P.Y, P.Z, the world hit
// point (`hitPoints`, one per pixel; render/camera.h hitPoints()).
ExrImage aovExr(const Frame& frame, const std::vector<glm::vec3>& hitPoints);

}  // namespace vkray
