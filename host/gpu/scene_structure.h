// The driver's acceleration structure over a scene's bounded objects, for
// the ray-query walk (gpu/traversal.h): one bottom level of boxes, the
// objects' world boxes in the order of the object BVH's entries (a box's
// primitive index is its entry, objectAt in the shader), under a top level
// of one instance. Internal to host/gpu.
#pragma once

#include "gpu/context_impl.h"
#include "scene/bvh.h"

#include <memory>
#include <span>

namespace vkray::gpu {

class SceneStructure {
public:
    // Builds it on the device and waits. Each box is widened by
    // kStructureBoxMargin of the scene's extent (`scale`: the largest
    // coordinate among the boxes and the eye), so that the driver's float
    // box test of the float ray misses no object the shader's test of its
    // own ray (in double for fp64) meets; an empty or unbounded box is an
    // inactive primitive. Throws Error where the device runs out of memory.
    SceneStructure(Context::Impl& c, std::span<const Aabb> boxes, double scale);
    ~SceneStructure();
    SceneStructure(const SceneStructure&) = delete;
    SceneStructure& operator=(const SceneStructure&) = delete;

    vk::AccelerationStructureKHR handle() const { return *top_; }
    double buildSeconds() const { return buildSeconds_; }  // both levels, on the device, waited for

private:
    std::unique_ptr<HostBuffer> boxes_, bottomStorage_, topStorage_, instances_;
    vk::raii::AccelerationStructureKHR bottom_ = nullptr, top_ = nullptr;
    double buildSeconds_ = 0;
};

// Of the scene's extent, how far each box is widened: 2^-16, where float's
// rounding of the ray and the box test's own come to a few 2^-24.
inline constexpr double kStructureBoxMargin = 1.0 / 65536;

}  // namespace vkray::gpu
