// Triangle meshes from 3VN polygons, the closedness test, and the dispatch to
// the built-in solids (polyhedra.cpp, teapot.cpp). Outlines: extrude.cpp.
#include "scene/triangle_mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/geometric.hpp>
#include <tuple>

#include "util/stopwatch.h"

namespace vkray {

bool normalizeSafely(const glm::dvec3& v, glm::dvec3* unit) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(largest > 0) || !std::isfinite(largest)) return false;
    const glm::dvec3 scaled = v / largest;
    *unit = scaled / glm::length(scaled);
    return true;
}

namespace {

// Newell's method: the polygon's area-weighted normal, right-handed with the
// corners' order; robust for non-planar and non-convex polygons.
glm::dvec3 polygonNormal(const PolygonMesh& polygons, const PolygonMesh::Face& face) {
    const std::span<const int> corners = polygons.vertexIndicesOf(face);
    const glm::dvec3 origin = polygons.vertices[std::size_t(corners[0])];
    glm::dvec3 sum{0};
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        sum += glm::cross(polygons.vertices[std::size_t(corners[i])] - origin,
                          polygons.vertices[std::size_t(corners[i + 1])] - origin);
    }
    glm::dvec3 unit;
    return normalizeSafely(sum, &unit) ? unit : glm::dvec3(0, 0, 1);  // degenerate face
}

// A key equal for equal coordinates: +0 and -0 are one position.
std::array<std::uint64_t, 3> positionKey(const glm::dvec3& p) {
    std::array<std::uint64_t, 3> key;
    for (int axis = 0; axis < 3; ++axis)
        key[std::size_t(axis)] = std::bit_cast<std::uint64_t>(p[axis] + 0.0);
    return key;
}

}  // namespace

void finishMesh(TriangleMesh& mesh) {
    const Stopwatch clock;
    std::vector<Aabb> boxes;
    boxes.reserve(mesh.triangles.size());
    mesh.bounds = Aabb{};
    for (const TriangleMesh::Triangle& triangle : mesh.triangles) {
        Aabb box;
        for (const std::uint32_t corner : triangle.position) box.grow(mesh.positions[corner]);
        mesh.bounds.grow(box);
        boxes.push_back(box);
    }
    mesh.bvh = buildBvh(boxes);
    mesh.bvhSeconds = clock.seconds();
}

bool isClosedSurface(std::span<const glm::dvec3> positions,
                     std::span<const TriangleMesh::Triangle> triangles) {
    if (triangles.empty()) return false;
    // Weld: one id per distinct position (files repeat vertices per face).
    std::vector<std::uint32_t> byValue(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) byValue[i] = std::uint32_t(i);
    std::sort(byValue.begin(), byValue.end(), [&](std::uint32_t a, std::uint32_t b) {
        return positionKey(positions[a]) < positionKey(positions[b]);
    });
    std::vector<std::uint32_t> weldedId(positions.size());
    for (std::size_t i = 0; i < byValue.size(); ++i) {
        const bool same =
            i > 0 && positionKey(positions[byValue[i]]) == positionKey(positions[byValue[i - 1]]);
        weldedId[byValue[i]] = same ? weldedId[byValue[i - 1]] : byValue[i];
    }
    // Every directed edge as (low id, high id, direction); a closed surface
    // has each undirected edge exactly once in each direction.
    std::vector<std::tuple<std::uint32_t, std::uint32_t, bool>> edges;
    edges.reserve(3 * triangles.size());
    for (const TriangleMesh::Triangle& triangle : triangles) {
        const std::uint32_t ids[3] = {weldedId[triangle.position[0]],
                                      weldedId[triangle.position[1]],
                                      weldedId[triangle.position[2]]};
        if (ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0]) continue;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = ids[k], to = ids[(k + 1) % 3];
            edges.emplace_back(std::min(from, to), std::max(from, to), from < to);
        }
    }
    if (edges.empty()) return false;
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size(); i += 2) {
        // Sorted: each edge must appear as exactly (backward, forward).
        if (i + 1 >= edges.size()) return false;
        const auto& [lowA, highA, forwardA] = edges[i];
        const auto& [lowB, highB, forwardB] = edges[i + 1];
        if (lowA != lowB || highA != highB || forwardA || !forwardB) return false;
        if (i + 2 < edges.size() && std::get<0>(edges[i + 2]) == lowA &&
            std::get<1>(edges[i + 2]) == highA)
            return false;
    }
    return true;
}

TriangleMesh meshFrom3vn(const PolygonMesh& polygons) {
    TriangleMesh mesh;
    mesh.name = std::filesystem::path(polygons.path).filename().string();
    mesh.positions = polygons.vertices;

    // The file's normals, normalised; a zero one is marked -1 and replaced,
    // corner by corner, by its face's geometric normal (appended once per face).
    constexpr std::int64_t kNoNormal = -1;
    std::vector<std::int64_t> normalIndex(polygons.normals.size(), kNoNormal);
    for (std::size_t i = 0; i < polygons.normals.size(); ++i) {
        glm::dvec3 unit;
        if (normalizeSafely(polygons.normals[i], &unit)) {
            normalIndex[i] = std::int64_t(mesh.normals.size());
            mesh.normals.push_back(unit);
        }
    }
    std::vector<std::int64_t> faceNormalIndex(polygons.faces.size(), kNoNormal);
    const auto cornerNormal = [&](int fileNormal, int face) -> std::uint32_t {
        if (normalIndex[std::size_t(fileNormal)] != kNoNormal)
            return std::uint32_t(normalIndex[std::size_t(fileNormal)]);
        std::int64_t& index = faceNormalIndex[std::size_t(face)];
        if (index == kNoNormal) {
            index = std::int64_t(mesh.normals.size());
            mesh.normals.push_back(polygonNormal(polygons, polygons.faces[std::size_t(face)]));
        }
        return std::uint32_t(index);
    };

    const std::vector<MeshTriangle> fans = fanTriangles(polygons);
    mesh.triangles.reserve(fans.size());
    for (const MeshTriangle& fan : fans) {
        TriangleMesh::Triangle triangle;
        for (int k = 0; k < 3; ++k) {
            triangle.position[k] = std::uint32_t(fan.vertex[k]);
            triangle.normal[k] = cornerNormal(fan.normal[k], fan.face);
        }
        mesh.triangles.push_back(triangle);
    }
    mesh.closed = isClosedSurface(mesh.positions, mesh.triangles);
    finishMesh(mesh);
    return mesh;
}

bool isBuiltInMesh(ShapeType type) {
    switch (type) {
    case ShapeType::Teapot:
    case ShapeType::Tetrahedron:
    case ShapeType::Octahedron:
    case ShapeType::Dodecahedron:
    case ShapeType::Icosahedron:
    case ShapeType::Buckyball:
    case ShapeType::Diamond: return true;
    default: return false;
    }
}

}  // namespace vkray
