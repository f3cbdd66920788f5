// Pictures for the HTML reports: thumbnails, and heat maps of per-pixel
// error on a logarithmic colour scale.
#pragma once

#include "image/image_io.h"

#include <glm/vec3.hpp>

#include <string>

namespace vkray {

// How a thumbnail pixel sums up the pixels it covers: their mean (a picture),
// or their largest value (an error map, where one bad pixel must stay seen).
enum class Shrink { Average, Largest };

// The image `factor` times smaller per side: each factor x factor block of
// pixels (partial at the right and bottom edges) becomes one.
Image shrink(const Image& image, int factor, Shrink how);

// The smallest whole factor that makes the image at most `width` wide.
int shrinkFactorFor(const Image& image, int width);

// A logarithmic colour scale from lo (and below, 0 included) at the cold end
// to hi (and above) at the hot end, each decade an equal step.
struct HeatScale {
    double lo = 1e-4, hi = 1;
};

// Where `value` sits on the scale, in [0, 1]; NaN is the hot end.
double heatPosition(const HeatScale& scale, double value);

// The colour at position t in [0, 1]: black through purple, red and orange
// to pale yellow (after matplotlib's "inferno": brightness grows with t, so
// it reads in grey too).
glm::vec3 heatColour(double t);

// A 1-channel image of values as a 3-channel heat map, colours in [0, 1].
Image heatMap(const Image& values, const HeatScale& scale);

// "#rrggbb" for a colour in [0, 1].
std::string hexColour(glm::vec3 colour);

}  // namespace vkray
