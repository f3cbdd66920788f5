// The Vulkan instance, the chosen physical device, its logical device and a
// compute queue. Vulkan types stay behind a pimpl so that this header is
// cheap to include.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vkray::gpu {

struct DeviceInfo {
    int index = -1;  // position in the Vulkan enumeration (--device N)
    std::string name;
    std::string type;  // "discrete GPU", "integrated GPU", "CPU", ...
    std::string driverName;
    std::string driverInfo;
    std::uint32_t apiVersion = 0;
    std::uint32_t driverVersion =
        0;  // vendor-encoded; printed raw and as Vulkan's major.minor.patch
    std::uint32_t subgroupSize = 0;
    bool hasCompute = false;
    bool shaderFloat64 = false;
    // VK_KHR_ray_query with VK_KHR_acceleration_structure and buffer device
    // addresses (`--traversal rayquery`): lavapipe from Mesa 24.1, RTX GPUs.
    bool rayQuery = false;
    std::uint64_t maxStorageBufferRange = 0;
    std::uint64_t maxUniformBufferRange = 0;
    std::uint64_t maxTexelBufferElements = 0;
    std::uint64_t maxMemoryAllocationSize = 0;  // Vulkan 1.1 (maintenance3)
    std::uint64_t memoryHeapBytes = 0;          // the heap of the first host-visible memory type
    std::uint32_t maxWorkgroupCount[3] = {};
    std::uint32_t maxWorkgroupSize[3] = {};
    // Timestamp queries on the compute queue (the GPU's own time of a
    // dispatch): the valid bits of a timestamp (0: none) and ns per tick.
    std::uint32_t timestampValidBits = 0;
    double timestampPeriodNs = 0;
    std::string apiVersionString() const;
};

struct ContextOptions {
    int deviceIndex = -1;     // -1: prefer a discrete GPU, then integrated, ..., then lavapipe
    bool validation = false;  // enable VK_LAYER_KHRONOS_validation
    int shareIndex = 0;       // automatic choice: this process's index among those on its node
    // A window to present to (`vkray view`): the instance extensions its
    // window system's surfaces need, and VK_KHR_swapchain on the device.
    std::vector<std::string> surfaceExtensions;
    bool swapchain = false;
};

class Context {
public:
    // Throws Error with what to install or change when there is no Vulkan
    // loader, no device, or no usable compute device.
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& device() const;
    // Validation messages seen so far (with ContextOptions::validation).
    int validationMessages() const;
    // Every device Vulkan reports, and the index `render` would pick.
    static std::vector<DeviceInfo> listDevices(int* preferred = nullptr);

    struct Impl;  // defined in context_impl.h (host/gpu only)
    Impl& impl() { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

// Test hook (docs/reliability.md, "Test hooks"): VKRAY_FAULT=NAME makes the GPU side
// fail as a real device can but a test cannot cause: `no-compute` (every
// device lacks a compute queue), `device-lost` (after the first tile),
// `out-of-device-memory` (at the first buffer allocation), `no-float64` (no
// device has shaderFloat64), `no-timestamps` (no queue has timestamps); or `slow-progress`: every
// progress report of a render waits 25 ms, so that tests of progress lines and interruption do not
// depend on the machine's speed; or `no-offset`: the shader's secondary rays start on the surface
// they leave (VKRAY_FAULT_NO_OFFSET = 1), so that tests can show `vkray stress` counting the acne
// that follows; or `no-ray-query`: no device has ray queries. Unset: None. An unknown NAME is an
// Error.
enum class Fault {
    None,
    NoCompute,
    DeviceLost,
    OutOfDeviceMemory,
    NoFloat64,
    NoTimestamps,
    SlowProgress,
    NoOffset,
    NoRayQuery
};
Fault injectedFault();

}  // namespace vkray::gpu
