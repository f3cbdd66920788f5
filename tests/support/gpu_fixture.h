// Shared pieces of the GPU tests: one Vulkan context for the whole test
// binary (lavapipe on machines without a GPU; a missing device is a failure,
// not a skip, because the project's setup installs lavapipe).
#pragma once

#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "render/camera.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"
#include "support/corpus.h"

#include <memory>
#include <string>

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray::test {

inline const std::string kSourceDir = VKRAY_SOURCE_DIR;
inline const std::string kShaderDir = kSourceDir + "/shaders";
// Scenes of the repository's own with the quirks of real files (CRLF,
// Latin-1 comments, Hill's words vkray lacks, missing meshes).
inline const std::string kDataDir = kSourceDir + "/tests/data";
// The corpus of real scenes: support/corpus.h (corpusDir(), VKRAY_NEED_CORPUS()).

inline gpu::Context& gpuContext() {
    static std::unique_ptr<gpu::Context> context = std::make_unique<gpu::Context>();
    return *context;
}

// The own walk's render (the ray-query walk has its tests: traversal_test.cpp).
inline Frame renderOnGpu(const Scene& scene, const CameraBasis& camera,
                         const RenderSettings& settings, gpu::GpuRenderStats* stats = nullptr,
                         bool allFeatures = false, bool worldTriangles = true) {
    gpu::GpuTracer tracer(gpuContext(), {.shaderDirectory = kShaderDir,
                                         .allFeatures = allFeatures,
                                         .worldTriangles = worldTriangles,
                                         .traversal = gpu::Traversal::Own});
    return tracer.render(scene, camera, settings, stats);
}

// The one ray eye -> look through the scene of SDL text, its meshes built;
// the text is read as if it were the file `scenePath` (files it names are
// found beside that).
inline Frame traceOneRay(const std::string& sdl, const std::string& scenePath, glm::dvec3 eye,
                         glm::dvec3 look, glm::dvec3 up) {
    Scene scene = parseSdl(sdl, scenePath, {});
    loadSceneGeometry(scene, false, nullptr);
    Camera camera;
    camera.eye = eye;
    camera.look = look;
    camera.up = up;
    return renderOnGpu(scene, makeCameraBasis(camera, 1, 1), {1, 1, 1});
}

}  // namespace vkray::test
