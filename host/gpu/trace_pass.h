// One render's pass on the device: the scene's buffers, made as the shader
// variant reads them and bound to its pipeline, and the dispatches that trace
// one tile within the driver's loop limit. Internal to host/gpu.
#pragma once

#include "gpu/compute_pipeline.h"
#include "gpu/gpu_tracer.h"
#include "gpu/shader_variant.h"
#include "render/camera.h"
#include "scene/scene.h"
#include "shaders/layout.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vkray::gpu {

// The compute pipeline of one shader variant, kept while the variant stays
// the same (lavapipe compiles SPIR-V to machine code at pipeline creation).
struct Pipeline {
    std::string key;
    uint workgroupX = WORKGROUP_X, workgroupY = WORKGROUP_Y;  // trace.comp's local size
    ComputePipeline compute;
};

// The descriptor type a binding of this kind is declared with.
vk::DescriptorType descriptorTypeOf(BindingKind kind);

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
              const RenderSettings& settings, int tile);

    // Traces the rays of the tile at (tx, ty) of w x h pixels and waits; the
    // tile's pixels are then in pixels(), row-major with stride w. Each ray
    // does at most `turnBudget` counted loop turns per dispatch and the tile
    // is dispatched again until all are done (the image does not depend on
    // the budget). A dispatch the driver cut short (its canary ran short)
    // starts the tile over with a quarter of the budget, which later tiles
    // keep; when a single ray overruns the driver's limit, it is an Error.
    void traceTile(int tx, int ty, int w, int h, int block, uint& turnBudget,
                   GpuRenderStats& stats);

    // One dispatch over the tile; `first`: its rays start afresh. With
    // timestamps, its time on the device is added to *deviceSeconds.
    GpuDispatchStatus dispatch(int tx, int ty, int w, int h, int block, uint turnBudget,
                               bool first, std::optional<double>& deviceSeconds);

    // The device's queue writes timestamps (DeviceInfo::timestampValidBits).
    bool timesDispatches() const { return bool(*timestamps_); }

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
    void add(uint binding, const std::vector<T>& items);
    BindingKind kindOf(uint binding) const;
    // The same, `bytes` left as they are: the shader writes before it reads.
    void allocate(uint binding, size_t bytes);
    // Copies what add() staged into the device-local buffers, and waits.
    void copyStaged();
    HostBuffer& buffer(uint binding) const { return *buffers_.at(binding); }

    Context::Impl& c_;
    const Pipeline& pipeline_;
    std::map<uint, BindingKind> kinds_;                    // the variant's bindings
    uint firstSample_, endSample_;                         // the samples each ray traces
    std::map<uint, std::unique_ptr<HostBuffer>> buffers_;  // by binding
    struct Staged {
        std::unique_ptr<HostBuffer> from;  // host-visible
        vk::Buffer to;                     // device-local
        vk::DeviceSize bytes;
    };
    std::vector<Staged> staged_;               // until copyStaged()
    std::vector<vk::raii::BufferView> views_;  // of the texel buffers
    std::optional<DescriptorSet> descriptors_;
    vk::raii::CommandBuffer commands_ = nullptr;
    vk::raii::Fence fence_ = nullptr;
    vk::raii::QueryPool timestamps_ = nullptr;  // before and after the dispatch, if the queue can
};

}  // namespace vkray::gpu
