// `vkray view`'s camera under the mouse: orbit around the look point, pan,
// zoom, and the `camera` line that puts the result into a scene.
#pragma once

#include "scene/scene.h"

#include <string>

namespace vkray {

// The eye turned about the look point: `right` degrees around the up
// direction (the eye moves right), `down` degrees over the top (the eye
// moves up), stopping 1 degree short of looking along up.
Camera orbit(const Camera& camera, double right, double down);

// Eye and look moved together in the view plane by (right, up) pixels of a
// window `height` pixels tall, so that the look point follows the mouse.
Camera pan(const Camera& camera, double right, double up, int height);

// The eye moved toward the look point: its distance times 0.9^steps
// (steps < 0 moves it away).
Camera zoom(const Camera& camera, double steps);

// "camera eye X Y Z look X Y Z up X Y Z fov F": each number the shortest that
// reads back as the same double, so the line pasted into a scene gives the
// very same camera.
std::string cameraLine(const Camera& camera);

// What the mouse does: degrees of orbit per pixel dragged.
inline constexpr double kOrbitDegreesPerPixel = 0.4;

}  // namespace vkray
