// Triangle meshes in an object's generic space: what `mesh file.3vn`,
// `extrude file.dat`, the built-in polyhedra and the teapot become. Each has
// its own BVH over its triangles.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scene/bvh.h"
#include "scene/mesh_file.h"
#include "scene/scene.h"

namespace vkray {

struct TriangleMesh {
    struct Triangle {
        std::uint32_t position[3];  // into positions
        std::uint32_t normal[3];    // into normals: interpolated across the triangle
    };
    std::string name;                   // "pawn.3vn", "built-in dodecahedron", ...
    std::vector<glm::dvec3> positions;  // object (generic) space
    std::vector<glm::dvec3> normals;    // unit length
    std::vector<Triangle> triangles;
    bool closed = false;    // a closed, consistently oriented surface: has an inside (CSG)
    Bvh bvh;                // over triangles (order indexes triangles)
    Aabb bounds;            // of the positions triangles use
    double bvhSeconds = 0;  // wall clock of finishMesh's BVH build
};

// Fills bvh, bounds and bvhSeconds from the triangles.
void finishMesh(TriangleMesh& mesh);

// 3VN polygons split into fans, the file's normals (normalised) interpolated.
// A corner whose file normal is zero gets its face's geometric normal
// (Newell's method over the polygon, so it follows the corners' order).
// closed: every edge is shared by exactly two triangles that run it in
// opposite directions (corners at equal positions count as one vertex).
TriangleMesh meshFrom3vn(const PolygonMesh& polygons);

// The outline in the z = 0 plane swept to z = 1, with both caps: a closed prism.
// Each side is two triangles with its own outward normal (sharp edges); the
// caps are ear-clipped (non-convex outlines work) with normals -z and +z.
// Either winding is fine. An outline that crosses or touches itself but has
// an even number of points is read as Hill's quad strip (ch. 6: p0 p1 | p2 p3
// | ... each pair a rung, as in hlArch.dat's arch): the prism is built on the
// strip's boundary p0 p2 p4 ... p(n-2) p(n-1) ... p3 p1. Anything else that
// crosses itself is an Error naming the outline's path, and so is an outline
// whose checks would take more than about a second (refused as too complex:
// e.g. a 100 000-point star, whose edges all overlap in x; a 1 000 000-point
// circle or a 200 000-point spiral extrude fine).
TriangleMesh extrudeOutline(const Outline& outline);

// Tetrahedron, Octahedron, Dodecahedron, Icosahedron, Buckyball, Diamond and
// Teapot, made by the project (docs/sdl.md gives each one's size and orientation;
// polyhedra.cpp and teapot.cpp say how each is built).
TriangleMesh builtInMesh(ShapeType type);
bool isBuiltInMesh(ShapeType type);
// Drawn as triangles: a built-in mesh, `mesh` or `extrude`.
inline bool isMeshShape(ShapeType type) {
    return type == ShapeType::Mesh || type == ShapeType::Extrude || isBuiltInMesh(type);
}

// ---- building blocks (used by builtInMesh; public for tests) -----------------

// v / |v|, or false when v is zero or not finite. Scaling by the largest
// component first keeps |v|^2 from overflowing or underflowing.
bool normalizeSafely(const glm::dvec3& v, glm::dvec3* unit);

// The convex hull of `vertices` as a closed mesh with one flat outward normal
// per face; coplanar vertices form one polygon face, fanned into triangles.
// Meant for the small point sets of the built-in solids (O(n^4)).
TriangleMesh convexPolyhedron(std::span<const glm::dvec3> vertices, const std::string& name);

// The Utah teapot at `segments` x `segments` quads per Bezier patch (see teapot.cpp).
inline constexpr int kTeapotSegments = 16;
TriangleMesh utahTeapot(int segments = kTeapotSegments);

// True when every edge is shared by exactly two triangles running it in
// opposite directions; positions are compared by value, degenerate triangles
// (two corners at one position) are ignored.
bool isClosedSurface(std::span<const glm::dvec3> positions,
                     std::span<const TriangleMesh::Triangle> triangles);

}  // namespace vkray
