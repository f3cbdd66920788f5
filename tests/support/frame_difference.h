// How far two renders of the same view are apart: object ids that differ,
// the largest colour difference, and how many pixels differ in colour by
// more than a threshold (the per-pixel threshold of `render --check`).
#pragma once

#include "image/frame.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

namespace vkray::test {

struct FrameDifference {
    std::size_t ids = 0;   // pixels whose object ids differ
    std::size_t over = 0;  // pixels whose colour differs by more than the threshold
    double maxColor = 0;   // the largest difference of a colour channel
};

// Values whose bits differ (bit patterns, so that -0 against +0 or two NaNs count as what they
// are).
template <typename T>
std::size_t differingValues(const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        differing += std::memcmp(&a[i], &b[i], sizeof(T)) != 0 ? 1 : 0;
    return differing;
}

inline FrameDifference frameDifference(const Frame& a, const Frame& b, double threshold = 0.02) {
    FrameDifference d;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) {
        if (a.id[i] != b.id[i]) ++d.ids;
        double error = 0;
        for (int c = 0; c < 3; ++c)
            error = std::max(error, double(std::abs(a.color[i][c] - b.color[i][c])));
        d.maxColor = std::max(d.maxColor, error);
        if (error > threshold) ++d.over;
    }
    return d;
}

}  // namespace vkray::test
