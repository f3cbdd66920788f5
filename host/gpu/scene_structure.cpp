#include "gpu/scene_structure.h"

#include "gpu/compute_pipeline.h"
#include "util/stopwatch.h"

#include <cmath>
#include <limits>
#include <vector>

namespace vkray::gpu {

namespace {

// The box in float, rounded outward and widened by `margin`; an empty or
// unbounded box is inactive (its minX NaN).
vk::AabbPositionsKHR floatBox(const Aabb& box, double margin) {
    if (!box.finite()) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        return {nan, 0, 0, nan, 0, 0};
    }
    const auto down = [&](double v) {
        return std::nextafter(float(v - margin), -std::numeric_limits<float>::infinity());
    };
    const auto up = [&](double v) {
        return std::nextafter(float(v + margin), std::numeric_limits<float>::infinity());
    };
    return {down(box.lo.x), down(box.lo.y), down(box.lo.z),
            up(box.hi.x),   up(box.hi.y),   up(box.hi.z)};
}

vk::DeviceSize alignedUp(vk::DeviceSize value, vk::DeviceSize alignment) {
    return alignment > 1 ? (value + alignment - 1) / alignment * alignment : value;
}

}  // namespace

SceneStructure::SceneStructure(Context::Impl& c, std::span<const Aabb> boxes, double scale) {
    using Usage = vk::BufferUsageFlagBits;
    const auto addressed = Usage::eShaderDeviceAddress;
    const vk::DeviceSize scratchAlignment =
        c.physicalDevice
            .getProperties2<vk::PhysicalDeviceProperties2,
                            vk::PhysicalDeviceAccelerationStructurePropertiesKHR>()
            .get<vk::PhysicalDeviceAccelerationStructurePropertiesKHR>()
            .minAccelerationStructureScratchOffsetAlignment;

    std::vector<vk::AabbPositionsKHR> floats;
    floats.reserve(boxes.size());
    for (const Aabb& box : boxes) floats.push_back(floatBox(box, kStructureBoxMargin * scale));
    const vk::DeviceSize boxBytes =
        sizeof(vk::AabbPositionsKHR) * std::max<size_t>(floats.size(), 1);
    boxes_ = std::make_unique<HostBuffer>(
        c, boxBytes, Usage::eAccelerationStructureBuildInputReadOnlyKHR | addressed);
    if (!floats.empty())
        boxes_->upload(floats.data(), sizeof(vk::AabbPositionsKHR) * floats.size());

    // Each box reported to the shader once: a feeler multiplies the
    // transparencies of the objects it meets.
    const vk::AccelerationStructureGeometryAabbsDataKHR boxData(boxes_->address(),
                                                                sizeof(vk::AabbPositionsKHR));
    const vk::AccelerationStructureGeometryKHR boxGeometry(
        vk::GeometryTypeKHR::eAabbs, boxData,
        vk::GeometryFlagBitsKHR::eNoDuplicateAnyHitInvocation);
    const std::uint32_t boxCount = std::uint32_t(floats.size());

    // Sizes, storage and scratch of one level; `build` gets its destination.
    std::vector<std::unique_ptr<HostBuffer>> scratch;
    const auto prepare = [&](vk::AccelerationStructureBuildGeometryInfoKHR& build,
                             std::uint32_t count, vk::AccelerationStructureTypeKHR type,
                             std::unique_ptr<HostBuffer>& storage) {
        const auto sizes = c.device.getAccelerationStructureBuildSizesKHR(
            vk::AccelerationStructureBuildTypeKHR::eDevice, build, count);
        storage = std::make_unique<HostBuffer>(
            c, std::max<vk::DeviceSize>(sizes.accelerationStructureSize, 256),
            Usage::eAccelerationStructureStorageKHR | addressed, BufferMemory::DeviceLocal);
        vk::raii::AccelerationStructureKHR structure(
            c.device, vk::AccelerationStructureCreateInfoKHR(
                          {}, storage->buffer(), 0, sizes.accelerationStructureSize, type));
        auto& room = scratch.emplace_back(std::make_unique<HostBuffer>(
            c, std::max<vk::DeviceSize>(sizes.buildScratchSize, 1) + scratchAlignment,
            Usage::eStorageBuffer | addressed, BufferMemory::DeviceLocal));
        build.dstAccelerationStructure = *structure;
        build.scratchData.deviceAddress = alignedUp(room->address(), scratchAlignment);
        return structure;
    };

    vk::AccelerationStructureBuildGeometryInfoKHR bottomBuild(
        vk::AccelerationStructureTypeKHR::eBottomLevel,
        vk::BuildAccelerationStructureFlagBitsKHR::ePreferFastTrace,
        vk::BuildAccelerationStructureModeKHR::eBuild, {}, {}, boxGeometry);
    bottom_ = prepare(bottomBuild, boxCount, vk::AccelerationStructureTypeKHR::eBottomLevel,
                      bottomStorage_);

    vk::AccelerationStructureInstanceKHR instance;
    for (int row = 0; row < 3; ++row) instance.transform.matrix[row][row] = 1;  // the identity
    instance.mask = 0xFF;
    instance.flags =
        VkGeometryInstanceFlagsKHR(vk::GeometryInstanceFlagBitsKHR::eTriangleFacingCullDisable);
    instance.accelerationStructureReference =
        c.device.getAccelerationStructureAddressKHR({*bottom_});
    instances_ = std::make_unique<HostBuffer>(
        c, sizeof instance, Usage::eAccelerationStructureBuildInputReadOnlyKHR | addressed);
    instances_->upload(&instance, sizeof instance);
    const vk::AccelerationStructureGeometryInstancesDataKHR instanceData(false,
                                                                         instances_->address());
    const vk::AccelerationStructureGeometryKHR instanceGeometry(vk::GeometryTypeKHR::eInstances,
                                                                instanceData);
    vk::AccelerationStructureBuildGeometryInfoKHR topBuild(
        vk::AccelerationStructureTypeKHR::eTopLevel,
        vk::BuildAccelerationStructureFlagBitsKHR::ePreferFastTrace,
        vk::BuildAccelerationStructureModeKHR::eBuild, {}, {}, instanceGeometry);
    top_ = prepare(topBuild, 1, vk::AccelerationStructureTypeKHR::eTopLevel, topStorage_);

    const Stopwatch building;
    vk::raii::CommandBuffer commands = makeCommandBuffer(c);
    commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    const vk::AccelerationStructureBuildRangeInfoKHR bottomRange(boxCount, 0, 0, 0);
    commands.buildAccelerationStructuresKHR(bottomBuild, &bottomRange);
    // The bottom level is built before the top level reads it, and both
    // before the first dispatch walks them.
    const auto built = [&](vk::PipelineStageFlags to, vk::AccessFlags access) {
        const vk::MemoryBarrier barrier(vk::AccessFlagBits::eAccelerationStructureWriteKHR, access);
        commands.pipelineBarrier(vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR, to, {},
                                 barrier, nullptr, nullptr);
    };
    built(vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
          vk::AccessFlagBits::eAccelerationStructureReadKHR);
    const vk::AccelerationStructureBuildRangeInfoKHR topRange(1, 0, 0, 0);
    commands.buildAccelerationStructuresKHR(topBuild, &topRange);
    built(vk::PipelineStageFlagBits::eComputeShader,
          vk::AccessFlagBits::eAccelerationStructureReadKHR);
    commands.end();
    const vk::raii::Fence fence(c.device, vk::FenceCreateInfo{});
    submitAndWait(c, vk::SubmitInfo({}, {}, *commands), fence,
                  "the acceleration structure's build");
    buildSeconds_ = building.seconds();
}

SceneStructure::~SceneStructure() = default;

}  // namespace vkray::gpu
