// Dispatch from a scene object to its generic intersector, and the way back
// to world space.
#include "reference/object_intersect.h"

#include "reference/csg.h"
#include "reference/mesh_intersect.h"
#include "util/error.h"
#include "util/file_loc.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <string>

namespace vkray::reference {

// With M the object's worldFromObject, the generic ray is M^-1 S + (M^-1 c) t:
// the same t names the same point in both spaces because M is affine, so the
// generic direction must not be renormalised. Normals are covectors: they go
// back to the world by (M^-1)^T, which keeps them perpendicular to the
// surface under non-uniform scaling.
Ray toObjectSpace(const SceneObject& object, const Ray& worldRay) {
    const glm::dmat4& objectFromWorld = object.objectFromWorld;
    return {glm::dvec3(objectFromWorld * glm::dvec4(worldRay.origin, 1)),
            glm::dvec3(objectFromWorld * glm::dvec4(worldRay.direction, 0))};
}

glm::dvec3 toWorldNormal(const SceneObject& object, const glm::dvec3& genericNormal) {
    return glm::transpose(glm::dmat3(object.objectFromWorld)) * genericNormal;
}

WorldHit facingHit(const Ray& worldRay, double t, glm::dvec3 normal, glm::dvec3 geometricNormal,
                   int index, const SceneObject* surface) {
    const bool entering = glm::dot(normal, worldRay.direction) < 0;
    if (geometricNormal == glm::dvec3(0)) geometricNormal = normal;
    if (glm::dot(geometricNormal, worldRay.direction) > 0) geometricNormal = -geometricNormal;
    if (glm::dot(normal, geometricNormal) < 0) normal = -normal;
    WorldHit hit{t, worldRay.origin + t * worldRay.direction, glm::normalize(normal), index};
    hit.geometricNormal = glm::normalize(geometricNormal);
    hit.entering = entering;
    hit.surface = surface;
    return hit;
}

double taperOf(const SceneObject& object) {
    switch (object.type) {
    case ShapeType::Cylinder: return 1;
    case ShapeType::Cone: return 0;
    default: return object.taper;
    }
}

const TriangleMesh& meshOf(const Scene& scene, const SceneObject& object) {
    if (object.mesh < 0 || size_t(object.mesh) >= scene.meshes.size() ||
        !scene.meshes[size_t(object.mesh)])
        throw Error(formatDiagnostic(object.loc, nullptr, "error",
                                     std::string("'") + shapeKeyword(object.type) +
                                         "' has no geometry loaded (call loadSceneGeometry)"));
    return *scene.meshes[size_t(object.mesh)];
}

namespace {

// The generic shape of a primitive (not a boolean, not a mesh).
std::optional<GenericHit> intersectGeneric(const SceneObject& object, const Ray& ray, double tMin) {
    switch (object.type) {
    case ShapeType::Sphere: return intersectSphere(ray, tMin);
    case ShapeType::Plane: return intersectPlane(ray, tMin);
    case ShapeType::Square: return intersectSquare(ray, tMin);
    case ShapeType::Cube: return intersectCube(ray, tMin);
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: return intersectTaperedCylinder(ray, taperOf(object), tMin);
    case ShapeType::Torus: return intersectTorus(ray, tMin);
    default: break;
    }
    // Every ShapeType is handled by intersectObject; reaching here is a bug.
    throw Error(formatDiagnostic(
        object.loc, nullptr, "error",
        std::string("internal: no generic intersector for '") + shapeKeyword(object.type) + "'"));
}

}  // namespace

std::optional<WorldHit> intersectObject(const Scene& scene, const SceneObject& object, int index,
                                        const Ray& worldRay, double tMin) {
    if (isBoolean(object.type)) return intersectBoolean(scene, object, index, worldRay, tMin);
    const Ray ray = toObjectSpace(object, worldRay);
    std::optional<GenericHit> hit;
    if (isMeshShape(object.type)) {
        const TriangleMesh& mesh = meshOf(scene, object);
        if (const std::optional<MeshHit> meshHit = intersectMesh(mesh, ray, tMin))
            hit = meshSurface(mesh, *meshHit);
    } else {
        hit = intersectGeneric(object, ray, tMin);
    }
    if (!hit) return std::nullopt;
    const glm::dvec3 geometric = hit->geometricNormal == glm::dvec3(0)
                                     ? glm::dvec3(0)
                                     : toWorldNormal(object, hit->geometricNormal);
    return facingHit(worldRay, hit->t, toWorldNormal(object, hit->normal), geometric, index,
                     &object);
}

void requireReferenceScene(const Scene& scene) {
    for (const SceneObject& object : scene.objects) {
        if (isMeshShape(object.type)) meshOf(scene, object);
        if (isBoolean(object.type)) requireCsgOperands(scene, object);
    }
}

}  // namespace vkray::reference
