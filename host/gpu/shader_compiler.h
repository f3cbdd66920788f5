// GLSL -> SPIR-V at run time with glslang's C++ API. Includes resolve inside
// the shader folder only; errors keep glslang's `file:line` through includes.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vkray::gpu {

struct ShaderSource {
    std::string directory;                // the shader folder (shaders/ or --shader-dir)
    std::string mainFile = "trace.comp";  // relative to directory
    std::vector<std::pair<std::string, std::string>> defines;  // NAME, VALUE
};

// The shader folder's sources (.comp, .glsl, .h, below it too) read once,
// by path relative to the folder. A compile and its SPIR-V cache key take
// the same bytes, however the files change in between (an editor saving
// while `vkray view` renders).
using ShaderFiles = std::map<std::string, std::string>;
ShaderFiles readShaderFiles(const std::string& directory);

// Compiles a compute shader for Vulkan 1.2 / SPIR-V 1.5 from `files` (the
// main file and every include among them). Throws Error with glslang's log
// (each message names the shader file and line) on failure.
std::vector<std::uint32_t> compileComputeShader(const ShaderSource& source,
                                                const ShaderFiles& files);
// The same, from the folder as it is now.
std::vector<std::uint32_t> compileComputeShader(const ShaderSource& source);

// glslang's version, part of the SPIR-V cache key.
std::string glslangVersion();

}  // namespace vkray::gpu
