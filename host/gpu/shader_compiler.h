// GLSL -> SPIR-V at run time with glslang's C++ API. Includes resolve inside
// the shader folder only; errors keep glslang's `file:line` through includes.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vkray::gpu {

struct ShaderSource {
    std::string directory;                // the shader folder (shaders/ or --shader-dir)
    std::string mainFile = "trace.comp";  // relative to directory
    std::vector<std::pair<std::string, std::string>> defines;  // NAME, VALUE
};

// Compiles a compute shader for Vulkan 1.2 / SPIR-V 1.5. Throws Error with
// glslang's log (each message names the shader file and line) on failure.
std::vector<std::uint32_t> compileComputeShader(const ShaderSource& source);

// glslang's version, part of the SPIR-V cache key.
std::string glslangVersion();

}  // namespace vkray::gpu
