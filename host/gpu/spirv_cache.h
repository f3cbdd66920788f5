// SPIR-V cached on disk, keyed by every source file in the shader folder,
// the defines and glslang's version. lavapipe's VkPipelineCache keeps nothing
// between runs, so without this every run would pay the GLSL compile.
#pragma once

#include "gpu/shader_compiler.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vkray::gpu {

struct CompiledShader {
    std::vector<std::uint32_t> spirv;
    std::string key;  // 16 hex digits
    bool cacheHit = false;
    double seconds = 0;  // load or compile time
};

// $VKRAY_CACHE_DIR, else $XDG_CACHE_HOME/vkray, else $HOME/.cache/vkray.
std::string spirvCacheDirectory();

// The cache key of `source` compiled from `files`: FNV-1a 64 over the
// cache's format, glslang's version, the main file name, the defines, and
// the path and bytes of every file; without `files`, of the folder as it is.
std::string spirvCacheKey(const ShaderSource& source, const ShaderFiles& files);
std::string spirvCacheKey(const ShaderSource& source);

// Loads the cached SPIR-V or compiles and stores it (atomically), the key
// and the compile from one reading of the folder. A cache folder that cannot
// be written only costs the compile. A load marks its entry used (its time);
// a store prunes the folder to kSpirvCacheLimitBytes.
CompiledShader loadOrCompile(const ShaderSource& source);

// The most the cache's entries may hold together: each shader edit adds one
// variant's SPIR-V (60 to 90 KB for trace.comp), so a folder left alone
// would only grow. 64 MiB keeps about 800 variants.
inline constexpr std::uintmax_t kSpirvCacheLimitBytes = std::uintmax_t(64) << 20;

// Removes the entries of cache folder `dir` (its files named as a key and
// ".spv"; nothing else there is touched) used least recently, oldest first,
// until they hold at most `limitBytes` together; the entry `keep` (a file
// name) stays whatever its size. An entry another process removed meanwhile
// is passed over. Returns how many it removed.
std::size_t pruneSpirvCache(const std::string& dir, std::uintmax_t limitBytes,
                            const std::string& keep);

}  // namespace vkray::gpu
