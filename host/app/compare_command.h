// `vkray compare A B`: two images (and their object ids) against a tolerance;
// render --check reports its GPU/CPU comparison the same way.
#pragma once

#include "app/options.h"
#include "image/image_io.h"
#include "image/metrics.h"

#include <iosfwd>

namespace vkray {

// Exit status: 0 within tolerance, 2 beyond it.
int runCompare(const Options& options, std::ostream& out);

// Compares colour (and ids, when both are given) and prints the report; the
// diff image, if asked for, is staged in `files`. True when within tolerance.
bool compareAndReport(const Image& a, const Image& b, const Image* idsA, const Image* idsB,
                      const CompareOptions& options, const std::string& diffPath,
                      StagedFiles& files, std::ostream& out);

}  // namespace vkray
