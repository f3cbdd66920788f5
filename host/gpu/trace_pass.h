// One render's pass on the device: the scene's buffers, made as the shader
// variant reads them and bound to its pipeline, and the dispatches that trace
// one tile within the driver's loop limit. Internal to host/gpu.
#pragma once

#include "gpu/compute_pipeline.h"
#include "gpu/gpu_tracer.h"
#include "gpu/scene_structure.h"
#include "gpu/shader_variant.h"
#include "render/camera.h"
#include "render/primary_cover.h"
#include "render/tile_schedule.h"
#include "scene/scene.h"
#include "shaders/layout.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
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

// Everything one render needs on the device: the scene's buffers, and for
// each of `slots` tiles in flight its own buffers (pixels, progress, status,
// pending rays, the debug and stress records), descriptor set, command
// buffer and fence. With several slots the next tiles are submitted before
// the host waits for this one, so the device traces them while the host
// reads this one back; traceTile() traces one tile in slot 0 and waits for it.
class TracePass {
public:
    // doubles: the fp64 variant, which also reads the camera and M^-1 in double.
    // cover: dispatch only the workgroups whose primary rays may meet an
    // object (render/primary_cover.h); the other pixels are misses
    // (missedPixel()), written into the pixel buffer too when
    // missesInBuffer (what reads the buffer itself wants every pixel there).
    struct Cover {
        bool enabled = false;
        bool missesInBuffer = false;
    };
    TracePass(Context::Impl& c, const Pipeline& pipeline, const ShaderFeatures& features,
              bool doubles, const Scene& scene, const CameraBasis& camera,
              const RenderSettings& settings, int tile, Cover cover, int slots = 1);
    // Waits for what is still in flight: the device may not outlive its buffers.
    ~TracePass();
    TracePass(const TracePass&) = delete;
    TracePass& operator=(const TracePass&) = delete;

    int slots() const { return int(slots_.size()); }
    // The ray-query variant's acceleration structure build, on the device (0: none).
    double structureSeconds() const { return structure_ ? structure_->buildSeconds() : 0; }
    // Workgroups dispatched, of all the workgroups of the tiles started.
    std::size_t groupsTraced() const { return groupsTraced_; }
    std::size_t groups() const { return groups_; }

    // Submits the first dispatch of the tile at (tx, ty) of w x h pixels in
    // `slot`, whose last tile must be finished; returns without waiting.
    void start(int slot, int tx, int ty, int w, int h, int block, uint turnBudget);
    // Waits for the tile of `slot` and dispatches it again until all its rays
    // are done; its pixels are then in pixels(slot), row-major with stride w.
    // Each ray does at most `turnBudget` counted loop turns per dispatch (the
    // image does not depend on the budget). A dispatch the driver cut short
    // (its canary ran short) starts the tile over with a quarter of the
    // budget, which later tiles keep; when a single ray overruns the
    // driver's limit, it is an Error. With timestamps, each dispatch's time
    // on the device is added to stats.deviceSeconds.
    void finish(int slot, uint& turnBudget, GpuRenderStats& stats);
    // Whether the slot's tile has a dispatch submitted and not yet finished
    // (none when all its rays meet nothing).
    bool inFlight(int slot) const { return slots_.at(size_t(slot)).inFlight; }
    // start() and finish() in slot 0.
    void traceTile(int tx, int ty, int w, int h, int block, uint& turnBudget,
                   GpuRenderStats& stats);

    // The pixels of the slot's tile that its dispatches wrote, and those
    // they left out, which are missedPixel()'s: tile-relative rectangles,
    // one a workgroup.
    const std::vector<TileRect>& tracedPixels(int slot = 0) const {
        return slots_.at(size_t(slot)).traced;
    }
    const std::vector<TileRect>& missedPixels(int slot = 0) const {
        return slots_.at(size_t(slot)).missed;
    }
    // The pixel of a primary ray that meets nothing, as the shader writes it.
    const GpuPixel& missedPixel() const { return missed_; }
    // A pixel's colour: the shader writes the sum of its samples, divided
    // here so that the mean is correctly rounded on every device (Vulkan
    // lets a device's division be 2.5 ulp off).
    glm::vec3 meanColor(const GpuPixel& p) const {
        const float n = float(endSample_ - firstSample_);
        return {p.color.x / n, p.color.y / n, p.color.z / n};
    }

