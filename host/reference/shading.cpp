// Whitted shading in double (see shading.h and docs/shading.md).
#include "reference/shading.h"

#include "reference/textures.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

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
    // Summed as the shader does (shade.glsl refracted): at eta = 1 exactly cos1^2.
    const double cos2Squared = (1 - eta * eta) + eta * eta * (cos1 * cos1);
    if (cos2Squared < 0) return std::nullopt;
    return glm::normalize(eta * d + (eta * cos1 - std::sqrt(cos2Squared)) * m);
}

const Material& materialOf(const Scene& scene, const WorldHit& hit) {
    return hit.surface ? hit.surface->material : scene.objects[size_t(hit.object)].material;
}

namespace {

double largestOf(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// M's largest scale, bounded above: the Frobenius norm of its linear part.
double scaleOf(const glm::dmat4& m) {
    double sum = 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) sum += m[c][r] * m[c][r];
    return std::sqrt(sum);
}

}  // namespace

double reachOf(const Scene& scene, const SceneObject& object, const glm::dvec3& origin) {
    if (!object.operands.empty()) {
        double reach = 0;
        for (const SceneObject& operand : object.operands)
            reach = std::max(reach, reachOf(scene, operand, origin));
        return reach;
    }
    const glm::dvec3 generic(object.objectFromWorld * glm::dvec4(origin, 1));
    return std::max(largestOf(generic), 1.0) * scaleOf(object.worldFromObject);
}

WhittedShader::WhittedShader(const Scene& scene, const SceneIntersector& intersector,
                             const RayPerturbation* perturbation)
    : scene_(scene),
      intersector_(intersector),
      perturbation_(perturbation),
      maxDepth_(std::clamp(scene.maxRecursionDepth, 0, kMaxRecursionDepth)) {}

double WhittedShader::reachAlong(const Ray& ray) const {
    double reach = largestOf(ray.origin - perturbation_->eye);
    const glm::dvec3 inverse = 1.0 / glm::normalize(ray.direction);
    for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
        const double own = reachOf(scene_, scene_.objects[i], ray.origin);
        if (own <= reach) continue;
        const Aabb& box = (*perturbation_->boxes)[i];
        if (box.empty()) continue;
        // Padded by twice the bound at this object's reach.
        Aabb padded = box;
        if (box.finite()) {
            const double pad =
                2 * (perturbation_->bound.position * own + perturbation_->bound.absolute);
            padded.lo -= glm::dvec3(pad);
            padded.hi += glm::dvec3(pad);
        }
        if (!box.finite() ||
            intersectAabb(padded, ray.origin, inverse, 0.0, std::numeric_limits<double>::max()))
            reach = own;
    }
    return reach;
}

double WhittedShader::boundOf(const Ray& ray, int level) const {
    const double bound =
        perturbation_->bound.position * reachAlong(ray) + perturbation_->bound.absolute;
    if (level == 0) return bound;
    return std::max(
        bound, perturbation_->bound.secondaryPosition * largestOf(ray.origin - perturbation_->eye));
}

Ray WhittedShader::moved(const Ray& ray, double bound, int level, const glm::dvec3* surface) const {
    if (!perturbation_->sideways) return ray;
    const glm::dvec3 d = glm::normalize(ray.direction);
    const glm::dvec3 across = std::abs(d.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(d, across));
    const glm::dvec3 e2 = glm::cross(d, e1);
    const glm::dvec3 side =
        std::cos(perturbation_->angle) * e1 + std::sin(perturbation_->angle) * e2;
    const double tilt =
        level == 0 ? perturbation_->bound.primaryTilt : perturbation_->bound.secondaryTilt;
    glm::dvec3 step = side;
    if (surface && glm::dot(*surface, *surface) > 0) {
        const glm::dvec3 n = glm::normalize(*surface);
        const glm::dvec3 along = side - glm::dot(side, n) * n;
        const double length = glm::length(along);
        step = length > 1e-6 ? along / length : glm::dvec3(0);
    }
    return {ray.origin + bound * step, glm::normalize(d + tilt * side)};
}

