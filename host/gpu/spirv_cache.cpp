#include "gpu/spirv_cache.h"

#include "util/files.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace vkray::gpu {

namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t kSpirvMagic = 0x07230203;

// Part of every key. Raised when entries already written cannot be trusted:
// 2 since the key and the compile read the same bytes (before, a file saved
// between the two could leave its SPIR-V under the old bytes' key).
constexpr const char* kCacheFormat = "vkray-spirv-cache 2";

constexpr std::size_t kKeyDigits = 16;

// A cache entry's name: the key's 16 hex digits and ".spv".
bool isEntryName(const std::string& name) {
    const std::string suffix = ".spv";
    if (name.size() != kKeyDigits + suffix.size() || !name.ends_with(suffix)) return false;
    return std::all_of(name.begin(), name.begin() + kKeyDigits,
                       [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

struct Fnv1a {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    void add(const std::string& bytes) {
        for (unsigned char c : bytes) hash = (hash ^ c) * 0x100000001b3ull;
        hash = (hash ^ 0xff) * 0x100000001b3ull;  // separator: "ab","c" != "a","bc"
    }
};

}  // namespace

std::string spirvCacheDirectory() {
    if (const char* dir = std::getenv("VKRAY_CACHE_DIR"); dir && *dir) return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return (fs::path(xdg) / "vkray").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".cache" / "vkray").string();
    return (fs::temp_directory_path() / "vkray-cache").string();
}

std::string spirvCacheKey(const ShaderSource& source) {
    return spirvCacheKey(source, readShaderFiles(source.directory));
}

std::string spirvCacheKey(const ShaderSource& source, const ShaderFiles& files) {
    Fnv1a h;
    h.add(kCacheFormat);
    h.add(glslangVersion());
    h.add(source.mainFile);
    for (const auto& [name, value] : source.defines) {
        h.add(name);
        h.add(value);
    }
    for (const auto& [path, bytes] : files) {
        h.add(path);
        h.add(bytes);
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.hash));
    return hex;
}

CompiledShader loadOrCompile(const ShaderSource& source) {
    const Stopwatch stopwatch;
    CompiledShader result;
    const ShaderFiles files = readShaderFiles(source.directory);
    result.key = spirvCacheKey(source, files);
    const fs::path file = fs::path(spirvCacheDirectory()) / (result.key + ".spv");

    if (const std::optional<std::string> cached = readFileIfPresent(file.string())) {
        const std::string& data = *cached;
        if (data.size() >= 20 && data.size() % 4 == 0) {
            result.spirv.resize(data.size() / 4);
            std::copy(data.begin(), data.end(), reinterpret_cast<char*>(result.spirv.data()));
            result.cacheHit = result.spirv[0] == kSpirvMagic;
        }
    }
    std::error_code ec;
    if (result.cacheHit) fs::last_write_time(file, fs::file_time_type::clock::now(), ec);
    if (!result.cacheHit) {
        result.spirv = compileComputeShader(source, files);
        fs::create_directories(file.parent_path(), ec);
        try {
            writeFileAtomically(file.string(),
                                std::string(reinterpret_cast<const char*>(result.spirv.data()),
                                            result.spirv.size() * 4));
            pruneSpirvCache(file.parent_path().string(), kSpirvCacheLimitBytes,
                            file.filename().string());
        } catch (const std::exception&) {
            // An unwritable cache costs only the next compile.
        }
    }
    result.seconds = stopwatch.seconds();
    return result;
}

std::size_t pruneSpirvCache(const std::string& dir, std::uintmax_t limitBytes,
                            const std::string& keep) {
    struct Entry {
        fs::path path;
        fs::file_time_type used;
        std::uintmax_t bytes;
    };
    std::vector<Entry> entries;
    std::uintmax_t total = 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!isEntryName(name)) continue;
        std::error_code statError;
        const std::uintmax_t bytes = it->file_size(statError);
        const fs::file_time_type used = it->last_write_time(statError);
        if (statError) continue;  // gone meanwhile, or not a plain file
        total += bytes;
        if (name != keep) entries.push_back({it->path(), used, bytes});
    }
    std::sort(entries.begin(), entries.end(),
              [](const Entry& a, const Entry& b) { return a.used < b.used; });
    std::size_t removed = 0;
    for (const Entry& entry : entries) {
        if (total <= limitBytes) break;
        std::error_code removeError;
        if (fs::remove(entry.path, removeError)) ++removed;
        total -= entry.bytes;  // removed by another process, if not by this one
    }
    return removed;
}

}  // namespace vkray::gpu
