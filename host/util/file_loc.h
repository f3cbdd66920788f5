// A place in an input file, carried by every token and scene node so that
// every diagnostic can say `file:line:col` (pbrt-v4's FileLoc, with the file
// name owned instead of leaked).
#pragma once

#include <memory>
#include <string>

namespace vkray {

struct FileLoc {
    std::shared_ptr<const std::string> file;  // shared by all tokens of one file
    int line = 0;                             // 1-based; 0 = no place known
    int column = 0;                           // 1-based, in bytes

    bool known() const { return file != nullptr; }
    // "scene.sdl:12:5", or "<unknown>" when no place is known.
    std::string str() const;
};

// Text pasted by `use NAME`: the chain of use sites, innermost first, so an
// error inside a def can say both where the bad text was written and where it
// was pasted.
struct Expansion {
    std::string name;                         // the def's name
    FileLoc useLoc;                           // where `use NAME` stood
    std::shared_ptr<const Expansion> parent;  // the use that pasted that `use`, if any
};

// A file the scene at `loc` names, as the scene wrote it (the reader resolved
// it against the scene's folder), for messages.
std::string writtenName(const FileLoc& loc, const std::string& resolvedPath);

// Formats "file:line:col: error: message" plus one note line per use site.
std::string formatDiagnostic(const FileLoc& loc, const Expansion* expansion, const char* severity,
                             const std::string& message);

}  // namespace vkray
