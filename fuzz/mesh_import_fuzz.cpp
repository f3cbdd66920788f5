// Fuzzes the mesh files read through Assimp (OBJ, PLY, STL, OFF, glTF) and
// what vkray makes of what Assimp returns (triangles, normals, closedness,
// BVH). The first byte picks the format; the rest is the file. Any exception
// other than vkray::Error is a bug, and so is an index out of range.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "scene/mesh_import.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const char* const kFormats[] = {"obj", "ply", "stl", "off", "glb", "gltf"};
    const std::string hint = kFormats[data[0] % (sizeof kFormats / sizeof kFormats[0])];
    const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
    try {
        const vkray::TriangleMesh mesh = vkray::importMeshBytes(bytes, hint, "fuzz." + hint);
        for (const vkray::TriangleMesh::Triangle& t : mesh.triangles)
            for (int k = 0; k < 3; ++k)
                if (t.position[k] >= mesh.positions.size() || t.normal[k] >= mesh.normals.size() ||
                    !std::isfinite(mesh.normals[t.normal[k]].x))
                    __builtin_trap();
    } catch (const vkray::Error&) {
    }
    return 0;
}
