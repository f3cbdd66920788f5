#include "gpu/context_impl.h"

#include "util/error.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace vkray::gpu {

namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// What to do when no device is usable: the same advice everywhere.
const char* kDeviceAdvice =
    "install a Vulkan driver (on Debian: apt-get install mesa-vulkan-drivers for lavapipe, "
    "the CPU implementation), check VK_ICD_FILENAMES if set, or render with --cpu";

std::string deviceTypeName(vk::PhysicalDeviceType type) {
    switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu: return "discrete GPU";
    case vk::PhysicalDeviceType::eIntegratedGpu: return "integrated GPU";
    case vk::PhysicalDeviceType::eVirtualGpu: return "virtual GPU";
    case vk::PhysicalDeviceType::eCpu: return "CPU";
    default: return "other";
    }
}

// Lower is better: real GPUs before lavapipe.
int typeRank(vk::PhysicalDeviceType type) {
    switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu: return 0;
    case vk::PhysicalDeviceType::eIntegratedGpu: return 1;
    case vk::PhysicalDeviceType::eVirtualGpu: return 2;
    case vk::PhysicalDeviceType::eCpu: return 3;
    default: return 4;
    }
}

std::optional<std::uint32_t> computeQueueFamily(const vk::raii::PhysicalDevice& device) {
    auto families = device.getQueueFamilyProperties();
    for (std::uint32_t i = 0; i < families.size(); ++i)
        if (families[i].queueFlags & vk::QueueFlagBits::eCompute) return i;
    return std::nullopt;
}

bool hasExtension(const vk::raii::PhysicalDevice& device, const char* name) {
    for (const auto& extension : device.enumerateDeviceExtensionProperties())
        if (std::strcmp(extension.extensionName.data(), name) == 0) return true;
    return false;
}

// The device extensions a ray query needs.
constexpr std::array kRayQueryExtensions{VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                         VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                         VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

bool supportsRayQueries(const vk::raii::PhysicalDevice& device) {
    for (const char* name : kRayQueryExtensions)
        if (!hasExtension(device, name)) return false;
    // Features of extensions the device lacks are not asked for.
    const auto features = device.getFeatures2<
        vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceAccelerationStructureFeaturesKHR,
        vk::PhysicalDeviceRayQueryFeaturesKHR, vk::PhysicalDeviceBufferDeviceAddressFeatures>();
    return features.get<vk::PhysicalDeviceAccelerationStructureFeaturesKHR>()
               .accelerationStructure &&
           features.get<vk::PhysicalDeviceRayQueryFeaturesKHR>().rayQuery &&
           features.get<vk::PhysicalDeviceBufferDeviceAddressFeatures>().bufferDeviceAddress;
}

DeviceInfo describe(const vk::raii::PhysicalDevice& device, int index) {
    DeviceInfo info;
    info.index = index;
    auto chain =
        device.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties,
                              vk::PhysicalDeviceSubgroupProperties,
                              vk::PhysicalDeviceMaintenance3Properties>();
    const auto& props = chain.get<vk::PhysicalDeviceProperties2>().properties;
    const auto& driver = chain.get<vk::PhysicalDeviceDriverProperties>();
    info.subgroupSize = chain.get<vk::PhysicalDeviceSubgroupProperties>().subgroupSize;
    info.driverVersion = props.driverVersion;
    info.name = props.deviceName.data();
    info.type = deviceTypeName(props.deviceType);
    info.driverName = driver.driverName.data();
    info.driverInfo = driver.driverInfo.data();
    info.apiVersion = props.apiVersion;
    info.hasCompute = computeQueueFamily(device).has_value() && injectedFault() != Fault::NoCompute;
    info.shaderFloat64 = device.getFeatures().shaderFloat64 && injectedFault() != Fault::NoFloat64;
    info.rayQuery = props.apiVersion >= VK_API_VERSION_1_2 && supportsRayQueries(device) &&
                    injectedFault() != Fault::NoRayQuery;
    info.maxStorageBufferRange = props.limits.maxStorageBufferRange;
    info.maxUniformBufferRange = props.limits.maxUniformBufferRange;
    info.maxTexelBufferElements = props.limits.maxTexelBufferElements;
    info.maxMemoryAllocationSize =
        chain.get<vk::PhysicalDeviceMaintenance3Properties>().maxMemoryAllocationSize;
    // vkray's buffers are host-visible (HostBuffer): their heap is the one that counts.
    const vk::PhysicalDeviceMemoryProperties memory = device.getMemoryProperties();
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if (memory.memoryTypes[i].propertyFlags & vk::MemoryPropertyFlagBits::eHostVisible) {
            info.memoryHeapBytes = memory.memoryHeaps[memory.memoryTypes[i].heapIndex].size;
            break;
        }
    }
    for (int i = 0; i < 3; ++i) {
        info.maxWorkgroupCount[i] = props.limits.maxComputeWorkGroupCount[i];
        info.maxWorkgroupSize[i] = props.limits.maxComputeWorkGroupSize[i];
    }
    if (const auto family = computeQueueFamily(device);
        family && injectedFault() != Fault::NoTimestamps) {
        info.timestampValidBits = device.getQueueFamilyProperties()[*family].timestampValidBits;
        info.timestampPeriodNs = double(props.limits.timestampPeriod);
    }
    return info;
}

