// Context internals, for host/gpu's own translation units. Members are
// declared in creation order, so they are destroyed in reverse (Vulkan-Hpp
// RAII: the device dies before the instance, the pool before the device).
#pragma once

#include "gpu/context.h"
#include "gpu/vulkan_pch.h"

#include <atomic>
#include <optional>

namespace vkray::gpu {

struct Context::Impl {
    std::atomic<int> validationMessages{0};  // counted by the debug messenger
    vk::raii::Context context;
    vk::raii::Instance instance = nullptr;
    std::optional<vk::raii::DebugUtilsMessengerEXT> messenger;
    vk::raii::PhysicalDevice physicalDevice = nullptr;
    DeviceInfo info;
    std::uint32_t queueFamily = 0;
    vk::raii::Device device = nullptr;
    vk::raii::Queue queue = nullptr;
    vk::raii::CommandPool commandPool = nullptr;

    // Finds a memory type with all `flags` among those `typeBits` allows.
    std::uint32_t findMemoryType(std::uint32_t typeBits, vk::MemoryPropertyFlags flags) const;
    // The first such memory type, if the device has one.
    std::optional<std::uint32_t> memoryTypeWith(std::uint32_t typeBits,
                                                vk::MemoryPropertyFlags flags) const;
};

// Vulkan's failures that can strike in the middle of a render (device lost,
// out of device or host memory), as an Error saying what happened and what
// to do; any other Vulkan failure is explained in general terms.
[[noreturn]] void explainVulkanFailure(const vk::SystemError& failure, const DeviceInfo& device);

// Where a buffer's memory lies: host-visible, mapped for the buffer's whole
// life; host-visible and cached where the device has such memory, for what
// the host reads back (a discrete GPU's uncached host-visible memory reads
// at a fraction of the speed); or device-local, never mapped, filled by a
// copy from a host-visible one (a discrete GPU then reads it from its own
// memory, not over the bus).
enum class BufferMemory { HostVisible, HostReadBack, DeviceLocal };

// A buffer and its memory. Member order fixes destruction order: the buffer
// goes before its memory.
class HostBuffer {
public:
    HostBuffer(Context::Impl& context, vk::DeviceSize size, vk::BufferUsageFlags usage,
               BufferMemory memory = BufferMemory::HostVisible);
    vk::Buffer buffer() const { return *buffer_; }
    vk::DeviceSize size() const { return size_; }
    void* data() const { return mapped_; }  // nullptr when device-local
    // With eShaderDeviceAddress usage: where the device finds it (else 0).
    vk::DeviceAddress address() const { return address_; }
    void upload(const void* source, vk::DeviceSize bytes);  // host-visible only
    // Makes host writes through data() visible to the device on non-coherent memory.
    void flush();
    // Makes device writes visible to the host on non-coherent memory.
    void invalidate();

private:
    vk::DeviceSize size_;
    const vk::raii::Device* device_;
    bool coherent_ = true;
    vk::raii::DeviceMemory memory_ = nullptr;
    vk::raii::Buffer buffer_ = nullptr;
    void* mapped_ = nullptr;
    vk::DeviceAddress address_ = 0;
};

}  // namespace vkray::gpu
