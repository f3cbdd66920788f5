// Texture colour k(p) for the CPU reference (docs/shading.md, "Textures"): Hill's
// `texture n` / `parameters` scale a surface's ambient and diffuse
// coefficients by a colour found at the hit's generic coordinates.
#pragma once

#include "scene/scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace vkray {
struct Image;
}

namespace vkray::reference {

// k(p) at world point p on `surface` (the primitive hit; for CSG the
// operand), whose world normal there is `worldNormal` (either side; it tells
// a cylinder's caps from its wall). (1, 1, 1) for texture 0. The scene
// supplies the pixmaps (loadSceneGeometry decoded them).
glm::dvec3 textureColor(const Scene& scene, const SceneObject& surface, const glm::dvec3& p,
                        const glm::dvec3& worldNormal);

// The parts, each from generic coordinates g:
// 1: 3D checkerboard of cells `size`, odd cells `color`.
glm::dvec3 checkerboard(const glm::dvec3& g, double size, const glm::dvec3& color);
// 2: rings of `width` about the generic z axis, shifted half a ring (ring
// floor(r / width + 1/2)), odd rings `color`.
glm::dvec3 woodRings(const glm::dvec3& g, double width, const glm::dvec3& color);
// 3: (u, v) of g on the generic shape of `type` (genericNormal: the outward
// normal there, any length), and the nearest texel at (u, v) (u wraps, v is
// clamped; v = 1 is the image's top row).
glm::dvec2 surfaceUv(ShapeType type, const glm::dvec3& g, const glm::dvec3& genericNormal);
glm::dvec3 nearestTexel(const Image& image, glm::dvec2 uv);

}  // namespace vkray::reference