vk::raii::Instance createInstance(vk::raii::Context& context, bool validation,
                                  const std::vector<std::string>& surfaceExtensions = {}) {
    vk::ApplicationInfo app("vkray", 1, "vkray", 1, VK_API_VERSION_1_2);
    std::vector<const char*> layers, extensions;
    for (const std::string& name : surfaceExtensions) {
        bool found = false;
        for (const auto& extension : context.enumerateInstanceExtensionProperties())
            found = found || name == extension.extensionName.data();
        if (!found)
            throw Error(
                "the Vulkan loader lacks " + name +
                ", which a window needs; install a "
                "Vulkan driver with window-system support (on Debian: mesa-vulkan-drivers)");
        extensions.push_back(name.c_str());
    }
    if (validation) {
        bool found = false;
        for (const auto& layer : context.enumerateInstanceLayerProperties())
            found = found || std::strcmp(layer.layerName.data(), kValidationLayer) == 0;
        if (!found)
            throw Error(std::string("--validation: the layer ") + kValidationLayer +
                        " is not installed; on Debian: apt-get install vulkan-validationlayers");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    vk::InstanceCreateInfo info({}, &app, layers, extensions);
    return vk::raii::Instance(context, info);
}

std::vector<vk::raii::PhysicalDevice> enumerate(vk::raii::Instance& instance) {
    try {
        return vk::raii::PhysicalDevices(instance);
    } catch (const vk::SystemError&) {
        return {};
    }
}

// Index of the best device with a compute queue, or -1. Where several are
// equally good (a node with several GPUs), process `share` of a job takes
// the (share mod n)-th of them, so that MPI ranks on one node spread out.
int preferredDevice(const std::vector<DeviceInfo>& devices,
                    const std::vector<vk::raii::PhysicalDevice>& physical, int share = 0) {
    std::vector<int> best;
    for (size_t i = 0; i < devices.size(); ++i) {
        if (!devices[i].hasCompute || devices[i].apiVersion < VK_API_VERSION_1_2) continue;
        const auto rank = typeRank(physical[i].getProperties().deviceType);
        const auto bestRank =
            best.empty() ? rank : typeRank(physical[size_t(best[0])].getProperties().deviceType);
        if (rank < bestRank) best.clear();
        if (rank <= bestRank) best.push_back(int(i));
    }
    return best.empty() ? -1 : best[size_t(std::max(share, 0)) % best.size()];
}

std::string loaderFailure(const std::exception& e) {
    return std::string("cannot start Vulkan: ") + e.what() +
           "; install the Vulkan loader "
           "(on Debian: apt-get install libvulkan1) and a driver, or render with --cpu";
}

}  // namespace

