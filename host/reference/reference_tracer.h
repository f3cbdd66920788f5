// The CPU reference renderer: written from the math, in double precision,
// independently of the shader, so that one bug cannot hide in both. It
// produces the same Frame as the GPU tracer.
#pragma once

#include "image/frame.h"
#include "image/pixel_trace.h"
#include "render/camera.h"
#include "render/render_progress.h"
#include "scene/scene.h"
#include "util/stopwatch.h"

namespace vkray::reference {

// Where a render's time went: the frame's allocation and the object BVH
// (preparation), then the rays (trace).
struct ReferenceStats {
    Elapsed prepare, trace;
};

struct ReferenceOptions {
    int threads = 0;                  // 0: std::thread::hardware_concurrency()
    bool bruteForce = false;          // test every object for every ray (the BVH's oracle)
    RenderProgress progress;          // after each row of blocks; false stops (Interrupted)
    ReferenceStats* stats = nullptr;  // filled when given
};

// Renders every pixel (or block: settings.block) with Whitted shading
// (shading.h): settings.spp samples each (1: the centre), their mean colour,
// and the AOVs of sample 0. Every shape type is drawn; throws Error (at the
// object's place) for a mesh object whose mesh is not loaded
// (loadSceneGeometry) and for a boolean operand without an inside, and for
// spp outside 1..kMaxSpp.
Frame render(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
             const ReferenceOptions& options = {});

// `vkray pixel`: sample settings.firstSample's primary ray of pixel (x, y), with every object
// test and the shading terms of its hit (attenuated by the shadow feelers,
// scaled by the texture); the colour is that ray's whole Whitted colour.
PixelTrace tracePixel(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                      int x, int y);

}  // namespace vkray::reference
