// Decision margins: what the CPU reference's value of a pixel can be when
// every ray of its samples is moved by a GPU mode's error bound. A GPU pixel
// that differs from the reference's is explained where it lies within that
// span: some decision (the closest hit and its runner-up, a silhouette or
// an edge, a texture cell's border, a feeler's blocker, a refraction's
// critical angle) is within the bound of going the other way. Anywhere
// else a difference is the GPU's fault.
#pragma once

#include "reference/shading.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace vkray::reference {

// The reference's value of one pixel (or block) over every play of the bound.
struct PixelSpan {
    glm::vec3 low{0}, high{0};  // per channel: the mean over samples of each one's least / most
    struct FirstHit {
        std::int32_t id = -1;
        float depth = 0;
        glm::vec3 normal{0};
    };
    std::vector<FirstHit> firstHits;  // sample 0's, one a play, the reference's own first
};

// The plays: the reference itself; its rays unmoved but leaving
// surfaces as the GPU's do (the GPU's own geometry, its offset's step
// along each new ray), and so with each step landing the bound further or
// shorter along the ray; eight sides of the bound, and in a scene with
// textures eight more that look them up where their hits are; and the
// runner-up winning every tie within it.
class MarginTracer {
public:
    // All must outlive the tracer.
    MarginTracer(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                 const ErrorBound& bound);
    ~MarginTracer();

    // The pixel (x, y)'s span; with a block, (x, y) is the block's first pixel.
    // Thread-safe.
    PixelSpan spanOf(int x, int y) const;
    // How many plays each sample is traced in (the reference's own first).
    int plays() const;

private:
    struct Plays;
    const CameraBasis& camera_;
    RenderSettings settings_;
    std::unique_ptr<Plays> plays_;
};

}  // namespace vkray::reference
