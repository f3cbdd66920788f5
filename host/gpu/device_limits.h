// What a scene asks of the Vulkan device, checked against what the device
// allows before anything is allocated: each buffer against the largest
// storage buffer, texel-buffer view and allocation, their sum against the memory
// heap, each dispatch against the largest workgroup count. A scene beyond a
// limit is refused with the count that is too big, the limit, and what to do.
// Pure functions over plain numbers, so the tests need no device.
#pragma once

#include "gpu/context.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vkray::gpu {

struct DeviceLimits {
    std::string deviceName;
    std::uint64_t maxStorageBufferRange = 0;
    std::uint64_t maxTexelBufferElements = 0;  // texels in one texel-buffer view
    std::uint64_t maxMemoryAllocationSize = 0;
    std::uint64_t memoryHeapBytes = 0;  // the heap vkray's (host-visible) buffers live in
    std::uint32_t maxWorkgroupCount[2] = {};
};

// The device's limits, lowered (never raised) by two test hooks, so that the
// refusals can be tested without a scene of gigabytes:
//   VKRAY_MAX_BUFFER_BYTES     caps the storage buffer range
//   VKRAY_MAX_TEXELS           caps the texels of one texel buffer
//   VKRAY_DEVICE_MEMORY_BYTES  caps the memory heap
// A value that is not a whole number > 0 is an Error naming the variable.
DeviceLimits deviceLimits(const DeviceInfo& device);

// One buffer a render needs: `count` items of `itemBytes` each ("triangles"
// of 96 bytes). `advice` says how to need fewer of them.
struct BufferNeed {
    std::string what;
    std::size_t count = 0;
    std::size_t itemBytes = 0;
    std::string advice;
    std::size_t texelBytes = 0;  // read through a texel buffer of texels this size (0: not)
};

// Throws Error when one buffer exceeds its range or the largest allocation,
// or all of them together (each rounded up as an allocator would) the heap.
void checkBufferNeeds(const std::vector<BufferNeed>& needs, const DeviceLimits& limits);

// The tile side (a multiple of `block`, at most `wanted`) whose pixel buffer
// (`pixelBytes` a pixel) fits one storage buffer and whose dispatch of
// `workgroupX` x `workgroupY` invocations, one per block, fits the workgroup
// count. Throws Error when not even one block fits.
int fitTileSide(int wanted, int block, std::size_t pixelBytes, std::uint32_t workgroupX,
                std::uint32_t workgroupY, const DeviceLimits& limits);

}  // namespace vkray::gpu
