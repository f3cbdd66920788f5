#include "app/commands.h"

#include "app/data_folder.h"
#include "app/difftest_command.h"
#include "app/features_report.h"
#include "app/pixel_report.h"
#include "app/progress.h"
#include "app/stress_command.h"
#include "app/view_command.h"
#include "app/watch.h"
#include "dist/distributed_render.h"
#include "dist/mpi_world.h"
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "reference/reference_tracer.h"
#include "render/camera.h"
#include "util/error.h"
#include "render/render_progress.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace vkray {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

void printError(const Error& e, std::ostream& err) {
    const std::string message = e.what();
    err << (message.find(": error: ") != std::string::npos ? "" : "vkray: error: ") << message
        << "\n";
}

namespace {

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

// --shader-dir, else shaders/ next to the binary (where the build copies
// them), else the installed share/vkray/shaders (app/data_folder.h).
std::string shaderDirectory(const Options& o) {
    if (!o.shaderDirectory.empty()) {
        if (!fs::exists(fs::path(o.shaderDirectory) / "trace.comp"))
            throw Error("--shader-dir " + o.shaderDirectory + ": no trace.comp there");
        return o.shaderDirectory;
    }
    const DataFolder shaders = findDataFolder("shaders", "shaders", "trace.comp");
    if (shaders.path.empty())
        throw Error("cannot find the shaders " + shaders.whereLooked() +
                    "; pass --shader-dir DIR (the project's shaders/ folder)");
    return shaders.path;
}

}  // namespace

void requireWritableFolder(const std::string& path, const char* what) {
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder) || ::access(folder.c_str(), W_OK) != 0)
        throw Error(std::string(what) + " '" + path + "': the folder '" + folder.string() +
                    "' does not exist or is not writable");
}

namespace {

}  // namespace

Camera chooseCamera(const Scene& scene, const Options& o) {
    Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    if (o.eye) camera.eye = *o.eye;
    if (o.look) camera.look = *o.look;
    if (o.up) camera.up = *o.up;
    if (o.fov) camera.fovDegrees = *o.fov;
    // Errors in the camera then name the options rather than the scene's line.
    if (o.eye || o.look || o.up) camera.loc = FileLoc{};
    return camera;
}

gpu::GpuRenderOptions gpuRenderOptions(const Options& o) {
    return {.shaderDirectory = shaderDirectory(o), .allFeatures = o.allFeatures,
            .userDefines = o.defines, .precision = o.precision};
}

namespace {

double mrays(std::size_t rays, double seconds) {
    return seconds > 0 ? double(rays) / seconds / 1e6 : 0;
}

std::size_t primaryRays(const RenderSettings& s) {
    return std::size_t((s.width + s.block - 1) / s.block) *
           std::size_t((s.height + s.block - 1) / s.block) * std::size_t(s.spp);
}

// The GPU side of a render session: one Vulkan context and tracer, kept
// across the re-renders of --watch.
struct GpuSession {
    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<gpu::GpuTracer> tracer;

