// The stress report's pictures: for each case, the oracle's view beside each
// GPU mode's image, with the pixels where the mode is wrong marked.
#pragma once

#include "image/frame.h"
#include "numerics/oracle.h"
#include "numerics/report_writer.h"
#include "numerics/stress_suite.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace vkray::numerics {

// The marks' colours: saturated, unlike the cases' own.
inline constexpr glm::vec3 kFlipMark{1, 0, 1};     // magenta: hit against miss
inline constexpr glm::vec3 kWrongIdMark{1, 1, 0};  // yellow: another object
inline constexpr glm::vec3 kAcneMark{0, 1, 1};     // cyan: a secondary ray failed

// Pictures wider than this are shrunk by a whole factor: a shown pixel is
// the mean of those it covers, or the mark of any of them that is marked
// (flips before wrong ids before acne).
inline constexpr int kStressPictureWidth = 320;

struct ModePicture {
    std::string mode;
    std::string png;
    std::size_t flips = 0, wrongIds = 0, acne = 0;  // the pixels marked
};

struct StressPicture {
    std::string caseName;
    std::string oraclePng;
    std::vector<ModePicture> modes;  // the GPU modes that ran
    int shrunkBy = 1;                // the pictures' factor (kStressPictureWidth)
};

// The oracle's view (it has no lights): each pixel's object in its diffuse
// colour, darker as its normal turns from the ray, 0.25 + 0.75 |n.d|; the
// scene's background where the exact ray hits nothing.
Image oraclePicture(const Scene& scene, const std::vector<OraclePixel>& oracle, int width,
                    int height);

// A GPU mode's colour image (clamped to [0, 1]) with its flips and wrong ids
// against the oracle (classifyPixel, in arithmetic `a`) and its pixels whose
// secondary rays failed (secondary_check.h SecondaryStats::failedPixels)
// painted in the marks' colours, as
// a PNG shrunk to at most kStressPictureWidth (the counts are the full
// image's).
ModePicture markedPicture(const std::string& mode, const Frame& frame,
                          const std::vector<OraclePixel>& oracle,
                          const std::vector<StressSample>& samples, Arithmetic a,
                          const std::vector<std::size_t>& acnePixels);

// The oracle's view as a PNG, shrunk as markedPicture shrinks.
std::string oraclePng(const Scene& scene, const std::vector<OraclePixel>& oracle, int width,
                      int height);

// A case's picture as bytes and back (from the MPI rank that ran the case).
std::string encodePicture(const StressPicture& picture);
StressPicture decodePicture(const std::string& bytes);

// Appends the gallery of the cases' pictures to the stress report.
void addStressPictures(Report& report, const std::vector<StressPicture>& pictures);

}  // namespace vkray::numerics
