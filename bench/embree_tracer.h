// Embree 3, the CPU ray tracer a user would otherwise pick, tracing the same
// primary rays as vkray (closest hit only: no shading), for the benchmark.
// Built only when CMake finds Embree (Debian's libembree-dev).
#pragma once

#include "render/camera.h"
#include "scene/scene.h"

#include <memory>
#include <string>
#include <vector>

namespace vkray::bench {

class EmbreeTracer {
public:
    // Builds Embree's BVH over the scene on `threads` threads: spheres placed
    // by a similarity as Embree's own spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT),
    // meshes and cubes as world-space triangles, every other bounded object
    // (quadrics, tori, booleans, stretched spheres) as a user primitive whose
    // intersection is the CPU reference's (double); unbounded objects
    // (planes) are tested for every ray after Embree's query.
    EmbreeTracer(const Scene& scene, int threads);
    ~EmbreeTracer();
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    // The closest hit's object index (-1: none) of every pixel's primary ray
    // (the pixel centre, as both renderers), row-major, traced on `threads`
    // std::threads with rtcIntersect1, or rtcIntersect8 on 4x2-pixel packets.
    std::vector<int> trace(const CameraBasis& camera, int width, int height, int threads,
                           bool packets) const;

    double buildSeconds() const;
    std::string contents() const;  // "256 spheres", "1002528 triangles, 3 user primitives", ...
    static std::string version();  // "3.13.5 (native ray8: yes)"

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkray::bench
