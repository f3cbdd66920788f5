// The checks of a scene's buffers against a device's limits, on made-up
// limits (no device needed): which need is refused, and what the message says.
#include "gpu/device_limits.h"

#include "util/error.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace vkray::gpu {
namespace {

DeviceLimits smallDevice() {
    DeviceLimits limits;
    limits.deviceName = "tiny GPU";
    limits.maxStorageBufferRange = 1 << 20;  // 1 MiB
    limits.maxTexelBufferElements = 65536;   // Vulkan's least
    limits.maxMemoryAllocationSize = 1 << 30;
    limits.memoryHeapBytes = 8 << 20;  // 8 MiB
    limits.maxWorkgroupCount[0] = limits.maxWorkgroupCount[1] = 65535;
    return limits;
}

std::string refusal(const std::vector<BufferNeed>& needs, const DeviceLimits& limits) {
    try {
        checkBufferNeeds(needs, limits);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(DeviceLimits, BufferWithinItsRangeIsAccepted) {
    EXPECT_NO_THROW(checkBufferNeeds({{"triangles", 10922, 96, "Use smaller meshes"}},
                                     smallDevice()));  // 1048512 bytes <= 1 MiB
}

// 10 923 triangles of 6 texels are 65 538 texels, two more than the view
// allows; the storage range is raised so that only the texel count refuses.
TEST(DeviceLimits, TexelBufferBeyondItsElementsNamesCountLimitAndAdvice) {
    DeviceLimits limits = smallDevice();
    limits.maxStorageBufferRange = 1 << 30;
    const BufferNeed within{"triangles", 10922, 96, "Use smaller meshes", 16};
    const BufferNeed beyond{"triangles", 10923, 96, "Use smaller meshes", 16};
    EXPECT_NO_THROW(checkBufferNeeds({within}, limits));  // 65 532 texels
    const std::string message = refusal({beyond}, limits);
    EXPECT_NE(message.find("10923 triangles need 65538 texels"), std::string::npos) << message;
    EXPECT_NE(message.find("at most 65536 (maxTexelBufferElements), room for 10922 triangles"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("Use smaller meshes, or render with --cpu"), std::string::npos)
        << message;
}

TEST(DeviceLimits, StorageBufferBeyondItsRangeNamesCountLimitAndAdvice) {
    const std::string message = refusal({{"objects", 10, 128, "Use fewer objects"},
                                         {"triangles", 10923, 96, "Use fewer or smaller meshes"}},
                                        smallDevice());
    EXPECT_NE(message.find("the scene's 10923 triangles need 1048608 bytes (1.0 MiB) in one "
                           "storage buffer"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("tiny GPU allows at most 1048576 bytes (1.0 MiB, "
                           "maxStorageBufferRange), room for 10922 triangles"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("Use fewer or smaller meshes, or render with --cpu"), std::string::npos)
        << message;
}

TEST(DeviceLimits, AllocationLimitAppliesWhenBelowTheRange) {
    DeviceLimits limits = smallDevice();
    limits.maxMemoryAllocationSize = 4096;
    const std::string message = refusal({{"objects", 64, 128, "Use fewer objects"}}, limits);
    EXPECT_NE(message.find("maxMemoryAllocationSize"), std::string::npos) << message;
    EXPECT_NE(message.find("room for 32 objects"), std::string::npos) << message;
}

TEST(DeviceLimits, TotalBeyondTheHeapIsRefusedWithTheLargeParts) {
    // Eight buffers of 1 MiB each (all within the range) plus small ones: over 8 MiB.
    std::vector<BufferNeed> needs;
    for (int i = 0; i < 8; ++i) needs.push_back({"triangles", 10922, 96, "x"});
    needs.push_back({"lights", 3, 32, "x"});
    const std::string message = refusal(needs, smallDevice());
    EXPECT_NE(message.find("the scene needs about"), std::string::npos) << message;
    EXPECT_NE(message.find("of device memory (triangles 1048512 bytes, triangles"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("tiny GPU's memory heap holds 8388608 bytes (8.0 MiB)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("render with --cpu"), std::string::npos) << message;
    needs.resize(7);
    EXPECT_EQ(refusal(needs, smallDevice()), "");
}

TEST(DeviceLimits, EmptyArraysStillTakeOneItem) {
    DeviceLimits limits = smallDevice();
    limits.maxStorageBufferRange = 100;
    EXPECT_NE(refusal({{"CSG nodes", 0, 128, "x"}}, limits), "");
}

TEST(DeviceLimits, TileShrinksToFitThePixelBufferAndWorkgroupCount) {
    DeviceLimits limits = smallDevice();
    // 1 MiB / 32 bytes = 32768 pixels: a 181 x 181 tile at most.
    EXPECT_EQ(fitTileSide(256, 1, 32, 8, 8, limits), 181);
    EXPECT_EQ(fitTileSide(128, 1, 32, 8, 8, limits), 128);
    EXPECT_EQ(fitTileSide(256, 5, 32, 8, 8, limits), 180);  // whole blocks
    // Two workgroups of 8 invocations, one ray per 3x3 block: 48 pixels.
    limits.maxWorkgroupCount[1] = 2;
    EXPECT_EQ(fitTileSide(256, 3, 32, 8, 8, limits), 48);
}

TEST(DeviceLimits, TileShrinksToFitThePixelTexelBuffer) {
    DeviceLimits limits = smallDevice();
    limits.maxStorageBufferRange = 1u << 30;
    // The shader writes pixels as 16-byte texels: 8192 texels hold 4096
    // 32-byte pixels, a 64 x 64 tile.
    limits.maxTexelBufferElements = 8192;
    EXPECT_EQ(fitTileSide(256, 1, 32, 8, 8, limits), 64);
}

TEST(DeviceLimits, BlockTooLargeForOnePixelBufferIsRefused) {
    DeviceLimits limits = smallDevice();
    limits.maxStorageBufferRange = 1000;
    try {
        fitTileSide(256, 8, 32, 8, 8, limits);
        FAIL() << "an 8x8 block needs 2048 bytes";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("Use a smaller --block, or render with --cpu"),
                  std::string::npos)
            << e.what();
    }
}

TEST(DeviceLimits, EnvironmentHooksOnlyLower) {
    DeviceInfo device;
    device.name = "dev";
    device.maxStorageBufferRange = 1000;
    device.memoryHeapBytes = 5000;
    ::setenv("VKRAY_MAX_BUFFER_BYTES", "100", 1);
    ::setenv("VKRAY_DEVICE_MEMORY_BYTES", "99999", 1);
    DeviceLimits limits = deviceLimits(device);
    EXPECT_EQ(limits.maxStorageBufferRange, 100u);
    EXPECT_EQ(limits.memoryHeapBytes, 5000u);  // never raised
    ::setenv("VKRAY_MAX_BUFFER_BYTES", "lots", 1);
    EXPECT_THROW(deviceLimits(device), Error);
    ::unsetenv("VKRAY_MAX_BUFFER_BYTES");
    ::unsetenv("VKRAY_DEVICE_MEMORY_BYTES");
    EXPECT_EQ(deviceLimits(device).maxStorageBufferRange, 1000u);
}

}  // namespace
}  // namespace vkray::gpu
