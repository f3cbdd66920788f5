// Everything a renderer needs from a scene besides what the SDL text says:
// the meshes it names (3VN files, extruded outlines, built-in solids), each
// object's world bounds, and the BVH over the objects.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/bvh.h"
#include "scene/scene.h"
#include "scene/sdl_reader.h"

namespace vkray {

// Loads each mesh and outline file once (paths were resolved against the
// scene's folder; one file however it is spelled), builds each built-in solid
// once, and sets every object's `mesh` (operands of booleans included).
// scene.meshes is rebuilt from scratch. A missing or malformed file is an
// Error at the `mesh`/`extrude` word, followed by the file's own message:
//   scene.sdl:44:80: error: cannot load mesh 'pawn.3vn'
//   /path/pawn.3vn: error: cannot read mesh file: No such file or directory
// Lenient: the object is left out with that warning instead ("...; left out",
// the file's message as a note); a failure inside a boolean leaves out the
// whole top-level boolean, and the warning says so. Then decodes the
// pixmaps and checks the textures that use them (scene/pixmaps.h).
void loadSceneGeometry(Scene& scene, bool lenient, std::vector<std::string>* warnings);

// Parse + loadSceneGeometry: what `vkray render` does.
Scene loadScene(const std::string& path, const SdlOptions& options,
                std::vector<std::string>* warnings);

// The generic shape's box in its own space (the boxes listed below);
// nullopt when it has none (a plane, a boolean, or a mesh not loaded yet).
std::optional<Aabb> genericBounds(const SceneObject& object, const Scene& scene);

// World bounds: the generic shape's box through M (its 8 corners), each
// corner widened by pbrt's bound on its rounding (gamma(3) times the
// magnitudes summed). Generic boxes: sphere and cube [-1, 1]^3; square
// [-1, 1]^2 x [0, 0] (kept flat: the slab test passes a zero-thickness box);
// cylinder, cone, taperedCylinder s: [-r, r]^2 x [0, 1], r = max(1, |s|);
// torus: [-(R + r), R + r]^2 x [-r, r]; meshes and built-ins: the mesh's
// bounds. A plane is unbounded (Aabb::finite() false), and so is a mesh
// object whose mesh is not loaded yet (mesh == -1) or a box that overflows.
// union: both operands' box; intersection: the overlap (an empty Aabb when
// they are apart); difference: the first operand's. Operands carry their own
// world transforms; the boolean's own M is not used.
Aabb worldBounds(const SceneObject& object, const Scene& scene);

// The BVH over the scene's bounded objects (order indexes scene.objects);
// unbounded ones (planes) are listed apart and tested for every ray. An
// object with an empty box (an intersection of objects whose boxes are apart)
// can never be hit and is in neither. Without meshes, the mesh objects
// (SceneObject::mesh set) are in neither either: the caller places their
// triangles.
struct ObjectBvh {
    Bvh bvh;
    std::vector<std::uint32_t> unbounded;
};
enum class MeshObjects { In, Apart };
ObjectBvh buildObjectBvh(const Scene& scene, MeshObjects meshes = MeshObjects::In);

}  // namespace vkray
