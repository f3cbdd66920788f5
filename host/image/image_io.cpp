#include "image/image_io.h"

#include "image/aov_images.h"
#include "image/exr_io.h"
#include "image/pfm.h"
#include "image/stb_codecs.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

#include "util/error.h"
#include "util/files.h"

namespace vkray {

namespace {

namespace fs = std::filesystem;

// ".PNG" -> ".png"; empty when the path has no extension.
std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

enum class Format { Png, Pfm, Exr, Bmp };

// What vkray writes (.png, .pfm, .exr), or with `reading` also what it reads
// (.bmp: Hill's pixmaps).
Format formatOf(const std::string& path, bool reading) {
    const std::string ext = lowerExtension(path);
    if (ext == ".png") return Format::Png;
    if (ext == ".pfm") return Format::Pfm;
    if (ext == ".exr") return Format::Exr;
    if (ext == ".bmp" && reading) return Format::Bmp;
    throw Error(path + ": unsupported image format '" + ext + "' (use .png, .pfm or .exr" +
                (reading ? ", or .bmp to read)" : ")"));
}

// An EXR's colour: R, G, B, else Y (what writeImage writes for 1 channel).
Image decodeExrImage(const std::string& path, const std::string& bytes) {
    const std::vector<std::string> names = exrChannelNames(bytes, path);
    const auto has = [&](const char* name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    std::vector<std::string> wanted{"R", "G", "B"};
    if (!(has("R") && has("G") && has("B")) && has("Y")) wanted = {"Y"};
    const ExrImage exr = decodeExr(bytes, path, wanted);
    Image image{exr.width, exr.height, int(wanted.size()), {}};
    image.pixels.resize(size_t(exr.width) * size_t(exr.height) * wanted.size());
    for (size_t c = 0; c < wanted.size(); ++c)
        for (size_t i = 0; i < exr.channels[c].values.size(); ++i)
            image.pixels[i * wanted.size() + c] = exr.channels[c].values[i];
    return image;
}

void requireWritable(const std::string& path, const Image& image) {
    const bool sizeOk =
        image.width > 0 && image.height > 0 && (image.channels == 1 || image.channels == 3) &&
        image.pixels.size() == size_t(image.width) * size_t(image.height) * size_t(image.channels);
    if (!sizeOk)
        throw Error("cannot write " + path + ": the image is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " with " + std::to_string(image.channels) +
                    " channel(s) and " + std::to_string(image.pixels.size()) +
                    " values; only non-empty 1- or 3-channel images with matching data can be "
                    "written");
}

}  // namespace

std::string pngBytes(const Image& image) {
    requireWritable("a PNG image", image);
    return encodePng("a PNG image", image);
}

void writeImage(const std::string& path, const Image& image) {
    StagedFiles files;
    stageImage(files, path, image);
    files.commit();
}

Image decodeImage(const std::string& bytes, const std::string& path) {
    switch (formatOf(path, true)) {
    case Format::Png: return decodePng(path, bytes);
    case Format::Bmp: return decodeBmp(path, bytes);
    case Format::Exr: return decodeExrImage(path, bytes);
    default: return decodePfm(path, bytes);
    }
}

Image readIds(const std::string& path) {
    if (formatOf(path, true) != Format::Exr) return readImage(path);
    const ExrImage exr = decodeExr(readFile(path), path, {kExrIdChannel});
    return Image{exr.width, exr.height, 1, exr.channels.front().values};
}

bool hasIdChannel(const std::string& path) {
    if (!isExrPath(path)) return false;
    const std::vector<std::string> names = exrChannelNames(readFile(path), path);
    return std::find(names.begin(), names.end(), kExrIdChannel) != names.end();
}

bool isExrPath(const std::string& path) {
    return lowerExtension(path) == ".exr";
}

Image readImage(const std::string& path) {
    formatOf(path, true);  // an unsupported extension is refused before the file is read
    return decodeImage(readFile(path), path);
}

// ---- staged images ---------------------------------------------------------

void stageColor(StagedFiles& files, const std::string& path, const Frame& frame) {
    if (formatOf(path, false) != Format::Png || frame.pixelCount() == 0)
        return stageImage(files, path, colorImage(frame));
    std::vector<unsigned char> bytes(frame.pixelCount() * 3);
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + size_t(c)] = pngByte(frame.color[i][c]);
    files.stage(path, encodePng(path, frame.width, frame.height, 3, bytes));
}

void stageImage(StagedFiles& files, const std::string& path, const Image& image) {
    const Format format = formatOf(path, false);
    requireWritable(path, image);
    files.stage(path, format == Format::Png   ? encodePng(path, image)
                      : format == Format::Exr ? encodeExr(exrFromImage(image), path)
                                              : encodePfm(image));
}

}  // namespace vkray
