#include "gpu/trace_pass.h"

#include "gpu/device_limits.h"
#include "gpu/gpu_scene.h"
#include "gpu/workgroup_order.h"
#include "scene/scene_geometry.h"
#include "util/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
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
    case BindingKind::Storage: return {vk::DescriptorType::eStorageBuffer, Usage::eStorageBuffer};
    case BindingKind::Texels:
        return {vk::DescriptorType::eStorageTexelBuffer, Usage::eStorageTexelBuffer,
                vk::Format::eR32G32B32A32Uint, 16};
    case BindingKind::UintTexels:
        return {vk::DescriptorType::eStorageTexelBuffer, Usage::eStorageTexelBuffer,
                vk::Format::eR32Uint, 4};
    case BindingKind::AccelerationStructure:
        return {vk::DescriptorType::eAccelerationStructureKHR, {}};
    }
    throw Error("internal: a binding of no known kind");
}

// What only the shader reads or writes lies in device-local memory: the
// scene's arrays, fp64's camera, each ray's progress and pending rays. What
// the host writes or reads during a render (the frame's parameters, the
// pixels, the status, the debug and stress records) stays host-visible,
// cached where the host reads it back.
BufferMemory memoryOf(uint binding, BindingKind kind) {
    const bool texels = kind == BindingKind::Texels || kind == BindingKind::UintTexels;
    if ((texels && binding != BINDING_PIXELS && binding != BINDING_RAY_GROUPS) ||
        binding == BINDING_DOUBLE_CAMERA || binding == BINDING_RAY_STACK)
        return BufferMemory::DeviceLocal;
    const bool readBack = binding == BINDING_PIXELS || binding == BINDING_STATUS ||
                          binding == BINDING_DEBUG || binding == BINDING_STRESS_OUTPUT;
    return readBack ? BufferMemory::HostReadBack : BufferMemory::HostVisible;
}

// Every buffer TracePass allocates for this variant, before it allocates any.
std::vector<BufferNeed> bufferNeeds(const GpuScene& packed, const ShaderFeatures& features,
                                    bool doubles, size_t tilePixels, size_t tileRays,
                                    size_t tileGroups, size_t pendingRays, size_t debugEntries,
                                    size_t slots) {
    std::map<uint, BindingKind> kinds;
    for (const ShaderBinding& b : bindingsFor(features)) kinds[b.binding] = b.kind;
    // A scene array: a texel buffer, its texels those of its binding's kind.
    const auto need = [&](uint binding, const char* what, const auto& items, const char* advice) {
        return BufferNeed{what, items.size(), sizeof(items[0]), advice,
                          useOf(kinds.at(binding)).texelBytes};
    };
    const char* fewerObjects = "Use fewer objects";
    const char* smallerMeshes = "Use fewer or smaller meshes";
    std::vector<BufferNeed> needs{
        {"frame parameters", 1, sizeof(FrameParams), "Use another --device"},
        need(BINDING_OBJECTS, "objects", packed.objects, fewerObjects),
        need(BINDING_MATERIALS, "materials", packed.materials, fewerObjects),
    };
    // Each tile in flight has its own.
    for (size_t slot = 0; slot < slots; ++slot) {
        needs.push_back(
            {"tile pixels", tilePixels, sizeof(GpuPixel), "Use a smaller --block", sizeof(uvec4)});
        needs.push_back(
            {"ray groups", tileGroups, sizeof(uint), "Use a smaller --block", sizeof(uint)});
        if (kinds.count(BINDING_PROGRESS))
            needs.push_back({"ray progress", tileRays, sizeof(GpuRayProgress),
                             "Use a smaller --block", sizeof(uvec4)});
        if (pendingRays > 0)
            needs.push_back({"pending rays", pendingRays,
                             doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask),
                             "Use a smaller maxRecursionDepth"});
        if (features.debugPixel)
            needs.push_back({"debug entries", debugEntries, sizeof(GpuDebugEntry), fewerObjects});
        if (features.stressOutput)
            needs.push_back(
                {"stress output", tilePixels, sizeof(GpuStressSample), "Use a smaller image"});
    }
    if (kinds.count(BINDING_LIGHTS))
        needs.push_back(need(BINDING_LIGHTS, "lights", packed.lights, "Use fewer lights"));
    if (features.objectBvh) {
        needs.push_back(
            need(BINDING_OBJECT_NODES, "object BVH nodes", packed.objectNodes, fewerObjects));
        needs.push_back(
            need(BINDING_OBJECT_INDEX, "object BVH entries", packed.objectIndex, fewerObjects));
    }
    if (features.kinds[KIND_MESH]) {
        needs.push_back(need(BINDING_MESHES, "meshes", packed.meshes, smallerMeshes));
        if (!meshNodesWithObjects(features))
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
    return needs;
}

