// The scene words of Whitted shading that can be wrong before anything is
// rendered: `makePixmap` images (decoded when the geometry loads), `texture`
// codes and the pixmaps they name, and the bound on maxRecursionDepth. Each
// error names the place of the word at fault.
#include "scene/pixmaps.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "image/image_io.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"
#include "support/error_of.h"
#include "support/temp_folder.h"
#include "util/error.h"

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray {
namespace {

// Scene text as if it were scenes/t.sdl, so "data/texels.png" is the test image.
const std::string kSceneFile = VKRAY_SOURCE_DIR "/scenes/t.sdl";

Scene load(const std::string& text, bool lenient = false,
           std::vector<std::string>* warnings = nullptr) {
    Scene scene = parseSdl(text, kSceneFile, SdlOptions{lenient}, warnings);
    loadSceneGeometry(scene, lenient, warnings);
    return scene;
}

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.rfind(prefix, 0) == 0;
}

// scenes/data/texels.png: 8 x 4, texel (x, y) (y = 0 the top row) is
// ((32x + 16) / 255, (64y + 32) / 255, (x + y even ? 128 : 255) / 255).
TEST(Pixmaps, TheTestImageDecodesToTheKnownTexels) {
    const Scene scene = load("makePixmap 3 data/texels.png\ntexture 3 parameters 1 3 sphere");
    const Pixmap* pixmap = findPixmap(scene, 3);
    ASSERT_NE(pixmap, nullptr);
    ASSERT_TRUE(pixmap->image);
    const Image& image = *pixmap->image;
    ASSERT_EQ(image.width, 8);
    ASSERT_EQ(image.height, 4);
    ASSERT_EQ(image.channels, 3);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 8; ++x) {
            const float* texel = &image.pixels[std::size_t(y * 8 + x) * 3];
            EXPECT_EQ(texel[0], float(32 * x + 16) / 255.0f);
            EXPECT_EQ(texel[1], float(64 * y + 32) / 255.0f);
            EXPECT_EQ(texel[2], float((x + y) % 2 == 0 ? 128 : 255) / 255.0f);
        }
    }
    EXPECT_EQ(findPixmap(scene, 0), nullptr);
    EXPECT_EQ(pixmapIndexOf(scene.objects[0].material), 3);
}

TEST(Pixmaps, AMissingFileFailsAtTheMakePixmapWord) {
    const std::string message = errorOf([] { load("sphere\n  makePixmap 0 data/none.png"); });
    EXPECT_TRUE(startsWith(message, kSceneFile + ":2:3: error: cannot load pixmap 'data/none.png' "
                                                 "(makePixmap 0)\n"))
        << message;
    EXPECT_NE(message.find("none.png: No such file or directory"), std::string::npos) << message;
}

TEST(Pixmaps, AnUndecodableImageFailsAtTheMakePixmapWord) {
    const test::TempFolder scratch("vkray-pixmaps-test");
    const std::filesystem::path& folder = scratch.path();
    std::ofstream(folder / "broken.png") << "this is not a PNG";
    std::ofstream(folder / "picture.tga") << "TGA";
    const std::string file = (folder / "t.sdl").string();
    const auto loadThere = [&](const std::string& text) {
        Scene scene = parseSdl(text, file, {});
        loadSceneGeometry(scene, false, nullptr);
    };
    std::string message = errorOf([&] { loadThere("makePixmap 1 broken.png"); });
    EXPECT_TRUE(startsWith(message, file + ":1:1: error: cannot load pixmap 'broken.png'"))
        << message;
    EXPECT_NE(message.find("not a readable PNG file"), std::string::npos) << message;
    message = errorOf([&] { loadThere("\n\nmakePixmap 2 picture.tga"); });
    EXPECT_TRUE(startsWith(message, file + ":3:1: error: cannot load pixmap 'picture.tga'"))
        << message;
    EXPECT_NE(
        message.find("unsupported image format '.tga' (use .png, .pfm or .exr, or .bmp to read)"),
        std::string::npos)
        << message;
}

TEST(Pixmaps, ADuplicateIndexFailsAtTheSecondMakePixmap) {
    EXPECT_EQ(
        errorOf([] { load("makePixmap 0 data/texels.png\nmakePixmap 0 data/texels.png"); }),
        kSceneFile + ":2:1: error: makePixmap 0 is already defined at " + kSceneFile + ":1:1");
}

