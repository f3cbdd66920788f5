#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>

#include "util/error.h"

namespace vkray {

namespace {

std::string sizeText(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

void requireConsistent(const Image& image, const char* which) {
    if (image.width < 0 || image.height < 0 || image.channels < 1 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw Error(std::string("image ") + which + " is malformed: " + sizeText(image) + " with " +
                    std::to_string(image.channels) + " channel(s) but " +
                    std::to_string(image.pixels.size()) + " values");
}

void requireSameShape(const Image& a, const Image& b) {
    requireConsistent(a, "A");
    requireConsistent(b, "B");
    if (a.width != b.width || a.height != b.height)
        throw Error("images differ in size: " + sizeText(a) + " vs " + sizeText(b));
    if (a.channels != b.channels)
        throw Error("images differ in channel count: " + std::to_string(a.channels) + " vs " +
                    std::to_string(b.channels));
}

// The difference a display would show: both values clamped to [0,1]. A NaN on
// either side is a full error of 1, so a broken pixel is never hidden.
double sampleError(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) return 1;
    return std::abs(double(std::clamp(a, 0.0f, 1.0f)) - double(std::clamp(b, 0.0f, 1.0f)));
}

double percentOf(size_t part, size_t whole) {
    return whole == 0 ? 0 : 100.0 * double(part) / double(whole);
}

// printf-style formatting into a std::string (g++ 12 has no std::format).
[[gnu::format(printf, 1, 2)]] std::string format(const char* pattern, ...) {
    char buffer[256];
    va_list args;
    va_start(args, pattern);
    const int length = std::vsnprintf(buffer, sizeof buffer, pattern, args);
    va_end(args);
    return std::string(buffer, size_t(std::clamp(length, 0, int(sizeof buffer) - 1)));
}

}  // namespace

CompareResult compareImages(const Image& a, const Image& b, const CompareOptions& options) {
    requireSameShape(a, b);
    CompareResult result;
    result.pixelCount = size_t(a.width) * size_t(a.height);
    const size_t channels = size_t(a.channels);
    double sumSquares = 0;
    for (size_t pixel = 0; pixel < result.pixelCount; ++pixel) {
        double pixelError = 0;
        for (size_t c = 0; c < channels; ++c) {
            const double e =
                sampleError(a.pixels[pixel * channels + c], b.pixels[pixel * channels + c]);
            sumSquares += e * e;
            pixelError = std::max(pixelError, e);
        }
        if (pixelError > result.maxAbsError) {  // the first pixel with the largest error
            result.maxAbsError = pixelError;
            result.maxErrorX = int(pixel % size_t(a.width));
            result.maxErrorY = int(pixel / size_t(a.width));
        }
        if (pixelError > options.failThreshold) ++result.pixelsOverThreshold;
    }
    const size_t samples = result.pixelCount * channels;
    result.rmse = samples == 0 ? 0 : std::sqrt(sumSquares / double(samples));
    result.psnr = result.rmse == 0 ? std::numeric_limits<double>::infinity()
                                   : 20 * std::log10(1 / result.rmse);
    result.percentOverThreshold = percentOf(result.pixelsOverThreshold, result.pixelCount);
    result.passed = result.percentOverThreshold <= options.failPercent;
    return result;
}

void compareIds(const Image& idsA, const Image& idsB, CompareResult& result) {
    requireSameShape(idsA, idsB);
    if (idsA.channels != 1)
        throw Error("object-id images must have 1 channel, these have " +
                    std::to_string(idsA.channels));
    size_t mismatches = 0;
    for (size_t i = 0; i < idsA.pixels.size(); ++i)
        if (!(idsA.pixels[i] == idsB.pixels[i])) ++mismatches;  // a NaN id never matches
    result.idMismatches = mismatches;
    result.idMismatchPercent = percentOf(mismatches, idsA.pixels.size());
    // `passed` is left alone: whether id disagreement fails a run is the caller's call.
}

Image errorImage(const Image& a, const Image& b) {
    requireSameShape(a, b);
    const size_t channels = size_t(a.channels);
    Image error{a.width, a.height, 1, std::vector<float>(a.pixels.size() / channels)};
    for (size_t i = 0; i < error.pixels.size(); ++i) {
        double largest = 0;
        for (size_t c = 0; c < channels; ++c)
            largest = std::max(largest,
                               sampleError(a.pixels[i * channels + c], b.pixels[i * channels + c]));
        error.pixels[i] = float(largest);
    }
    return error;
}

Image diffImage(const Image& a, const Image& b, double scale) {
    requireSameShape(a, b);
    Image diff{a.width, a.height, a.channels, std::vector<float>(a.pixels.size())};
    for (size_t i = 0; i < a.pixels.size(); ++i)
        diff.pixels[i] = float(std::clamp(sampleError(a.pixels[i], b.pixels[i]) * scale, 0.0, 1.0));
    return diff;
}

std::string formatCompareReport(const CompareResult& result, const CompareOptions& options) {
    std::string report;
    report += format("max abs error   %.4g at (%d, %d)\n", result.maxAbsError, result.maxErrorX,
                     result.maxErrorY);
    report += format("RMSE            %.2e\n", result.rmse);
    report += std::isinf(result.psnr) ? std::string("PSNR            inf dB (identical)\n")
                                      : format("PSNR            %.1f dB\n", result.psnr);
    report += format(
        "over threshold  %zu of %zu pixels (%.4g %%) with error > %.4g, "
        "allowed %.4g %%\n",
        result.pixelsOverThreshold, result.pixelCount, result.percentOverThreshold,
        options.failThreshold, options.failPercent);
    if (result.idMismatches)
        report += format("object ids      %zu of %zu pixels differ (%.4g %%)\n",
                         *result.idMismatches, result.pixelCount, result.idMismatchPercent);
    report += result.passed ? "result          PASS\n" : "result          FAIL\n";
    return report;
}

}  // namespace vkray