std::optional<WorldHit> WhittedShader::perturbedHit(const Ray& ray, double bound) const {
    std::optional<WorldHit> best = intersector_.closestHit(ray, 0.0);
    if (!best || !perturbation_->runnerUp) return best;
    const double limit = best->t + bound;
    std::optional<WorldHit> chosen = best;
    intersector_.forEachCandidate(ray, 0.0, limit, [&](int index) {
        if (index <= chosen->object) return true;
        const std::optional<WorldHit> hit =
            intersectObject(scene_, scene_.objects[std::size_t(index)], index, ray, 0.0);
        if (hit && hit->t <= limit) chosen = hit;
        return true;
    });
    return chosen;
}

glm::dvec3 WhittedShader::leave(const WorldHit& hit, const glm::dvec3& from,
                                const glm::dvec3& direction, const glm::dvec3& side) const {
    const glm::dvec3 origin = offsetRayOrigin(hit.point, hit.geometricNormal, side);
    if (!perturbation_) return origin;
    // The GPU's step (shaders/precision.glsl, offsetOrigin): the bound of the
    // point's or the ray's origin's distance from the eye, or the object's
    // scale, taken along the new ray (up to 8 steps), the rest along the normal.
    const SceneObject& surface = hit.surface ? *hit.surface : scene_.objects[size_t(hit.object)];
    const double step =
        perturbation_->bound.position *
            std::max({largestOf(hit.point - perturbation_->eye),
                      largestOf(from - perturbation_->eye), scaleOf(surface.worldFromObject)}) +
        perturbation_->bound.absolute;
    if (step <= glm::length(origin - hit.point)) return origin;
    const glm::dvec3 n =
        glm::dot(hit.geometricNormal, side) < 0 ? -hit.geometricNormal : hit.geometricNormal;
    const glm::dvec3 a = glm::normalize(direction);
    const double c = glm::dot(n, a);
    const double forward = c > 0 ? std::min(step / c, 8 * step) : 0.0;
    const double landed = std::max(forward + perturbation_->stepAhead * step, 0.0);
    return hit.point + landed * a + std::max(step - forward * c, 0.0) * n;
}