TEST(Pixmaps, TextureThreeNeedsAnExistingPixmapIndex) {
    EXPECT_EQ(
        errorOf([] { load("makePixmap 0 data/texels.png\n  texture 3 parameters 1 2 cube"); }),
        kSceneFile +
            ":2:3: error: texture 3 uses pixmap 2, but the scene has no 'makePixmap 2 FILE'");
    EXPECT_EQ(errorOf([] { load("texture 3 sphere"); }),
              kSceneFile +
                  ":1:1: error: texture 3 needs 'parameters 1 i' naming a 'makePixmap i FILE'; "
                  "there are no parameters");
    EXPECT_TRUE(startsWith(errorOf([] { load("texture 3 parameters 1 0.5 sphere"); }),
                           kSceneFile + ":1:1: error: texture 3 needs a pixmap index"));
    // Operands of booleans are shapes too.
    EXPECT_TRUE(startsWith(errorOf([] { load("union sphere\ntexture 3 parameters 1 4 cube"); }),
                           kSceneFile + ":2:1: error: texture 3 uses pixmap 4"));
    // A texture no shape is made with is never looked at.
    EXPECT_NO_THROW(load("sphere texture 3 parameters 1 9"));
}

TEST(Pixmaps, LenientDropsABadPixmapAndDrawsItsShapesUntextured) {
    std::vector<std::string> warnings;
    const Scene scene = load(
        "makePixmap 0 data/none.png\ntexture 3 parameters 1 0 sphere\n"
        "texture 1 parameters 0 cube",
        true, &warnings);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_TRUE(startsWith(warnings[0], kSceneFile +
                                            ":1:1: warning: cannot load pixmap 'data/none.png' "
                                            "(makePixmap 0); left out"))
        << warnings[0];
    EXPECT_EQ(warnings[1], kSceneFile +
                               ":2:1: warning: texture 3 uses pixmap 0, which could not be "
                               "loaded; the 'sphere' at " +
                               kSceneFile + ":2:26 is drawn untextured");
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].material.texture, 0);
    EXPECT_EQ(scene.objects[1].material.texture, 1);
}

TEST(TextureWord, OnlyCodesZeroToThreeAreKnown) {
    for (const char* code : {"0", "1", "2", "3"})
        EXPECT_NO_THROW(parseSdl(std::string("texture ") + code, "t.sdl", {}));
    EXPECT_EQ(errorOf([] { parseSdl("sphere\n texture 7 cube", "t.sdl", {}); }),
              "t.sdl:2:2: error: texture 7 is not one of 0 none, 1 checkerboard, 2 wood, "
              "3 image");
    EXPECT_EQ(errorOf([] { parseSdl("texture 1.5", "t.sdl", {}); }),
              "t.sdl:1:1: error: texture 1.5 is not one of 0 none, 1 checkerboard, 2 wood, "
              "3 image");
    const Scene scene = parseSdl("\n   texture 2 sphere", "t.sdl", {});
    EXPECT_EQ(scene.objects[0].material.textureLoc.str(), "t.sdl:2:4");
}

TEST(TextureWord, CellSizeAndRingWidthMustBePositive) {
    EXPECT_EQ(
        errorOf([] { load("sphere\ntexture 1 parameters 1 0 cube"); }),
        kSceneFile + ":2:1: error: texture 1 needs a checkerboard size > 0 as its first parameter");
    EXPECT_EQ(
        errorOf([] { load("texture 2 parameters 4 -1 1 0 0 cube"); }),
        kSceneFile + ":1:1: error: texture 2 needs a wood ring width > 0 as its first parameter");
    EXPECT_NO_THROW(load("texture 1 parameters 1 0.25 cube texture 2 sphere"));
}

// Lenient: a course scene's negative checker size warns with its place and
// the shape is drawn untextured, as with an unusable pixmap.
TEST(TextureWord, LenientDrawsAShapeWithAnUnusableSizeUntextured) {
    std::vector<std::string> warnings;
    const Scene scene = load("sphere\ntexture 1 parameters 4 -1 -1 1 1 cube", true, &warnings);
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[1].material.texture, 0);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], kSceneFile +
                               ":2:1: warning: texture 1 needs a checkerboard size > 0 as its "
                               "first parameter; the 'cube' at " +
                               kSceneFile + ":2:34 is drawn untextured");
}

TEST(MaxRecursionDepth, IsBoundedByTheGpuStack) {
    EXPECT_EQ(parseSdl("maxRecursionDepth 64", "t.sdl", {}).maxRecursionDepth, kMaxRecursionDepth);
    EXPECT_EQ(errorOf([] { parseSdl("light 1 2 3 1 1 1\nmaxRecursionDepth 65", "t.sdl", {}); }),
              "t.sdl:2:19: error: 'maxRecursionDepth' needs a whole number from 0 to 64, found "
              "'65' (the GPU follows reflections and refractions with a stack of that depth)");
}

}  // namespace
}  // namespace vkray
