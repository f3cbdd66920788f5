// Where in the image a primary ray can meet an object: the boxes of the
// scene's bounded objects and the planes, projected through the camera. A
// pixel outside the cover shows the background whatever its samples, so a
// renderer may leave its rays out. On lavapipe a ray that meets nothing costs
// nearly what one that meets something does (every loop of the shader runs
// its first turn; docs/lavapipe.md), and most scenes leave much of the image
// to the background.
#pragma once

#include "render/camera.h"
#include "scene/bvh.h"
#include "scene/scene.h"

#include <cstdint>
#include <vector>

namespace vkray {

// A plane n . p + c = 0 in the world (n not necessarily of unit length).
struct WorldPlane {
    glm::dvec3 normal;
    double offset = 0;
};

// What a cover projects: boxes around everything bounded, the planes apart,
// and whether some other object has no finite box (then the cover is the
// whole image).
struct CoverShapes {
    std::vector<Aabb> boxes;
    std::vector<WorldPlane> planes;
    bool unbounded = false;
};

// The shapes of `scene`: each bounded object's world box (worldBounds), or
// with more than `most` of them the nodes of its object BVH `bvh` at the
// shallowest cut of at most `most` nodes; its planes; and whether any other
// object is unbounded.
CoverShapes coverShapesOf(const Scene& scene, const Bvh* bvh, std::size_t most = 2048);

class PrimaryCover {
public:
    // Cells of this many pixels a side are the cover's grain.
    static constexpr int kCell = 4;
    // With more planes than this the cover is the whole image.
    static constexpr std::size_t kMostPlanes = 16;

    // The whole image: every ray may meet something.
    explicit PrimaryCover(const RenderSettings& settings);

    // The image points whose primary rays may meet one of the shapes, grown
    // by a margin that covers the float rounding of a shader's ray (at least
    // a pixel), over the samples' extent: the image rounded up to whole
    // blocks. The whole image when a box reaches the plane of the eye (a box
    // behind it covers nothing), with an unbounded shape, with more than
    // kMostPlanes planes, or when a figure is not finite.
    PrimaryCover(const CoverShapes& shapes, const CameraBasis& camera,
                 const RenderSettings& settings);

    // Whether some sample in pixels [x0, x1) x [y0, y1) may meet an object.
    bool mayHit(int x0, int y0, int x1, int y1) const;

    // The share of the extent's cells in the cover (1 for the whole image).
    double share() const;

private:
    void coverAll();
    int cellCount(int cx0, int cy0, int cx1, int cy1) const;  // covered cells in the range

    int width_, height_;  // the samples' extent, in pixels
    int cellsX_, cellsY_;
    // Summed-area table of covered cells: (cellsX_ + 1) x (cellsY_ + 1).
    std::vector<std::int32_t> sums_;
};

}  // namespace vkray
