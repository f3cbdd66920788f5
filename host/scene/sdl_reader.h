// Reader for Hill's Scene Description Language (Computer Graphics Using
// OpenGL, ch. 14), with vkray's `camera` extension. Every error carries
// `file:line:col` (and, for text pasted by `use`, where it was pasted).
#pragma once

#include "scene/scene.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace vkray {

struct SdlOptions {
    // Strict (default): anything Hill's grammar does not define is an error.
    // Lenient: unknown words (and the numbers right after them) are skipped
    // with a warning naming word and place, as real files need.
    bool lenient = false;
    // def/use expansion limits: a recursive def is always an error; these stop
    // exponential pasting (def a {use b use b} def b {use c use c} ...).
    std::size_t maxExpandedTokens = 5'000'000;
    int maxUseDepth = 64;
};

// Parses `text` as if read from file `fileName` (used in messages and to
// resolve mesh/extrude/makePixmap paths). Throws Error with a located message.
// Warnings (lenient mode) are appended to `warnings` when it is not null,
// each formatted "file:line:col: warning: ...".
Scene parseSdl(std::string_view text, const std::string& fileName, const SdlOptions& options,
               std::vector<std::string>* warnings = nullptr);

// Reads and parses a file; a missing or unreadable file is an Error naming it.
Scene loadSdlFile(const std::string& path, const SdlOptions& options,
                  std::vector<std::string>* warnings = nullptr);

}  // namespace vkray
