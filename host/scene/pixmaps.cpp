#include "scene/pixmaps.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <utility>

#include "image/image_io.h"
#include "util/error.h"

namespace vkray {

namespace {

namespace fs = std::filesystem;

// The reader's own "PATH: error: ..." becomes a note under a warning.
std::string asNote(std::string message) {
    const std::size_t at = message.find(": error: ");
    if (at != std::string::npos) message.replace(at, 9, ": note: ");
    return message;
}

// Renderers read three channels: a grey PFM becomes three equal ones.
std::shared_ptr<const Image> asColor(Image image) {
    if (image.channels == 1) {
        std::vector<float> rgb;
        rgb.reserve(image.pixels.size() * 3);
        for (const float v : image.pixels) rgb.insert(rgb.end(), {v, v, v});
        image.pixels = std::move(rgb);
        image.channels = 3;
    }
    return std::make_shared<const Image>(std::move(image));
}

void report(bool lenient, std::vector<std::string>* warnings, const FileLoc& loc,
            const std::string& message, const std::string& detail = "") {
    if (!lenient) {
        std::string text = formatDiagnostic(loc, nullptr, "error", message);
        if (!detail.empty()) text += "\n" + detail;
        throw Error(text);
    }
    if (!warnings) return;
    std::string text = formatDiagnostic(loc, nullptr, "warning", message);
    if (!detail.empty()) text += "\n" + asNote(detail);
    warnings->push_back(std::move(text));
}

void checkTexture(SceneObject& object, const Scene& scene, bool lenient,
                  std::vector<std::string>* warnings) {
    for (SceneObject& operand : object.operands) checkTexture(operand, scene, lenient, warnings);
    Material& material = object.material;
    const FileLoc& where = material.textureLoc.known() ? material.textureLoc : object.loc;
    std::string problem;
    const int index = pixmapIndexOf(material);
    if ((material.texture == 1 || material.texture == 2) && !material.textureParameters.empty() &&
        !(material.textureParameters[0] > 0)) {
        // Cells and rings are measured in it: 0 would divide by zero.
        const char* what = material.texture == 1 ? "checkerboard size" : "wood ring width";
        problem = std::string("texture ") + std::to_string(material.texture) + " needs a " + what +
                  " > 0 as its first parameter";
    } else if (material.texture != 3) {
        return;
    } else if (index < 0) {
        problem = material.textureParameters.empty()
                      ? "texture 3 needs 'parameters 1 i' naming a 'makePixmap i FILE'; "
                        "there are no parameters"
                      : "texture 3 needs a pixmap index (a whole number >= 0) as its first "
                        "parameter; found " +
                            std::to_string(material.textureParameters[0]);
    } else if (!findPixmap(scene, index)) {
        bool leftOut = false;
        for (const Pixmap& pixmap : scene.pixmaps) leftOut = leftOut || pixmap.index == index;
        problem =
            "texture 3 uses pixmap " + std::to_string(index) +
            (leftOut ? ", which could not be loaded"
                     : ", but the scene has no 'makePixmap " + std::to_string(index) + " FILE'");
    }
    if (problem.empty()) return;
    if (lenient)
        problem += "; the '" + std::string(shapeKeyword(object.type)) + "' at " + object.loc.str() +
                   " is drawn untextured";
    report(lenient, warnings, where, problem);
    material.texture = 0;  // lenient only: report() threw otherwise
}

}  // namespace

int pixmapIndexOf(const Material& material) {
    if (material.textureParameters.empty()) return -1;
    const double index = material.textureParameters[0];
    if (!(index >= 0 && index <= 2147483647.0) || index != std::floor(index)) return -1;
    return int(index);
}

const Pixmap* findPixmap(const Scene& scene, int index) {
    for (const Pixmap& pixmap : scene.pixmaps)
        if (pixmap.index == index && pixmap.image) return &pixmap;
    return nullptr;
}

void loadPixmaps(Scene& scene, bool lenient, std::vector<std::string>* warnings) {
    for (std::size_t i = 0; i < scene.pixmaps.size(); ++i) {
        Pixmap& pixmap = scene.pixmaps[i];
        pixmap.image = nullptr;
        const std::string what = "cannot load pixmap '" + writtenName(pixmap.loc, pixmap.file) +
                                 "' (makePixmap " + std::to_string(pixmap.index) + ")";
        bool duplicate = false;
        for (std::size_t j = 0; j < i && !duplicate; ++j) {
            if (scene.pixmaps[j].index != pixmap.index) continue;
            duplicate = true;
            report(lenient, warnings, pixmap.loc,
                   "makePixmap " + std::to_string(pixmap.index) + " is already defined at " +
                       scene.pixmaps[j].loc.str() + (lenient ? "; this one is ignored" : ""));
        }
        if (duplicate) continue;
        try {
            pixmap.image = asColor(readImage(pixmap.file));
        } catch (const Error& e) {
            report(lenient, warnings, pixmap.loc, what + (lenient ? "; left out" : ""),
                   std::string(e.what()));
        }
    }
    for (SceneObject& object : scene.objects) checkTexture(object, scene, lenient, warnings);
}

}  // namespace vkray
