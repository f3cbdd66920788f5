#include "app/render_command.h"

#include "app/commands.h"
#include "app/progress.h"
#include "app/watch.h"
#include "dist/distributed_render.h"
#include "dist/mpi_world.h"
#include "gpu/gpu_tracer.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "numerics/agreement.h"
#include "reference/reference_tracer.h"
#include "render/camera.h"
#include "render/render_progress.h"
#include "scene/scene_geometry.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>
#include <ostream>
#include <thread>

namespace vkray {

namespace fs = std::filesystem;

namespace {

double mrays(std::size_t rays, double seconds) {
    return seconds > 0 ? double(rays) / seconds / 1e6 : 0;
}

std::size_t primaryRays(const RenderSettings& s) {
    return std::size_t((s.width + s.block - 1) / s.block) *
           std::size_t((s.height + s.block - 1) / s.block) * std::size_t(s.spp);
}

// The dispatches' own time, from the device's timestamps, and its share of
// the render's wall clock (the rest: submits, waits, read-back).
std::string deviceTime(const gpu::GpuRenderStats& stats) {
    if (!stats.deviceSeconds) return "not measured (the device's queue has no timestamps)";
    std::string text = fixedDigits(*stats.deviceSeconds, 3) + " s (timestamp queries";
    if (stats.renderSeconds > 0)
        text += ", " + fixedDigits(100 * *stats.deviceSeconds / stats.renderSeconds, 0) +
                " % of the render's wall clock";
    return text + ")";
}

// The progress display's callback; it also stops the render on Ctrl-C.
RenderProgress progressTo(ProgressDisplay& display) {
    const bool paced = gpu::injectedFault() == gpu::Fault::SlowProgress;
    return [&display, paced](std::size_t done, std::size_t total) {
        if (paced) std::this_thread::sleep_for(std::chrono::milliseconds(25));
        display.update(done, total);
        return !stopRequested();
    };
}

// Where a one-shot render's wall clock went, stage by stage: printed last,
// once the image is encoded.
struct StageTimes {
    double scene = 0, encode = 0;
    double meshFiles = 0, meshBvhs = 0;            // within scene: its mesh files, and their BVHs
    std::optional<double> device;                  // the context was made for this render
    std::optional<gpu::GpuRenderStats> gpu;        // the GPU rendered (in this process)
    std::optional<reference::ReferenceStats> cpu;  // --cpu
};

std::string stageLine(const StageTimes& t, double total) {
    const auto s = [](double seconds) { return fixedDigits(seconds, 3) + " s"; };
    std::string line = "time: scene " + s(t.scene);
    if (t.meshFiles > 0)
        line += " (mesh files " + s(t.meshFiles) + ", their BVHs " + s(t.meshBvhs) + ")";
    double counted = t.scene + t.encode;
    if (t.device) {
        line += ", device set-up " + s(*t.device);
        counted += *t.device;
    }
    if (t.gpu) {
        const gpu::GpuRenderStats& g = *t.gpu;
        line +=
            ", shader " + s(g.shader.seconds) + (g.shader.cacheHit ? " (cached)" : " (compiled)");
        if (g.pipelineSeconds > 0) line += ", pipeline " + s(g.pipelineSeconds);
        line += ", preparation and upload " + s(g.setupSeconds);
        if (g.structureSeconds > 0)
            line += " (acceleration structure " + s(g.structureSeconds) + ")";
        line += ", trace " + s(g.renderSeconds - g.readBackSeconds) + " (its first tile " +
                s(g.firstTileSeconds) + "), read-back " + s(g.readBackSeconds);
        counted += g.shader.seconds + g.pipelineSeconds + g.setupSeconds + g.renderSeconds;
    }
    if (t.cpu) {
        line += ", preparation (frame, BVH) " + s(t.cpu->prepare.wall) + ", trace " +
                s(t.cpu->trace.wall);
        counted += t.cpu->prepare.wall + t.cpu->trace.wall;
    }
    // The rest: the camera, the precision's choice, the reports, --check.
    return line + ", encode " + s(t.encode) + ", other " + s(std::max(total - counted, 0.0)) +
           "; total " + s(total);
}

Frame renderGpu(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                const Options& o, GpuSession& session, std::ostream& out, std::ostream& err,
                StageTimes& times) {
    const bool fresh = session.tracer == nullptr;
    gpu::GpuTracer& tracer = session.tracerFor(o, out);
    if (fresh) times.device = session.deviceSetupSeconds;
    gpu::GpuRenderStats stats;
    ProgressDisplay display(err, ProgressDisplay::styleForStderr(o.quiet), "gpu render");
    const dist::World& world = dist::World::current();
    if (!world.distributed()) {
        Frame frame = tracer.render(scene, camera, settings, &stats, progressTo(display));
        display.finish();
        reportShader(stats, o, out);
        out << "gpu render: " << fixedDigits(stats.renderSeconds, 3) << " s, precision "
            << precisionName(o.precision) << ", " << stats.tiles
            << (stats.tiles == 1 ? " tile" : " tiles") << " in " << stats.dispatches
            << (stats.dispatches == 1 ? " dispatch, " : " dispatches, ")
            << fixedDigits(mrays(stats.rays, stats.renderSeconds), 2) << " Mrays/s\n";
        if (stats.groupsTraced < stats.groups)
            out << "gpu render: " << stats.groupsTraced << " of " << stats.groups
                << " workgroups traced; the other rays meet nothing, their pixels the "
                   "background's\n";
        out << "gpu render: device time " << deviceTime(stats) << "\n";
        out << "gpu render: traversal " << stats.traversal << "\n";
        if (stats.tilesRedone > 0)
            out << "gpu render: " << stats.tilesRedone
                << (stats.tilesRedone == 1 ? " tile was" : " tiles were")
                << " traced again with less work per dispatch: the driver's loop limit cut a "
                   "dispatch short\n";
        session.requireNoValidationMessages(o);
        times.gpu = stats;
        return frame;
    }
    const Stopwatch stopwatch;
    dist::DistributedStats shares;
    Frame frame = dist::renderAcrossRanks(world, tracer, scene, camera, settings, &stats,
                                          progressTo(display), &shares);
    if (world.rank() != 0) return frame;  // its tiles are with rank 0, which reports
    const double seconds =
        stopwatch.seconds() - stats.shader.seconds - stats.pipelineSeconds - stats.setupSeconds;
    display.finish();
    reportShader(stats, o, out);
    std::size_t tiles = 0;
    std::string perRank;
    for (const std::size_t count : shares.tilesPerRank) {
        perRank += (perRank.empty() ? "" : ", ") + std::to_string(count);
        tiles += count;
    }
    const std::size_t workerTiles = tiles - shares.tilesPerRank[0];
    out << "gpu render: " << fixedDigits(seconds, 3) << " s, precision "
        << precisionName(o.precision) << ", " << tiles << " tiles on " << world.size()
        << " MPI ranks (tiles per rank: " << perRank << "; hand-out "
        << fixedDigits(workerTiles ? 1e3 * shares.handOutSeconds / double(workerTiles) : 0.0, 3)
        << " ms a tile), " << fixedDigits(mrays(primaryRays(settings), seconds), 2) << " Mrays/s\n";
    session.requireNoValidationMessages(o);
    return frame;
}

Frame renderCpu(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                const Options& o, std::ostream& out, std::ostream& err,
                reference::ReferenceStats& stats) {
    const Stopwatch stopwatch;
    const int threads =
        o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    ProgressDisplay display(err, ProgressDisplay::styleForStderr(o.quiet), "cpu reference");
    reference::ReferenceOptions options;
    options.threads = threads;
    options.progress = progressTo(display);
    options.stats = &stats;
    Frame frame = reference::render(scene, camera, settings, options);
    display.finish();
    const double seconds = stopwatch.seconds();
    out << "cpu reference render: " << fixedDigits(seconds, 3) << " s (preparation "
        << fixedDigits(stats.prepare.wall, 3) << " s, trace " << fixedDigits(stats.trace.wall, 3)
        << " s), " << threads << " threads, "
        << fixedDigits(mrays(primaryRays(settings), seconds), 2) << " Mrays/s\n";
    return frame;
}

int renderOnce(const Options& o, GpuSession& session, std::ostream& out, std::ostream& err) {
    const Stopwatch total;
    StageTimes times;
    const Scene scene = loadSceneFor(o, err);
    times.scene = total.seconds();
    times.meshFiles = scene.meshFileSeconds;
    times.meshBvhs = scene.meshBvhSeconds;
    const std::string output =
        o.outputPath.empty() ? fs::path(o.scenePath).stem().string() + ".png" : o.outputPath;
    requireWritableFolder(output, "output");
    if (!o.aovPrefix.empty()) requireWritableFolder(o.aovPrefix, "--aov");
    if (!o.diffPath.empty()) requireWritableFolder(o.diffPath, "--diff");
    if (!o.dumpSpirvDirectory.empty())
        requireWritableFolder((fs::path(o.dumpSpirvDirectory) / "x").string(), "--dump-spirv");

    RenderSettings settings{o.width, o.height, o.block, o.spp, o.seed};
    // The object id is always there; --check compares depth and normals too.
    settings.aovs = !o.aovPrefix.empty() || o.check;
    const CameraBasis camera = makeCameraBasis(chooseCamera(scene, o), o.width, o.height);
    out << "scene: " << o.scenePath << " (" << scene.objects.size() << " objects, "
        << scene.lights.size() << " lights), " << o.width << "x" << o.height
        << (o.block > 1 ? ", block " + std::to_string(o.block) : std::string())
        << (o.spp > 1 ? ", " + std::to_string(o.spp) + " spp, seed " + std::to_string(o.seed)
                      : std::string())
        << std::endl;  // before the progress display starts
    // The options with --precision auto resolved for this scene and camera.
    Options run = o;
    PrecisionInForce force;
    if (!o.cpu || o.check) force = precisionInForce(scene, camera, o, out, err);
    run.precision = force.precision;

    reference::ReferenceStats cpuStats;
    Frame frame = o.cpu ? renderCpu(scene, camera, settings, run, out, err, cpuStats)
                        : renderGpu(scene, camera, settings, run, session, out, err, times);
    if (o.cpu) times.cpu = cpuStats;
    if (dist::World::current().rank() != 0) return 0;  // rank 0 has the frame
    bool passed = true;
    // Every output is written in full beside its destination, then all are
    // renamed into place together: a failed or interrupted run changes none.
    StagedFiles files;
    if (o.check) {
        reference::ReferenceStats referenceStats;
        Frame reference = renderCpu(scene, camera, settings, o, out, err, referenceStats);
        AgreementOptions rule;
        rule.colorThreshold = o.failThreshold.value_or(kCheckFailThreshold);
        rule.allowedPercent = o.failPercent.value_or(kCheckFailPercent);
        rule.threads = o.threads;
        const Agreement agreement =
            judgeAgreement(scene, camera, settings, run.precision, frame, reference, rule);
        out << "gpu vs cpu reference (the margin rule, " << precisionName(run.precision)
            << "'s error bound):\n"
            << formatAgreement(agreement, rule);
        if (!o.diffPath.empty())
            stageImage(files, o.diffPath, agreementImage(frame, reference, agreement));
        passed = agreement.passed;
        if (!force.comparable)
            out << "verdict         not comparable: " << force.why
                << "; the result above is not counted (exit status 3)\n";
    }

    if (stopRequested()) throw Interrupted();
    const Stopwatch encoding;
    // `-o X.exr --aov X.exr`: the AOV file holds the image too (R, G, B).
    const bool imageInAovs =
        !o.aovPrefix.empty() && isExrPath(o.aovPrefix) &&
        fs::path(output).lexically_normal() == fs::path(o.aovPrefix).lexically_normal();
    if (!imageInAovs) stageColor(files, output, frame);
    if (!o.aovPrefix.empty())
        stageAovs(
            files, o.aovPrefix, frame,
            isExrPath(o.aovPrefix) ? hitPoints(frame, camera, settings) : std::vector<glm::vec3>{});
    if (stopRequested()) throw Interrupted();
    files.commit();
    times.encode = encoding.seconds();
    if (!o.diffPath.empty()) out << "wrote " << o.diffPath << "\n";
    if (!imageInAovs) out << "wrote " << output << "\n";
    if (!o.aovPrefix.empty()) out << "wrote " << aovFilesText(o.aovPrefix) << "\n";
    if (times.gpu || times.cpu) out << stageLine(times, total.seconds()) << "\n";
    if (o.check && !force.comparable) return 3;
    return passed ? 0 : 2;
}

// --watch: render, then re-render whenever an input or a shader changes, until
// Ctrl-C. A failed render prints its error and keeps the last good image.
int runWatch(const Options& o, std::ostream& out, std::ostream& err) {
    GpuSession session;
    const std::string shaders = o.cpu ? std::string() : shaderDirectoryFor(o);
    // Watching from before the first render: a save made while a render runs
    // brings the next one.
    FileWatcher watcher;
    for (bool first = true; !stopRequested(); first = false) {
        for (const std::string& file : sceneInputs(o)) watcher.watchFile(file);
        if (!shaders.empty()) watcher.watchFolder(shaders);
        const Stopwatch stopwatch;
        try {
            renderOnce(o, session, out, err);
            out << (first ? "rendered" : "reloaded") << " in "
                << fixedDigits(stopwatch.seconds(), 3) << " s\n";
        } catch (const Error& e) {
            printError(e, err);
            err << "vkray: kept the last good image; fix the error and save to retry\n";
        }
        out << "watching " << o.scenePath << (shaders.empty() ? "" : " and " + shaders)
            << " (Ctrl-C stops)" << std::endl;
        err.flush();
        if (!watcher.waitForChange()) break;
    }
    out << "stopped\n";
    return 0;
}

}  // namespace

int runRender(const Options& o, std::ostream& out, std::ostream& err) {
    // Ctrl-C and SIGTERM set a flag: the render stops between tiles (rows on
    // the CPU) and writes nothing (Interrupted), or --watch stops waiting.
    const StopOnSignal stopOnSignal;
    GpuSession session;
    if (dist::World::current().distributed()) {
        if (o.watch)
            throw ErrorOnEveryRank("--watch does not run across MPI ranks; run it without mpirun");
        if (o.cpu)
            throw ErrorOnEveryRank(
                "--cpu renders in one process (its threads share the cores); run it "
                "without mpirun");
    }
    if (o.watch) return runWatch(o, out, err);
    return renderOnce(o, session, out, err);
}

}  // namespace vkray
