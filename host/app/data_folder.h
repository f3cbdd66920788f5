// Where the binary finds the data it ships with (its GLSL, the stress cases),
// from its own path (/proc/self/exe), whatever the current folder: first next
// to the binary, as the build tree lays it out (build/vkray, build/shaders,
// build/scenes/stress), then in the installed layout of `cmake --install` and
// the .deb (P/bin/vkray, P/share/vkray/shaders, P/share/vkray/stress).
#pragma once

#include <string>

namespace vkray {

struct DataFolder {
    std::string path;       // the folder found; empty when neither place has it
    std::string beside;     // <binary dir>/<besideBinary>
    std::string installed;  // <binary dir>/../share/vkray/<installed>

    // "next to the binary (BESIDE) nor in the installed place (INSTALLED)",
    // for a message that says where it looked.
    std::string whereLooked() const;
};

// The first of the two places that is a folder holding `mustHold` (any folder
// when mustHold is empty).
DataFolder findDataFolder(const std::string& besideBinary, const std::string& installed,
                          const std::string& mustHold = "");

}  // namespace vkray
