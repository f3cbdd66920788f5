// The commands of the vkray binary. Library errors arrive as exceptions; this
// layer alone prints them and chooses the exit status.
#pragma once

#include "app/options.h"

#include <iosfwd>
#include <string>

namespace vkray {

// Exit status: 0 success, 1 error (printed to err), 2 images beyond tolerance.
int runCommand(const Options& options, std::ostream& out, std::ostream& err);

// The GLSL folder: --shader-dir, else shaders/ next to the binary, else the
// installed <binary dir>/../share/vkray/shaders. Throws Error when it has no
// trace.comp.
std::string shaderDirectoryFor(const Options& options);

// Parses argv and runs; catches every exception into a message and status 1.
int vkrayMain(int argc, char** argv);

// --check's default tolerance: GPU float against CPU double. At most this
// percent of pixels may differ by more than kCheckFailThreshold (silhouette
// pixels, where float and double can pick different objects), and object ids
// may differ on at most the same percent.
inline constexpr double kCheckFailThreshold = 0.02;
inline constexpr double kCheckFailPercent = 0.1;

}  // namespace vkray