glm::dvec3 WhittedShader::lightThrough(const glm::dvec3& origin, const glm::dvec3& lightPosition,
                                       const glm::dvec3* surface) const {
    const glm::dvec3 toLight = lightPosition - origin;
    double distance = glm::length(toLight);
    if (!(distance > 0)) return glm::dvec3(1);
    Ray feeler{origin, toLight / distance};
    if (perturbation_) {
        const double bound = boundOf(feeler, 1);
        feeler = moved(feeler, bound, 1, surface);
        distance += perturbation_->feelerSide * bound;
    }
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
glm::dvec3 WhittedShader::localShade(const WorldHit& hit, const glm::dvec3& from,
                                     const Material& material, const glm::dvec3& v,
                                     const glm::dvec3& k, PixelTrace* trace) const {
    const glm::dvec3& p = hit.point;
    const glm::dvec3& m = hit.normal;
    glm::dvec3 color = material.emissive + k * material.ambient * scene_.globalAmbient;
    // Lit lights are on m's side of the surface: the feelers leave from there.
    const glm::dvec3 feelerOrigin = leave(hit, from, m);
    for (const Light& light : scene_.lights) {
        PixelTrace::LightTerms term;
        const glm::dvec3 toLight = light.position - p;
        // A light on the surface has no direction; one straight behind, no halfway vector.
        if (glm::dot(toLight, toLight) > 0) {
            const glm::dvec3 s = glm::normalize(toLight);
            const glm::dvec3 halfway = s + v;
            term.mDotS = glm::dot(m, s);
            if (glm::dot(halfway, halfway) > 0) term.mDotH = glm::dot(m, glm::normalize(halfway));
            // Played, each feeler leaves as the GPU's does (feelerToward):
            // its offset's step taken along the feeler itself, which near an
            // edge can carry it out through the next face.
            const glm::dvec3 a =
                term.mDotS > 0 ? lightThrough(perturbation_ ? leave(hit, from, s, m) : feelerOrigin,
                                              light.position, &hit.geometricNormal)
                               : glm::dvec3(0);
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

glm::dvec3 WhittedShader::radiance(const Ray& given, int level, const Medium& medium,
                                   std::optional<WorldHit>* firstHit, PixelTrace* trace) const {
    return radianceLeaving(given, level, medium, nullptr, firstHit, trace);
}

glm::dvec3 WhittedShader::radianceLeaving(const Ray& given, int level, const Medium& medium,
                                          const glm::dvec3* leftNormal,
                                          std::optional<WorldHit>* firstHit,
                                          PixelTrace* trace) const {
    // Primary rays start at the eye and secondary rays off the surface
    // (offsetRayOrigin), so t > 0 needs no epsilon.
    Ray ray = given;
    std::optional<WorldHit> hit;
    if (perturbation_) {
        const double bound = boundOf(given, level);
        ray = moved(given, bound, level, leftNormal);
        hit = perturbedHit(ray, bound);
    } else {
        hit = intersector_.closestHit(ray, 0.0);
    }
    if (firstHit) *firstHit = hit;
    if (!hit) return scene_.background;
    const Material& material = materialOf(scene_, *hit);
    const SceneObject& surface = hit->surface ? *hit->surface : scene_.objects[size_t(hit->object)];
    glm::dvec3 texturePoint = hit->point;
    if (perturbation_ && perturbation_->sideways) {
        const double reach =
            std::max(largestOf(hit->point - perturbation_->eye),
                     reachOf(scene_, scene_.objects[size_t(hit->object)], hit->point));
        // To the side and along the ray (a float point is rounded in every
        // coordinate; seen at grazing incidence, along the ray is across the
        // cells).
        const Ray aside =
            moved({hit->point, ray.direction},
                  perturbation_->bound.texture * reach + perturbation_->bound.absolute, -1);
        texturePoint = aside.origin + double(perturbation_->feelerSide) *
                                          glm::length(aside.origin - hit->point) *
                                          glm::normalize(ray.direction);
    }
    const glm::dvec3 k = textureColor(scene_, surface, texturePoint, hit->normal);
    if (trace) {
        trace->emissive = material.emissive;
        trace->ambient = k * material.ambient * scene_.globalAmbient;
    }
    glm::dvec3 color = localShade(*hit, ray.origin, material, -ray.direction, k, trace);
    if (level >= maxDepth_) return color;

    const glm::dvec3& d = ray.direction;
    const glm::dvec3& m = hit->normal;
    if (material.reflectivity > scene_.minReflectivity) {
        const glm::dvec3 r = reflectDirection(d, m);
        const Ray reflected{leave(*hit, ray.origin, r), r};
        color += material.reflectivity * radianceLeaving(reflected, level + 1, medium,
                                                         &hit->geometricNormal, nullptr, nullptr);
    }
    if (material.transparency > scene_.minTransparency) {
        // Entering pushes the object's medium, leaving pops it; on total
        // internal reflection the ray stays where it was, mirrored.
        const Medium beyond = hit->entering ? medium.entered(material.speedOfLight) : medium.left();
        const std::optional<glm::dvec3> t = refractDirection(d, m, beyond.speed() / medium.speed());
        const glm::dvec3 direction = t ? *t : reflectDirection(d, m);
        const Ray transmitted{leave(*hit, ray.origin, direction), direction};
        color +=
            material.transparency * radianceLeaving(transmitted, level + 1, t ? beyond : medium,
                                                    &hit->geometricNormal, nullptr, nullptr);
    }
    return color;
}

}  // namespace vkray::reference
