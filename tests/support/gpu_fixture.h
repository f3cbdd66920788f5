// Shared pieces of the GPU tests: one Vulkan context for the whole test
// binary (lavapipe on machines without a GPU; a missing device is a failure,
// not a skip, because the project's setup installs lavapipe).
#pragma once

#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "scene/sdl_reader.h"

#include <memory>
#include <string>

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray::test {

inline const std::string kSourceDir = VKRAY_SOURCE_DIR;
inline const std::string kShaderDir = kSourceDir + "/shaders";
inline const std::string kCorpusDir = kSourceDir + "/../shared/sdl-corpus";

inline gpu::Context& gpuContext() {
    static std::unique_ptr<gpu::Context> context = std::make_unique<gpu::Context>();
    return *context;
}

inline Frame renderOnGpu(const Scene& scene, const CameraBasis& camera,
                         const RenderSettings& settings, gpu::GpuRenderStats* stats = nullptr,
                         bool allFeatures = false) {
    gpu::GpuTracer tracer(gpuContext(), {.shaderDirectory = kShaderDir, .allFeatures = allFeatures});
    return tracer.render(scene, camera, settings, stats);
}

}  // namespace vkray::test
