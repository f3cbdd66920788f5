// The GPU renderer: packs the scene into the std430 arrays of
// shaders/layout.h, compiles (or loads from cache) the shader variant the
// scene needs, and dispatches it in tiles.
#pragma once

#include "gpu/context.h"
#include "gpu/precision.h"
#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"
#include "gpu/traversal.h"
#include "image/frame.h"
#include "image/pixel_trace.h"
#include "image/stress_sample.h"
#include "render/camera.h"
#include "render/render_progress.h"
#include "render/tile_schedule.h"
#include "scene/scene.h"
#include "util/error.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vkray::gpu {

// The tile side that suits a device: 256 on a CPU (lavapipe: two tiles in
// flight keep both threads busy, and a short dispatch answers `vkray view`
// soon), 1024 on a GPU, whose thousands of lanes a 256-pixel tile leaves
// idle (an H200 traced a million-triangle mesh in 5 ms of device time a
// 1080p frame with 1024-pixel tiles, 18 ms with 256: BENCHMARKS.md).
int defaultTileSide(const DeviceInfo& device);

struct GpuRenderOptions {
    std::string shaderDirectory;
    bool allFeatures = false;  // compile every shape in, whatever the scene uses
    // The mesh objects' triangles placed in world space where they fit
    // (meshesFitWorldSpace); false: each mesh walked in its generic space,
    // as the all-features variant does (tests compare the two).
    bool worldTriangles = true;
    // Pixels per tile side (rounded to a multiple of the block); 0: the
    // device's own (defaultTileSide()).
    int tileSize = 0;
    Defines userDefines;  // -D NAME=VALUE, after the variant's own
    // gpu/precision.h: the mode's defines and host-side scene preparation.
    Precision precision = Precision::Robust;
    // trace.comp's workgroup size; 0: layout.h's WORKGROUP_X x WORKGROUP_Y.
    // Other shapes are for benchmarks (vkray_bench --workgroup).
    int workgroupX = 0, workgroupY = 0;
    bool serpentineTiles = false;  // tile rows alternately right to left (else all left to right)
    // The walk that finds the objects (gpu/traversal.h); `vkray pixel` and
    // the stress record always take the own walk, whose tests they count.
    Traversal traversal = Traversal::Auto;
    // Dispatch only the workgroups whose primary rays may meet an object
    // (render/primary_cover.h); the others' pixels are written as misses,
    // the same bytes. Robust and fp64 only: naive's misses are as the
    // textbook's formulas make them. Benchmarks turn it off to compare.
    bool primaryCover = true;
    // Counted loop turns one ray may run in one dispatch before it pauses
    // (0: the renderer's own bound, well below llvmpipe's loop limit). The
    // image is the same whatever the bound; tests set it low to prove that.
    int turnBudget = 0;
};

struct GpuRenderStats {
    double renderSeconds = 0;  // the dispatch loop, tiles read back included
    double renderCpuSeconds =
        0;  // CPU time of the process (all threads: lavapipe's too) in that loop
    // The scene's preparation before the first dispatch: its device inputs,
    // object BVH, world-space triangles, primary cover, buffers, uploads and
    // the frame (the shader's compile and the pipeline's creation excluded).
    double setupSeconds = 0, setupCpuSeconds = 0;
    double pipelineSeconds = 0;  // the driver creating the pipeline (0 when it was kept)
    double readBackSeconds = 0;  // within the dispatch loop: tiles copied into the frame
    // Within the dispatch loop: until the first dispatched tile was traced.
    // lavapipe compiles a pipeline's machine code at its first dispatch, so
    // on a fresh pipeline this holds that compile.
    double firstTileSeconds = 0;
    // The dispatches' own time on the device, from timestamp queries written
    // before and after each: what the wall clock holds less the host's part
    // (submits, waits, read-back). Empty where the queue has no timestamps.
    std::optional<double> deviceSeconds;
    CompiledShader shader;  // SPIR-V, key, cache hit, compile/load time
    std::string variant;    // describe(features), e.g. "sphere+cube"
    std::string traversal;  // the walk taken and why (chooseTraversal)
    // Within setupSeconds: the ray-query variant's acceleration structure
    // built on the device (0 for the own walk, whose BVH is built on the host).
    double structureSeconds = 0;
    std::size_t tiles = 0;
    std::size_t dispatches = 0;   // a tile takes several when its rays pause (turnBudget)
    std::size_t tilesRedone = 0;  // started over: the driver's loop limit cut a dispatch short
    std::size_t rays = 0;         // primary rays traced (or known to meet nothing)
    // Workgroups of rays dispatched, of all the frame's: the others' primary
    // rays meet nothing (GpuRenderOptions::primaryCover).
    std::size_t groupsTraced = 0, groups = 0;
};

