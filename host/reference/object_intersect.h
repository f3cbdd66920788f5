// One scene object against a world ray: the ray taken into the object's
// generic space, the generic shape (or mesh, or boolean) intersected there,
// and the hit brought back to the world.
#pragma once

#include "reference/shapes.h"
#include "scene/scene.h"
#include "scene/triangle_mesh.h"

#include <glm/vec3.hpp>

#include <optional>

namespace vkray::reference {

// A hit in world space: the generic normal taken back by the inverse
// transpose, normalised and turned to face the ray (for meshes, the
// interpolated normal is turned to the side the triangle itself faces).
struct WorldHit {
    double t;
    glm::dvec3 point;
    glm::dvec3 normal;
    int object;  // index in scene.objects (a boolean counts as one object)
    // The unit geometric normal (the triangle's own for meshes, else the
    // same as `normal`), facing the ray: secondary rays leave from beside it.
    glm::dvec3 geometricNormal{0};
    // Whether the ray meets the surface from outside: the intersector's
    // outward normal (a mesh's interpolated one; for a boolean, outward of
    // the result) points against the ray. Refraction enters or leaves by it.
    bool entering = true;
    // The primitive whose surface was hit: the object itself, or for a
    // boolean the operand the boundary lies on. Its material shades the hit
    // (Hill ch. 14 shades a boolean's hit with the hit primitive's material).
    const SceneObject* surface = nullptr;
};

// The world ray in the object's generic space (M^-1 applied, not renormalised).
Ray toObjectSpace(const SceneObject& object, const Ray& worldRay);

// A generic normal (a covector) in world space: (M^-1)^T n, not normalised.
glm::dvec3 toWorldNormal(const SceneObject& object, const glm::dvec3& genericNormal);

// The hit as the world sees it, from world-space normals: `normal` faced to
// the ray, or, when a geometric normal is given (meshes), faced to the same
// side as the geometric normal turned toward the ray.
WorldHit facingHit(const Ray& worldRay, double t, glm::dvec3 normal, glm::dvec3 geometricNormal,
                   int index, const SceneObject* surface);

// The taper s of Hill's generic tapered cylinder: 1 for `cylinder`, 0 for
// `cone`, the written s for `taperedCylinder`.
double taperOf(const SceneObject& object);

// The mesh a mesh-kind object (mesh, extrude, teapot, the polyhedra) draws.
// Throws Error "file:line:col: error: 'mesh' has no geometry loaded (call
// loadSceneGeometry)" when scene.meshes has none for it.
const TriangleMesh& meshOf(const Scene& scene, const SceneObject& object);

// The nearest hit with t > tMin of one object of the scene (any shape type,
// booleans included), reported as object `index`. The scene supplies the
// meshes. Throws Error (with the object's place) for a missing mesh or a
// boolean operand without an inside.
std::optional<WorldHit> intersectObject(const Scene& scene, const SceneObject& object, int index,
                                        const Ray& worldRay, double tMin);

// Everything intersectObject would refuse, checked once up front for the
// whole scene (every object, operands included); throws the same Errors.
void requireReferenceScene(const Scene& scene);

}  // namespace vkray::reference
