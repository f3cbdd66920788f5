// Frame: the one currency between renderers, writers and comparers. Every
// renderer produces one; every comparison takes two.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vkray {

struct Frame {
    int width = 0;
    int height = 0;
    // Row 0 is the top of the image. All arrays hold width * height entries.
    std::vector<glm::vec3> color;   // linear RGB radiance, unclamped (PNG clamps to [0,1])
    std::vector<float> depth;       // distance from the eye along the ray; +inf on a miss
    std::vector<glm::vec3> normal;  // world unit normal facing the ray; 0 on a miss
    std::vector<std::int32_t> id;   // object index in scene order; -1 on a miss

    Frame() = default;
    // Every pixel of colour `fill` and depth `depth`, normal 0, id -1: a
    // renderer that knows which pixels its rays miss writes only the others.
    Frame(int w, int h, glm::vec3 fill = {}, float depth = 0)
        : width(w),
          height(h),
          color(size_t(w) * h, fill),
          depth(size_t(w) * h, depth),
          normal(size_t(w) * h),
          id(size_t(w) * h, -1) {}

    size_t pixelCount() const { return size_t(width) * size_t(height); }
    size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
};

}  // namespace vkray
