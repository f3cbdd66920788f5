// A rendered Frame as images and files: the colour and each AOV (depth,
// normal, object id) as an Image, and `--aov TARGET`'s files.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "image/frame.h"
#include "image/image_io.h"
#include "util/files.h"

namespace vkray {

Image colorImage(const Frame& frame);   // 3 channels: the colour, unclamped
Image depthImage(const Frame& frame);   // 1 channel: depth (+inf on a miss)
Image normalImage(const Frame& frame);  // 3 channels: world normal
Image idImage(const Frame& frame);      // 1 channel: object id as float (-1 = background)

// --aov TARGET. TARGET ending in .exr: one OpenEXR file with every layer
// (exr_io.h aovExr(): the colour, depth, normal, id and the world hit
// points `hitPoints`, one per pixel). Otherwise TARGET is a prefix:
// TARGET.depth.pfm, TARGET.normal.pfm, TARGET.id.pfm (no hit points).
void writeAovs(const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints);

// writeAovs as part of a set of files written together.
void stageAovs(StagedFiles& files, const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints);

// The files writeAovs writes for `target`, for a "wrote ..." line.
std::string aovFilesText(const std::string& target);

}  // namespace vkray
