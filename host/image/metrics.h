// Image comparison in the spirit of OpenImageIO's idiff: per-pixel error is
// the largest absolute channel difference; a comparison fails when more than
// failPercent % of the pixels have an error above failThreshold.
#pragma once

#include "image/image_io.h"

#include <cstddef>
#include <optional>
#include <string>

namespace vkray {

struct CompareOptions {
    double failThreshold = 1e-6;  // idiff --fail
    double failPercent = 0;       // idiff --failpercent
};

struct CompareResult {
    double maxAbsError = 0;  // over all pixels and channels
    int maxErrorX = 0, maxErrorY = 0;
    double rmse = 0;  // over all pixels and channels
    double psnr = 0;  // 20 log10(1 / rmse), peak 1; +inf when identical
    std::size_t pixelsOverThreshold = 0;
    double percentOverThreshold = 0;
    std::size_t pixelCount = 0;
    // Only when object-id images were given.
    std::optional<std::size_t> idMismatches;
    double idMismatchPercent = 0;
    bool passed = true;  // percentOverThreshold <= failPercent
};

// Colour values are compared clamped to [0,1] (what a display shows), so a
// difference hidden above white does not count. Throws Error when sizes or
// channel counts differ.
CompareResult compareImages(const Image& a, const Image& b, const CompareOptions& options);

// Adds id mismatch counts (ids must be 1-channel images of the same size).
void compareIds(const Image& idsA, const Image& idsB, CompareResult& result);

// Per pixel, the error compareImages measures: the largest absolute channel
// difference of the clamped colours (1 where either is NaN); 1 channel.
Image errorImage(const Image& a, const Image& b);

// A diff image: per pixel, the absolute difference scaled by `scale` (idiff's
// --scale; default 1), clamped to [0,1].
Image diffImage(const Image& a, const Image& b, double scale = 1);

// The lines printed by `vkray compare` and `render --check`.
std::string formatCompareReport(const CompareResult& result, const CompareOptions& options);

}  // namespace vkray