Fault injectedFault() {
    const char* name = std::getenv("VKRAY_FAULT");
    if (!name || !*name) return Fault::None;
    const std::string fault = name;
    if (fault == "no-compute") return Fault::NoCompute;
    if (fault == "device-lost") return Fault::DeviceLost;
    if (fault == "out-of-device-memory") return Fault::OutOfDeviceMemory;
    if (fault == "no-float64") return Fault::NoFloat64;
    if (fault == "no-timestamps") return Fault::NoTimestamps;
    if (fault == "slow-progress") return Fault::SlowProgress;
    if (fault == "no-offset") return Fault::NoOffset;
    if (fault == "no-ray-query") return Fault::NoRayQuery;
    throw Error("VKRAY_FAULT='" + fault +
                "' is not a fault vkray can inject (no-compute, device-lost, "
                "out-of-device-memory, no-float64, no-timestamps, slow-progress, "
                "no-offset, no-ray-query); it is a test hook: "
                "unset it");
}

void explainVulkanFailure(const vk::SystemError& failure, const DeviceInfo& device) {
    const std::string on = " on " + device.name + " ";
    switch (vk::Result(failure.code().value())) {
    case vk::Result::eErrorDeviceLost:
        throw Error("the Vulkan device was lost during the render" + on +
                    "(VK_ERROR_DEVICE_LOST: the driver crashed or reset the GPU, e.g. after a "
                    "dispatch ran too long); nothing was written. Run again, check the driver "
                    "with `vkray devices`, or render with --cpu");
    case vk::Result::eErrorOutOfDeviceMemory:
        throw Error("out of device memory during the render" + on +
                    "(VK_ERROR_OUT_OF_DEVICE_MEMORY); nothing was written. Close other programs "
                    "that use the GPU, use fewer objects or smaller meshes, or render with --cpu");
    case vk::Result::eErrorOutOfHostMemory:
        throw Error("out of host memory during the render" + on +
                    "(VK_ERROR_OUT_OF_HOST_MEMORY); nothing was written. Use fewer objects or "
                    "smaller meshes, or render with --cpu");
    default:
        throw Error(std::string("Vulkan failed during the render") + on + "(" + failure.what() +
                    "); nothing was written. Check the driver with `vkray devices`, or render "
                    "with --cpu");
    }
}

std::string DeviceInfo::apiVersionString() const {
    return std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." +
           std::to_string(VK_API_VERSION_MINOR(apiVersion)) + "." +
           std::to_string(VK_API_VERSION_PATCH(apiVersion));
}

std::optional<std::uint32_t> Context::Impl::memoryTypeWith(std::uint32_t typeBits,
                                                           vk::MemoryPropertyFlags flags) const {
    auto memory = physicalDevice.getMemoryProperties();
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags)
            return i;
    return std::nullopt;
}

std::uint32_t Context::Impl::findMemoryType(std::uint32_t typeBits,
                                            vk::MemoryPropertyFlags flags) const {
    if (const std::optional<std::uint32_t> type = memoryTypeWith(typeBits, flags)) return *type;
    throw Error(
        std::string("the Vulkan device has no ") +
        (flags & vk::MemoryPropertyFlagBits::eHostVisible ? "host-visible" : "device-local") +
        " memory type for vkray's buffers");
}

