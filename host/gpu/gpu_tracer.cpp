#include "gpu/gpu_tracer.h"

#include "gpu/context_impl.h"
#include "gpu/device_limits.h"
#include "gpu/gpu_scene.h"
#include "gpu/shader_variant.h"
#include "shaders/layout.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <time.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>

namespace vkray::gpu {

// The compute pipeline of one shader variant, kept while the variant stays
// the same (lavapipe compiles SPIR-V to machine code at pipeline creation).
struct Pipeline {
    std::string key;
    uint workgroupX = WORKGROUP_X, workgroupY = WORKGROUP_Y;  // trace.comp's local size
    vk::raii::DescriptorSetLayout setLayout = nullptr;
    vk::raii::PipelineLayout layout = nullptr;
    vk::raii::ShaderModule module = nullptr;
    vk::raii::Pipeline pipeline = nullptr;
};

namespace {

// CPU time of the whole process, lavapipe's worker threads included: on a
// machine shared with other work it stays about the work done.
double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

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

template <typename T>
std::unique_ptr<HostBuffer> makeBuffer(Context::Impl& c, const std::vector<T>& items,
                                       vk::BufferUsageFlags usage) {
    // Vulkan forbids empty buffers: an empty array still gets one element.
    // (Sizes were checked against the device's limits by checkBufferNeeds.)
    const vk::DeviceSize bytes = sizeof(T) * std::max<size_t>(items.size(), 1);
    auto buffer = std::make_unique<HostBuffer>(c, bytes, usage);
    if (!items.empty()) buffer->upload(items.data(), sizeof(T) * items.size());
    return buffer;
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
        {"tile pixels", tilePixels, sizeof(GpuPixel), false, "Use a smaller --block"},
        {"ray progress", tileRays, sizeof(GpuRayProgress), false, "Use a smaller --block"},
    };
    if (kinds.count(BINDING_LIGHTS))
        needs.push_back(need(BINDING_LIGHTS, "lights", packed.lights, "Use fewer lights"));
    if (pendingRays > 0)
        needs.push_back({"pending rays", pendingRays,
                         doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask), false,
                         "Use a smaller maxRecursionDepth"});
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

// Loop turns one ray may run in one dispatch (counted in trace.comp as
// loopTurns). llvmpipe ends every loop of an invocation once 65 535 turns
// have run in it, silently; 8 lanes share that count, and some loops are not
// counted, hence the margin. The canary catches what the margin misses.
constexpr uint kTurnBudget = 4096;
constexpr uint kCanaryTurns = 4;

// Everything one render needs on the device: the scene's buffers, the
// descriptor set and a command buffer; traceTile() traces one tile and
// waits for it.
class TracePass {
public:
    // doubles: the fp64 variant, which also reads the camera and M^-1 in double.
    TracePass(Context::Impl& c, const Pipeline& pipeline, const ShaderFeatures& features,
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
        const bool rayStack =
            features.has(Shading::Reflection) || features.has(Shading::Refraction);
        const size_t pendingRays = rayStack ? tileRays * size_t(pendingRayEntries(scene)) : 0;
        checkBufferNeeds(bufferNeeds(packed, features, doubles, size_t(tile) * size_t(tile),
                                     tileRays, pendingRays, debugEntries),
                         deviceLimits(c.info));
        const std::vector<FrameParams> frameParams{packFrame(scene, packed, camera, settings)};
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

        std::map<vk::DescriptorType, uint> descriptorCounts;
        for (const ShaderBinding& b : bindings) ++descriptorCounts[useOf(b.kind).descriptor];
        std::vector<vk::DescriptorPoolSize> poolSizes;
        for (const auto& [type, count] : descriptorCounts) poolSizes.emplace_back(type, count);
        pool_ = vk::raii::DescriptorPool(
            c.device, {vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, poolSizes});
        set_ = std::move(vk::raii::DescriptorSets(c.device, {*pool_, *pipeline.setLayout}).front());
        std::vector<vk::DescriptorBufferInfo> infos;
        infos.reserve(buffers_.size());
        views_.reserve(buffers_.size());
        std::vector<vk::WriteDescriptorSet> writes;
        for (const auto& [binding, buffer] : buffers_) {
            const BindingUse use = useOf(kindOf(binding));
            vk::WriteDescriptorSet& write =
                writes.emplace_back(*set_, binding, 0, 1, use.descriptor);
            if (use.texelBytes > 0) {
                views_.emplace_back(
                    c.device,
                    vk::BufferViewCreateInfo({}, buffer->buffer(), use.format, 0, VK_WHOLE_SIZE));
                write.setPTexelBufferView(&*views_.back());  // reserved: the views stay put
            } else {
                write.setPBufferInfo(&infos.emplace_back(buffer->buffer(), 0, VK_WHOLE_SIZE));
            }
        }
        c.device.updateDescriptorSets(writes, nullptr);

        commands_ = std::move(vk::raii::CommandBuffers(
                                  c.device, {*c.commandPool, vk::CommandBufferLevel::ePrimary, 1})
                                  .front());
        fence_ = vk::raii::Fence(c.device, vk::FenceCreateInfo{});
    }

