#include "scene/file_loc.h"

namespace vkray {

std::string FileLoc::str() const {
    if (!file) return "<unknown>";
    return *file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string formatDiagnostic(const FileLoc& loc, const Expansion* expansion,
                             const char* severity, const std::string& message) {
    std::string out = loc.str() + ": " + severity + ": " + message;
    for (const Expansion* e = expansion; e; e = e->parent.get())
        out.append("\n").append(e->useLoc.str()).append(": note: in text pasted by 'use ")
            .append(e->name).append("'");
    return out;
}

}  // namespace vkray
