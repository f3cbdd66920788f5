// SPIR-V cached on disk, keyed by every source file in the shader folder,
// the defines and glslang's version. lavapipe's VkPipelineCache keeps nothing
// between runs, so without this every run would pay the GLSL compile.
#pragma once

#include "gpu/shader_compiler.h"

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
// be written only costs the compile.
CompiledShader loadOrCompile(const ShaderSource& source);

}  // namespace vkray::gpu
