#include "scene/scene.h"

namespace vkray {

const char* shapeKeyword(ShapeType type) {
    static const char* const names[kShapeTypeCount] = {
        "sphere",     "plane",           "square",      "cube",         "cylinder",
        "cone",       "taperedCylinder", "torus",       "teapot",       "tetrahedron",
        "octahedron", "dodecahedron",    "icosahedron", "buckyball",    "diamond",
        "mesh",       "extrude",         "union",       "intersection", "difference",
    };
    return names[static_cast<int>(type)];
}

bool isBoolean(ShapeType type) {
    return type == ShapeType::Union || type == ShapeType::Intersection ||
           type == ShapeType::Difference;
}

}  // namespace vkray
