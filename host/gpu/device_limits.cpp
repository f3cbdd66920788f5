#include "gpu/device_limits.h"

#include "util/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace vkray::gpu {

namespace {

// Allocators hand out memory in aligned blocks; the estimate rounds each
// buffer up so that it errs on the side of refusing.
constexpr std::uint64_t kAllocationGranule = 64 * 1024;

std::uint64_t lowerByEnvironment(const char* name, std::uint64_t value) {
    const char* text = std::getenv(name);
    if (!text || !*text) return value;
    std::uint64_t limit = 0;
    const char* end = text + std::strlen(text);
    const auto [stop, error] = std::from_chars(text, end, limit);
    if (error != std::errc() || stop != end || limit == 0)
        throw Error(std::string(name) + "='" + text +
                    "' is not a whole number of bytes > 0 (a test hook that lowers a device "
                    "limit; unset it)");
    return std::min(value, limit);
}

// "134217728 bytes (128.0 MiB)", or with a note "... (128.0 MiB, NOTE)"
std::string bytesText(std::uint64_t bytes, const std::string& note = "") {
    char size[64] = "";
    if (bytes >= (std::uint64_t(1) << 30))
        std::snprintf(size, sizeof size, "%.1f GiB", double(bytes) / double(1 << 30));
    else if (bytes >= (1u << 20))
        std::snprintf(size, sizeof size, "%.1f MiB", double(bytes) / double(1 << 20));
    const std::string inParentheses =
        std::string(size) + (size[0] && !note.empty() ? ", " : "") + note;
    return std::to_string(bytes) + " bytes" +
           (inParentheses.empty() ? std::string() : " (" + inParentheses + ")");
}

std::uint64_t rounded(std::uint64_t bytes) {
    return (bytes + kAllocationGranule - 1) / kAllocationGranule * kAllocationGranule;
}

}  // namespace

DeviceLimits deviceLimits(const DeviceInfo& device) {
    DeviceLimits limits;
    limits.deviceName = device.name;
    limits.maxStorageBufferRange =
        lowerByEnvironment("VKRAY_MAX_BUFFER_BYTES", device.maxStorageBufferRange);
    limits.maxTexelBufferElements =
        lowerByEnvironment("VKRAY_MAX_TEXELS", device.maxTexelBufferElements);
    limits.maxMemoryAllocationSize = device.maxMemoryAllocationSize;
    limits.memoryHeapBytes =
        lowerByEnvironment("VKRAY_DEVICE_MEMORY_BYTES", device.memoryHeapBytes);
    limits.maxWorkgroupCount[0] = device.maxWorkgroupCount[0];
    limits.maxWorkgroupCount[1] = device.maxWorkgroupCount[1];
    return limits;
}

void checkBufferNeeds(const std::vector<BufferNeed>& needs, const DeviceLimits& limits) {
    std::uint64_t total = 0;
    std::vector<std::pair<std::uint64_t, std::string>> sizes;  // bytes, what
    for (const BufferNeed& need : needs) {
        // Vulkan forbids empty buffers: an empty array still takes one item.
        const std::uint64_t items = std::max<std::uint64_t>(need.count, 1);
        const std::uint64_t bytes = items * need.itemBytes;
        const std::uint64_t range = limits.maxStorageBufferRange;
        const char* rangeName = "maxStorageBufferRange";
        // A texel buffer's bound is its texel count (below), not a buffer range.
        const bool overRange = need.texelBytes == 0 && bytes > range;
        if (overRange ||
            (limits.maxMemoryAllocationSize && bytes > limits.maxMemoryAllocationSize)) {
            const std::uint64_t limit = overRange ? range : limits.maxMemoryAllocationSize;
            throw Error("the scene's " + std::to_string(need.count) + " " + need.what + " need " +
                        bytesText(bytes) + " in one storage buffer; " + limits.deviceName +
                        " allows at most " +
                        bytesText(limit, overRange ? rangeName : "maxMemoryAllocationSize") +
                        ", room for " + std::to_string(limit / need.itemBytes) + " " + need.what +
                        ". " + need.advice + ", or render with --cpu (no such limit)");
        }
        if (need.texelBytes > 0 && bytes / need.texelBytes > limits.maxTexelBufferElements) {
            const std::uint64_t room =
                limits.maxTexelBufferElements * need.texelBytes / need.itemBytes;
            throw Error("the scene's " + std::to_string(need.count) + " " + need.what + " need " +
                        std::to_string(bytes / need.texelBytes) + " texels in one texel buffer; " +
                        limits.deviceName + " allows at most " +
                        std::to_string(limits.maxTexelBufferElements) +
                        " (maxTexelBufferElements), room for " + std::to_string(room) + " " +
                        need.what + ". " + need.advice + ", or render with --cpu (no such limit)");
        }
        total += rounded(bytes);
        sizes.emplace_back(bytes, need.what);
    }
    if (limits.memoryHeapBytes && total > limits.memoryHeapBytes) {
        // The three largest buffers say where the memory goes.
        std::stable_sort(sizes.begin(), sizes.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        std::string parts;
        for (std::size_t i = 0; i < std::min<std::size_t>(sizes.size(), 3); ++i)
            parts += (i ? ", " : "") + sizes[i].second + " " + bytesText(sizes[i].first);
        throw Error("the scene needs about " + bytesText(total) + " of device memory (" + parts +
                    (sizes.size() > 3 ? ", ..." : "") + "); " + limits.deviceName +
                    "'s memory heap holds " + bytesText(limits.memoryHeapBytes) +
                    ". Use fewer objects or smaller meshes, or render with --cpu");
    }
}

int fitTileSide(int wanted, int block, std::size_t pixelBytes, std::uint32_t workgroupX,
                std::uint32_t workgroupY, const DeviceLimits& limits) {
    block = std::max(block, 1);
    // One pixel buffer of side^2 pixels, written by one dispatch per tile.
    const std::uint64_t bufferLimit =
        limits.maxMemoryAllocationSize
            ? std::min(limits.maxStorageBufferRange, limits.maxMemoryAllocationSize)
            : limits.maxStorageBufferRange;
    // The shader writes it as a texel buffer of 16-byte texels, too.
    const std::uint64_t byBuffer = std::uint64_t(std::sqrt(
        double(std::min(bufferLimit / pixelBytes,
                        std::uint64_t(limits.maxTexelBufferElements) * 16 / pixelBytes))));
    // ceil(ceil(side / block) / workgroup) <= maxWorkgroupCount on each axis.
    const std::uint64_t byCount =
        std::uint64_t(block) * std::min(std::uint64_t(limits.maxWorkgroupCount[0]) * workgroupX,
                                        std::uint64_t(limits.maxWorkgroupCount[1]) * workgroupY);
    std::uint64_t side = std::min({std::uint64_t(std::max(wanted, block)), byBuffer, byCount});
    side = side / std::uint64_t(block) * std::uint64_t(block);
    if (side == 0)
        throw Error("one " + std::to_string(block) + "x" + std::to_string(block) + " block needs " +
                    bytesText(std::uint64_t(block) * block * pixelBytes) + " of pixel buffer; " +
                    limits.deviceName + " allows at most " + bytesText(bufferLimit) +
                    " in one storage buffer. Use a smaller --block, "
                    "or render with --cpu");
    return int(side);
}

}  // namespace vkray::gpu
