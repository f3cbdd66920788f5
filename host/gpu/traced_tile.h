// A tile the GPU tracer has just traced, as its TileListener hears of it:
// where it lies in the image and the device buffer that holds its pixels.
#pragma once

#include "gpu/vulkan_pch.h"
#include "scene/tile_schedule.h"

namespace vkray::gpu {

struct TracedTile {
    TileRect rect;       // pixels of the image
    vk::Buffer pixels;   // GpuPixel[rect.width * rect.height], row-major; valid until the next tile
};

}  // namespace vkray::gpu
