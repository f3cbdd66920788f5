// Mesh files in the formats Assimp reads (OBJ, PLY, glTF 2.0 as .gltf and
// .glb, STL, OFF, Collada, 3DS, FBX, ...), turned into the triangle meshes
// that `mesh FILE` places. 3VN files keep vkray's own reader (mesh_file.h).
//
// What is taken from a file: every triangle of every mesh in it (polygons
// triangulated, points and lines dropped), placed by the file's own node
// transforms; the file's vertex normals where it has them (interpolated:
// Hill's smooth shading), each triangle's own face normal where it has none
// or where one is zero. Materials, texture coordinates, cameras and lights
// are not taken: the object gets the scene's current material.
//
// Errors are Error "PATH: error: ..." with Assimp's own message; a caller
// that read the name from a scene adds its place in front (see mesh_file.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/triangle_mesh.h"

namespace vkray {

// True where `mesh FILE` reads the file with the 3VN reader: a name ending
// in ".3vn", in any case.
bool is3vnPath(const std::string& path);

// `mesh FILE`: meshFrom3vn(load3vn(path)) for a 3VN file, importMeshFile
// otherwise.
TriangleMesh loadMeshFile(const std::string& path, std::vector<std::string>* warnings = nullptr);

// The time Assimp may take on one file before it is refused.
inline constexpr double kMeshImportSeconds = 60;

// The file through Assimp. Refused, with the path: a missing or unreadable
// file, one that is not a regular file or is larger than kMaxDataFileBytes,
// what Assimp cannot read (its message), a file without triangles, more than
// kMaxMeshVertices vertices or kMaxMeshFaces triangles, or a position that is
// not finite. Files the file names (.mtl, .bin) are read beside it by Assimp.
// Assimp runs in a child process: a file it takes longer than
// kMeshImportSeconds on, or crashes on, is refused too. Its warnings (faces
// it dropped, data it ignored: at most 20) go to `warnings`, each
// "Assimp: ..." without the path.
TriangleMesh importMeshFile(const std::string& path, std::vector<std::string>* warnings = nullptr);

// The same from bytes in memory; `formatHint` is the extension without its
// dot ("obj", "ply", "glb"), and `path` names the mesh in messages. Used by
// the fuzzer and the tests; external files cannot be found from memory.
TriangleMesh importMeshBytes(std::string_view bytes, const std::string& formatHint,
                             const std::string& path);

}  // namespace vkray