// The pixel of a ray that meets nothing.
GpuPixel missOf(const glm::dvec3& background, bool aovs, uint samples) {
    // As the shader makes it: each sample's colour is the background's float,
    // their sum in sample order (meanColor() divides it).
    const float br = float(background.x), bg = float(background.y), bb = float(background.z);
    float r = 0, g = 0, bl = 0;
    for (uint k = 0; k < samples; ++k) r += br, g += bg, bl += bb;
    GpuPixel p{};
    p.color = {r, g, bl, 0};
    const std::int32_t none = -1;
    std::memcpy(&p.color.w, &none, sizeof none);
    if (aovs) p.normal = {0, 0, 0, std::numeric_limits<float>::infinity()};
    return p;
}

}  // namespace

vk::DescriptorType descriptorTypeOf(BindingKind kind) {
    return useOf(kind).descriptor;
}

namespace {

// The bindings the shader writes: each tile in flight has its own.
bool perTile(uint binding) {
    return binding == BINDING_PIXELS || binding == BINDING_RAY_GROUPS || binding == BINDING_TILE ||
           binding == BINDING_PROGRESS || binding == BINDING_STATUS ||
           binding == BINDING_RAY_STACK || binding == BINDING_DEBUG ||
           binding == BINDING_STRESS_OUTPUT;
}

}  // namespace

template <typename T>
void TracePass::add(uint binding, const std::vector<T>& items, int slot) {
    // Vulkan forbids empty buffers: an empty array still gets one element.
    // (Sizes were checked against the device's limits by checkBufferNeeds.)
    const vk::DeviceSize bytes = sizeof(T) * std::max<size_t>(items.size(), 1);
    const BindingKind kind = kindOf(binding);
    vk::BufferUsageFlags usage = useOf(kind).usage;
    // `vkray view`'s presenter reads the tile's pixels as a storage buffer.
    if (binding == BINDING_PIXELS) usage |= vk::BufferUsageFlagBits::eStorageBuffer;
    Buffers& into = slot < 0 ? buffers_ : slots_[size_t(slot)].buffers;
    if (const BufferMemory memory = memoryOf(binding, kind); memory != BufferMemory::DeviceLocal) {
        auto buffer = std::make_unique<HostBuffer>(c_, bytes, usage, memory);
        if (!items.empty()) buffer->upload(items.data(), sizeof(T) * items.size());
        into.emplace(binding, std::move(buffer));
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
    into.emplace(binding, std::move(buffer));
}

void TracePass::copyStaged() {
    if (staged_.empty() && zeroed_.empty()) return;
    const vk::raii::CommandBuffer& commands = slots_[0].commands;
    commands.reset();
    commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    for (const Staged& s : staged_)
        commands.copyBuffer(s.from->buffer(), s.to, vk::BufferCopy(0, 0, s.bytes));
    // Written once before any dispatch: on lavapipe, device memory is memory
    // no one has touched, and a shader's first write to a page it has read
    // faults, and makes the kernel flush every thread's TLB (IPIs), a few
    // per cent of a render that keeps rays between dispatches.
    for (const vk::Buffer buffer : zeroed_) commands.fillBuffer(buffer, 0, VK_WHOLE_SIZE, 0);
    // The copies must land before the first dispatch reads them.
    vk::MemoryBarrier copied(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eShaderRead);
    commands.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                             vk::PipelineStageFlagBits::eComputeShader, {}, copied, nullptr,
                             nullptr);
    commands.end();
    submitAndWait(c_, vk::SubmitInfo({}, {}, *commands), slots_[0].fence, "the scene's upload");
    staged_.clear();
    zeroed_.clear();
}

