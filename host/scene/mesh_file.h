// Readers for the two data files an SDL scene can name: Hill's 3VN polygon
// meshes (`mesh file.3vn`) and the 2D outlines that vkray's `extrude`
// extension sweeps into prisms (`extrude file.dat`). Both are plain
// whitespace-separated numbers; every error is an Error
// "PATH:line:col: error: ..." at the offending token (or at the end of the
// file when data is missing).
//
// A caller that read the file name from a scene adds its own place
// in front, e.g. formatDiagnostic(meshWord.loc, expansion, "error",
// "cannot load mesh 'x.3vn'") + "\n" + e.what(), so the user sees both the
// `mesh` word and the mesh file's own line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkray {

// Limits, checked before anything is allocated. They keep a corrupt or hostile
// header from asking for gigabytes; real meshes are far below them.
inline constexpr std::size_t kMaxMeshVertices = 20'000'000;
inline constexpr std::size_t kMaxMeshNormals = 20'000'000;
inline constexpr std::size_t kMaxMeshFaces = 20'000'000;
inline constexpr std::size_t kMaxMeshCorners = 60'000'000;  // sum of all faces' vertex counts
inline constexpr std::size_t kMaxOutlinePoints = 1'000'000;
// Larger files are refused before reading: far beyond any mesh within the
// count limits, and it keeps a mistaken path (a disk image) from filling memory.
inline constexpr std::uint64_t kMaxDataFileBytes = std::uint64_t(2) << 30;

// A 3VN mesh as written: polygons (convex in Hill's files) whose corners each
// name a vertex and a normal. The corner indices of all faces are stored end
// to end (one allocation, not one per face); Face says where its run is.
struct PolygonMesh {
    struct Face {
        std::size_t firstCorner = 0;  // into vertexIndices / normalIndices
        int cornerCount = 0;          // >= 3
        int line = 0;                 // the line of the face's count in the file, for messages
    };

    std::vector<glm::dvec3> vertices;
    std::vector<glm::dvec3> normals;  // as in the file (not renormalised)
    std::vector<int> vertexIndices;   // per corner, 0-based, < vertices.size()
    std::vector<int> normalIndices;   // per corner, 0-based, < normals.size()
    std::vector<Face> faces;
    std::string path;

    std::span<const int> vertexIndicesOf(const Face& face) const {
        return {vertexIndices.data() + face.firstCorner, std::size_t(face.cornerCount)};
    }
    std::span<const int> normalIndicesOf(const Face& face) const {
        return {normalIndices.data() + face.firstCorner, std::size_t(face.cornerCount)};
    }
};

// One triangle of a split polygon: corner k has vertex vertex[k] and normal
// normal[k] (indices into the mesh's arrays, so normals can be interpolated
// across it), and `face` is the polygon it came from.
struct MeshTriangle {
    int vertex[3];
    int normal[3];
    int face;
};

// Splits every face into a fan around its first corner (n - 2 triangles per
// n-gon), in face order. Right for the convex polygons of 3VN files.
std::vector<MeshTriangle> fanTriangles(const PolygonMesh& mesh);
std::size_t triangleCount(const PolygonMesh& mesh);

// Axis-aligned bounds of the vertices that faces use (unused vertices do not
// count). Empty mesh: lo > hi (lo = +inf, hi = -inf).
struct MeshBounds {
    glm::dvec3 lo, hi;
};
MeshBounds boundsOf(const PolygonMesh& mesh);

// Hill's 3VN: "nVerts nNormals nFaces", then nVerts (x y z), nNormals (x y z),
// then per face: n, n vertex indices, n normal indices (0-based). Any
// whitespace (CRLF too) separates numbers. Refused, with the place: malformed,
// NaN, infinite or overflowing numbers; negative or excessive counts; a header
// whose counts cannot fit in the file's size; missing data; faces with fewer
// than 3 corners; indices out of range; anything after the last face.
// `path` is used in messages and stored in the mesh.
PolygonMesh parse3vn(std::string_view text, const std::string& path);
PolygonMesh load3vn(const std::string& path);  // a missing file is an Error naming it

// A closed 2D outline for `extrude`: "n", then n (x y) pairs (hlArch.dat).
struct Outline {
    std::vector<glm::dvec2> points;  // at least 3
    std::string path;
};

Outline parseOutline(std::string_view text, const std::string& path);
Outline loadOutline(const std::string& path);

}  // namespace vkray
