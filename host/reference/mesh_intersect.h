// Rays against triangle meshes in generic space: the watertight test of
// Woop, Benthin and Wald (JCGT 2013) in double, the mesh's BVH walked for
// the nearest hit, brute force kept as its oracle, and every crossing along
// the line for the spans of closed meshes (CSG).
#pragma once

#include "reference/shapes.h"
#include "scene/triangle_mesh.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace vkray::reference {

// The ray, prepared once for any number of triangles: the axis it runs most
// along becomes z, and a shear maps its direction onto that axis, so every
// triangle test is 2D, about the origin.
struct WatertightRay {
    explicit WatertightRay(const Ray& ray);

    glm::dvec3 origin;
    int kx = 0, ky = 1, kz = 2;  // a permutation of the axes, orientation kept
    double shearX = 0, shearY = 0, shearZ = 0;
    bool valid = false;  // false for a zero (or NaN) direction
};

// The crossing of a ray and triangle (p0, p1, p2): t, and the barycentric
// weights of the three corners (sum 1). `entering` is true when the ray meets
// the side that (p1 - p0) x (p2 - p0) points to against that normal: the
// outside of a counter-clockwise-wound surface.
struct TriangleHit {
    double t;
    double b0, b1, b2;
    bool entering;
};

// Watertight: a ray through an edge or vertex shared by triangles meets
// exactly one of them (on the same side of an edge, the edge functions of
// the two triangles are exact negatives; signs rounded to 0 are recomputed
// exactly, and an exact 0 is broken by a fixed perturbation of the ray, the
// "simulation of simplicity"). A ray in the triangle's plane misses it. Hits
// with tMin < t < tMax only.
std::optional<TriangleHit> intersectTriangle(const WatertightRay& ray, const glm::dvec3& p0,
                                             const glm::dvec3& p1, const glm::dvec3& p2,
                                             double tMin, double tMax);

struct MeshHit {
    double t;
    std::uint32_t triangle;  // index into mesh.triangles
    TriangleHit crossing;
};

// The nearest hit with t > tMin through the mesh's BVH, and the same by
// testing every triangle. Ties in t go to the lower triangle index in both.
std::optional<MeshHit> intersectMesh(const TriangleMesh& mesh, const Ray& ray, double tMin);
std::optional<MeshHit> intersectMeshBruteForce(const TriangleMesh& mesh, const Ray& ray,
                                               double tMin);

// Every crossing along the whole line (any t), sorted by t (then triangle).
std::vector<MeshHit> meshCrossings(const TriangleMesh& mesh, const Ray& ray);

// The hit as a surface point: the corners' normals interpolated with the
// barycentric weights (the geometric normal where they cancel), and the
// triangle's geometric normal (p1 - p0) x (p2 - p0).
GenericHit meshSurface(const TriangleMesh& mesh, const MeshHit& hit);

// Where the ray is inside a closed mesh, by the even-odd rule: crossings
// alternate in and out along a line, whichever way the faces are wound.
std::vector<GenericSpan> meshSpans(const TriangleMesh& mesh, const Ray& ray);

}  // namespace vkray::reference
