// The CPU reference renderer: written from the math, in double precision,
// independently of the shader, so that one bug cannot hide in both. It
// produces the same Frame as the GPU tracer.
#pragma once

#include "image/frame.h"
#include "image/pixel_trace.h"
#include "scene/camera.h"
#include "scene/render_progress.h"
#include "scene/scene.h"

namespace vkray::reference {

struct ReferenceOptions {
    int threads = 0;          // 0: std::thread::hardware_concurrency()
    bool bruteForce = false;  // test every object for every ray (the BVH's oracle)
    RenderProgress progress;  // after each row of blocks; false stops (Interrupted)
};

// Renders every pixel (one primary ray per pixel, or per block) with Hill's
// local shading model. Every shape type is drawn; throws Error (at the
// object's place) for a mesh object whose mesh is not loaded
// (loadSceneGeometry) and for a boolean operand without an inside.
Frame render(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
             const ReferenceOptions& options = {});

// `vkray pixel`: the one primary ray of pixel (x, y), with every object test
// and every shading term, as PixelTrace records them.
PixelTrace tracePixel(const Scene& scene, const CameraBasis& camera,
                      const RenderSettings& settings, int x, int y);

}  // namespace vkray::reference