    // Traces the rays of the tile at (tx, ty) of w x h pixels and waits; the
    // tile's pixels are then in pixels(), row-major with stride w. Each ray
    // does at most `turnBudget` counted loop turns per dispatch and the tile
    // is dispatched again until all are done (the image does not depend on
    // the budget). A dispatch the driver cut short (its canary ran short)
    // starts the tile over with a quarter of the budget, which later tiles
    // keep; when a single ray overruns the driver's limit, it is an Error.
    void traceTile(int tx, int ty, int w, int h, int block, uint& turnBudget,
                   GpuRenderStats& stats) {
        for (;;) {
            GpuDispatchStatus status{};
            bool first = true;
            do {
                status = dispatch(tx, ty, w, h, block, turnBudget, first);
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

    // One dispatch over the tile; `first`: its rays start afresh.
    GpuDispatchStatus dispatch(int tx, int ty, int w, int h, int block, uint turnBudget,
                               bool first) {
        const uint raysX = uint((w + block - 1) / block), raysY = uint((h + block - 1) / block);
        const TileParams tileParams{{uint(tx), uint(ty), uint(w), uint(h)},
                                    {turnBudget, first ? 1u : 0u, kCanaryTurns, raysX},
                                    {firstSample_, endSample_, 0u, 0u}};
        const GpuDispatchStatus zero{};
        buffer(BINDING_STATUS).upload(&zero, sizeof zero);
        commands_.reset();
        commands_.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
        commands_.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
        commands_.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, *set_,
                                     nullptr);
        commands_.pushConstants<TileParams>(*pipeline_.layout, vk::ShaderStageFlagBits::eCompute, 0,
                                            tileParams);
        const uint groupX = pipeline_.workgroupX, groupY = pipeline_.workgroupY;
        commands_.dispatch((raysX + groupX - 1) / groupX, (raysY + groupY - 1) / groupY, 1);
        // Shader writes must be visible to the host before the read-back.
        vk::MemoryBarrier toHost(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
        commands_.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                                  vk::PipelineStageFlagBits::eHost, {}, toHost, nullptr, nullptr);
        commands_.end();
        c_.queue.submit(vk::SubmitInfo({}, {}, *commands_), *fence_);
        if (c_.device.waitForFences(*fence_, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
            throw Error("the GPU did not finish a tile");
        if (injectedFault() == Fault::DeviceLost)  // after the wait: nothing still runs
            throw vk::DeviceLostError("vkWaitForFences (injected by VKRAY_FAULT)");
        c_.device.resetFences(*fence_);
        buffer(BINDING_PIXELS).invalidate();
        buffer(BINDING_STATUS).invalidate();
        if (buffers_.count(BINDING_DEBUG)) buffer(BINDING_DEBUG).invalidate();
        if (buffers_.count(BINDING_STRESS_OUTPUT)) buffer(BINDING_STRESS_OUTPUT).invalidate();
        return *static_cast<const GpuDispatchStatus*>(buffer(BINDING_STATUS).data());
    }

    const GpuPixel* pixels() const {
        return static_cast<const GpuPixel*>(buffer(BINDING_PIXELS).data());
    }
    std::uint64_t pixelBuffer() const {
        const VkBuffer handle = buffer(BINDING_PIXELS).buffer();
        std::uint64_t bits = 0;
        static_assert(sizeof bits == sizeof handle);
        std::memcpy(&bits, &handle, sizeof bits);
        return bits;
    }
    const GpuStressSample* stressSamples() const {
        return static_cast<const GpuStressSample*>(buffer(BINDING_STRESS_OUTPUT).data());
    }
    const GpuDebugHeader& debugHeader() const {
        return *static_cast<const GpuDebugHeader*>(buffer(BINDING_DEBUG).data());
    }
    const GpuDebugEntry* debugEntries() const {
        return reinterpret_cast<const GpuDebugEntry*>(&debugHeader() + 1);
    }

private:
    // The buffer of `binding`, made for the way the variant reads it, holding `items`.
    template <typename T>
    void add(uint binding, const std::vector<T>& items) {
        buffers_.emplace(binding, makeBuffer(c_, items, useOf(kindOf(binding)).usage));
    }
    BindingKind kindOf(uint binding) const {
        const auto found = kinds_.find(binding);
        if (found == kinds_.end())
            throw Error("internal: binding " + std::to_string(binding) + " is not the variant's");
        return found->second;
    }
    // The same, `bytes` left as they are: the shader writes before it reads.
    void allocate(uint binding, size_t bytes) {
        buffers_.emplace(binding,
                         std::make_unique<HostBuffer>(c_, bytes, useOf(kindOf(binding)).usage));
    }
    HostBuffer& buffer(uint binding) const { return *buffers_.at(binding); }

    Context::Impl& c_;
    const Pipeline& pipeline_;
    std::map<uint, BindingKind> kinds_;                    // the variant's bindings
    uint firstSample_, endSample_;                         // the samples each ray traces
    std::map<uint, std::unique_ptr<HostBuffer>> buffers_;  // by binding
    std::vector<vk::raii::BufferView> views_;              // of the texel buffers
    vk::raii::DescriptorPool pool_ = nullptr;
    vk::raii::DescriptorSet set_ = nullptr;
    vk::raii::CommandBuffer commands_ = nullptr;
    vk::raii::Fence fence_ = nullptr;
};

glm::dvec3 toDvec3(const vec4& v) {
    return {v.x, v.y, v.z};
}

double doubleOf(uint low, uint high) {
    const std::uint64_t bits = std::uint64_t(low) | (std::uint64_t(high) << 32);
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
}

// A GpuStressSample as the host reads it: t and the normal in double where
// the fp64 variant wrote them so.
StressSample decodeStressSample(const GpuStressSample& g, bool doubles) {
    StressSample s;
    std::memcpy(&s.object, &g.hit.x, sizeof s.object);
    s.inDouble = doubles;
    if (doubles) {
        s.t = doubleOf(g.primaryDouble.x, g.primaryDouble.y);
        s.normal = {doubleOf(g.primaryDouble.z, g.primaryDouble.w),
                    doubleOf(g.normalDouble.x, g.normalDouble.y),
                    doubleOf(g.normalDouble.z, g.normalDouble.w)};
    } else {
        s.t = g.primary.w;
        s.normal = toDvec3(g.primary);
    }
    if (s.object < 0) s.t = std::numeric_limits<double>::infinity();
    s.feelersTraced = g.hit.y;
    s.feelersMet = g.hit.z;
    s.feelersMetLeft = g.hit.w;
    s.refractedTraced = g.refractedHit.y != 0;
    std::memcpy(&s.refractedObject, &g.refractedHit.x, sizeof s.refractedObject);
    s.refractedT = g.refracted.w;
    s.refractedPoint = toDvec3(g.refracted);
    return s;
}

}  // namespace

void requirePrecisionSupported(Precision precision, const DeviceInfo& device) {
    if (precision == Precision::Fp64 && !device.shaderFloat64)
        throw Error("--precision fp64: the Vulkan device " + std::to_string(device.index) + " (" +
                    device.name +
                    ") has no shaderFloat64 (double in shaders); use --precision "
                    "robust, another --device (`vkray devices` lists them), or --cpu for the "
                    "double CPU reference");
}

ShaderFeatures variantFeatures(const Scene& scene, const RenderSettings& settings, bool allFeatures,
                               Precision precision) {
    ShaderFeatures features = featuresOf(scene, settings, allFeatures);
    features.doubles = precision == Precision::Fp64;
    return features;
}

ShaderSource variantSource(const std::string& shaderDirectory, const ShaderFeatures& features,
                           Precision precision, const Defines& userDefines) {
    Defines defines = precisionDefines(precision);
    defines.insert(defines.end(), userDefines.begin(), userDefines.end());
    return {shaderDirectory, "trace.comp", definesFor(features, defines)};
}

GpuTracer::GpuTracer(Context& context, GpuRenderOptions options)
    : context_(context), options_(std::move(options)) {}

GpuTracer::~GpuTracer() = default;

void GpuTracer::setTileListener(TileListener listener) {
    tileListener_ = std::move(listener);
}

const Pipeline& GpuTracer::pipelineFor(const ShaderFeatures& features, GpuRenderStats& stats) {
    requirePrecisionSupported(options_.precision, context_.device());
    ShaderSource source =
        variantSource(options_.shaderDirectory, features, options_.precision, options_.userDefines);
    const bool otherWorkgroup = options_.workgroupX > 0 && options_.workgroupY > 0;
    if (otherWorkgroup) {
        source.defines.emplace_back("VKRAY_WORKGROUP_X", std::to_string(options_.workgroupX));
        source.defines.emplace_back("VKRAY_WORKGROUP_Y", std::to_string(options_.workgroupY));
    }
    stats.shader = loadOrCompile(source);
    stats.variant = describe(features);
    for (auto kept = pipelines_.begin(); kept != pipelines_.end(); ++kept) {
        if ((*kept)->key != stats.shader.key) continue;
        std::rotate(kept, kept + 1, pipelines_.end());  // the last used goes last
        return *pipelines_.back();
    }

    Context::Impl& c = context_.impl();
    auto p = std::make_unique<Pipeline>();
    p->key = stats.shader.key;
    if (otherWorkgroup) {
        p->workgroupX = uint(options_.workgroupX);
        p->workgroupY = uint(options_.workgroupY);
    }
    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    const auto bind = [&](uint binding, vk::DescriptorType type) {
        bindings.emplace_back(binding, type, 1, vk::ShaderStageFlagBits::eCompute);
    };
    for (const ShaderBinding& b : bindingsFor(features)) bind(b.binding, useOf(b.kind).descriptor);
    p->setLayout = vk::raii::DescriptorSetLayout(c.device, {{}, bindings});
    const vk::PushConstantRange pushRange(vk::ShaderStageFlagBits::eCompute, 0, sizeof(TileParams));
    p->layout = vk::raii::PipelineLayout(c.device, {{}, *p->setLayout, pushRange});
    p->module = vk::raii::ShaderModule(c.device, {{}, stats.shader.spirv});
    p->pipeline = vk::raii::Pipeline(
        c.device, nullptr,
        vk::ComputePipelineCreateInfo(
            {}, {{}, vk::ShaderStageFlagBits::eCompute, *p->module, "main"}, *p->layout));
    if (pipelines_.size() == kPipelinesKept) pipelines_.erase(pipelines_.begin());
    pipelines_.push_back(std::move(p));
    return *pipelines_.back();
}

Frame GpuTracer::render(const Scene& scene, const CameraBasis& camera,
                        const RenderSettings& settings, GpuRenderStats* stats,
                        const RenderProgress& progress, TileSchedule* schedule) {
    return renderFrame(scene, camera, settings, stats, progress, schedule, nullptr);
}

Frame GpuTracer::renderStressOutput(const Scene& scene, const CameraBasis& camera,
                                    const RenderSettings& settings,
                                    std::vector<StressSample>& samples, GpuRenderStats* stats) {
    if (settings.block != 1) throw Error("internal: the stress output is per pixel (block 1)");
    return renderFrame(scene, camera, settings, stats, nullptr, nullptr, &samples);
}

Frame GpuTracer::renderFrame(const Scene& original, const CameraBasis& originalCamera,
                             const RenderSettings& settings, GpuRenderStats* stats,
                             const RenderProgress& progress, TileSchedule* schedule,
                             std::vector<StressSample>* stressSamples) try {
    const GpuInputs inputs = prepareGpuInputs(options_.precision, original, originalCamera);
    const Scene& scene = inputs.scene;
    const CameraBasis& camera = inputs.camera;
    if (settings.width < 1 || settings.height < 1 || settings.block < 1)
        throw Error("render: width, height and block must be at least 1");
    GpuRenderStats local;
    GpuRenderStats& st = stats ? *stats : local;

    const Stopwatch setup;
    if (settings.spp < 1 || settings.spp > kMaxSpp)
        throw Error("render: samples per pixel must be from 1 to " + std::to_string(kMaxSpp));
    const int samples = sampleEnd(settings) - settings.firstSample;  // traced per pixel
    ShaderFeatures features =
        variantFeatures(scene, settings, options_.allFeatures, options_.precision);
    features.stressOutput = stressSamples != nullptr;
    if (stressSamples && scene.lights.size() > STRESS_MAX_LIGHTS)
        throw Error("the stress output records the feelers of " +
                    std::to_string(STRESS_MAX_LIGHTS) + " lights; this scene has " +
                    std::to_string(scene.lights.size()));
    const Pipeline& pipeline = pipelineFor(features, st);
    // Tiles hold whole blocks, so a block never straddles two dispatches;
    // they shrink with the samples per pixel, so that no dispatch runs long,
    // and where the device's buffer or workgroup limits need it.
    const int block = settings.block;
    const int side = std::max(std::min(16, options_.tileSize),
                              options_.tileSize / int(std::ceil(std::sqrt(double(samples)))));
    // Per pixel at most (a ray per pixel): its pixel, progress and pending rays.
    const bool rayStack = features.has(Shading::Reflection) || features.has(Shading::Refraction);
    const size_t pixelBytes =
        sizeof(GpuPixel) + sizeof(GpuRayProgress) +
        (features.stressOutput ? sizeof(GpuStressSample) : 0) +
        (rayStack ? size_t(pendingRayEntries(scene)) *
                        (features.doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask))
                  : 0);
    const int tile =
        fitTileSide(std::max(block, side / block * block), block, pixelBytes, pipeline.workgroupX,
                    pipeline.workgroupY, deviceLimits(context_.device()));
    TracePass pass(context_.impl(), pipeline, features, features.doubles, scene, camera, settings,
                   tile);
    st.setupSeconds = setup.seconds() - st.shader.seconds;

    Frame frame(settings.width, settings.height);
    if (stressSamples) stressSamples->assign(frame.pixelCount(), StressSample{});
    const Stopwatch rendering;
    const double renderCpuStart = processCpuSeconds();
    st.tiles = 0;
    st.dispatches = 0;
    st.tilesRedone = 0;
    st.rays = 0;
    const size_t totalRays = size_t((settings.width + block - 1) / block) *
                             size_t((settings.height + block - 1) / block) * size_t(samples);
    if (progress && !progress(0, totalRays)) throw Interrupted();
    uint turnBudget = options_.turnBudget > 0 ? uint(options_.turnBudget) : kTurnBudget;
    AllTilesInRows everyTile(options_.serpentineTiles);
    TileSchedule& tiles = schedule ? *schedule : everyTile;
    tiles.plan(settings.width, settings.height, tile);
    while (const std::optional<TileRect> given = tiles.next()) {
        // A tile handed out by another process may be larger than this
        // device's: it is traced in pieces of this device's tile side.
        for (const TileRect& piece : tilesOf(given->width, given->height, tile)) {
            const int tx = given->x + piece.x, ty = given->y + piece.y;
            const int w = piece.width, h = piece.height;
            pass.traceTile(tx, ty, w, h, block, turnBudget, st);
            if (tileListener_) tileListener_(TracedTile{{tx, ty, w, h}, pass.pixelBuffer()});
            const GpuPixel* pixels = pass.pixels();
            const bool aovs = settings.firstSample == 0;  // sample 0 traced
            for (int y = 0; y < h; ++y) {
                for (int x = 0; x < w; ++x) {
                    const GpuPixel& p = pixels[size_t(y) * size_t(w) + size_t(x)];
                    const size_t i = frame.index(tx + x, ty + y);
                    frame.color[i] = {p.color.x, p.color.y, p.color.z};
                    if (!aovs) continue;
                    frame.depth[i] = p.color.w;
                    frame.normal[i] = {p.normal.x, p.normal.y, p.normal.z};
                    std::memcpy(&frame.id[i], &p.normal.w, sizeof(std::int32_t));
                    if (stressSamples)
                        (*stressSamples)[i] = decodeStressSample(
                            pass.stressSamples()[size_t(y) * size_t(w) + size_t(x)],
                            features.doubles);
                }
            }
            st.rays +=
                size_t((w + block - 1) / block) * size_t((h + block - 1) / block) * size_t(samples);
            ++st.tiles;
            if (progress && !progress(st.rays, totalRays)) throw Interrupted();
        }
        tiles.finished(*given, frame);
    }
    st.renderSeconds = rendering.seconds();
    st.renderCpuSeconds = processCpuSeconds() - renderCpuStart;
    return frame;
} catch (const vk::SystemError& failure) {
    explainVulkanFailure(failure, context_.device());
}

PixelTrace GpuTracer::tracePixel(const Scene& original, const CameraBasis& originalCamera,
                                 const RenderSettings& settings, int x, int y,
                                 GpuRenderStats* stats) try {
    const GpuInputs inputs = prepareGpuInputs(options_.precision, original, originalCamera);
    const Scene& scene = inputs.scene;
    const CameraBasis& camera = inputs.camera;
    if (x < 0 || y < 0 || x >= settings.width || y >= settings.height)
        throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                    std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                    " image");
    GpuRenderStats local;
    GpuRenderStats& st = stats ? *stats : local;
    // The debug record describes one ray: the pixel's centre, one sample.
    RenderSettings oneSample = settings;
    oneSample.spp = 1;
    oneSample.firstSample = 0;
    oneSample.sampleCount = 0;
    ShaderFeatures features =
        variantFeatures(scene, oneSample, options_.allFeatures, options_.precision);
    features.shading[size_t(Shading::Antialias)] = false;
    features.debugPixel = true;
    features.stressOutput = true;
    const Pipeline& pipeline = pipelineFor(features, st);
    TracePass pass(context_.impl(), pipeline, features, features.doubles, scene, camera, oneSample,
                   1);
    // A one-pixel tile at the corner of the pixel's block: its one ray is the block's.
    const int block = std::max(settings.block, 1);
    uint turnBudget = kTurnBudget;
    pass.traceTile(x - x % block, y - y % block, 1, 1, block, turnBudget, st);

    const GpuDebugHeader& header = pass.debugHeader();
    const GpuDebugEntry* entries = pass.debugEntries();
    const StressSample sample = decodeStressSample(pass.stressSamples()[0], features.doubles);
    PixelTrace trace;
    trace.x = x;
    trace.y = y;
    trace.digits = 9;  // the debug record and shading are float
    trace.geometryDigits = sample.inDouble ? 17 : 9;
    // Back from the mode's camera-relative world (gpu/precision.h) to the scene's.
    const glm::dvec3 shift = originalCamera.eye - camera.eye;
    trace.rayOrigin = toDvec3(header.rayOrigin) + shift;
    trace.rayDirection = toDvec3(header.rayDirection);
    for (uint i = 0; i < header.counts.x; ++i) {
        const float t = entries[i].first.w;
        trace.objects.push_back({toDvec3(entries[i].first), toDvec3(entries[i].second),
                                 std::isinf(t) ? std::nullopt : std::optional<double>(t)});
    }
    std::memcpy(&trace.hitObject, &header.normal.w, sizeof(std::int32_t));
    if (trace.hitObject >= 0) {
        trace.t = sample.t;
        trace.point = toDvec3(header.hitPoint) + shift;
        trace.normal = sample.normal;
        trace.emissive = toDvec3(header.emissive);
        trace.ambient = toDvec3(header.ambient);
    }
    for (uint i = 0; i < header.counts.y; ++i) {
        const GpuDebugEntry& e = entries[header.counts.x + i];
        PixelTrace::LightTerms terms{e.first.w, e.second.w, toDvec3(e.first), toDvec3(e.second)};
        if (i < STRESS_MAX_LIGHTS && sample.feelerTraced(int(i))) {
            terms.feelerMet = sample.feelerMet(int(i));
            terms.feelerMetLeft = sample.feelerMetLeft(int(i));
        }
        trace.lights.push_back(terms);
    }
    trace.color = toDvec3(header.color);
    return trace;
} catch (const vk::SystemError& failure) {
    explainVulkanFailure(failure, context_.device());
}

}  // namespace vkray::gpu
