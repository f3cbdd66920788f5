// The CPU reference renderer's driver: the primary rays of every pixel (or
// block), spp jittered samples each (shaders/sampling.h, through
// jitteredSample), the closest hits through the object BVH (or by brute
// force), and Whitted shading (shading.h), all in double.
#include "reference/reference_tracer.h"

#include "reference/scene_intersector.h"
#include "reference/shading.h"
#include "util/error.h"
#include "util/parallel_for.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace vkray::reference {
namespace {

// The primary ray through image point (px, py), in pixels with y down. The
// direction is unit, so a hit's t is its distance from the eye.
Ray primaryRay(const CameraBasis& camera, const RenderSettings& settings, PixelSample s) {
    return {camera.eye, primaryDirection(camera, settings, s)};
}

// What one pixel (or block) shows: the mean colour of its samples, and the
// AOVs of sample 0.
struct PixelValue {
    glm::vec3 color;
    float depth;
    glm::vec3 normal;
    std::int32_t id;
};

PixelValue tracePixelSamples(const WhittedShader& shader, const CameraBasis& camera,
                             const RenderSettings& settings, int x, int y) {
    const int end = sampleEnd(settings);
    glm::dvec3 sum(0);
    std::optional<WorldHit> first;
    for (int k = settings.firstSample; k < end; ++k) {
        const Ray ray = primaryRay(camera, settings, jitteredSample(x, y, settings, k));
        sum += shader.radiance(ray, 0, Medium{}, k == 0 ? &first : nullptr);
    }
    const glm::vec3 color(sum / double(end - settings.firstSample));
    if (settings.firstSample > 0) return {color, 0, glm::vec3(0), -1};  // as Frame() makes them
    if (!first) return {color, std::numeric_limits<float>::infinity(), glm::vec3(0), -1};
    return {color, float(first->t), glm::vec3(first->normal), first->object};
}

// One band of the image: the block row starting at y0. With block > 1 every
// pixel of a block shows the ray through the block's centre, so that ray is
// traced once and its value copied (clipped at the image's right and bottom).
void renderBlockRow(const WhittedShader& shader, const CameraBasis& camera,
                    const RenderSettings& settings, int block, int y0, Frame& frame) {
    const int y1 = std::min(y0 + block, frame.height);
    for (int x0 = 0; x0 < frame.width; x0 += block) {
        const PixelValue value = tracePixelSamples(shader, camera, settings, x0, y0);
        const int x1 = std::min(x0 + block, frame.width);
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const size_t i = frame.index(x, y);
                frame.color[i] = value.color;
                frame.id[i] = value.id;
                if (!settings.aovs) continue;  // as Frame() made them
                frame.depth[i] = value.depth;
                frame.normal[i] = value.normal;
            }
        }
    }
}

}  // namespace

PixelTrace tracePixel(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                      int x, int y) {
    requireReferenceScene(scene);
    PixelTrace trace;
    trace.x = x;
    trace.y = y;
    // Sample firstSample's ray (the pixel centre with one sample per pixel).
    const Ray ray =
        primaryRay(camera, settings, jitteredSample(x, y, settings, settings.firstSample));
    trace.rayOrigin = ray.origin;
    trace.rayDirection = ray.direction;
    // Each top-level object on its own (a boolean's generic ray is that of its
    // own transform, which its operands do not use: they carry their own).
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        const Ray generic = toObjectSpace(object, ray);
        const std::optional<WorldHit> hit = intersectObject(scene, object, int(i), ray, 0.0);
        trace.objects.push_back({generic.origin, generic.direction,
                                 hit ? std::optional<double>(hit->t) : std::nullopt});
    }
    // Brute force throughout: the pixel report checks the BVH, not uses it.
    const SceneIntersector intersector(scene, true);
    const WhittedShader shader(scene, intersector);
    std::optional<WorldHit> hit;
    trace.color = shader.radiance(ray, 0, Medium{}, &hit, &trace);
    if (hit) {
        trace.hitObject = hit->object;
        trace.t = hit->t;
        trace.point = hit->point;
        trace.normal = hit->normal;
    }
    return trace;
}

Frame render(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
             const ReferenceOptions& options) {
    requireReferenceScene(scene);
    if (settings.width <= 0 || settings.height <= 0)
        throw Error("render: the image size must be positive (got " +
                    std::to_string(settings.width) + " x " + std::to_string(settings.height) + ")");
    if (settings.spp < 1 || settings.spp > kMaxSpp)
        throw Error("render: samples per pixel must be 1.." + std::to_string(kMaxSpp) + " (got " +
                    std::to_string(settings.spp) + ")");
    sampleEnd(settings);  // the samples asked for are among the pixel's
    const int block = std::max(settings.block, 1);
    const StageClock preparing;
    Frame frame(settings.width, settings.height);

    // Block rows are handed out to the threads in turn. Each pixel's value
    // depends only on its own ray, so the image is the same for any thread
    // count and any order.
    const int blockRows = (settings.height + block - 1) / block;

    const SceneIntersector intersector(scene, options.bruteForce);  // one BVH for all rays
    const WhittedShader shader(scene, intersector);
    const Elapsed prepared = preparing.elapsed();
    const StageClock tracing;
    const std::size_t raysPerRow = std::size_t((settings.width + block - 1) / block);
    const std::size_t totalRays = raysPerRow * std::size_t(blockRows);
    if (options.progress && !options.progress(0, totalRays)) throw Interrupted();
    std::atomic<std::size_t> raysDone{0};
    // The first failure (Interrupted included) stops every worker and is
    // rethrown here.
    parallelFor(
        std::size_t(blockRows),
        [&](std::size_t row) {
            renderBlockRow(shader, camera, settings, block, int(row) * block, frame);
            const std::size_t done = raysDone += raysPerRow;
            if (options.progress && !options.progress(done, totalRays)) throw Interrupted();
        },
        options.threads);
    if (options.stats) *options.stats = {prepared, tracing.elapsed()};
    return frame;
}

}  // namespace vkray::reference
