// What the commands of the vkray binary share: finding the shaders, loading
// the scene, the camera, the GPU session, and how an error is printed. Each
// command is in its own file (app/*_command.h); main.cpp dispatches to them
// and alone chooses the exit status.
#pragma once

#include "app/options.h"
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace vkray {

// The GLSL folder: --shader-dir, else shaders/ next to the binary, else the
// installed <binary dir>/../share/vkray/shaders. Throws Error when it has no
// trace.comp.
std::string shaderDirectoryFor(const Options& options);

// What `render` and `view` share, so that both draw the same image.
// The scene as the options say (warnings to err).
Scene loadSceneFor(const Options& options, std::ostream& err);
// The scene's camera, or the automatic one, with --eye, --look, --up, --fov applied.
Camera chooseCamera(const Scene& scene, const Options& options);
// The GPU tracer's options (shaders, variant, -D, precision).
gpu::GpuRenderOptions gpuRenderOptions(const Options& options);
// The precision a render of this scene from this camera runs in: the
// explicit --precision, or for auto robust where the scene is inside robust's
// envelope and fp64 where it is not (numerics/envelope.h). Prints the choice
// and what forced it to `out` ("precision: auto chose fp64: the 'sphere' at
// s.sdl:3:1 is ..."), and to `err` a warning where the scene passes the
// envelope of the mode in force (for auto: fp64's, beyond every mode's).
// `comparable` is false where the scene passes every mode's envelope:
// --check then reports the verdict as not comparable.
struct PrecisionInForce {
    Precision precision = Precision::Robust;
    bool comparable = true;
    std::string why;  // what passes every mode's envelope, when not comparable
};
PrecisionInForce precisionInForce(const Scene& scene, const CameraBasis& camera,
                                  const Options& options, std::ostream& out, std::ostream& err);
// The files a render reads besides the shaders: the scene and what it names.
std::vector<std::string> sceneInputs(const Options& options);
// Fails before rendering when an output could never be written (`what`: the flag).
void requireWritableFolder(const std::string& path, const char* what);
// An Error as vkray prints it: "file:line:col: error: ..." or "vkray: error: ...".
void printError(const Error& error, std::ostream& err);

// An error every rank of an MPI job reaches alike, before any rank waits on
// another (the command line; a command or option that does not run across
// ranks): rank 0 says it and every rank leaves the job with status 1. An
// abort would do, but mpirun may drop what the ranks wrote just before it.
class ErrorOnEveryRank : public Error {
public:
    using Error::Error;
    explicit ErrorOnEveryRank(const Error& error) : Error(error) {}
};

// The GPU side of a command: one Vulkan context and tracer, made on first
// use and kept (across the re-renders of --watch).
struct GpuSession {
    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<gpu::GpuTracer> tracer;
    double deviceSetupSeconds = 0;  // making the context (instance, device, queue)

    // Prints the device chosen when it first makes them.
    gpu::GpuTracer& tracerFor(const Options& options, std::ostream& out);
    // --validation: throws when the layer printed any message.
    void requireNoValidationMessages(const Options& options) const;
};

// The shader line of a GPU command's report; writes the SPIR-V for --dump-spirv.
void reportShader(const gpu::GpuRenderStats& stats, const Options& options, std::ostream& out);

// `value` with `digits` digits after the point, as the reports print times.
std::string fixedDigits(double value, int digits);

// --check's defaults (numerics/agreement.h): a colour differs above
// kCheckFailThreshold (relative above 1), and no differing pixel may go
// unexplained by the mode's error bound.
inline constexpr double kCheckFailThreshold = 0.02;
inline constexpr double kCheckFailPercent = 0;

}  // namespace vkray