    gpu::GpuTracer& tracerFor(const Options& o, std::ostream& out) {
        if (!tracer) {
            // Ranks of an MPI job on one node spread over its equally good devices.
            context = std::make_unique<gpu::Context>(gpu::ContextOptions{
                o.device, o.validation, dist::World::current().localRank()});
            const gpu::DeviceInfo& device = context->device();
            out << "device: " << device.name << " (" << device.type << ", " << device.driverName
                << " " << device.driverInfo << ")\n";
            tracer = std::make_unique<gpu::GpuTracer>(*context, gpuRenderOptions(o));
        }
        return *tracer;
    }
    void requireNoValidationMessages(const Options& o) const {
        if (o.validation && context && context->validationMessages() > 0)
            throw Error("--validation: " + std::to_string(context->validationMessages()) +
                        " validation message(s), printed above");
    }
};

void reportShader(const gpu::GpuRenderStats& stats, const Options& o, std::ostream& out) {
    out << "shader: " << stats.variant << " variant " << stats.shader.key
        << (stats.shader.cacheHit ? " (cached, " : " (compiled, ") << fixed(stats.shader.seconds, 3)
        << " s)\n";
    if (o.dumpSpirvDirectory.empty()) return;
    const std::string path =
        (fs::path(o.dumpSpirvDirectory) / ("trace-" + stats.shader.key + ".spv")).string();
    writeFileAtomically(path, std::string(reinterpret_cast<const char*>(stats.shader.spirv.data()),
                                          stats.shader.spirv.size() * sizeof(std::uint32_t)));
    out << "wrote " << path << " (spirv-dis " << path << " disassembles it)\n";
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

Frame renderGpu(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                const Options& o, GpuSession& session, std::ostream& out, std::ostream& err) {
    gpu::GpuTracer& tracer = session.tracerFor(o, out);
    gpu::GpuRenderStats stats;
    ProgressDisplay display(err, ProgressDisplay::styleForStderr(o.quiet), "gpu render");
    const dist::World& world = dist::World::current();
    if (!world.distributed()) {
        Frame frame = tracer.render(scene, camera, settings, &stats, progressTo(display));
        display.finish();
        reportShader(stats, o, out);
        out << "gpu render: " << fixed(stats.renderSeconds, 3) << " s, precision "
            << precisionName(o.precision) << ", " << stats.tiles
            << (stats.tiles == 1 ? " tile" : " tiles") << " in " << stats.dispatches
            << (stats.dispatches == 1 ? " dispatch, " : " dispatches, ")
            << fixed(mrays(stats.rays, stats.renderSeconds), 2) << " Mrays/s\n";
        if (stats.tilesRedone > 0)
            out << "gpu render: " << stats.tilesRedone
                << (stats.tilesRedone == 1 ? " tile was" : " tiles were")
                << " traced again with less work per dispatch: the driver's loop limit cut a "
                   "dispatch short\n";
        session.requireNoValidationMessages(o);
        return frame;
    }
    const auto start = Clock::now();
    dist::DistributedStats shares;
    Frame frame = dist::renderAcrossRanks(world, tracer, scene, camera, settings, &stats,
                                          progressTo(display), &shares);
    if (world.rank() != 0) return frame;  // its tiles are with rank 0, which reports
    const double seconds = secondsSince(start) - stats.shader.seconds - stats.setupSeconds;
    display.finish();
    reportShader(stats, o, out);
    std::size_t tiles = 0;
    std::string perRank;
    for (const std::size_t count : shares.tilesPerRank) {
        perRank += (perRank.empty() ? "" : ", ") + std::to_string(count);
        tiles += count;
    }
    const std::size_t workerTiles = tiles - shares.tilesPerRank[0];
    out << "gpu render: " << fixed(seconds, 3) << " s, precision " << precisionName(o.precision)
        << ", " << tiles << " tiles on " << world.size() << " MPI ranks (tiles per rank: "
        << perRank << "; hand-out "
        << fixed(workerTiles ? 1e3 * shares.handOutSeconds / double(workerTiles) : 0.0, 3)
        << " ms a tile), " << fixed(mrays(primaryRays(settings), seconds), 2) << " Mrays/s\n";
    session.requireNoValidationMessages(o);
    return frame;
}

Frame renderCpu(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                const Options& o, std::ostream& out, std::ostream& err) {
    const auto start = Clock::now();
    const int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    ProgressDisplay display(err, ProgressDisplay::styleForStderr(o.quiet), "cpu reference");
    reference::ReferenceOptions options;
    options.threads = threads;
    options.progress = progressTo(display);
    Frame frame = reference::render(scene, camera, settings, options);
    display.finish();
    const double seconds = secondsSince(start);
    out << "cpu reference render: " << fixed(seconds, 3) << " s, " << threads << " threads, "
        << fixed(mrays(primaryRays(settings), seconds), 2) << " Mrays/s\n";
    return frame;
}

// Compares colour (and ids) of two frames or files; prints the report.
// The diff image, if asked for, is staged in `files`.
bool compareAndReport(const Image& a, const Image& b, const Image* idsA, const Image* idsB,
                      const CompareOptions& options, const std::string& diffPath,
                      StagedFiles& files, std::ostream& out) {
    CompareResult result = compareImages(a, b, options);
    if (idsA && idsB) {
        compareIds(*idsA, *idsB, result);
        result.passed = result.passed && result.idMismatchPercent <= options.failPercent;
    }
    if (!diffPath.empty()) stageImage(files, diffPath, diffImage(a, b));
    out << formatCompareReport(result, options);
    return result.passed;
}

}  // namespace

Scene loadSceneFor(const Options& o, std::ostream& err) {
    std::vector<std::string> warnings;
    Scene scene = loadScene(o.scenePath, {o.lenient}, &warnings);
    for (const std::string& w : warnings) err << w << "\n";
    return scene;
}

namespace {

int renderOnce(const Options& o, GpuSession& session, std::ostream& out, std::ostream& err) {
    const Scene scene = loadSceneFor(o, err);
    const std::string output =
        o.outputPath.empty() ? fs::path(o.scenePath).stem().string() + ".png" : o.outputPath;
    requireWritableFolder(output, "output");
    if (!o.aovPrefix.empty()) requireWritableFolder(o.aovPrefix, "--aov");
    if (!o.diffPath.empty()) requireWritableFolder(o.diffPath, "--diff");
    if (!o.dumpSpirvDirectory.empty())
        requireWritableFolder((fs::path(o.dumpSpirvDirectory) / "x").string(), "--dump-spirv");

    const RenderSettings settings{o.width, o.height, o.block, o.spp, o.seed};
    const CameraBasis camera = makeCameraBasis(chooseCamera(scene, o), o.width, o.height);
    out << "scene: " << o.scenePath << " (" << scene.objects.size() << " objects, "
        << scene.lights.size() << " lights), " << o.width << "x" << o.height
        << (o.block > 1 ? ", block " + std::to_string(o.block) : std::string())
        << (o.spp > 1 ? ", " + std::to_string(o.spp) + " spp, seed " + std::to_string(o.seed)
                      : std::string())
        << std::endl;  // before the progress display starts

    Frame frame = o.cpu ? renderCpu(scene, camera, settings, o, out, err)
                        : renderGpu(scene, camera, settings, o, session, out, err);
    if (dist::World::current().rank() != 0) return 0;  // rank 0 has the frame
    bool passed = true;
    // Every output is written in full beside its destination, then all are
    // renamed into place together: a failed or interrupted run changes none.
    StagedFiles files;
    if (o.check) {
        Frame reference = renderCpu(scene, camera, settings, o, out, err);
        const CompareOptions tolerance{o.failThreshold.value_or(kCheckFailThreshold),
                                       o.failPercent.value_or(kCheckFailPercent)};
        const Image idsGpu = idImage(frame), idsCpu = idImage(reference);
        out << "gpu vs cpu reference:\n";
        passed = compareAndReport(colorImage(frame), colorImage(reference), &idsGpu, &idsCpu,
                                  tolerance, o.diffPath, files, out);
    }

    if (stopRequested()) throw Interrupted();
    // `-o X.exr --aov X.exr`: the AOV file holds the image too (R, G, B).
    const bool imageInAovs =
        !o.aovPrefix.empty() && isExrPath(o.aovPrefix) &&
        fs::path(output).lexically_normal() == fs::path(o.aovPrefix).lexically_normal();
    if (!imageInAovs) stageImage(files, output, colorImage(frame));
    if (!o.aovPrefix.empty())
        stageAovs(files, o.aovPrefix, frame,
            isExrPath(o.aovPrefix) ? hitPoints(frame, camera, settings) : std::vector<glm::vec3>{});
    if (stopRequested()) throw Interrupted();
    files.commit();
    if (!o.diffPath.empty()) out << "wrote " << o.diffPath << "\n";
    if (!imageInAovs) out << "wrote " << output << "\n";
    if (!o.aovPrefix.empty()) out << "wrote " << aovFilesText(o.aovPrefix) << "\n";
    return passed ? 0 : 2;
}

}  // namespace

std::vector<std::string> sceneInputs(const Options& o) {
    std::vector<std::string> files{o.scenePath};
    try {
        const Scene scene = loadSdlFile(o.scenePath, {true}, nullptr);
        for (const SceneObject& object : scene.objects)
            if (!object.file.empty()) files.push_back(object.file);
        for (const Pixmap& pixmap : scene.pixmaps) files.push_back(pixmap.file);
    } catch (const Error&) {
        // The render has reported the error; the scene file alone is watched.
    }
    return files;
}

namespace {

// --watch: render, then re-render whenever an input or a shader changes, until
// Ctrl-C. A failed render prints its error and keeps the last good image.
int runWatch(const Options& o, std::ostream& out, std::ostream& err) {
    GpuSession session;
    const std::string shaders = o.cpu ? std::string() : shaderDirectory(o);
    for (bool first = true; !stopRequested(); first = false) {
        const auto start = Clock::now();
        try {
            renderOnce(o, session, out, err);
            out << (first ? "rendered" : "reloaded") << " in " << fixed(secondsSince(start), 3)
                << " s\n";
        } catch (const Error& e) {
            printError(e, err);
            err << "vkray: kept the last good image; fix the error and save to retry\n";
        }
        FileWatcher watcher;
        for (const std::string& file : sceneInputs(o)) watcher.watchFile(file);
        if (!shaders.empty()) watcher.watchFolder(shaders);
        out << "watching " << o.scenePath << (shaders.empty() ? "" : " and " + shaders)
            << " (Ctrl-C stops)" << std::endl;
        err.flush();
        if (!watcher.waitForChange()) break;
    }
    out << "stopped\n";
    return 0;
}

int runRender(const Options& o, std::ostream& out, std::ostream& err) {
    // Ctrl-C and SIGTERM set a flag: the render stops between tiles (rows on
    // the CPU) and writes nothing (Interrupted), or --watch stops waiting.
    const StopOnSignal stopOnSignal;
    GpuSession session;
    if (dist::World::current().distributed()) {
        if (o.watch) throw Error("--watch does not run across MPI ranks; run it without mpirun");
        if (o.cpu)
            throw Error("--cpu renders in one process (its threads share the cores); run it "
                        "without mpirun");
    }
    if (o.watch) return runWatch(o, out, err);
    return renderOnce(o, session, out, err);
}

// `vkray pixel`: the same pixel on the GPU (debug-pixel variant) and the CPU.
int runPixel(const Options& o, std::ostream& out, std::ostream& err) {
    const Scene scene = loadSceneFor(o, err);
    const RenderSettings settings{o.width, o.height, o.block};
    const CameraBasis camera = makeCameraBasis(chooseCamera(scene, o), o.width, o.height);
    GpuSession session;
    gpu::GpuRenderStats stats;
    const PixelTrace gpu =
        session.tracerFor(o, out).tracePixel(scene, camera, settings, o.pixelX, o.pixelY, &stats);
    reportShader(stats, o, out);
    session.requireNoValidationMessages(o);
    const PixelTrace cpu = reference::tracePixel(scene, camera, settings, o.pixelX, o.pixelY);
    out << formatPixelReport(scene, settings, gpu, cpu);
    return 0;
}

// `vkray shaders check`: every variant compiles; each failure with file:line.
int runShadersCheck(const Options& o, std::ostream& out, std::ostream& err) {
    const std::string directory = shaderDirectory(o);
    int failures = 0;
    const std::vector<gpu::ShaderFeatures> variants = gpu::allVariants(o.everyVariant);
    for (const gpu::ShaderFeatures& features : variants) {
        const auto start = Clock::now();
        try {
            gpu::compileComputeShader(
                {directory, "trace.comp", gpu::definesFor(features, precisionDefines(o.precision))});
            out << "ok    " << gpu::describe(features) << " (" << fixed(secondsSince(start), 2)
                << " s)\n";
        } catch (const Error& e) {
            ++failures;
            out << "FAIL  " << gpu::describe(features) << "\n";
            err << e.what() << "\n";
        }
    }
    out << variants.size() - failures << " of " << variants.size() << " variants compiled ("
        << precisionName(o.precision) << ")"
        << (failures ? ", " + std::to_string(failures) + " failed" : std::string()) << "\n";
    return failures ? 1 : 0;
}

// `vkray features`: the variant `render` would compile, and what it binds.
int runFeatures(const Options& o, std::ostream& out, std::ostream& err) {
    const Scene scene = loadSceneFor(o, err);
    RenderSettings settings;
    settings.spp = o.spp;
    const gpu::ShaderFeatures features =
        gpu::variantFeatures(scene, settings, o.allFeatures, o.precision);
    const gpu::ShaderSource source =
        gpu::variantSource(shaderDirectory(o), features, o.precision, o.defines);
    out << formatFeatureReport(scene, settings, features, o.precision, source.defines,
                               gpu::spirvCacheKey(source));
    return 0;
}

// Where an image's object ids are, as `render` writes them: the image's own id
// channel (X.exr from --aov X.exr), X.id.pfm (--aov X) or X.exr with an id
// channel beside it (-o X.png --aov X.exr); "" when none is there.
std::string idsBeside(const std::string& image) {
    if (hasIdChannel(image)) return image;
    const std::string stem = fs::path(image).replace_extension().string();
    if (fs::exists(stem + ".id.pfm")) return stem + ".id.pfm";
    if (fs::exists(stem + ".exr") && hasIdChannel(stem + ".exr")) return stem + ".exr";
    return "";
}

int runCompare(const Options& o, std::ostream& out) {
    const Image a = readImage(o.imageA), b = readImage(o.imageB);
    if (!o.diffPath.empty()) requireWritableFolder(o.diffPath, "--diff");
    const CompareOptions tolerance{o.failThreshold.value_or(CompareOptions{}.failThreshold),
                                   o.failPercent.value_or(CompareOptions{}.failPercent)};
    // Ids: given with --ids, or found for both images with idsBeside().
    std::string idsPathA = o.idsA, idsPathB = o.idsB;
    if (idsPathA.empty()) {
        const std::string besideA = idsBeside(o.imageA), besideB = idsBeside(o.imageB);
        if (!besideA.empty() && !besideB.empty()) {
            idsPathA = besideA;
            idsPathB = besideB;
            out << "object ids from " << idsPathA << " and " << idsPathB << "\n";
        }
    }
    StagedFiles files;
    bool passed = false;
    if (idsPathA.empty()) {
        passed = compareAndReport(a, b, nullptr, nullptr, tolerance, o.diffPath, files, out);
    } else {
        const Image idsA = readIds(idsPathA), idsB = readIds(idsPathB);
        passed = compareAndReport(a, b, &idsA, &idsB, tolerance, o.diffPath, files, out);
    }
    files.commit();
    return passed ? 0 : 2;
}

int runDevices(std::ostream& out) {
    int preferred = -1;
    const auto devices = gpu::Context::listDevices(&preferred);
    if (devices.empty())
        throw Error("no Vulkan device found; install mesa-vulkan-drivers (lavapipe) or a GPU "
                    "driver, or check VK_ICD_FILENAMES");
    for (const gpu::DeviceInfo& d : devices) {
        out << d.index << ": " << d.name << (d.index == preferred ? "  [render picks this]" : "")
            << "\n   type " << d.type << ", driver " << d.driverName << " " << d.driverInfo
            << " (version " << d.driverVersion << "), Vulkan " << d.apiVersionString()
            << "\n   compute " << (d.hasCompute ? "yes" : "no") << ", shaderFloat64 "
            << (d.shaderFloat64 ? "yes" : "no") << ", subgroup size " << d.subgroupSize
            << ", max storage buffer " << d.maxStorageBufferRange << " bytes"
            << ", max uniform buffer " << d.maxUniformBufferRange << " bytes"
            << ", max texel buffer " << d.maxTexelBufferElements << " texels"
            << ", memory heap " << d.memoryHeapBytes << " bytes"
            << ", max workgroup size " << d.maxWorkgroupSize[0] << "x" << d.maxWorkgroupSize[1]
            << "x" << d.maxWorkgroupSize[2] << ", max workgroup count " << d.maxWorkgroupCount[0]
            << "x" << d.maxWorkgroupCount[1] << "x" << d.maxWorkgroupCount[2] << "\n";
    }
    return 0;
}

// The command itself, on this rank.
int runOnRank(const Options& o, std::ostream& out, std::ostream& err) {
    switch (o.command) {
    case Command::Help: out << usageText(); return 0;
    case Command::Version:
        out << "vkray 0.1.0\nMPI: " << dist::World::support() << "\n";
        return 0;
    case Command::Render: return runRender(o, out, err);
    case Command::Pixel: return runPixel(o, out, err);
    case Command::ShadersCheck: return runShadersCheck(o, out, err);
    case Command::Compare: return runCompare(o, out);
    case Command::Devices: return runDevices(out);
    case Command::Stress: return runStress(o, out, err);
    case Command::Difftest: return runDifftest(o, out, err);
    case Command::Report: return runReport(o, out, err);
    case Command::Features: return runFeatures(o, out, err);
    case Command::View: return runView(o, out, err);
    }
    return 1;
}

}  // namespace

std::string shaderDirectoryFor(const Options& o) { return shaderDirectory(o); }

int runCommand(const Options& o, std::ostream& out, std::ostream& err) {
    const dist::World& world = dist::World::current();
    if (world.distributed()) {
        const bool spreads = o.command == Command::Render || o.command == Command::Stress ||
                             o.command == Command::Report;
        const bool trivial = o.command == Command::Version || o.command == Command::Help;
        if (!spreads && !trivial)
            throw Error("only `vkray render`, `vkray stress` and `vkray report` run across MPI "
                        "ranks; run this command without mpirun");
        if (trivial && world.rank() != 0) return 0;  // rank 0 answers
        if (world.rank() != 0) {
            // Only rank 0 speaks; the others' errors still reach stderr.
            std::ostream quiet(nullptr);
            return runOnRank(o, quiet, quiet);
        }
    }
    return runOnRank(o, out, err);
}


int vkrayMain(int argc, char** argv) {
    int status = 1;
    std::string message;
    try {
        dist::World& world = dist::World::join(argc, argv);
        const Options options = parseOptions(std::vector<std::string>(argv + 1, argv + argc));
        status = runCommand(options, std::cout, std::cerr);
        world.finish();
        return status;
    } catch (const Interrupted&) {
        // Under mpirun the signal is as likely mpirun ending the job after
        // another rank failed (that rank has said why) as a Ctrl-C.
        message = dist::World::current().distributed()
                      ? "vkray: stopped by a signal (Ctrl-C, or mpirun ending the job because "
                        "another rank failed); nothing was written\n"
                      : "vkray: interrupted; nothing was written (existing files are as they "
                        "were)\n";
        status = 130;
    } catch (const Error& e) {
        std::ostringstream text;
        printError(e, text);
        message = text.str();
    } catch (const std::bad_alloc&) {
        message = "vkray: error: out of memory; render a smaller image or scene\n";
    } catch (const std::exception& e) {
        // Vulkan errors (device lost, out of device memory) arrive here.
        message = std::string("vkray: error: ") + e.what() +
                  "\n  (a Vulkan or system failure; `vkray devices` shows the devices, "
                  "--cpu renders without Vulkan)\n";
    }
    // In an MPI job, a failing rank says which it is and ends every rank: the
    // others would otherwise wait for it for ever.
    const dist::World& world = dist::World::current();
    if (world.distributed()) {
        // One write: mpirun interleaves the ranks' output write by write.
        std::cerr << "[" + world.describeRank() + "] " + message << std::flush;
        world.abort(status);
    }
    std::cerr << message;
    return status;
}

}  // namespace vkray
