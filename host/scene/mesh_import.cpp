#include "scene/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <algorithm>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/geometric.hpp>
#include <system_error>
#include <type_traits>

#include "scene/mesh_file.h"
#include "util/child_process.h"
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

// Assimp's warnings about the file (faces it dropped, data it ignored), as
// its logger writes them, collected for the caller to show.
class WarningsKept : public Assimp::LogStream {
public:
    explicit WarningsKept(std::vector<std::string>& kept) : kept_(kept) {}
    void write(const char* message) override {
        std::string text = message;
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
            text.pop_back();
        // "Warn,  T0: glTF2: ..." -> "glTF2: ..."
        if (const size_t colon = text.find(": "); text.rfind("Warn", 0) == 0 && colon != text.npos)
            text.erase(0, colon + 2);
        if (kept_.size() < kMaxWarnings) kept_.push_back(text);
    }
    static constexpr size_t kMaxWarnings = 20;

private:
    std::vector<std::string>& kept_;
};

// The mesh (before finishMesh) and the warnings, as bytes from the child
// that imported them to the process that shows them.
template <typename T>
void append(std::string& bytes, const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::uint64_t count = values.size();
    bytes.append(reinterpret_cast<const char*>(&count), sizeof count);
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

template <typename T>
std::vector<T> take(const std::string& bytes, size_t& at) {
    std::uint64_t count = 0;
    if (at + sizeof count > bytes.size()) throw Error("internal: a short mesh import answer");
    std::memcpy(&count, bytes.data() + at, sizeof count);
    at += sizeof count;
    if (count > (bytes.size() - at) / sizeof(T))
        throw Error("internal: a short mesh import answer");
    std::vector<T> values(count);
    std::memcpy(values.data(), bytes.data() + at, count * sizeof(T));
    at += count * sizeof(T);
    return values;
}

std::string meshBytes(const TriangleMesh& mesh, const std::vector<std::string>& warnings) {
    std::string bytes;
    // One allocation: a million triangles are about 50 MB, and each
    // regrowth would copy them and touch fresh pages again.
    size_t size = 5 * sizeof(std::uint64_t) + mesh.name.size() + 1 +
                  (mesh.positions.size() + mesh.normals.size()) * sizeof(glm::dvec3) +
                  mesh.triangles.size() * sizeof(TriangleMesh::Triangle);
    for (const std::string& warning : warnings) size += sizeof(std::uint64_t) + warning.size();
    bytes.reserve(size);
    append(bytes, std::vector<char>(mesh.name.begin(), mesh.name.end()));
    append(bytes, mesh.positions);
    append(bytes, mesh.normals);
    append(bytes, mesh.triangles);
    append(bytes, std::vector<char>{char(mesh.closed)});
    for (const std::string& warning : warnings)
        append(bytes, std::vector<char>(warning.begin(), warning.end()));
    return bytes;
}

TriangleMesh meshOfBytes(const std::string& bytes, std::vector<std::string>& warnings) {
    size_t at = 0;
    TriangleMesh mesh;
    const std::vector<char> name = take<char>(bytes, at);
    mesh.name.assign(name.begin(), name.end());
    mesh.positions = take<glm::dvec3>(bytes, at);
    mesh.normals = take<glm::dvec3>(bytes, at);
    mesh.triangles = take<TriangleMesh::Triangle>(bytes, at);
    const std::vector<char> closed = take<char>(bytes, at);
    mesh.closed = !closed.empty() && closed[0] != 0;
    while (at < bytes.size()) {
        const std::vector<char> warning = take<char>(bytes, at);
        warnings.emplace_back(warning.begin(), warning.end());
    }
    return mesh;
}

}  // namespace

bool is3vnPath(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".3vn";
}

TriangleMesh loadMeshFile(const std::string& path, std::vector<std::string>* warnings) {
    return is3vnPath(path) ? meshFrom3vn(load3vn(path)) : importMeshFile(path, warnings);
}

TriangleMesh importMeshFile(const std::string& path, std::vector<std::string>* warnings) {
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
    // In a child process under a time limit: Assimp may loop or crash on a
    // damaged file (fuzzing found a 5 s stall on a few hundred bytes); vkray
    // then refuses the file instead of hanging or dying with it.
    const std::string answer = runInChild(
        [&] {
            std::vector<std::string> kept;
            Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
            Assimp::DefaultLogger::get()->attachStream(new WarningsKept(kept),
                                                       Assimp::Logger::Warn);
            Assimp::Importer importer;
            configure(importer);
            const TriangleMesh mesh =
                meshFromImport(importer.ReadFile(path, kImportSteps), importer, path);
            return meshBytes(mesh, kept);
        },
        kMeshImportSeconds, path + ": error: Assimp reading the mesh file");
    std::vector<std::string> kept;
    TriangleMesh mesh = meshOfBytes(answer, kept);
    if (warnings)
        for (const std::string& warning : kept) warnings->push_back("Assimp: " + warning);
    finishMesh(mesh);
    return mesh;
}

TriangleMesh importMeshBytes(std::string_view bytes, const std::string& formatHint,
                             const std::string& path) {
    if (bytes.size() > kMaxDataFileBytes)
        refuse(path, "the mesh file is " + std::to_string(bytes.size()) +
                         " bytes, above vkray's limit of " + std::to_string(kMaxDataFileBytes));
    Assimp::Importer importer;
    configure(importer);
    TriangleMesh mesh = meshFromImport(
        importer.ReadFileFromMemory(bytes.data(), bytes.size(), kImportSteps, formatHint.c_str()),
        importer, path);
    finishMesh(mesh);
    return mesh;
}

}  // namespace vkray
