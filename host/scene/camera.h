// From a Camera (eye, look, up, fov) to the orthonormal basis both renderers
// build primary rays from, and the automatic framing used when a scene has no
// camera.
#pragma once

#include "scene/scene.h"

namespace vkray {

// What a renderer needs besides the scene: image size and the seed's block
// size (one ray per block x block pixels, the block filled with its colour).
struct RenderSettings {
    int width = 640;
    int height = 480;
    int block = 1;
};

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
struct PixelSample { double px, py; };
PixelSample primarySample(int x, int y, int block);

}  // namespace vkray
