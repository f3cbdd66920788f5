// Depth-first traversal of a Bvh (scene/bvh.h) for the CPU reference, shared
// by the mesh (triangles) and scene (objects) intersectors.
#pragma once

#include "reference/shapes.h"
#include "scene/bvh.h"

#include <array>
#include <cstdint>
#include <stdexcept>

namespace vkray::reference {

// Calls leaf(primitive) for every primitive (bvh.order entry) of each leaf
// whose box the ray meets within [tMin, tMax()]; tMax() may shrink as the
// caller finds hits, and boxes entered beyond it are skipped. The nearer
// child goes first. Boxes are met by the conservative slab test of bvh.h, so
// a primitive whose hit lies within its box is never skipped.
template <typename TMax, typename Leaf>
void walkBvh(const Bvh& bvh, const Ray& ray, double tMin, TMax tMax, Leaf leaf) {
    if (bvh.nodes.empty()) return;
    const glm::dvec3 inverse = 1.0 / ray.direction;  // +-inf for a zero component
    struct Entry {
        std::uint32_t node;
        double tEntry;
    };
    // Each level pops one node and pushes at most two: depth + 1 entries.
    std::array<Entry, kMaxBvhDepth + 2> stack;
    std::size_t size = 0;
    double rootEntry;
    if (!intersectAabb(bvh.nodes[0].bounds, ray.origin, inverse, tMin, tMax(), &rootEntry)) return;
    stack[size++] = {0, rootEntry};
    while (size > 0) {
        const Entry entry = stack[--size];
        if (entry.tEntry > tMax()) continue;  // a nearer hit was found since it was pushed
        const BvhNode& node = bvh.nodes[entry.node];
        if (node.leaf()) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) leaf(bvh.order[k]);
            continue;
        }
        if (size + 2 > stack.size())  // only a BVH deeper than its contract allows
            throw std::logic_error("BVH deeper than kMaxBvhDepth");
        const std::uint32_t children[2] = {entry.node + 1, node.first};
        double entries[2] = {0, 0};
        bool met[2];
        for (int i = 0; i < 2; ++i)
            met[i] = intersectAabb(bvh.nodes[children[i]].bounds, ray.origin, inverse, tMin, tMax(),
                                   &entries[i]);
        // Push the farther first, so that the nearer is popped next.
        const int nearer = met[0] && met[1] ? (entries[1] < entries[0] ? 1 : 0) : (met[0] ? 0 : 1);
        const int farther = 1 - nearer;
        if (met[farther]) stack[size++] = {children[farther], entries[farther]};
        if (met[nearer]) stack[size++] = {children[nearer], entries[nearer]};
    }
}

}  // namespace vkray::reference