    const GpuPixel* pixels(int slot = 0) const {
        return static_cast<const GpuPixel*>(buffer(BINDING_PIXELS, slot).data());
    }
    std::uint64_t pixelBuffer(int slot = 0) const {
        const VkBuffer handle = buffer(BINDING_PIXELS, slot).buffer();
        std::uint64_t bits = 0;
        static_assert(sizeof bits == sizeof handle);
        std::memcpy(&bits, &handle, sizeof bits);
        return bits;
    }
    const GpuStressSample* stressSamples(int slot = 0) const {
        return static_cast<const GpuStressSample*>(buffer(BINDING_STRESS_OUTPUT, slot).data());
    }
    const GpuDebugHeader& debugHeader() const {
        return *static_cast<const GpuDebugHeader*>(buffer(BINDING_DEBUG, 0).data());
    }
    const GpuDebugEntry* debugEntries() const {
        return reinterpret_cast<const GpuDebugEntry*>(&debugHeader() + 1);
    }

private:
    using Buffers = std::map<uint, std::unique_ptr<HostBuffer>>;  // by binding
    // One tile in flight: what the shader writes, and how it is dispatched.
    struct Slot {
        Buffers buffers;
        std::vector<vk::raii::BufferView> views;  // of its texel buffers, and of the scene's
        std::optional<DescriptorSet> descriptors;
        vk::raii::CommandBuffer commands = nullptr;
        vk::raii::Fence fence = nullptr;
        vk::raii::QueryPool timestamps =
            nullptr;                   // before and after the dispatch, if the queue can
        TileParams params{};           // of the dispatch submitted last
        uint groups = 0;               // the workgroups of its dispatches (none: nothing to trace)
        std::vector<TileRect> traced;  // their pixels
        std::vector<TileRect> missed;  // those of the workgroups left out
        bool inFlight = false;         // submitted, not yet waited for
    };

    // Records and submits one dispatch of the slot's tile; `first`: its rays start afresh.
    void submit(Slot& slot, bool first);
    // Waits for the slot's dispatch and returns its status.
    GpuDispatchStatus wait(Slot& slot, std::optional<double>& deviceSeconds);
    // The buffer of `binding`, made for the way the variant reads it, holding
    // `items`: the scene's, or with slot >= 0 that slot's own.
    template <typename T>
    void add(uint binding, const std::vector<T>& items, int slot = -1);
    BindingKind kindOf(uint binding) const;
    // The same, `bytes` left as they are: the shader writes before it reads.
    void allocate(uint binding, size_t bytes, int slot);
    // Copies what add() staged into the device-local buffers, and waits.
    void copyStaged();
    HostBuffer& buffer(uint binding, int slot = 0) const;

    Context::Impl& c_;
    const Pipeline& pipeline_;
    std::map<uint, BindingKind> kinds_;  // the variant's bindings
    uint firstSample_, endSample_;       // the samples each ray traces
    PrimaryCover cover_;                 // where primary rays may meet an object
    bool missesInBuffer_;                // the pixels outside it written into the buffer too
    GpuPixel missed_{};                  // the pixel of a ray that meets nothing
    std::size_t groupsTraced_ = 0, groups_ = 0;
    Buffers buffers_;  // the scene's, shared by the slots
    struct Staged {
        std::unique_ptr<HostBuffer> from;  // host-visible
        vk::Buffer to;                     // device-local
        vk::DeviceSize bytes;
    };
    std::vector<Staged> staged_;      // until copyStaged()
    std::vector<vk::Buffer> zeroed_;  // what the shader alone writes, filled by copyStaged()
    std::vector<Slot> slots_;
    std::unique_ptr<SceneStructure> structure_;  // the ray-query variant's
};

}  // namespace vkray::gpu