BindingKind TracePass::kindOf(uint binding) const {
    const auto found = kinds_.find(binding);
    if (found == kinds_.end())
        throw Error("internal: binding " + std::to_string(binding) + " is not the variant's");
    return found->second;
}

HostBuffer& TracePass::buffer(uint binding, int slot) const {
    return perTile(binding) ? *slots_.at(size_t(slot)).buffers.at(binding) : *buffers_.at(binding);
}

void TracePass::allocate(uint binding, size_t bytes, int slot) {
    const BindingKind kind = kindOf(binding);
    auto buffer = std::make_unique<HostBuffer>(
        c_, bytes, useOf(kind).usage | vk::BufferUsageFlagBits::eTransferDst,
        memoryOf(binding, kind));
    zeroed_.push_back(buffer->buffer());
    slots_[size_t(slot)].buffers.emplace(binding, std::move(buffer));
}

TracePass::TracePass(Context::Impl& c, const Pipeline& pipeline, const ShaderFeatures& features,
                     bool doubles, const Scene& scene, const CameraBasis& camera,
                     const RenderSettings& settings, int tile, Cover cover, int slots)
    : c_(c),
      pipeline_(pipeline),
      firstSample_(uint(settings.firstSample)),
      endSample_(uint(sampleEnd(settings))),
      cover_(settings),
      missesInBuffer_(cover.missesInBuffer),
      slots_(size_t(std::max(slots, 1))) {
    GpuScene packed = packScene(scene, features);
    if (cover.enabled)
        cover_ = PrimaryCover(coverShapesOf(scene, packed.objectBvh ? &*packed.objectBvh : nullptr),
                              camera, settings);
    packed.objectBvh.reset();
    missed_ = missOf(scene.background, features.aovs, endSample_ - firstSample_);
    const size_t debugEntries = 4 + scene.objects.size() + scene.lights.size();
    const size_t raysPerSide = size_t((tile + settings.block - 1) / settings.block);
    const size_t tileRays = raysPerSide * raysPerSide;
    const size_t tileGroups = ((raysPerSide + pipeline.workgroupX - 1) / pipeline.workgroupX) *
                              ((raysPerSide + pipeline.workgroupY - 1) / pipeline.workgroupY);
    const bool rayStack = features.has(Shading::Reflection) || features.has(Shading::Refraction);
    const size_t pendingRays = rayStack ? tileRays * size_t(pendingRayEntries(scene)) : 0;
    checkBufferNeeds(bufferNeeds(packed, features, doubles, size_t(tile) * size_t(tile), tileRays,
                                 tileGroups, pendingRays, debugEntries, slots_.size()),
                     deviceLimits(c.info));
    const std::vector<FrameParams> frameParams{packFrame(scene, packed, camera, settings)};
    for (Slot& slot : slots_) {
        slot.commands = makeCommandBuffer(c);
        slot.fence = vk::raii::Fence(c.device, vk::FenceCreateInfo{});
        if (c.info.timestampValidBits > 0 && c.info.timestampPeriodNs > 0)
            slot.timestamps = vk::raii::QueryPool(
                c.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
    }
    // Only the buffers this variant reads (the same list as its bindings).
    const std::vector<ShaderBinding> bindings = bindingsFor(features);
    for (const ShaderBinding& b : bindings) kinds_[b.binding] = b.kind;
    add(BINDING_FRAME, frameParams);
    add(BINDING_OBJECTS, packed.objects);
    add(BINDING_MATERIALS, packed.materials);
    if (kinds_.count(BINDING_LIGHTS)) add(BINDING_LIGHTS, packed.lights);
    for (int s = 0; s < int(slots_.size()); ++s) {
        add(BINDING_PIXELS, std::vector<GpuPixel>(size_t(tile) * size_t(tile)), s);
        add(BINDING_RAY_GROUPS, std::vector<uint>(tileGroups), s);
        if (kinds_.count(BINDING_PROGRESS))
            allocate(BINDING_PROGRESS, sizeof(GpuRayProgress) * tileRays, s);
        add(BINDING_STATUS, std::vector<GpuDispatchStatus>(1), s);
        add(BINDING_TILE, std::vector<TileParams>(1), s);
        if (rayStack)
            allocate(BINDING_RAY_STACK,
                     pendingRays * (doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask)), s);
        if (features.debugPixel) {
            // A header and one entry per object and per light, zeroed.
            static_assert(sizeof(GpuDebugHeader) == 4 * sizeof(GpuDebugEntry));
            add(BINDING_DEBUG, std::vector<GpuDebugEntry>(debugEntries), s);
        }
        if (features.stressOutput)
            add(BINDING_STRESS_OUTPUT, std::vector<GpuStressSample>(size_t(tile) * size_t(tile)),
                s);
    }
    if (features.objectBvh) {
        add(BINDING_OBJECT_NODES, packed.objectNodes);
        add(BINDING_OBJECT_INDEX, packed.objectIndex);
    }
    if (features.kinds[KIND_MESH]) {
        add(BINDING_MESHES, packed.meshes);
        if (!meshNodesWithObjects(features)) add(BINDING_MESH_NODES, packed.meshNodes);
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
    if (features.rayQuery) {
        // The boxes of the bounded objects, in the order of the BVH's entries (objectAt).
        std::vector<Aabb> boxes;
        double scale = 0;
        const auto reach = [&](const glm::dvec3& p) {
            scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        };
        reach(camera.eye);
        for (uint entry = 0; entry < packed.unboundedFirst; ++entry) {
            const Aabb box = worldBounds(scene.objects.at(packed.objectIndex[entry]), scene);
            if (box.finite()) reach(box.lo), reach(box.hi);
            boxes.push_back(box);
        }
        structure_ = std::make_unique<SceneStructure>(c, boxes, scale);
    }
    // Exactly the variant's bindings (bindingsFor): no buffer uploaded for nothing.
    if (bindings.size() != buffers_.size() + slots_[0].buffers.size() + (structure_ ? 1 : 0))
        throw Error("internal: the buffers uploaded differ from the variant's bindings");
    copyStaged();

    for (Slot& slot : slots_) {
        slot.descriptors.emplace(c, pipeline.compute);
        const vk::DescriptorSet set = *slot.descriptors->set;
        std::vector<vk::DescriptorBufferInfo> infos;
        infos.reserve(bindings.size());
        slot.views.reserve(bindings.size());
        std::vector<vk::WriteDescriptorSet> writes;
        for (const Buffers* group : {&buffers_, &slot.buffers}) {
            for (const auto& [binding, buffer] : *group) {
                const BindingUse use = useOf(kindOf(binding));
                vk::WriteDescriptorSet& write =
                    writes.emplace_back(set, binding, 0, 1, use.descriptor);
                if (use.texelBytes > 0) {
                    slot.views.emplace_back(
                        c.device, vk::BufferViewCreateInfo({}, buffer->buffer(), use.format, 0,
                                                           VK_WHOLE_SIZE));
                    write.setPTexelBufferView(&*slot.views.back());  // reserved: the views stay put
                } else {
                    write.setPBufferInfo(&infos.emplace_back(buffer->buffer(), 0, VK_WHOLE_SIZE));
                }
            }
        }
        const vk::AccelerationStructureKHR structure = structure_ ? structure_->handle() : nullptr;
        const vk::WriteDescriptorSetAccelerationStructureKHR structureInfo(structure);
        if (structure_)
            writes
                .emplace_back(set, BINDING_SCENE_STRUCTURE, 0, 1,
                              vk::DescriptorType::eAccelerationStructureKHR)
                .setPNext(&structureInfo);
        c.device.updateDescriptorSets(writes, nullptr);
    }
}

TracePass::~TracePass() {
    for (Slot& slot : slots_) {
        if (!slot.inFlight) continue;
        // Unwinding (an error, an interruption): the device finishes before
        // the buffers go; a failing wait changes nothing then.
        try {
            (void)c_.device.waitForFences(*slot.fence, VK_TRUE, UINT64_MAX);
        } catch (...) {
        }
    }
}

void TracePass::traceTile(int tx, int ty, int w, int h, int block, uint& turnBudget,
                          GpuRenderStats& stats) {
    start(0, tx, ty, w, h, block, turnBudget);
    finish(0, turnBudget, stats);
}

void TracePass::start(int slot, int tx, int ty, int w, int h, int block, uint turnBudget) {
    Slot& s = slots_.at(size_t(slot));
    if (s.inFlight) throw Error("internal: a tile started in a slot still in flight");
    const uint raysX = uint((w + block - 1) / block), raysY = uint((h + block - 1) / block);
    s.params = TileParams{{uint(tx), uint(ty), uint(w), uint(h)},
                          {turnBudget, 1u, kCanaryTurns, raysX},
                          {firstSample_, endSample_, 0u, 0u}};
    // The workgroups whose rays may meet an object are dispatched; the
    // others' pixels are misses.
    const int groupX = int(pipeline_.workgroupX), groupY = int(pipeline_.workgroupY);
    HostBuffer& pixels = buffer(BINDING_PIXELS, slot);
    HostBuffer& groups = buffer(BINDING_RAY_GROUPS, slot);
    auto* tilePixels = static_cast<GpuPixel*>(pixels.data());
    auto* groupList = static_cast<uint*>(groups.data());
    s.groups = 0;
    s.traced.clear();
    s.missed.clear();
    for (int gy = 0; gy * groupY < int(raysY); ++gy) {
        for (int gx = 0; gx * groupX < int(raysX); ++gx) {
            // Its rays' blocks, which may reach past the tile at the image's edge.
            const int x0 = gx * groupX * block, y0 = gy * groupY * block;
            const int x1 = std::min((gx + 1) * groupX, int(raysX)) * block;
            const int y1 = std::min((gy + 1) * groupY, int(raysY)) * block;
            ++groups_;
            const TileRect rect{x0, y0, std::min(x1, w) - x0, std::min(y1, h) - y0};
            if (cover_.mayHit(tx + x0, ty + y0, tx + x1, ty + y1)) {
                groupList[s.groups++] = uint(gx) | (uint(gy) << RAY_GROUP_SHIFT);
                s.traced.push_back(rect);
                continue;
            }
            s.missed.push_back(rect);
            if (!missesInBuffer_) continue;
            for (int y = y0; y < std::min(y1, h); ++y)
                for (int x = x0; x < std::min(x1, w); ++x)
                    tilePixels[size_t(y) * size_t(w) + size_t(x)] = missed_;
        }
    }
    groupsTraced_ += s.groups;
    spreadForContiguousSplits({groupList, s.groups});
    pixels.flush();
    groups.flush();
    if (s.groups > 0) submit(s, true);
}

void TracePass::finish(int slot, uint& turnBudget, GpuRenderStats& stats) {
    Slot& s = slots_.at(size_t(slot));
    if (s.groups == 0) return;  // every pixel of the tile shows the background
    for (;;) {
        const GpuDispatchStatus status = wait(s, stats.deviceSeconds);
        ++stats.dispatches;
        if (status.counts.y != 0) {
            // The driver cut a dispatch short: the tile starts over, with less work a dispatch.
            ++stats.tilesRedone;
            const TileParams& p = s.params;
            if (p.work.x == 1)
                throw BeyondTheLoopLimit(
                    "the GPU cannot trace one ray of the tile at (" + std::to_string(p.tile.x) +
                    ", " + std::to_string(p.tile.y) + ") within the driver's loop limit (" +
                    c_.info.name +
                    " ends every loop of an invocation after a fixed "
                    "number of turns; llvmpipe's is 65 535), so the result would be "
                    "wrong. Render with --cpu, or make the scene simpler for one ray "
                    "(fewer lights, objects or triangles along it)");
            turnBudget = std::min(turnBudget, std::max<uint>(1, p.work.x / 4));
            s.params.work.x = turnBudget;
            submit(s, true);
        } else if (status.counts.x > 0) {
            submit(s, false);  // some rays paused: they go on where they stopped
        } else {
            return;
        }
    }
}

void TracePass::submit(Slot& s, bool first) {
    s.params.work.y = first ? 1u : 0u;
    const GpuDispatchStatus zero{};
    buffer(BINDING_STATUS, int(&s - slots_.data())).upload(&zero, sizeof zero);
    buffer(BINDING_TILE, int(&s - slots_.data())).upload(&s.params, sizeof s.params);
    const vk::raii::CommandBuffer& commands = s.commands;
    commands.reset();
    commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    // A resumed tile reads the progress and pending rays its previous
    // dispatch wrote, and any dispatch overwrites what the slot's last one
    // wrote: those writes must be visible to this one (the fence orders the
    // host's reads only).
    const vk::MemoryBarrier previous(
        vk::AccessFlagBits::eShaderWrite,
        vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
    commands.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                             vk::PipelineStageFlagBits::eComputeShader, {}, previous, nullptr,
                             nullptr);
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.compute.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.compute.layout, 0,
                                *s.descriptors->set, nullptr);
    if (*s.timestamps) {
        commands.resetQueryPool(*s.timestamps, 0, 2);
        // Written once earlier dispatches (the other slot's) are done with
        // the compute stage, so that no two tiles' intervals overlap.
        commands.writeTimestamp(vk::PipelineStageFlagBits::eComputeShader, *s.timestamps, 0);
    }
    commands.dispatch(s.groups, 1, 1);
    if (*s.timestamps)
        commands.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *s.timestamps, 1);
    // Shader writes must be visible to the host before the read-back.
    vk::MemoryBarrier toHost(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
    commands.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                             vk::PipelineStageFlagBits::eHost, {}, toHost, nullptr, nullptr);
    commands.end();
    c_.queue.submit(vk::SubmitInfo({}, {}, *commands), *s.fence);
    s.inFlight = true;
}