std::vector<DeviceInfo> Context::listDevices(int* preferred) {
    try {
        vk::raii::Context context;
        vk::raii::Instance instance = createInstance(context, false);
        auto physical = enumerate(instance);
        std::vector<DeviceInfo> devices;
        for (size_t i = 0; i < physical.size(); ++i)
            devices.push_back(describe(physical[i], int(i)));
        if (preferred) *preferred = preferredDevice(devices, physical);
        return devices;
    } catch (const vk::IncompatibleDriverError&) {
        if (preferred) *preferred = -1;
        return {};
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(loaderFailure(e));
    }
}

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
    Impl& s = *impl_;
    try {
        s.instance = createInstance(s.context, options.validation, options.surfaceExtensions);
    } catch (const vk::IncompatibleDriverError&) {
        throw Error(std::string("no Vulkan driver found; ") + kDeviceAdvice);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(loaderFailure(e));
    }
    if (options.validation) {
        // Every validation message becomes an error with its text.
        vk::DebugUtilsMessengerCreateInfoEXT info(
            {},
            vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning |
                vk::DebugUtilsMessageSeverityFlagBitsEXT::eError,
            vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral |
                vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation |
                vk::DebugUtilsMessageTypeFlagBitsEXT::ePerformance,
            [](VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
               const VkDebugUtilsMessengerCallbackDataEXT* data, void* count) -> VkBool32 {
                std::fprintf(stderr, "vkray: validation: %s\n", data->pMessage);
                ++*static_cast<std::atomic<int>*>(count);
                return VK_FALSE;
            },
            &s.validationMessages);
        s.messenger.emplace(s.instance, info);
    }

    auto physical = enumerate(s.instance);
    if (physical.empty()) throw Error(std::string("no Vulkan device found; ") + kDeviceAdvice);
    std::vector<DeviceInfo> devices;
    for (size_t i = 0; i < physical.size(); ++i) devices.push_back(describe(physical[i], int(i)));

    int chosen = options.deviceIndex;
    if (chosen < 0) {
        chosen = preferredDevice(devices, physical, options.shareIndex);
        if (chosen < 0)
            throw Error(std::string("no Vulkan device with a compute queue and Vulkan 1.2; ") +
                        kDeviceAdvice);
    } else if (chosen >= int(physical.size())) {
        throw Error("--device " + std::to_string(chosen) + ": there are only " +
                    std::to_string(physical.size()) + " Vulkan devices (0 .. " +
                    std::to_string(physical.size() - 1) + "); `vkray devices` lists them");
    } else if (!devices[size_t(chosen)].hasCompute ||
               devices[size_t(chosen)].apiVersion < VK_API_VERSION_1_2) {
        throw Error("--device " + std::to_string(chosen) + " (" + devices[size_t(chosen)].name +
                    ") has no compute queue or lacks Vulkan 1.2; choose another with --device "
                    "(`vkray devices` lists them), or render with --cpu");
    }
    s.physicalDevice = std::move(physical[size_t(chosen)]);
    s.info = devices[size_t(chosen)];
    s.queueFamily = *computeQueueFamily(s.physicalDevice);

    float priority = 1.0f;
    vk::DeviceQueueCreateInfo queueInfo({}, s.queueFamily, 1, &priority);
    // Double in shaders (--precision fp64) where the device has it.
    vk::PhysicalDeviceFeatures enabled;
    enabled.shaderFloat64 = s.info.shaderFloat64;
    std::vector<const char*> deviceExtensions;
    if (options.swapchain) {
        bool found = false;
        for (const auto& extension : s.physicalDevice.enumerateDeviceExtensionProperties())
            found = found || std::strcmp(extension.extensionName.data(),
                                         VK_KHR_SWAPCHAIN_EXTENSION_NAME) == 0;
        if (!found)
            throw Error("the Vulkan device " + std::to_string(s.info.index) + " (" + s.info.name +
                        ") cannot present to a window (no " VK_KHR_SWAPCHAIN_EXTENSION_NAME
                        "); choose another with --device, or use `vkray render --watch`");
        deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    }
    // Ray queries where the device has them (--traversal rayquery).
    vk::StructureChain<vk::DeviceCreateInfo, vk::PhysicalDeviceAccelerationStructureFeaturesKHR,
                       vk::PhysicalDeviceRayQueryFeaturesKHR,
                       vk::PhysicalDeviceBufferDeviceAddressFeatures>
        chain;
    if (s.info.rayQuery) {
        deviceExtensions.insert(deviceExtensions.end(), kRayQueryExtensions.begin(),
                                kRayQueryExtensions.end());
        chain.get<vk::PhysicalDeviceAccelerationStructureFeaturesKHR>().accelerationStructure =
            true;
        chain.get<vk::PhysicalDeviceRayQueryFeaturesKHR>().rayQuery = true;
        chain.get<vk::PhysicalDeviceBufferDeviceAddressFeatures>().bufferDeviceAddress = true;
    } else {
        chain.unlink<vk::PhysicalDeviceAccelerationStructureFeaturesKHR>();
        chain.unlink<vk::PhysicalDeviceRayQueryFeaturesKHR>();
        chain.unlink<vk::PhysicalDeviceBufferDeviceAddressFeatures>();
    }
    vk::DeviceCreateInfo& deviceInfo = chain.get<vk::DeviceCreateInfo>();
    deviceInfo.setQueueCreateInfos(queueInfo);
    deviceInfo.setPEnabledExtensionNames(deviceExtensions);
    deviceInfo.setPEnabledFeatures(&enabled);
    s.device = vk::raii::Device(s.physicalDevice, deviceInfo);
    s.queue = s.device.getQueue(s.queueFamily, 0);
    s.commandPool = vk::raii::CommandPool(
        s.device, {vk::CommandPoolCreateFlagBits::eResetCommandBuffer, s.queueFamily});
}

