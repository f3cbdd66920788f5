#include "gpu/trace_pass.h"

#include "gpu/device_limits.h"
#include "gpu/gpu_scene.h"
#include "util/error.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace vkray::gpu {

namespace {

// How a binding of each kind is made: its descriptor, its buffer's usage
// and, for a texel buffer, the view's format and the bytes of one texel.
struct BindingUse {
    vk::DescriptorType descriptor;
    vk::BufferUsageFlags usage;
    vk::Format format = vk::Format::eUndefined;
    std::size_t texelBytes = 0;  // 0: not a texel buffer
};

BindingUse useOf(BindingKind kind) {
    using Usage = vk::BufferUsageFlagBits;
    switch (kind) {
    case BindingKind::Uniform: return {vk::DescriptorType::eUniformBuffer, Usage::eUniformBuffer};
    case BindingKind::Storage: return {vk::DescriptorType::eStorageBuffer, Usage::eStorageBuffer};
    case BindingKind::Texels:
        return {vk::DescriptorType::eStorageTexelBuffer, Usage::eStorageTexelBuffer,
                vk::Format::eR32G32B32A32Uint, 16};
    case BindingKind::UintTexels:
        return {vk::DescriptorType::eStorageTexelBuffer, Usage::eStorageTexelBuffer,
                vk::Format::eR32Uint, 4};
    }
    throw Error("internal: a binding of no known kind");
}

// What only the shader reads or writes lies in device-local memory: the
// scene's arrays, fp64's camera, each ray's progress and pending rays. What
// the host writes or reads during a render (the frame's parameters, the
// pixels, the status, the debug and stress records) stays host-visible.
BufferMemory memoryOf(uint binding, BindingKind kind) {
    const bool texels = kind == BindingKind::Texels || kind == BindingKind::UintTexels;
    return (texels && binding != BINDING_PIXELS) || binding == BINDING_DOUBLE_CAMERA
               ? BufferMemory::DeviceLocal
               : BufferMemory::HostVisible;
}

// Every buffer TracePass allocates for this variant, before it allocates any.
std::vector<BufferNeed> bufferNeeds(const GpuScene& packed, const ShaderFeatures& features,
                                    bool doubles, size_t tilePixels, size_t tileRays,
                                    size_t pendingRays, size_t debugEntries) {
    std::map<uint, BindingKind> kinds;
    for (const ShaderBinding& b : bindingsFor(features)) kinds[b.binding] = b.kind;
    // A scene array: a texel buffer, its texels those of its binding's kind.
    const auto need = [&](uint binding, const char* what, const auto& items, const char* advice) {
        return BufferNeed{what,  items.size(), sizeof(items[0]),
                          false, advice,       useOf(kinds.at(binding)).texelBytes};
    };
    const char* fewerObjects = "Use fewer objects";
    const char* smallerMeshes = "Use fewer or smaller meshes";
    std::vector<BufferNeed> needs{
        {"frame parameters", 1, sizeof(FrameParams), true, "Use another --device"},
        need(BINDING_OBJECTS, "objects", packed.objects, fewerObjects),
        need(BINDING_MATERIALS, "materials", packed.materials, fewerObjects),
        {"tile pixels", tilePixels, sizeof(GpuPixel), false, "Use a smaller --block",
         sizeof(uvec4)},
        {"ray progress", tileRays, sizeof(GpuRayProgress), false, "Use a smaller --block",
         sizeof(uvec4)},
    };
    if (kinds.count(BINDING_LIGHTS))
        needs.push_back(need(BINDING_LIGHTS, "lights", packed.lights, "Use fewer lights"));
    if (pendingRays > 0)
        needs.push_back({"pending rays", pendingRays,
                         doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask), false,
                         "Use a smaller maxRecursionDepth", sizeof(uvec4)});
    if (features.debugPixel)
        needs.push_back(
            {"debug entries", debugEntries, sizeof(GpuDebugEntry), false, fewerObjects});
    if (features.objectBvh) {
        needs.push_back(
            need(BINDING_OBJECT_NODES, "object BVH nodes", packed.objectNodes, fewerObjects));
        needs.push_back(
            need(BINDING_OBJECT_INDEX, "object BVH entries", packed.objectIndex, fewerObjects));
    }
    if (features.kinds[KIND_MESH]) {
        needs.push_back(need(BINDING_MESHES, "meshes", packed.meshes, smallerMeshes));
        needs.push_back(
            need(BINDING_MESH_NODES, "mesh BVH nodes", packed.meshNodes, smallerMeshes));
        needs.push_back(need(BINDING_TRIANGLES, "triangles", packed.triangles, smallerMeshes));
    }
    if (features.kinds[KIND_BOOLEAN])
        needs.push_back(
            need(BINDING_CSG_NODES, "CSG nodes", packed.csgNodes, "Use fewer or simpler booleans"));
    if (doubles)
        needs.push_back(
            need(BINDING_DOUBLE_OBJECTS, "double transforms", packed.doubleObjects, fewerObjects));
    if (features.stressOutput)
        needs.push_back(
            {"stress output", tilePixels, sizeof(GpuStressSample), false, "Use a smaller image"});
    return needs;
}

}  // namespace

