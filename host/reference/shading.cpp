// Whitted shading in double (see shading.h and docs/shading.md).
#include "reference/shading.h"

#include "reference/textures.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace vkray::reference {

double Medium::speed() const {
    return depth == 0 ? 1.0 : speeds[std::size_t(std::min(depth, kMediumStackSize) - 1)];
}

Medium Medium::entered(double speed) const {
    Medium inside = *this;
    if (inside.depth < kMediumStackSize) inside.speeds[std::size_t(inside.depth)] = speed;
    ++inside.depth;
    return inside;
}

Medium Medium::left() const {
    Medium outside = *this;
    if (outside.depth > 0) --outside.depth;
    return outside;
}

glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& direction) {
    const double scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1.0});
    const glm::dvec3 side = glm::dot(n, direction) < 0 ? -n : n;
    return p + side * (scale * kSecondaryRayOffset);
}

glm::dvec3 reflectDirection(const glm::dvec3& d, const glm::dvec3& m) {
    return glm::normalize(d - 2 * glm::dot(d, m) * m);
}

std::optional<glm::dvec3> refractDirection(const glm::dvec3& d, const glm::dvec3& m, double eta) {
    const double cos1 = -glm::dot(m, d);
    const double cos2Squared = 1 - eta * eta * (1 - cos1 * cos1);
    if (cos2Squared < 0) return std::nullopt;
    return glm::normalize(eta * d + (eta * cos1 - std::sqrt(cos2Squared)) * m);
}

const Material& materialOf(const Scene& scene, const WorldHit& hit) {
    return hit.surface ? hit.surface->material : scene.objects[size_t(hit.object)].material;
}

WhittedShader::WhittedShader(const Scene& scene, const SceneIntersector& intersector)
    : scene_(scene),
      intersector_(intersector),
      maxDepth_(std::clamp(scene.maxRecursionDepth, 0, kMaxRecursionDepth)) {}

glm::dvec3 WhittedShader::lightThrough(const glm::dvec3& origin,
                                       const glm::dvec3& lightPosition) const {
    const glm::dvec3 toLight = lightPosition - origin;
    const double distance = glm::length(toLight);
    if (!(distance > 0)) return glm::dvec3(1);
    const Ray feeler{origin, toLight / distance};
    double through = 1;
    intersector_.forEachCandidate(feeler, 0.0, distance, [&](int index) {
        const std::optional<WorldHit> hit =
            intersectObject(scene_, scene_.objects[std::size_t(index)], index, feeler, 0.0);
        if (hit && hit->t < distance) through *= materialOf(scene_, *hit).transparency;
        return through > 0;
    });
    return glm::dvec3(std::max(through, 0.0));
}

// Hill's local model at the hit, seen from direction v (unit, toward the
// viewer), with texture colour k:
//     emissive + k ambient globalAmbient
//       + sum over lights of a L (k diffuse max(0, m.s) + specular max(0, m.h)^f)
// s the unit vector toward the light, h = normalize(s + v), a what the
// light's feeler lets through (0 for a light behind the surface: the surface
// itself shadows it).
glm::dvec3 WhittedShader::localShade(const WorldHit& hit, const Material& material,
                                     const glm::dvec3& v, const glm::dvec3& k,
                                     PixelTrace* trace) const {
    const glm::dvec3& p = hit.point;
    const glm::dvec3& m = hit.normal;
    glm::dvec3 color = material.emissive + k * material.ambient * scene_.globalAmbient;
    // Lit lights are on m's side of the surface: the feelers leave from there.
    const glm::dvec3 feelerOrigin = offsetRayOrigin(p, hit.geometricNormal, m);
    for (const Light& light : scene_.lights) {
        PixelTrace::LightTerms term;
        const glm::dvec3 toLight = light.position - p;
        // A light on the surface has no direction; one straight behind, no halfway vector.
        if (glm::dot(toLight, toLight) > 0) {
            const glm::dvec3 s = glm::normalize(toLight);
            const glm::dvec3 halfway = s + v;
            term.mDotS = glm::dot(m, s);
            if (glm::dot(halfway, halfway) > 0) term.mDotH = glm::dot(m, glm::normalize(halfway));
            const glm::dvec3 a =
                term.mDotS > 0 ? lightThrough(feelerOrigin, light.position) : glm::dvec3(0);
            if (term.mDotS > 0) term.feelerMet = a != glm::dvec3(1);
            if (a != glm::dvec3(0)) {
                term.diffuse = a * light.color * k * material.diffuse * term.mDotS;
                if (term.mDotH > 0)
                    term.specular = a * light.color * material.specular *
                                    std::pow(term.mDotH, material.specularExponent);
            }
        }
        color += term.diffuse + term.specular;
        if (trace) trace->lights.push_back(term);
    }
    return color;
}

glm::dvec3 WhittedShader::radiance(const Ray& ray, int level, const Medium& medium,
                                   std::optional<WorldHit>* firstHit, PixelTrace* trace) const {
    // Primary rays start at the eye and secondary rays off the surface
    // (offsetRayOrigin), so t > 0 needs no epsilon.
    const std::optional<WorldHit> hit = intersector_.closestHit(ray, 0.0);
    if (firstHit) *firstHit = hit;
    if (!hit) return scene_.background;
    const Material& material = materialOf(scene_, *hit);
    const SceneObject& surface = hit->surface ? *hit->surface : scene_.objects[size_t(hit->object)];
    const glm::dvec3 k = textureColor(scene_, surface, hit->point, hit->normal);
    if (trace) {
        trace->emissive = material.emissive;
        trace->ambient = k * material.ambient * scene_.globalAmbient;
    }
    glm::dvec3 color = localShade(*hit, material, -ray.direction, k, trace);
    if (level >= maxDepth_) return color;

    const glm::dvec3& d = ray.direction;
    const glm::dvec3& m = hit->normal;
    if (material.reflectivity > scene_.minReflectivity) {
        const glm::dvec3 r = reflectDirection(d, m);
        const Ray reflected{offsetRayOrigin(hit->point, hit->geometricNormal, r), r};
        color += material.reflectivity * radiance(reflected, level + 1, medium);
    }
    if (material.transparency > scene_.minTransparency) {
        // Entering pushes the object's medium, leaving pops it; on total
        // internal reflection the ray stays where it was, mirrored.
        const Medium beyond = hit->entering ? medium.entered(material.speedOfLight) : medium.left();
        const std::optional<glm::dvec3> t = refractDirection(d, m, beyond.speed() / medium.speed());
        const glm::dvec3 direction = t ? *t : reflectDirection(d, m);
        const Ray transmitted{offsetRayOrigin(hit->point, hit->geometricNormal, direction),
                              direction};
        color += material.transparency * radiance(transmitted, level + 1, t ? beyond : medium);
    }
    return color;
}

}  // namespace vkray::reference
