#include "image/pictures.h"

#include "util/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace vkray {

Image shrink(const Image& image, int factor, Shrink how) {
    if (factor < 1) throw Error("internal: shrink factor " + std::to_string(factor));
    const int width = (image.width + factor - 1) / factor,
              height = (image.height + factor - 1) / factor;
    const size_t channels = size_t(image.channels);
    Image small{width, height, image.channels,
                std::vector<float>(size_t(width) * size_t(height) * channels)};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (size_t c = 0; c < channels; ++c) {
                double sum = 0, largest = -INFINITY;
                int count = 0;
                for (int sy = y * factor; sy < std::min((y + 1) * factor, image.height); ++sy) {
                    for (int sx = x * factor; sx < std::min((x + 1) * factor, image.width); ++sx) {
                        const float v =
                            image
                                .pixels[(size_t(sy) * size_t(image.width) + size_t(sx)) * channels +
                                        c];
                        sum += v;
                        largest = std::isnan(v) || std::isnan(largest)
                                      ? NAN
                                      : std::max(largest, double(v));
                        ++count;
                    }
                }
                small.pixels[(size_t(y) * size_t(width) + size_t(x)) * channels + c] =
                    float(how == Shrink::Average ? sum / count : largest);
            }
        }
    }
    return small;
}

int shrinkFactorFor(const Image& image, int width) {
    return std::max(1, (image.width + width - 1) / std::max(width, 1));
}

double heatPosition(const HeatScale& scale, double value) {
    if (std::isnan(value)) return 1;
    if (!(value > scale.lo)) return 0;
    if (value >= scale.hi) return 1;
    return std::log10(value / scale.lo) / std::log10(scale.hi / scale.lo);
}

glm::vec3 heatColour(double t) {
    // Samples of matplotlib's inferno at t = 0, 1/8, ..., 1.
    static constexpr std::array<std::array<float, 3>, 9> kStops{{{0.001f, 0.000f, 0.014f},
                                                                 {0.096f, 0.047f, 0.241f},
                                                                 {0.258f, 0.039f, 0.406f},
                                                                 {0.416f, 0.090f, 0.433f},
                                                                 {0.578f, 0.148f, 0.404f},
                                                                 {0.735f, 0.216f, 0.330f},
                                                                 {0.865f, 0.317f, 0.226f},
                                                                 {0.955f, 0.469f, 0.099f},
                                                                 {0.988f, 0.998f, 0.645f}}};
    const double at = std::clamp(std::isnan(t) ? 1.0 : t, 0.0, 1.0) * double(kStops.size() - 1);
    const size_t i = std::min(size_t(at), kStops.size() - 2);
    const float f = float(at - double(i));
    const auto& a = kStops[i];
    const auto& b = kStops[i + 1];
    return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

Image heatMap(const Image& values, const HeatScale& scale) {
    if (values.channels != 1) throw Error("internal: a heat map is made of 1-channel values");
    Image map{values.width, values.height, 3, {}};
    map.pixels.reserve(values.pixels.size() * 3);
    for (const float v : values.pixels) {
        const glm::vec3 c = heatColour(heatPosition(scale, v));
        map.pixels.insert(map.pixels.end(), {c.r, c.g, c.b});
    }
    return map;
}

std::string hexColour(glm::vec3 colour) {
    const auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
    char text[8];
    std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(colour.r), byte(colour.g),
                  byte(colour.b));
    return text;
}

}  // namespace vkray
