// Fuzzes the 3VN mesh reader and what the scene does with a mesh it read
// (triangle fans, bounds). Any exception other than vkray::Error is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "scene/mesh_file.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const vkray::PolygonMesh mesh = vkray::parse3vn(text, "fuzz.3vn");
        const auto triangles = vkray::fanTriangles(mesh);
        // Every index the reader let through must be in range.
        for (const vkray::MeshTriangle& t : triangles)
            for (int k = 0; k < 3; ++k)
                if (std::size_t(t.vertex[k]) >= mesh.vertices.size() ||
                    std::size_t(t.normal[k]) >= mesh.normals.size())
                    __builtin_trap();
        vkray::boundsOf(mesh);
    } catch (const vkray::Error&) {
    }
    return 0;
}
