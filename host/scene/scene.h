// The scene model: everything an SDL file says, in double precision, with the
// place each object and light was written. Renderers (GPU and CPU reference)
// read it; nothing in it depends on how it is rendered.
#pragma once

#include "util/file_loc.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vkray {

struct TriangleMesh;  // scene/triangle_mesh.h
struct Image;         // image/image_io.h

// Every shape keyword of Hill's SDL (plus the extrude extension), in the
// order of shapeKeyword().
enum class ShapeType {
    Sphere,
    Plane,
    Square,
    Cube,
    Cylinder,
    Cone,
    TaperedCylinder,
    Torus,
    Teapot,
    Tetrahedron,
    Octahedron,
    Dodecahedron,
    Icosahedron,
    Buckyball,
    Diamond,
    Mesh,
    Extrude,
    Union,
    Intersection,
    Difference,
};
inline constexpr int kShapeTypeCount = 20;

const char* shapeKeyword(ShapeType type);

// The generic torus: axis z, centre at the origin, the tube's centre circle
// of radius kTorusMajorRadius in the plane z = 0, tube radius kTorusTubeRadius
// (both exact in float; shaders/layout.h repeats them, checked at compile time).
inline constexpr double kTorusMajorRadius = 1.0;
inline constexpr double kTorusTubeRadius = 0.25;
bool isBoolean(ShapeType type);

// Hill's material state, copied into each shape when it is made.
struct Material {
    glm::dvec3 ambient{0.1, 0.1, 0.1};
    glm::dvec3 diffuse{0.8, 0.8, 0.8};
    glm::dvec3 specular{0, 0, 0};
    glm::dvec3 emissive{0, 0, 0};
    double specularExponent = 1;
    double reflectivity = 0;
    double transparency = 0;
    double speedOfLight = 1;
    double specularFraction = 0;
    double surfaceRoughness = 0;
    int texture = 0;                        // `texture n`: 0 none, 1 checkerboard, 2 wood, 3 image
    std::vector<double> textureParameters;  // `parameters n p1 .. pn`
    FileLoc textureLoc;                     // the `texture` word (errors about the texture)
};

struct SceneObject {
    ShapeType type = ShapeType::Sphere;
    FileLoc loc;                      // the shape keyword
    glm::dmat4 worldFromObject{1.0};  // M: generic object space -> world
    glm::dmat4 objectFromWorld{1.0};  // M^-1, composed from exact inverses
    Material material;
    double taper = 1;  // taperedCylinder s (cylinder 1, cone 0)
    std::string file;  // mesh / extrude: path resolved against the scene's folder
    int mesh = -1;     // mesh, extrude, polyhedra, teapot: index into Scene::meshes
    std::vector<SceneObject> operands;  // union / intersection / difference: exactly two
};

struct Light {
    glm::dvec3 position{0, 0, 0};
    glm::dvec3 color{1, 1, 1};
    FileLoc loc;
};

// Camera extension (Hill's grammar has none; his programs set it in code):
//   camera eye X Y Z look X Y Z up X Y Z fov DEGREES   (each part optional)
struct Camera {
    glm::dvec3 eye{20, 15, 20};
    glm::dvec3 look{0, 0, 0};
    glm::dvec3 up{0, 1, 0};
    double fovDegrees = 60;  // vertical view angle
    FileLoc loc;             // the last `camera` word; unknown for the automatic camera
};

// The largest magnitude of any number in a scene, of any coordinate in a mesh
// or outline file, and of any entry of an object's M or M^-1. The GPU works
// in float (largest 3.4e38); with every input below 1e18 the squares and
// products its intersection tests form stay finite, so an absurd value is
// refused at its place instead of rendering as black or NaN.
inline constexpr double kMaxSceneMagnitude = 1e18;

// Booleans nest at most this deep (`union union ... A B C`): renderers and
// the scene's own code walk the tree recursively, and a deeper tree (10 000
// levels) would overflow the stack. The GPU takes far less (8 spans a list).
inline constexpr int kMaxCsgDepth = 1000;

// `makePixmap i file`: an image a texture refers to by index.
struct Pixmap {
    int index = 0;
    std::string file;  // resolved against the scene's folder
    FileLoc loc;
    // Filled by loadSceneGeometry (scene/pixmaps.h): 3 channels, row 0 at the
    // top, 8-bit files as value / 255.
    std::shared_ptr<const Image> image;
};

// maxRecursionDepth is refused above this by the reader: the GPU follows
// reflected and refracted rays with an explicit stack sized from it.
inline constexpr int kMaxRecursionDepth = 64;

struct Scene {
    std::string path;  // the file it was read from ("" for text)
    glm::dvec3 background{0, 0, 0.6};
    glm::dvec3 globalAmbient{0.1, 0.1, 0.1};
    double minReflectivity = 0.5;
    double minTransparency = 0.5;
    int maxRecursionDepth = 3;  // 0..kMaxRecursionDepth
    std::vector<Light> lights;
    std::vector<SceneObject> objects;  // scene order: object id i is objects[i]
    std::vector<Pixmap> pixmaps;
    // Filled by loadSceneGeometry (scene/scene_geometry.h): one entry per
    // distinct mesh file, extruded outline or built-in solid.
    std::vector<std::shared_ptr<const TriangleMesh>> meshes;
    // Wall seconds loadSceneGeometry spent reading mesh and outline files
    // (their BVHs included), and building those files' BVHs.
    double meshFileSeconds = 0, meshBvhSeconds = 0;
    std::optional<Camera> camera;  // set by the `camera` extension
};

}  // namespace vkray
