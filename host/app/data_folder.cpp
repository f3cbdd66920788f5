#include "app/data_folder.h"

#include <filesystem>

namespace vkray {

namespace fs = std::filesystem;

std::string DataFolder::whereLooked() const {
    return "next to the binary (" + beside + ") nor in the installed place (" + installed + ")";
}

DataFolder findDataFolder(const std::string& besideBinary, const std::string& installed,
                          const std::string& mustHold) {
    std::error_code ec;
    const fs::path binaryDir = fs::read_symlink("/proc/self/exe", ec).parent_path();
    DataFolder found;
    found.beside = (binaryDir / besideBinary).string();
    found.installed = (binaryDir.parent_path() / "share" / "vkray" / installed).string();
    if (ec) return found;
    for (const std::string& dir : {found.beside, found.installed}) {
        std::error_code e;
        if (fs::is_directory(dir, e) &&
            (mustHold.empty() || fs::exists(fs::path(dir) / mustHold, e))) {
            found.path = dir;
            break;
        }
    }
    return found;
}

}  // namespace vkray
