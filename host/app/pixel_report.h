// The side-by-side table `vkray pixel` prints: every step of one primary ray
// on the GPU and in the CPU reference, and how far apart the two are.
#pragma once

#include "image/pixel_trace.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <string>

namespace vkray {

std::string formatPixelReport(const Scene& scene, const RenderSettings& settings,
                              const PixelTrace& gpu, const PixelTrace& cpu);

}  // namespace vkray
