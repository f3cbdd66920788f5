// `makePixmap i FILE` images and the `texture 3` materials that name them:
// decoded once when the scene's geometry is loaded, so that both renderers
// read the same texels and a bad file or index fails before rendering.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkray {

// Decodes every pixmap into Pixmap::image (BMP, PNG or PFM, by extension; grey
// becomes three equal channels) and checks every object's texture (operands
// of booleans included): `texture 3` needs `parameters` whose first value
// is the index of a makePixmap of the scene. Errors (strict):
//   scene.sdl:4:1: error: cannot load pixmap 'wood.png' (makePixmap 0)
//   /path/wood.png: ...the image reader's message...
//   scene.sdl:4:1: error: makePixmap 0 is already defined at scene.sdl:2:1
//   scene.sdl:9:1: error: texture 3 uses pixmap 2, but the scene has no 'makePixmap 2 FILE'
//   scene.sdl:9:1: error: texture 1 needs a checkerboard size > 0 as its first parameter
// (the last also in lenient mode: it is not about a file).
// Lenient: a pixmap that cannot be loaded is dropped with that warning, and
// an object whose texture 3 has no pixmap is drawn untextured (texture 0)
// with a warning at its `texture` word.
void loadPixmaps(Scene& scene, bool lenient, std::vector<std::string>* warnings);

// The loaded pixmap with SDL index `index`, or null.
const Pixmap* findPixmap(const Scene& scene, int index);

// The pixmap index a `texture 3` material names (its first parameter), or
// -1 when it names none (no parameters, or not a whole number >= 0).
int pixmapIndexOf(const Material& material);

}  // namespace vkray
