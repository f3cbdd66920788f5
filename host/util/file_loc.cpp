#include "util/file_loc.h"

#include <filesystem>

namespace vkray {

std::string FileLoc::str() const {
    if (!file) return "<unknown>";
    return *file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string formatDiagnostic(const FileLoc& loc, const Expansion* expansion, const char* severity,
                             const std::string& message) {
    std::string out = loc.str() + ": " + severity + ": " + message;
    for (const Expansion* e = expansion; e; e = e->parent.get())
        out.append("\n")
            .append(e->useLoc.str())
            .append(": note: in text pasted by 'use ")
            .append(e->name)
            .append("'");
    return out;
}

std::string writtenName(const FileLoc& loc, const std::string& resolvedPath) {
    if (loc.known()) {
        const std::filesystem::path folder = std::filesystem::path(*loc.file).parent_path();
        const std::filesystem::path relative =
            std::filesystem::path(resolvedPath).lexically_relative(folder);
        // An absolute name far from the scene ("/usr/share/x.obj") reads
        // better as written than as a climb out of the scene's folder.
        const bool climbsOut = relative.begin() != relative.end() && *relative.begin() == "..";
        if (!relative.empty() && !(climbsOut && relative.string().size() >= resolvedPath.size()))
            return relative.string();
    }
    return resolvedPath;
}

}  // namespace vkray