GpuDispatchStatus TracePass::wait(Slot& s, std::optional<double>& deviceSeconds) {
    const int slot = int(&s - slots_.data());
    if (c_.device.waitForFences(*s.fence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
        throw Error("waiting for a tile failed");
    s.inFlight = false;
    c_.device.resetFences(*s.fence);
    if (injectedFault() == Fault::DeviceLost)  // after the wait: nothing still runs
        throw vk::DeviceLostError("vkWaitForFences (injected by VKRAY_FAULT)");
    if (*s.timestamps) {
        // Both were written before the fence signalled: no wait.
        const auto [result, ticks] = s.timestamps.getResults<std::uint64_t>(
            0, 2, 2 * sizeof(std::uint64_t), sizeof(std::uint64_t), vk::QueryResultFlagBits::e64);
        if (result != vk::Result::eSuccess)
            throw Error("the device's timestamps of a tile were not ready after its fence");
        const unsigned bits = c_.info.timestampValidBits;
        const std::uint64_t mask = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
        const std::uint64_t elapsed = ((ticks[1] & mask) - (ticks[0] & mask)) & mask;
        deviceSeconds =
            deviceSeconds.value_or(0.0) + double(elapsed) * c_.info.timestampPeriodNs * 1e-9;
    }
    buffer(BINDING_PIXELS, slot).invalidate();
    buffer(BINDING_STATUS, slot).invalidate();
    if (kinds_.count(BINDING_DEBUG)) buffer(BINDING_DEBUG, slot).invalidate();
    if (kinds_.count(BINDING_STRESS_OUTPUT)) buffer(BINDING_STRESS_OUTPUT, slot).invalidate();
    return *static_cast<const GpuDispatchStatus*>(buffer(BINDING_STATUS, slot).data());
}

}  // namespace vkray::gpu
