// The benchmark's scenes: generated sphere fields and a large mesh (built in
// code, so the harness needs no data files), and scenes read from SDL.
#pragma once

#include "scene/scene.h"

#include <string>

namespace vkray::bench {

// n unit spheres at random (fixed seed) in a cube whose side grows like
// n^(1/3), so that the image stays about as full whatever n; one light, a
// camera framing the cube.
Scene randomSpheres(int n);

// A UV sphere of 2 * rings * rings triangles with smooth normals, its BVH
// built (rings = 708: about a million triangles).
Scene uvSphereMesh(int rings);

// n unit spheres far to the side of a camera looking down -z: no primary ray
// comes near one (every discriminant is negative), so a render costs ray
// setup + n sphere tests + the background write per ray. Kept at most 8 so
// that no object BVH is built: every ray tests every sphere.
Scene missedSpheres(int n);

// An SDL file, --lenient (corpus scenes hold words and meshes vkray lacks).
Scene sdlScene(const std::string& path);

}  // namespace vkray::bench
