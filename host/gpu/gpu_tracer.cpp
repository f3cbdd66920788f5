#include "gpu/gpu_tracer.h"

#include "gpu/device_limits.h"
#include "gpu/gpu_scene.h"
#include "gpu/trace_pass.h"
#include "shaders/layout.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

namespace vkray::gpu {

namespace {

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

int defaultTileSide(const DeviceInfo& device) {
    return device.type == "CPU" ? 256 : 1024;
}

void requirePrecisionSupported(Precision precision, const DeviceInfo& device) {
    if (precision == Precision::Fp64 && !device.shaderFloat64)
        throw Error("--precision fp64: the Vulkan device " + std::to_string(device.index) + " (" +
                    device.name +
                    ") has no shaderFloat64 (double in shaders); use --precision "
                    "robust, another --device (`vkray devices` lists them), or --cpu for the "
                    "double CPU reference");
}

ShaderFeatures variantFeatures(const Scene& scene, const RenderSettings& settings, bool allFeatures,
                               Precision precision, const glm::dvec3& eye,
                               std::uint64_t maxTexels) {
    ShaderFeatures features = featuresOf(scene, settings, allFeatures);
    features.doubles = precision == Precision::Fp64;
    if (precision == Precision::Robust && !allFeatures)
        placeMeshesInWorldWhereTheyFit(scene, eye, maxTexels, features);
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
    stats.pipelineSeconds = 0;
    for (auto kept = pipelines_.begin(); kept != pipelines_.end(); ++kept) {
        if ((*kept)->key != stats.shader.key) continue;
        std::rotate(kept, kept + 1, pipelines_.end());  // the last used goes last
        return *pipelines_.back();
    }

    uint workgroupX = WORKGROUP_X, workgroupY = WORKGROUP_Y;
    if (otherWorkgroup) {
        workgroupX = uint(options_.workgroupX);
        workgroupY = uint(options_.workgroupY);
    }
    std::vector<ComputeBinding> bindings;
    for (const ShaderBinding& b : bindingsFor(features))
        bindings.push_back({b.binding, descriptorTypeOf(b.kind)});
    const Stopwatch creating;
    auto p = std::make_unique<Pipeline>(
        Pipeline{stats.shader.key, workgroupX, workgroupY,
                 ComputePipeline(context_.impl(), stats.shader.spirv, std::move(bindings), 0)});
    stats.pipelineSeconds = creating.seconds();
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
    const StageClock setup;
    const GpuInputs inputs = prepareGpuInputs(options_.precision, original, originalCamera);
    const Scene& scene = inputs.scene;
    const CameraBasis& camera = inputs.camera;
    if (settings.width < 1 || settings.height < 1 || settings.block < 1)
        throw Error("render: width, height and block must be at least 1");
    GpuRenderStats local;
    GpuRenderStats& st = stats ? *stats : local;

    if (settings.spp < 1 || settings.spp > kMaxSpp)
        throw Error("render: samples per pixel must be from 1 to " + std::to_string(kMaxSpp));
    const int samples = sampleEnd(settings) - settings.firstSample;  // traced per pixel
    ShaderFeatures features = variantFeatures(
        scene, settings, options_.allFeatures, options_.precision, camera.eye,
        options_.worldTriangles ? deviceLimits(context_.device()).maxTexelBufferElements
                                : 0);  // no room: each mesh walked in its generic space
    features.stressOutput = stressSamples != nullptr;
    st.traversal = chooseTraversal(options_.traversal, context_.device(), scene, features);
    if (stressSamples && scene.lights.size() > STRESS_MAX_LIGHTS)
        throw Error("the stress output records the feelers of " +
                    std::to_string(STRESS_MAX_LIGHTS) + " lights; this scene has " +
                    std::to_string(scene.lights.size()));
    const StageClock compiling;
    const Pipeline& pipeline = pipelineFor(features, st);
    const Elapsed compiled = compiling.elapsed();
    // Tiles hold whole blocks, so a block never straddles two dispatches;
    // they shrink with the samples per pixel, so that no dispatch runs long,
    // and where the device's buffer or workgroup limits need it.
    const int block = settings.block;
    // Per pixel at most (a ray per pixel): its pixel, progress and pending rays.
    const bool rayStack = features.has(Shading::Reflection) || features.has(Shading::Refraction);
    const size_t pixelBytes =
        sizeof(GpuPixel) + (tracesInOnePass(features) ? 0 : sizeof(GpuRayProgress)) +
        (features.stressOutput ? sizeof(GpuStressSample) : 0) +
        (rayStack ? size_t(pendingRayEntries(scene)) *
                        (features.doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask))
                  : 0);
    // The device's side unless one was asked for, its buffers at most 256 MiB
    // a tile in flight (deep pending-ray stacks take hundreds of bytes a pixel).
    const int tileSize = options_.tileSize > 0
                             ? options_.tileSize
                             : std::min(defaultTileSide(context_.device()),
                                        int(std::sqrt(double(256u << 20) / double(pixelBytes))));
    const int side =
        std::max(std::min(16, tileSize), tileSize / int(std::ceil(std::sqrt(double(samples)))));
    const int tile =
        fitTileSide(std::max(block, side / block * block), block, pixelBytes, pipeline.workgroupX,
                    pipeline.workgroupY, deviceLimits(context_.device()));
    // One process tracing every tile keeps two in flight: the device traces
    // the next while the host reads this one back (a third slot measured no
    // faster). A schedule of another process (MPI) hands out one tile at a
    // time.
    const bool overlap = schedule == nullptr;
    // Rays that provably meet nothing are left out; naive keeps them, and
    // the stress and debug records want every ray.
    const bool cover = options_.primaryCover && options_.precision != Precision::Naive &&
                       !features.stressOutput && !features.debugPixel;
    TracePass pass(context_.impl(), pipeline, features, features.doubles, scene, camera, settings,
                   tile, {cover, bool(tileListener_)}, overlap ? 2 : 1);
    st.structureSeconds = pass.structureSeconds();

