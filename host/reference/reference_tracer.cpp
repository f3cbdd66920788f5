// The CPU reference renderer: one primary ray per pixel (or per block), the
// closest hit through the object BVH (or by brute force), and Hill's local
// shading model without shadows (ch. 8 and 14), all in double.
#include "reference/reference_tracer.h"

#include "reference/scene_intersector.h"
#include "scene/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace vkray::reference {
namespace {

// The primary ray through image point (px, py), in pixels with y down. The
// direction is unit, so a hit's t is its distance from the eye.
Ray primaryRay(const CameraBasis& camera, const RenderSettings& settings, PixelSample s) {
    const double sx = 2 * s.px / settings.width - 1;   // -1 left .. 1 right
    const double sy = 1 - 2 * s.py / settings.height;  // -1 bottom .. 1 top
    const glm::dvec3 direction =
        glm::normalize(-camera.n + sx * camera.tanHalfFov * camera.aspect * camera.u +
                       sy * camera.tanHalfFov * camera.v);
    return {camera.eye, direction};
}

// Hill's local model at point p with unit normal m facing the viewer, who
// looks from direction v (unit, from p toward the eye):
//     emissive + ambient * globalAmbient
//       + sum over lights of (diffuse max(0, m.s) + specular max(0, m.h)^f) * light
// with s the unit vector toward the light and h = normalize(s + v) the halfway
// vector. No shadows: every light is seen from every point.
glm::dvec3 shade(const Scene& scene, const Material& material, const glm::dvec3& p,
                 const glm::dvec3& m, const glm::dvec3& v,
                 std::vector<PixelTrace::LightTerms>* terms = nullptr) {
    glm::dvec3 color = material.emissive + material.ambient * scene.globalAmbient;
    for (const Light& light : scene.lights) {
        PixelTrace::LightTerms term;
        const glm::dvec3 toLight = light.position - p;
        const glm::dvec3 s = glm::normalize(toLight);
        const glm::dvec3 halfway = s + v;
        // A light on the surface has no direction; one straight behind, no halfway vector.
        if (glm::dot(toLight, toLight) > 0) {
            term.mDotS = glm::dot(m, s);
            if (term.mDotS > 0) term.diffuse = material.diffuse * term.mDotS * light.color;
            if (glm::dot(halfway, halfway) > 0) {
                term.mDotH = glm::dot(m, glm::normalize(halfway));
                if (term.mDotH > 0)
                    term.specular = material.specular *
                                    std::pow(term.mDotH, material.specularExponent) * light.color;
            }
        }
        color += term.diffuse + term.specular;
        if (terms) terms->push_back(term);
    }
    return color;
}

// What one primary ray sees, in the Frame's terms.
struct PixelValue {
    glm::vec3 color;
    float depth;
    glm::vec3 normal;
    std::int32_t id;
};

// The material that shades a hit: the surface's own (for a boolean, the
// operand that was hit, as in Hill's ch. 14).
const Material& materialOf(const Scene& scene, const WorldHit& hit) {
    return hit.surface ? hit.surface->material : scene.objects[size_t(hit.object)].material;
}

PixelValue tracePrimary(const Scene& scene, const SceneIntersector& intersector, const Ray& ray) {
    // Primary rays start at the eye, not on a surface, so t > 0 needs no epsilon.
    const std::optional<WorldHit> hit = intersector.closestHit(ray, 0.0);
    if (!hit)
        return {glm::vec3(scene.background), std::numeric_limits<float>::infinity(),
                glm::vec3(0), -1};
    const Material& material = materialOf(scene, *hit);
    const glm::dvec3 color = shade(scene, material, hit->point, hit->normal, -ray.direction);
    return {glm::vec3(color), float(hit->t), glm::vec3(hit->normal), hit->object};
}

// One band of the image: the block row starting at y0. With block > 1 every
// pixel of a block shows the ray through the block's centre, so that ray is
// traced once and its value copied (clipped at the image's right and bottom).
void renderBlockRow(const Scene& scene, const SceneIntersector& intersector,
                    const CameraBasis& camera, const RenderSettings& settings, int block, int y0,
                    Frame& frame) {
    const int y1 = std::min(y0 + block, frame.height);
    for (int x0 = 0; x0 < frame.width; x0 += block) {
        const Ray ray = primaryRay(camera, settings, primarySample(x0, y0, block));
        const PixelValue value = tracePrimary(scene, intersector, ray);
        const int x1 = std::min(x0 + block, frame.width);
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const size_t i = frame.index(x, y);
                frame.color[i] = value.color;
                frame.depth[i] = value.depth;
                frame.normal[i] = value.normal;
                frame.id[i] = value.id;
            }
        }
    }
}

}  // namespace

PixelTrace tracePixel(const Scene& scene, const CameraBasis& camera,
                      const RenderSettings& settings, int x, int y) {
    requireReferenceScene(scene);
    PixelTrace trace;
    trace.x = x;
    trace.y = y;
    const Ray ray = primaryRay(camera, settings, primarySample(x, y, std::max(settings.block, 1)));
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
    const std::optional<WorldHit> hit = closestHitBruteForce(scene, ray, 0.0);
    if (!hit) {
        trace.color = scene.background;
        return trace;
    }
    const Material& material = materialOf(scene, *hit);
    trace.hitObject = hit->object;
    trace.t = hit->t;
    trace.point = hit->point;
    trace.normal = hit->normal;
    trace.emissive = material.emissive;
    trace.ambient = material.ambient * scene.globalAmbient;
    trace.color = shade(scene, material, hit->point, hit->normal, -ray.direction, &trace.lights);
    return trace;
}

Frame render(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
             const ReferenceOptions& options) {
    requireReferenceScene(scene);
    if (settings.width <= 0 || settings.height <= 0)
        throw Error("render: the image size must be positive (got " +
                    std::to_string(settings.width) + " x " + std::to_string(settings.height) +
                    ")");
    const int block = std::max(settings.block, 1);
    Frame frame(settings.width, settings.height);

    // Block rows are handed out through an atomic counter. Each pixel's value
    // depends only on its own ray, so the image is the same for any thread
    // count and any order.
    const int blockRows = (settings.height + block - 1) / block;
    int threads = options.threads > 0 ? options.threads
                                      : int(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, blockRows);

    const SceneIntersector intersector(scene, options.bruteForce);  // one BVH for all rays
    const std::size_t raysPerRow = std::size_t((settings.width + block - 1) / block);
    const std::size_t totalRays = raysPerRow * std::size_t(blockRows);
    if (options.progress && !options.progress(0, totalRays)) throw Interrupted();
    std::atomic<std::size_t> raysDone{0};
    std::atomic<int> nextRow{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto worker = [&] {
        try {
            for (int row = nextRow++; row < blockRows; row = nextRow++) {
                renderBlockRow(scene, intersector, camera, settings, block, row * block, frame);
                const std::size_t done = raysDone += raysPerRow;
                if (options.progress && !options.progress(done, totalRays)) throw Interrupted();
            }
        } catch (...) {
            // Stop every worker and rethrow the first failure on the caller's thread.
            nextRow = blockRows;
            const std::lock_guard<std::mutex> lock(failureMutex);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) {
        try {
            pool.emplace_back(worker);
        } catch (const std::system_error&) {
            break;  // no more threads to be had: the ones we have finish the image
        }
    }
    worker();  // the calling thread works too
    for (std::thread& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
    return frame;
}

}  // namespace vkray::reference