vk::DescriptorType descriptorTypeOf(BindingKind kind) {
    return useOf(kind).descriptor;
}

template <typename T>
void TracePass::add(uint binding, const std::vector<T>& items) {
    // Vulkan forbids empty buffers: an empty array still gets one element.
    // (Sizes were checked against the device's limits by checkBufferNeeds.)
    const vk::DeviceSize bytes = sizeof(T) * std::max<size_t>(items.size(), 1);
    const BindingKind kind = kindOf(binding);
    vk::BufferUsageFlags usage = useOf(kind).usage;
    // `vkray view`'s presenter reads the tile's pixels as a storage buffer.
    if (binding == BINDING_PIXELS) usage |= vk::BufferUsageFlagBits::eStorageBuffer;
    if (memoryOf(binding, kind) == BufferMemory::HostVisible) {
        auto buffer = std::make_unique<HostBuffer>(c_, bytes, usage);
        if (!items.empty()) buffer->upload(items.data(), sizeof(T) * items.size());
        buffers_.emplace(binding, std::move(buffer));
        return;
    }
    auto buffer = std::make_unique<HostBuffer>(
        c_, bytes, usage | vk::BufferUsageFlagBits::eTransferDst, BufferMemory::DeviceLocal);
    if (!items.empty()) {
        auto staging =
            std::make_unique<HostBuffer>(c_, bytes, vk::BufferUsageFlagBits::eTransferSrc);
        staging->upload(items.data(), sizeof(T) * items.size());
        staged_.push_back({std::move(staging), buffer->buffer(), sizeof(T) * items.size()});
    }
    buffers_.emplace(binding, std::move(buffer));
}

void TracePass::copyStaged() {
    if (staged_.empty()) return;
    commands_.reset();
    commands_.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    for (const Staged& s : staged_)
        commands_.copyBuffer(s.from->buffer(), s.to, vk::BufferCopy(0, 0, s.bytes));
    // The copies must land before the first dispatch reads them.
    vk::MemoryBarrier copied(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eShaderRead);
    commands_.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                              vk::PipelineStageFlagBits::eComputeShader, {}, copied, nullptr,
                              nullptr);
    commands_.end();
    submitAndWait(c_, vk::SubmitInfo({}, {}, *commands_), fence_, "the scene's upload");
    staged_.clear();
}

BindingKind TracePass::kindOf(uint binding) const {
    const auto found = kinds_.find(binding);
    if (found == kinds_.end())
        throw Error("internal: binding " + std::to_string(binding) + " is not the variant's");
    return found->second;
}

void TracePass::allocate(uint binding, size_t bytes) {
    const BindingKind kind = kindOf(binding);
    buffers_.emplace(binding, std::make_unique<HostBuffer>(c_, bytes, useOf(kind).usage,
                                                           memoryOf(binding, kind)));
}