    // Tracing every tile, the frame starts as the background, so that a
    // tile's pixels whose rays meet nothing (most of many images) are not
    // copied over one by one; a schedule's frame keeps Frame()'s pixels
    // outside the tiles it hands this process.
    const GpuPixel& miss = pass.missedPixel();
    const bool missedInFrame = overlap;
    Frame frame = missedInFrame
                      ? Frame(settings.width, settings.height, pass.meanColor(miss),
                              settings.firstSample == 0 && features.aovs ? miss.normal.w : 0)
                      : Frame(settings.width, settings.height);
    if (stressSamples) stressSamples->assign(frame.pixelCount(), StressSample{});
    const Elapsed prepared = setup.elapsed();
    st.setupSeconds = prepared.wall - compiled.wall;
    st.setupCpuSeconds = prepared.cpu - compiled.cpu;
    const Stopwatch rendering;
    const double renderCpuStart = processCpuSeconds();
    st.tiles = 0;
    st.dispatches = 0;
    st.tilesRedone = 0;
    st.rays = 0;
    st.deviceSeconds.reset();  // the dispatches add theirs, where the queue has timestamps
    const size_t totalRays = size_t((settings.width + block - 1) / block) *
                             size_t((settings.height + block - 1) / block) * size_t(samples);
    if (progress && !progress(0, totalRays)) throw Interrupted();
    uint turnBudget = options_.turnBudget > 0 ? uint(options_.turnBudget) : kTurnBudget;
    // The finished tile of `slot` into the frame, and to the listener.
    st.readBackSeconds = 0;
    st.firstTileSeconds = 0;
    const auto readBack = [&](int slot, const TileRect& piece) {
        const Stopwatch copying;
        const int tx = piece.x, ty = piece.y, w = piece.width, h = piece.height;
        if (tileListener_) tileListener_(TracedTile{piece, pass.pixelBuffer(slot)});
        const GpuPixel* pixels = pass.pixels(slot);
        const bool sample0 = settings.firstSample == 0;  // the id and AOVs were traced
        const auto take = [&](const GpuPixel& p, int x, int y) {
            const size_t i = frame.index(tx + x, ty + y);
            frame.color[i] = pass.meanColor(p);
            if (!sample0) return;
            std::memcpy(&frame.id[i], &p.color.w, sizeof(std::int32_t));
            if (!features.aovs) return;
            frame.depth[i] = p.normal.w;
            frame.normal[i] = {p.normal.x, p.normal.y, p.normal.z};
        };
        if (!missedInFrame)
            for (const TileRect& r : pass.missedPixels(slot))
                for (int y = r.y; y < r.y + r.height; ++y)
                    for (int x = r.x; x < r.x + r.width; ++x) take(pass.missedPixel(), x, y);
        for (const TileRect& r : pass.tracedPixels(slot)) {
            for (int y = r.y; y < r.y + r.height; ++y) {
                for (int x = r.x; x < r.x + r.width; ++x) {
                    take(pixels[size_t(y) * size_t(w) + size_t(x)], x, y);
                    if (stressSamples)
                        (*stressSamples)[frame.index(tx + x, ty + y)] = decodeStressSample(
                            pass.stressSamples(slot)[size_t(y) * size_t(w) + size_t(x)],
                            features.doubles);
                }
            }
        }
        st.rays +=
            size_t((w + block - 1) / block) * size_t((h + block - 1) / block) * size_t(samples);
        ++st.tiles;
        st.readBackSeconds += copying.seconds();
        if (progress && !progress(st.rays, totalRays)) throw Interrupted();
    };
    if (overlap) {
        const std::vector<TileRect> pieces =
            tilesOf(settings.width, settings.height, tile, options_.serpentineTiles);
        // A tile whose rays all meet nothing dispatches nothing: it is read
        // back at once and holds no slot, so that runs of such tiles leave
        // the device no less to do.
        std::deque<std::pair<size_t, int>> inFlight;  // (piece, slot), in order of submission
        std::vector<int> freeSlots(size_t(pass.slots()));
        std::iota(freeSlots.begin(), freeSlots.end(), 0);
        size_t next = 0;
        const auto fill = [&] {
            for (; next < pieces.size() && !freeSlots.empty(); ++next) {
                const TileRect& p = pieces[next];
                const int slot = freeSlots.back();
                pass.start(slot, p.x, p.y, p.width, p.height, block, turnBudget);
                if (pass.inFlight(slot)) {
                    freeSlots.pop_back();
                    inFlight.emplace_back(next, slot);
                } else {
                    readBack(slot, p);
                }
            }
        };
        fill();
        while (!inFlight.empty()) {
            const auto [piece, slot] = inFlight.front();
            inFlight.pop_front();
            pass.finish(slot, turnBudget, st);
            if (st.firstTileSeconds == 0) st.firstTileSeconds = rendering.seconds();
            readBack(slot, pieces[piece]);
            freeSlots.push_back(slot);
            fill();
        }
    } else {
        schedule->plan(settings.width, settings.height, tile);
        while (const std::optional<TileRect> given = schedule->next()) {
            // A tile handed out by another process may be larger than this
            // device's: it is traced in pieces of this device's tile side.
            for (const TileRect& piece : tilesOf(given->width, given->height, tile)) {
                const TileRect at{given->x + piece.x, given->y + piece.y, piece.width,
                                  piece.height};
                pass.traceTile(at.x, at.y, at.width, at.height, block, turnBudget, st);
                if (st.firstTileSeconds == 0) st.firstTileSeconds = rendering.seconds();
                readBack(0, at);
            }
            schedule->finished(*given, frame);
        }
    }
    st.renderSeconds = rendering.seconds();
    st.renderCpuSeconds = processCpuSeconds() - renderCpuStart;
    st.groupsTraced = pass.groupsTraced();
    st.groups = pass.groups();
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
    // The debug record describes one ray: sample firstSample of the pixel's
    // (its centre with one sample a pixel).
    RenderSettings oneSample = settings;
    oneSample.sampleCount = 1;
    ShaderFeatures features = variantFeatures(
        scene, oneSample, options_.allFeatures, options_.precision, camera.eye,
        options_.worldTriangles ? deviceLimits(context_.device()).maxTexelBufferElements : 0);
    features.shading[size_t(Shading::Antialias)] = settings.spp > 1;
    features.debugPixel = true;
    features.stressOutput = true;
    const Pipeline& pipeline = pipelineFor(features, st);
    TracePass pass(context_.impl(), pipeline, features, features.doubles, scene, camera, oneSample,
                   1, {});
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
