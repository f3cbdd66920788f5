#include "app/compare_command.h"

#include "app/commands.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"

#include <filesystem>
#include <ostream>

namespace vkray {

namespace fs = std::filesystem;

bool compareAndReport(const Image& a, const Image& b, const Image* idsA, const Image* idsB,
                      const CompareOptions& options, const std::string& diffPath,
                      StagedFiles& files, std::ostream& out) {
    CompareResult result = compareImages(a, b, options);
    if (idsA && idsB) {
        compareIds(*idsA, *idsB, result);
        result.passed = result.passed && result.idMismatchPercent <= options.failPercent;
    }
    if (!diffPath.empty()) stageImage(files, diffPath, diffImage(a, b));
    out << formatCompareReport(result, options);
    return result.passed;
}

namespace {

// Where an image's object ids are, as `render` writes them: the image's own id
// channel (X.exr from --aov X.exr), X.id.pfm (--aov X) or X.exr with an id
// channel beside it (-o X.png --aov X.exr); "" when none is there.
std::string idsBeside(const std::string& image) {
    if (hasIdChannel(image)) return image;
    const std::string stem = fs::path(image).replace_extension().string();
    if (fs::exists(stem + ".id.pfm")) return stem + ".id.pfm";
    if (fs::exists(stem + ".exr") && hasIdChannel(stem + ".exr")) return stem + ".exr";
    return "";
}

}  // namespace

int runCompare(const Options& o, std::ostream& out) {
    const Image a = readImage(o.imageA), b = readImage(o.imageB);
    if (!o.diffPath.empty()) requireWritableFolder(o.diffPath, "--diff");
    const CompareOptions tolerance{o.failThreshold.value_or(CompareOptions{}.failThreshold),
                                   o.failPercent.value_or(CompareOptions{}.failPercent)};
    // Ids: given with --ids, or found for both images with idsBeside().
    std::string idsPathA = o.idsA, idsPathB = o.idsB;
    if (idsPathA.empty()) {
        const std::string besideA = idsBeside(o.imageA), besideB = idsBeside(o.imageB);
        if (!besideA.empty() && !besideB.empty()) {
            idsPathA = besideA;
            idsPathB = besideB;
            out << "object ids from " << idsPathA << " and " << idsPathB << "\n";
        }
    }
    StagedFiles files;
    bool passed = false;
    if (idsPathA.empty()) {
        passed = compareAndReport(a, b, nullptr, nullptr, tolerance, o.diffPath, files, out);
    } else {
        const Image idsA = readIds(idsPathA), idsB = readIds(idsPathB);
        passed = compareAndReport(a, b, &idsA, &idsB, tolerance, o.diffPath, files, out);
    }
    files.commit();
    return passed ? 0 : 2;
}

}  // namespace vkray