TracePass::TracePass(Context::Impl& c, const Pipeline& pipeline, const ShaderFeatures& features,
                     bool doubles, const Scene& scene, const CameraBasis& camera,
                     const RenderSettings& settings, int tile)
    : c_(c),
      pipeline_(pipeline),
      firstSample_(uint(settings.firstSample)),
      endSample_(uint(sampleEnd(settings))) {
    const GpuScene packed = packScene(scene, features);
    const size_t debugEntries = 4 + scene.objects.size() + scene.lights.size();
    const size_t raysPerSide = size_t((tile + settings.block - 1) / settings.block);
    const size_t tileRays = raysPerSide * raysPerSide;
    const bool rayStack = features.has(Shading::Reflection) || features.has(Shading::Refraction);
    const size_t pendingRays = rayStack ? tileRays * size_t(pendingRayEntries(scene)) : 0;
    checkBufferNeeds(bufferNeeds(packed, features, doubles, size_t(tile) * size_t(tile), tileRays,
                                 pendingRays, debugEntries),
                     deviceLimits(c.info));
    const std::vector<FrameParams> frameParams{packFrame(scene, packed, camera, settings)};
    commands_ = makeCommandBuffer(c);
    fence_ = vk::raii::Fence(c.device, vk::FenceCreateInfo{});
    if (c.info.timestampValidBits > 0 && c.info.timestampPeriodNs > 0)
        timestamps_ = vk::raii::QueryPool(
            c.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
    // Only the buffers this variant reads (the same list as its bindings).
    const std::vector<ShaderBinding> bindings = bindingsFor(features);
    for (const ShaderBinding& b : bindings) kinds_[b.binding] = b.kind;
    add(BINDING_FRAME, frameParams);
    add(BINDING_OBJECTS, packed.objects);
    add(BINDING_MATERIALS, packed.materials);
    if (kinds_.count(BINDING_LIGHTS)) add(BINDING_LIGHTS, packed.lights);
    add(BINDING_PIXELS, std::vector<GpuPixel>(size_t(tile) * size_t(tile)));
    allocate(BINDING_PROGRESS, sizeof(GpuRayProgress) * tileRays);
    add(BINDING_STATUS, std::vector<GpuDispatchStatus>(1));
    if (rayStack)
        allocate(BINDING_RAY_STACK,
                 pendingRays * (doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask)));
    if (features.debugPixel) {
        // A header and one entry per object and per light, zeroed.
        static_assert(sizeof(GpuDebugHeader) == 4 * sizeof(GpuDebugEntry));
        add(BINDING_DEBUG, std::vector<GpuDebugEntry>(debugEntries));
    }
    if (features.objectBvh) {
        add(BINDING_OBJECT_NODES, packed.objectNodes);
        add(BINDING_OBJECT_INDEX, packed.objectIndex);
    }
    if (features.kinds[KIND_MESH]) {
        add(BINDING_MESHES, packed.meshes);
        add(BINDING_MESH_NODES, packed.meshNodes);
        add(BINDING_TRIANGLES, packed.triangles);
    }
    if (features.kinds[KIND_BOOLEAN]) add(BINDING_CSG_NODES, packed.csgNodes);
    if (features.has(Shading::Pixmaps)) {
        add(BINDING_PIXMAPS, packed.pixmaps);
        add(BINDING_TEXELS, packed.texels);
    }
    if (doubles) {
        add(BINDING_DOUBLE_CAMERA, std::vector<GpuDoubleCamera>{packDoubleCamera(camera)});
        add(BINDING_DOUBLE_OBJECTS, packed.doubleObjects);
    }
    if (features.stressOutput)
        add(BINDING_STRESS_OUTPUT, std::vector<GpuStressSample>(size_t(tile) * size_t(tile)));
    // Exactly the variant's bindings (bindingsFor): no buffer uploaded for nothing.
    if (bindings.size() != buffers_.size())
        throw Error("internal: the buffers uploaded differ from the variant's bindings");
    copyStaged();

    descriptors_.emplace(c, pipeline.compute);
    const vk::DescriptorSet set = *descriptors_->set;
    std::vector<vk::DescriptorBufferInfo> infos;
    infos.reserve(buffers_.size());
    views_.reserve(buffers_.size());
    std::vector<vk::WriteDescriptorSet> writes;
    for (const auto& [binding, buffer] : buffers_) {
        const BindingUse use = useOf(kindOf(binding));
        vk::WriteDescriptorSet& write = writes.emplace_back(set, binding, 0, 1, use.descriptor);
        if (use.texelBytes > 0) {
            views_.emplace_back(c.device, vk::BufferViewCreateInfo({}, buffer->buffer(), use.format,
                                                                   0, VK_WHOLE_SIZE));
            write.setPTexelBufferView(&*views_.back());  // reserved: the views stay put
        } else {
            write.setPBufferInfo(&infos.emplace_back(buffer->buffer(), 0, VK_WHOLE_SIZE));
        }
    }
    c.device.updateDescriptorSets(writes, nullptr);
}