// The variant a render of `scene` uses, and its source: what render
// compiles and `vkray features` reports (the same SPIR-V cache key). `eye`
// and the device's maxTexels decide whether meshes go into world space
// (placeMeshesInWorldWhereTheyFit).
ShaderFeatures variantFeatures(const Scene& scene, const RenderSettings& settings, bool allFeatures,
                               Precision precision, const glm::dvec3& eye, std::uint64_t maxTexels);
ShaderSource variantSource(const std::string& shaderDirectory, const ShaderFeatures& features,
                           Precision precision, const Defines& userDefines);

struct Pipeline;

// A tile just traced, its pixels still in the device's buffer: what `vkray
// view` copies to its window on the device (gpu/presenter.h). Each pixel's
// colour is the sum of the samples traced (view traces one a pass).
struct TracedTile {
    TileRect rect;                  // pixels of the image
    std::uint64_t pixelBuffer = 0;  // its VkBuffer: GpuPixel[rect.width * rect.height], row-major
};
using TileListener = std::function<void(const TracedTile&)>;

// The render the device cannot do right: one ray needs more loop turns than
// the driver runs in one invocation (llvmpipe's loop limit). It is refused
// rather than drawn wrong.
class BeyondTheLoopLimit : public Error {
public:
    using Error::Error;
};

// Throws Error, naming the device, where it cannot run the precision mode
// (fp64 without shaderFloat64).
void requirePrecisionSupported(Precision precision, const DeviceInfo& device);

class GpuTracer {
public:
    GpuTracer(Context& context, GpuRenderOptions options);

    // The precision mode of the renders from now on (`--precision auto`
    // chooses it per scene).
    void setPrecision(Precision precision) { options_.precision = precision; }

    ~GpuTracer();

    // Checks the scene against the device's limits before allocating (an
    // Error naming the count, the limit and what to do), then traces it tile
    // by tile; `progress` hears after each tile and can stop the render
    // (Interrupted). A device lost or out of memory is an Error saying so.
    // `schedule` chooses the tiles, one at a time, and the frame's other
    // pixels are left as Frame() made them; without one, every tile is
    // traced in rows, the next submitted before the host waits for this one.
    Frame render(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                 GpuRenderStats* stats = nullptr, const RenderProgress& progress = nullptr,
                 TileSchedule* schedule = nullptr);

    // `vkray stress`: render (block 1) with the stress-output variant, which
    // also writes what each pixel's primary ray and its secondary rays met;
    // `samples` gets one per pixel, row-major.
    Frame renderStressOutput(const Scene& scene, const CameraBasis& camera,
                             const RenderSettings& settings, std::vector<StressSample>& samples,
                             GpuRenderStats* stats = nullptr);

    // `vkray pixel`: traces sample settings.firstSample of pixel (x, y) alone
    // with the debug-pixel variant, which records every object test and
    // shading term, and the stress output (t and the normal as computed: in
    // double for fp64; the shadow feelers' verdicts).
    PixelTrace tracePixel(const Scene& scene, const CameraBasis& camera,
                          const RenderSettings& settings, int x, int y,
                          GpuRenderStats* stats = nullptr);

    // From now on `listener` hears of each tile render() traces, after the
    // device has finished it and before the next one starts ({}: none).
    void setTileListener(TileListener listener);

private:
    const Pipeline& pipelineFor(const ShaderFeatures& features, GpuRenderStats& stats);
    Frame renderFrame(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                      GpuRenderStats* stats, const RenderProgress& progress, TileSchedule* schedule,
                      std::vector<StressSample>* stressSamples);

    Context& context_;
    GpuRenderOptions options_;
    // The last two variants' pipelines, reused while they stay: `vkray view`
    // goes back and forth between its block passes' and its samples'.
    static constexpr std::size_t kPipelinesKept = 2;
    std::vector<std::unique_ptr<Pipeline>> pipelines_;  // the last used last
    TileListener tileListener_;
};

}  // namespace vkray::gpu
