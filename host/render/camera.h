// From a Camera (eye, look, up, fov) to the orthonormal basis both renderers
// build primary rays from, and the automatic framing used when a scene has no
// camera.
#pragma once

#include "image/frame.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace vkray {

// What a renderer needs besides the scene: image size, the seed's block
// size (one ray per block x block pixels, the block filled with its colour)
// and anti-aliasing: spp jittered samples per pixel (or block), placed by
// shaders/sampling.h from `seed` (same seed, same image).
struct RenderSettings {
    int width = 640;
    int height = 480;
    int block = 1;
    int spp = 1;  // 1..kMaxSpp; 1: the pixel (block) centre
    std::uint32_t seed = 0;
    // The samples traced, of the spp each pixel has: sampleCount of them
    // from firstSample on (0: all from there). The colour is their mean; the
    // AOVs are sample 0's, so with firstSample > 0 they stay as Frame() made
    // them. `vkray view` traces one sample a pass and sums the passes.
    int firstSample = 0;
    int sampleCount = 0;
    // Whether the renderer writes each pixel's depth and normal (sample 0's
    // AOVs; the object id is always written). Without, they stay as Frame()
    // made them: a GPU variant that leaves them out stores a quarter of the
    // words a ray would otherwise (shaders/layout.h, GpuPixel).
    bool aovs = true;
};
inline constexpr int kMaxSpp = 4096;

// The end of the samples `settings` traces (one past the last); throws
// Error unless 0 <= firstSample < end <= spp.
int sampleEnd(const RenderSettings& settings);

// Hill's camera basis: n points from the look point back to the eye, u right,
// v up. A primary ray through image point (sx, sy) in [-1, 1]^2 (x right, y up)
// has direction normalize(-n + sx * tanHalfFov * aspect * u + sy * tanHalfFov * v).
struct CameraBasis {
    glm::dvec3 eye, u, v, n;
    double tanHalfFov = 0;
    double aspect = 1;  // width / height
};

// Throws Error when eye == look, up is zero or parallel to the view
// direction, or a coordinate is beyond kMaxSceneMagnitude: at the camera's
// place (file:line:col) when it has one.
CameraBasis makeCameraBasis(const Camera& camera, int width, int height);

// No camera in the scene: look from the direction of Hill's usual eye
// (20, 15, 20) toward the centre of the finite objects' world bounds, 60
// degrees, far enough that their bounding sphere fills the view.
Camera autoCamera(const Scene& scene);

// The image point, in pixels (x right, y down, continuous), that the primary
// ray of pixel (x, y) goes through: the pixel centre, or with block > 1 the
// centre of the block holding it.
struct PixelSample {
    double px, py;
};
PixelSample primarySample(int x, int y, int block);

// Sample k (0 <= k < settings.spp) of pixel (x, y): with spp 1 the
// primarySample; otherwise the block's top-left corner (the pixel's, for
// block 1) plus block times shaders/sampling.h's stratified offset, drawn for
// settings.seed and the index y0 * width + x0 of the block's first pixel.
PixelSample jitteredSample(int x, int y, const RenderSettings& settings, int k);

// The unit direction of the primary ray through image point `s`, as
// CameraBasis describes it.
glm::dvec3 primaryDirection(const CameraBasis& camera, const RenderSettings& settings,
                            PixelSample s);

// Each pixel's world hit point: eye + depth times the direction of its
// sample 0 (the ray whose depth, normal and id a Frame holds), in double,
// rounded to float; 0 where the depth is not finite (a miss).
std::vector<glm::vec3> hitPoints(const Frame& frame, const CameraBasis& camera,
                                 const RenderSettings& settings);

}  // namespace vkray
