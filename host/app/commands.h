// The commands of the vkray binary. Library errors arrive as exceptions; this
// layer alone prints them and chooses the exit status.
#pragma once

#include "app/options.h"
#include "gpu/gpu_tracer.h"
#include "scene/scene.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace vkray {

// Exit status: 0 success, 1 error (printed to err), 2 images beyond tolerance.
int runCommand(const Options& options, std::ostream& out, std::ostream& err);

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
// The files a render reads besides the shaders: the scene and what it names.
std::vector<std::string> sceneInputs(const Options& options);
// Fails before rendering when an output could never be written (`what`: the flag).
void requireWritableFolder(const std::string& path, const char* what);
// An Error as vkray prints it: "file:line:col: error: ..." or "vkray: error: ...".
void printError(const Error& error, std::ostream& err);

// Parses argv and runs; catches every exception into a message and status 1.
int vkrayMain(int argc, char** argv);

// --check's default tolerance: GPU float against CPU double. At most this
// percent of pixels may differ by more than kCheckFailThreshold (silhouette
// pixels, where float and double can pick different objects), and object ids
// may differ on at most the same percent.
inline constexpr double kCheckFailThreshold = 0.02;
inline constexpr double kCheckFailPercent = 0.1;

}  // namespace vkray