Context::~Context() = default;

const DeviceInfo& Context::device() const {
    return impl_->info;
}

int Context::validationMessages() const {
    return impl_->validationMessages.load();
}

HostBuffer::HostBuffer(Context::Impl& context, vk::DeviceSize size, vk::BufferUsageFlags usage,
                       BufferMemory memory)
    : size_(size), device_(&context.device) {
    if (injectedFault() == Fault::OutOfDeviceMemory)
        throw vk::OutOfDeviceMemoryError("vkAllocateMemory (injected by VKRAY_FAULT)");
    buffer_ = vk::raii::Buffer(context.device, {{}, size, usage, vk::SharingMode::eExclusive});
    auto requirements = buffer_.getMemoryRequirements();
    auto properties = context.physicalDevice.getMemoryProperties();
    const bool local = memory == BufferMemory::DeviceLocal;
    const std::optional<std::uint32_t> cached =
        memory == BufferMemory::HostReadBack
            ? context.memoryTypeWith(requirements.memoryTypeBits,
                                     vk::MemoryPropertyFlagBits::eHostVisible |
                                         vk::MemoryPropertyFlagBits::eHostCached)
            : std::nullopt;
    const std::uint32_t type =
        cached ? *cached
               : context.findMemoryType(requirements.memoryTypeBits,
                                        local ? vk::MemoryPropertyFlagBits::eDeviceLocal
                                              : vk::MemoryPropertyFlagBits::eHostVisible);
    coherent_ = bool(properties.memoryTypes[type].propertyFlags &
                     vk::MemoryPropertyFlagBits::eHostCoherent);
    // Acceleration structures and their inputs are found by address.
    const bool addressed = bool(usage & vk::BufferUsageFlagBits::eShaderDeviceAddress);
    vk::MemoryAllocateFlagsInfo flags(vk::MemoryAllocateFlagBits::eDeviceAddress);
    memory_ = vk::raii::DeviceMemory(context.device,
                                     {requirements.size, type, addressed ? &flags : nullptr});
    buffer_.bindMemory(*memory_, 0);
    if (addressed) address_ = context.device.getBufferAddress({*buffer_});
    if (!local) mapped_ = memory_.mapMemory(0, VK_WHOLE_SIZE);
}

void HostBuffer::upload(const void* source, vk::DeviceSize bytes) {
    if (!mapped_) throw Error("internal: an upload to a device-local buffer without staging");
    std::memcpy(mapped_, source, size_t(bytes));
    flush();
}

void HostBuffer::flush() {
    if (coherent_) return;
    device_->flushMappedMemoryRanges(vk::MappedMemoryRange(*memory_, 0, VK_WHOLE_SIZE));
}

void HostBuffer::invalidate() {
    if (coherent_) return;
    device_->invalidateMappedMemoryRanges(vk::MappedMemoryRange(*memory_, 0, VK_WHOLE_SIZE));
}

}  // namespace vkray::gpu