void TracePass::traceTile(int tx, int ty, int w, int h, int block, uint& turnBudget,
                          GpuRenderStats& stats) {
    for (;;) {
        GpuDispatchStatus status{};
        bool first = true;
        do {
            status = dispatch(tx, ty, w, h, block, turnBudget, first, stats.deviceSeconds);
            ++stats.dispatches;
            first = false;
        } while (status.counts.y == 0 && status.counts.x > 0);
        if (status.counts.y == 0) return;
        ++stats.tilesRedone;
        if (turnBudget == 1)
            throw BeyondTheLoopLimit(
                "the GPU cannot trace one ray of the tile at (" + std::to_string(tx) + ", " +
                std::to_string(ty) + ") within the driver's loop limit (" + c_.info.name +
                " ends every loop of an invocation after a fixed "
                "number of turns; llvmpipe's is 65 535), so the result would be "
                "wrong. Render with --cpu, or make the scene simpler for one ray "
                "(fewer lights, objects or triangles along it)");
        turnBudget = std::max<uint>(1, turnBudget / 4);
    }
}

GpuDispatchStatus TracePass::dispatch(int tx, int ty, int w, int h, int block, uint turnBudget,
                                      bool first, std::optional<double>& deviceSeconds) {
    const uint raysX = uint((w + block - 1) / block), raysY = uint((h + block - 1) / block);
    const TileParams tileParams{{uint(tx), uint(ty), uint(w), uint(h)},
                                {turnBudget, first ? 1u : 0u, kCanaryTurns, raysX},
                                {firstSample_, endSample_, 0u, 0u}};
    const GpuDispatchStatus zero{};
    buffer(BINDING_STATUS).upload(&zero, sizeof zero);
    commands_.reset();
    commands_.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    commands_.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.compute.pipeline);
    commands_.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.compute.layout, 0,
                                 *descriptors_->set, nullptr);
    commands_.pushConstants<TileParams>(*pipeline_.compute.layout,
                                        vk::ShaderStageFlagBits::eCompute, 0, tileParams);
    if (timesDispatches()) {
        commands_.resetQueryPool(*timestamps_, 0, 2);
        commands_.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *timestamps_, 0);
    }
    const uint groupX = pipeline_.workgroupX, groupY = pipeline_.workgroupY;
    commands_.dispatch((raysX + groupX - 1) / groupX, (raysY + groupY - 1) / groupY, 1);
    if (timesDispatches())
        commands_.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps_, 1);
    // Shader writes must be visible to the host before the read-back.
    vk::MemoryBarrier toHost(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
    commands_.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                              vk::PipelineStageFlagBits::eHost, {}, toHost, nullptr, nullptr);
    commands_.end();
    submitAndWait(c_, vk::SubmitInfo({}, {}, *commands_), fence_, "a tile");
    if (injectedFault() == Fault::DeviceLost)  // after the wait: nothing still runs
        throw vk::DeviceLostError("vkWaitForFences (injected by VKRAY_FAULT)");
    if (timesDispatches()) {
        // Both were written before the fence signalled: no wait.
        const auto [result, ticks] = timestamps_.getResults<std::uint64_t>(
            0, 2, 2 * sizeof(std::uint64_t), sizeof(std::uint64_t), vk::QueryResultFlagBits::e64);
        if (result != vk::Result::eSuccess)
            throw Error("the device's timestamps of a tile were not ready after its fence");
        const unsigned bits = c_.info.timestampValidBits;
        const std::uint64_t mask = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
        const std::uint64_t elapsed = ((ticks[1] & mask) - (ticks[0] & mask)) & mask;
        deviceSeconds = deviceSeconds.value_or(0.0) + double(elapsed) * c_.info.timestampPeriodNs * 1e-9;
    }
    buffer(BINDING_PIXELS).invalidate();
    buffer(BINDING_STATUS).invalidate();
    if (buffers_.count(BINDING_DEBUG)) buffer(BINDING_DEBUG).invalidate();
    if (buffers_.count(BINDING_STRESS_OUTPUT)) buffer(BINDING_STRESS_OUTPUT).invalidate();
    return *static_cast<const GpuDispatchStatus*>(buffer(BINDING_STATUS).data());
}

}  // namespace vkray::gpu
