#include "scene/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <system_error>

#include "scene/mesh_file.h"
#include "util/error.h"

namespace vkray {

namespace {

namespace fs = std::filesystem;

// Triangulate splits polygons (concave ones too, unlike a fan);
// PreTransformVertices places every mesh by its nodes' transforms (glTF and
// Collada scenes are trees); SortByPType with the removal below drops points
// and lines; ValidateDataStructure refuses indices out of range and other
// broken data that some readers let through.
constexpr unsigned kImportSteps = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_SortByPType | aiProcess_PreTransformVertices |
                                  aiProcess_ValidateDataStructure;

void configure(Assimp::Importer& importer) {
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
}

constexpr const char* kNoTriangles =
    "the mesh file holds no triangles (only points or lines, or nothing)";

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    throw Error(path + ": error: " + why);
}

std::string assimpSays(const Assimp::Importer& importer) {
    std::string message = importer.GetErrorString();
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back())))
        message.pop_back();
    return message.empty() ? std::string("no reason given") : message;
}

glm::dvec3 toDouble(const aiVector3D& v) {
    return {double(v.x), double(v.y), double(v.z)};
}

TriangleMesh meshFromScene(const aiScene& scene, const std::string& path) {
    // The counts first, so that the limits hold before anything is allocated.
    std::size_t vertexCount = 0, triangleCount = 0;
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh& part = *scene.mMeshes[m];
        vertexCount += part.mNumVertices;
        for (unsigned f = 0; f < part.mNumFaces; ++f)
            triangleCount += part.mFaces[f].mNumIndices == 3 ? 1 : 0;
    }
    if (triangleCount == 0) refuse(path, kNoTriangles);
    if (vertexCount > kMaxMeshVertices)
        refuse(path, "the mesh has " + std::to_string(vertexCount) +
                         " vertices, above vkray's limit of " + std::to_string(kMaxMeshVertices));
    if (triangleCount > kMaxMeshFaces)
        refuse(path, "the mesh has " + std::to_string(triangleCount) +
                         " triangles, above vkray's limit of " + std::to_string(kMaxMeshFaces));

    TriangleMesh mesh;
    mesh.name = fs::path(path).filename().string();
    mesh.positions.reserve(vertexCount);
    mesh.triangles.reserve(triangleCount);
    constexpr std::uint32_t kNoNormal = ~std::uint32_t(0);
    std::vector<std::uint32_t> vertexNormal;  // per vertex of the current part
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh& part = *scene.mMeshes[m];
        const std::uint32_t base = std::uint32_t(mesh.positions.size());
        for (unsigned v = 0; v < part.mNumVertices; ++v) {
            const glm::dvec3 p = toDouble(part.mVertices[v]);
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                refuse(path, "vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                                 " is not finite");
            mesh.positions.push_back(p);
        }
        vertexNormal.assign(part.mNumVertices, kNoNormal);
        if (part.HasNormals()) {
            for (unsigned v = 0; v < part.mNumVertices; ++v) {
                glm::dvec3 unit;
                if (!normalizeSafely(toDouble(part.mNormals[v]), &unit)) continue;
                vertexNormal[v] = std::uint32_t(mesh.normals.size());
                mesh.normals.push_back(unit);
            }
        }
        for (unsigned f = 0; f < part.mNumFaces; ++f) {
            const aiFace& face = part.mFaces[f];
            if (face.mNumIndices != 3) continue;
            TriangleMesh::Triangle triangle;
            for (int k = 0; k < 3; ++k) {
                if (face.mIndices[k] >= part.mNumVertices)
                    refuse(path, "face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                                     " names vertex " + std::to_string(face.mIndices[k]) + " of " +
                                     std::to_string(part.mNumVertices));
                triangle.position[k] = base + face.mIndices[k];
            }
            std::uint32_t faceNormal = kNoNormal;
            for (int k = 0; k < 3; ++k) {
                triangle.normal[k] = vertexNormal[face.mIndices[k]];
                if (triangle.normal[k] != kNoNormal) continue;
                if (faceNormal == kNoNormal) {
                    const glm::dvec3& a = mesh.positions[triangle.position[0]];
                    glm::dvec3 unit{0, 0, 1};  // a degenerate triangle, which no ray hits
                    normalizeSafely(glm::cross(mesh.positions[triangle.position[1]] - a,
                                               mesh.positions[triangle.position[2]] - a),
                                    &unit);
                    faceNormal = std::uint32_t(mesh.normals.size());
                    mesh.normals.push_back(unit);
                }
                triangle.normal[k] = faceNormal;
            }
            mesh.triangles.push_back(triangle);
        }
    }
    mesh.closed = isClosedSurface(mesh.positions, mesh.triangles);
    finishMesh(mesh);
    return mesh;
}

TriangleMesh meshFromImport(const aiScene* scene, const Assimp::Importer& importer,
                            const std::string& path) {
    if (!scene) {
        const std::string message = assimpSays(importer);
        // What the removal of points and lines leaves as Assimp's error.
        if (message.find("No meshes remaining") != std::string::npos)
            refuse(path, std::string(kNoTriangles) + "; Assimp: " + message);
        refuse(path, "Assimp cannot read the mesh file: " + message);
    }
    if (scene->mNumMeshes == 0) refuse(path, kNoTriangles);
    return meshFromScene(*scene, path);
}

}  // namespace

bool is3vnPath(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".3vn";
}

TriangleMesh loadMeshFile(const std::string& path) {
    return is3vnPath(path) ? meshFrom3vn(load3vn(path)) : importMeshFile(path);
}

TriangleMesh importMeshFile(const std::string& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (error || !fs::exists(status))
        refuse(path, "cannot read mesh file: " +
                         (error ? error.message() : std::string("No such file or directory")));
    if (!fs::is_regular_file(status)) refuse(path, "cannot read mesh file: not a regular file");
    const std::uintmax_t size = fs::file_size(path, error);
    if (error) refuse(path, "cannot read mesh file: " + error.message());
    if (size > kMaxDataFileBytes)
        refuse(path, "the mesh file is " + std::to_string(size) +
                         " bytes, above vkray's limit of " + std::to_string(kMaxDataFileBytes));
    Assimp::Importer importer;
    configure(importer);
    return meshFromImport(importer.ReadFile(path, kImportSteps), importer, path);
}

TriangleMesh importMeshBytes(std::string_view bytes, const std::string& formatHint,
                             const std::string& path) {
    if (bytes.size() > kMaxDataFileBytes)
        refuse(path, "the mesh file is " + std::to_string(bytes.size()) +
                         " bytes, above vkray's limit of " + std::to_string(kMaxDataFileBytes));
    Assimp::Importer importer;
    configure(importer);
    return meshFromImport(
        importer.ReadFileFromMemory(bytes.data(), bytes.size(), kImportSteps, formatHint.c_str()),
        importer, path);
}

}  // namespace vkray
