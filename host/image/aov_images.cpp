#include "image/aov_images.h"

#include "image/exr_io.h"

namespace vkray {

Image colorImage(const Frame& frame) {
    Image image{frame.width, frame.height, 3, {}};
    image.pixels.reserve(frame.pixelCount() * 3);
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels.push_back(frame.color.at(i)[c]);
    return image;
}

Image depthImage(const Frame& frame) {
    Image image{frame.width, frame.height, 1, {}};
    image.pixels.reserve(frame.pixelCount());
    for (size_t i = 0; i < frame.pixelCount(); ++i) image.pixels.push_back(frame.depth.at(i));
    return image;
}

Image normalImage(const Frame& frame) {
    Image image{frame.width, frame.height, 3, {}};
    image.pixels.reserve(frame.pixelCount() * 3);
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels.push_back(frame.normal.at(i)[c]);
    return image;
}

Image idImage(const Frame& frame) {
    Image image{frame.width, frame.height, 1, {}};
    image.pixels.reserve(frame.pixelCount());
    // Object indices stay exact as floats up to 2^24, far beyond any scene.
    for (size_t i = 0; i < frame.pixelCount(); ++i) image.pixels.push_back(float(frame.id.at(i)));
    return image;
}

void writeAovs(const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints) {
    StagedFiles files;
    stageAovs(files, target, frame, hitPoints);
    files.commit();
}

std::string aovFilesText(const std::string& target) {
    if (isExrPath(target)) return target + " (R, G, B, Z, N.X, N.Y, N.Z, id, P.X, P.Y, P.Z)";
    return target + ".depth.pfm, .normal.pfm, .id.pfm";
}

void stageAovs(StagedFiles& files, const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints) {
    if (isExrPath(target)) {
        files.stage(target, encodeExr(aovExr(frame, hitPoints), target));
        return;
    }
    const std::string& prefix = target;
    stageImage(files, prefix + ".depth.pfm", depthImage(frame));
    stageImage(files, prefix + ".normal.pfm", normalImage(frame));
    stageImage(files, prefix + ".id.pfm", idImage(frame));
}

}  // namespace vkray
