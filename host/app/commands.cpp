#include "app/commands.h"

#include "app/data_folder.h"
#include "dist/mpi_world.h"
#include "image/image_io.h"
#include "numerics/envelope.h"
#include "render/camera.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <ostream>

namespace vkray {

namespace fs = std::filesystem;

std::string fixedDigits(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

void printError(const Error& e, std::ostream& err) {
    const std::string message = e.what();
    err << (message.find(": error: ") != std::string::npos ? "" : "vkray: error: ") << message
        << "\n";
}

// --shader-dir, else shaders/ next to the binary (where the build copies
// them), else the installed share/vkray/shaders (app/data_folder.h).
std::string shaderDirectoryFor(const Options& o) {
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

void requireWritableFolder(const std::string& path, const char* what) {
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder) || ::access(folder.c_str(), W_OK) != 0)
        throw Error(std::string(what) + " '" + path + "': the folder '" + folder.string() +
                    "' does not exist or is not writable");
}

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
    return {.shaderDirectory = shaderDirectoryFor(o),
            .allFeatures = o.allFeatures,
            .userDefines = o.defines,
            .precision = o.precision,
            .traversal = o.traversal};
}

namespace {

// The first excess, and how many more there are.
std::string firstOf(const std::vector<EnvelopeExcess>& excesses, Precision precision) {
    return describe(excesses.front(), precision) +
           (excesses.size() > 1 ? " (and " + std::to_string(excesses.size() - 1) + " more)"
                                : std::string());
}

}  // namespace

PrecisionInForce precisionInForce(const Scene& scene, const CameraBasis& camera, const Options& o,
                                  std::ostream& out, std::ostream& err) {
    PrecisionInForce force;
    std::vector<EnvelopeExcess> beyond;  // fp64's envelope's
    if (o.precisionGiven) {
        // An explicit mode means exactly that mode; the warning says what it misses.
        force.precision = o.precision;
        beyond = envelopeExcesses(scene, camera, Precision::Fp64);
        const std::vector<EnvelopeExcess> missed =
            o.precision == Precision::Fp64 ? beyond : envelopeExcesses(scene, camera, o.precision);
        if (!missed.empty()) {
            err << "vkray: warning: " << firstOf(missed, o.precision)
                << "; the GPU may differ from the CPU reference there (docs/numerics.md, "
                   "\"Envelope\")\n";
            if (beyond.empty())
                err << "vkray: note: --precision fp64 (or auto) is inside its envelope here\n";
        }
    } else {
        const PrecisionChoice choice = choosePrecision(scene, camera);
        force.precision = choice.precision;
        if (choice.outside.empty())
            out << "precision: auto chose robust (the scene is inside robust's envelope)\n";
        else
            out << "precision: auto chose fp64: " << firstOf(choice.outside, Precision::Robust)
                << "\n";
        beyond = choice.beyondEvery;
        if (!beyond.empty())
            err << "vkray: warning: " << firstOf(beyond, Precision::Fp64)
                << "; no precision mode is documented to agree with the CPU reference there "
                   "(docs/numerics.md, \"Envelope\")\n";
    }
    if (!beyond.empty()) {
        force.comparable = false;
        force.why = describe(beyond.front(), Precision::Fp64);
    }
    return force;
}

Scene loadSceneFor(const Options& o, std::ostream& err) {
    std::vector<std::string> warnings;
    Scene scene = loadScene(o.scenePath, {o.lenient}, &warnings);
    for (const std::string& w : warnings) err << w << "\n";
    return scene;
}

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

gpu::GpuTracer& GpuSession::tracerFor(const Options& o, std::ostream& out) {
    if (!tracer) {
        // Ranks of an MPI job on one node spread over its equally good devices.
        const Stopwatch making;
        context = std::make_unique<gpu::Context>(
            gpu::ContextOptions{o.device, o.validation, dist::World::current().localRank()});
        const gpu::DeviceInfo& device = context->device();
        out << "device: " << device.name << " (" << device.type << ", " << device.driverName << " "
            << device.driverInfo << ")\n";
        tracer = std::make_unique<gpu::GpuTracer>(*context, gpuRenderOptions(o));
        deviceSetupSeconds = making.seconds();
    }
    tracer->setPrecision(o.precision);  // --precision auto may choose anew on a reload
    return *tracer;
}

void GpuSession::requireNoValidationMessages(const Options& o) const {
    if (o.validation && context && context->validationMessages() > 0)
        throw Error("--validation: " + std::to_string(context->validationMessages()) +
                    " validation message(s), printed above");
}

void reportShader(const gpu::GpuRenderStats& stats, const Options& o, std::ostream& out) {
    out << "shader: " << stats.variant << " variant " << stats.shader.key
        << (stats.shader.cacheHit ? " (cached, " : " (compiled, ")
        << fixedDigits(stats.shader.seconds, 3) << " s)\n";
    if (o.dumpSpirvDirectory.empty()) return;
    const std::string path =
        (fs::path(o.dumpSpirvDirectory) / ("trace-" + stats.shader.key + ".spv")).string();
    writeFileAtomically(path, std::string(reinterpret_cast<const char*>(stats.shader.spirv.data()),
                                          stats.shader.spirv.size() * sizeof(std::uint32_t)));
    out << "wrote " << path << " (spirv-dis " << path << " disassembles it)\n";
}

}  // namespace vkray
