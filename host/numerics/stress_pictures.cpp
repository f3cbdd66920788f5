#include "numerics/stress_pictures.h"

#include "dist/bytes.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/pictures.h"
#include "util/error.h"

#include <algorithm>
#include <cmath>

namespace vkray::numerics {

namespace {

void paint(Image& image, std::size_t pixel, glm::vec3 colour) {
    for (int c = 0; c < 3; ++c) image.pixels.at(pixel * 3 + size_t(c)) = colour[c];
}

std::string count(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The marks by priority: where a shrunk pixel covers several, the largest shows.
constexpr float kNoMark = 0, kAcne = 1, kWrongId = 2, kFlip = 3;

int pictureFactor(int width) {
    return shrinkFactorFor(Image{width, 1, 1, {}}, kStressPictureWidth);
}

}  // namespace

Image oraclePicture(const Scene& scene, const std::vector<OraclePixel>& oracle, int width,
                    int height) {
    if (oracle.size() != std::size_t(width) * std::size_t(height))
        throw Error("internal: the oracle's pixels do not fill the picture");
    Image image{width, height, 3, std::vector<float>(oracle.size() * 3)};
    for (std::size_t i = 0; i < oracle.size(); ++i) {
        const OracleHit& hit = oracle[i].hit;
        if (hit.id < 0 || std::size_t(hit.id) >= scene.objects.size()) {
            paint(image, i, glm::vec3(scene.background));
            continue;
        }
        const double facing = std::abs(glm::dot(toDvec3(hit.normal), toDvec3(oracle[i].direction)));
        paint(image, i,
              glm::vec3(scene.objects[std::size_t(hit.id)].material.diffuse *
                        (0.25 + 0.75 * facing)));
    }
    return image;
}

ModePicture markedPicture(const std::string& mode, const Frame& frame,
                          const std::vector<OraclePixel>& oracle,
                          const std::vector<StressSample>& samples, Arithmetic a,
                          const std::vector<std::size_t>& acnePixels) {
    if (oracle.size() != frame.pixelCount() || samples.size() != frame.pixelCount())
        throw Error("internal: the oracle's pixels and the frame's differ in number");
    Image image = colorImage(frame);
    for (float& v : image.pixels) v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    ModePicture picture;
    picture.mode = mode;
    Image marks{frame.width, frame.height, 1, std::vector<float>(frame.pixelCount(), kNoMark)};
    for (const std::size_t i : acnePixels) {
        marks.pixels.at(i) = kAcne;
        ++picture.acne;
    }
    for (std::size_t i = 0; i < oracle.size(); ++i) {
        const PixelVerdict verdict = classifyPixel(oracle[i], samples[i], a);
        if (verdict == PixelVerdict::Flip) {
            marks.pixels[i] = kFlip;
            ++picture.flips;
        } else if (verdict == PixelVerdict::WrongId) {
            marks.pixels[i] = kWrongId;
            ++picture.wrongIds;
        }
    }
    const int factor = pictureFactor(frame.width);
    image = shrink(image, factor, Shrink::Average);
    marks = shrink(marks, factor, Shrink::Largest);
    const glm::vec3 colours[] = {{}, kAcneMark, kWrongIdMark, kFlipMark};
    for (std::size_t i = 0; i < marks.pixels.size(); ++i)
        if (marks.pixels[i] != kNoMark) paint(image, i, colours[int(marks.pixels[i])]);
    picture.png = pngBytes(image);
    return picture;
}

std::string oraclePng(const Scene& scene, const std::vector<OraclePixel>& oracle, int width,
                      int height) {
    return pngBytes(
        shrink(oraclePicture(scene, oracle, width, height), pictureFactor(width), Shrink::Average));
}

std::string encodePicture(const StressPicture& picture) {
    dist::ByteWriter writer;
    writer << picture.caseName << picture.oraclePng << picture.shrunkBy
           << std::uint64_t(picture.modes.size());
    for (const ModePicture& m : picture.modes)
        writer << m.mode << m.png << std::uint64_t(m.flips) << std::uint64_t(m.wrongIds)
               << std::uint64_t(m.acne);
    return writer.bytes();
}

StressPicture decodePicture(const std::string& bytes) {
    dist::ByteReader reader(bytes);
    StressPicture picture;
    std::uint64_t modes = 0;
    reader >> picture.caseName >> picture.oraclePng >> picture.shrunkBy >> modes;
    if (modes > bytes.size()) throw Error("MPI: a case's pictures came back garbled");
    picture.modes.resize(modes);
    for (ModePicture& m : picture.modes) {
        std::uint64_t flips = 0, wrongIds = 0, acne = 0;
        reader >> m.mode >> m.png >> flips >> wrongIds >> acne;
        m.flips = flips;
        m.wrongIds = wrongIds;
        m.acne = acne;
    }
    return picture;
}

void addStressPictures(Report& report, const std::vector<StressPicture>& pictures) {
    Gallery gallery;
    gallery.title = "Pictures";
    gallery.paragraphs = {
        "For each case: the oracle's view (the object each exact ray hits in its diffuse colour, "
        "darker as the surface turns from the ray; the oracle traces no lights), then the image "
        "each GPU mode rendered, with the pixels where that mode is wrong painted over. Set-aside "
        "pixels (left out of the metrics) are not marked. A mode that did not run has no picture. "
        "Pictures wider than " +
        std::to_string(kStressPictureWidth) +
        " pixels are shown shrunk "
        "(the caption says by how much): a shown pixel is the mean of those it covers, or marked "
        "when any of them is (a flip before a wrong id before acne); the counts are the full "
        "image's."};
    gallery.legend = {
        {hexColour(kFlipMark), "flip: hit where the oracle misses, or miss where it hits"},
        {hexColour(kWrongIdMark), "wrong id: another object than the oracle's"},
        {hexColour(kAcneMark), "acne: a shadow feeler or refracted ray fails"}};
    for (const StressPicture& picture : pictures) {
        FigureGroup group;
        group.title = picture.caseName;
        if (picture.shrunkBy > 1)
            group.note = "shown at 1/" + std::to_string(picture.shrunkBy) + " size";
        group.figures.push_back({"oracle (long double)", picture.oraclePng, std::nullopt, ""});
        for (const ModePicture& m : picture.modes)
            group.figures.push_back({m.mode + ": " + count(m.flips, "flip", "flips") + ", " +
                                         count(m.wrongIds, "wrong id", "wrong ids") + ", " +
                                         count(m.acne, "acne pixel", "acne pixels"),
                                     m.png, std::nullopt, ""});
        gallery.groups.push_back(std::move(group));
    }
    report.galleries.push_back(std::move(gallery));
}

}  // namespace vkray::numerics
