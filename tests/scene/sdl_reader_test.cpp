#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

#include "support/temp_folder.h"
#include "util/error.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

Scene parse(const std::string& text, bool lenient = false,
            std::vector<std::string>* warnings = nullptr) {
    SdlOptions options;
    options.lenient = lenient;
    return parseSdl(text, "t.sdl", options, warnings);
}

std::string errorOf(const std::string& text, const SdlOptions& options = {}) {
    try {
        parseSdl(text, "t.sdl", options);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

// The message must hold `expected` (place and wording); the failure shows it.
#define EXPECT_ERROR(text, expected)                                                      \
    do {                                                                                  \
        const std::string message_ = errorOf(text);                                       \
        EXPECT_NE(message_.find(expected), std::string::npos) << "message: " << message_; \
    } while (0)

glm::dvec3 transformPoint(const glm::dmat4& m, const glm::dvec3& p) {
    return glm::dvec3(m * glm::dvec4(p, 1.0));
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-12) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expectInversePair(const SceneObject& object) {
    const glm::dmat4 product = object.worldFromObject * object.objectFromWorld;
    const glm::dmat4 reverse = object.objectFromWorld * object.worldFromObject;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(product[c][r], c == r ? 1.0 : 0.0, 1e-12) << c << "," << r;
            EXPECT_NEAR(reverse[c][r], c == r ? 1.0 : 0.0, 1e-12) << c << "," << r;
        }
}

// ---- scene settings -------------------------------------------------------

TEST(SdlReader, LightsRecordPositionColourAndPlace) {
    const Scene scene = parse("light 1 2 3 0.5 0.6 0.7\n  light -1 +2 .5 1 1 1");
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].position, glm::dvec3(1, 2, 3));
    EXPECT_EQ(scene.lights[0].color, glm::dvec3(0.5, 0.6, 0.7));
    EXPECT_EQ(scene.lights[0].loc.str(), "t.sdl:1:1");
    EXPECT_EQ(scene.lights[1].position, glm::dvec3(-1, 2, 0.5));
    EXPECT_EQ(scene.lights[1].loc.str(), "t.sdl:2:3");
    EXPECT_TRUE(scene.objects.empty());
    EXPECT_EQ(scene.path, "");
}

TEST(SdlReader, SceneSettingsAndTheirDefaults) {
    const Scene defaults = parse("");
    EXPECT_EQ(defaults.background, glm::dvec3(0, 0, 0.6));
    EXPECT_EQ(defaults.globalAmbient, glm::dvec3(0.1, 0.1, 0.1));
    EXPECT_EQ(defaults.minReflectivity, 0.5);
    EXPECT_EQ(defaults.minTransparency, 0.5);
    EXPECT_EQ(defaults.maxRecursionDepth, 3);
    EXPECT_FALSE(defaults.camera.has_value());

    const Scene scene = parse(
        "background 0.1 0.2 0.3 globalAmbient 0.4 0.5 0.6\n"
        "minReflectivity 0.7 minTransparency 0.8 maxRecursionDepth 6");
    EXPECT_EQ(scene.background, glm::dvec3(0.1, 0.2, 0.3));
    EXPECT_EQ(scene.globalAmbient, glm::dvec3(0.4, 0.5, 0.6));
    EXPECT_EQ(scene.minReflectivity, 0.7);
    EXPECT_EQ(scene.minTransparency, 0.8);
    EXPECT_EQ(scene.maxRecursionDepth, 6);
    EXPECT_EQ(parse("maxRecursionDepth 0").maxRecursionDepth, 0);
}

TEST(SdlReader, MaxRecursionDepthIsAWholeNumber) {
    EXPECT_ERROR("maxRecursionDepth 2.5", "t.sdl:1:19: error: 'maxRecursionDepth' needs");
    EXPECT_ERROR("\nmaxRecursionDepth -1", "t.sdl:2:19: error:");
}

// ---- transforms -----------------------------------------------------------

TEST(SdlReader, TranslateThenScaleComposesByPostMultiplying) {
    const Scene scene = parse("translate 1 2 3 scale 2 2 2 sphere");
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& s = scene.objects[0];
    // M = T * S: the generic point is scaled first, then moved.
    expectNear(transformPoint(s.worldFromObject, {1, 0, 0}), {3, 2, 3});
    expectNear(transformPoint(s.objectFromWorld, {3, 2, 3}), {1, 0, 0});
    expectInversePair(s);
}

TEST(SdlReader, TranslateAlone) {
    const SceneObject s = parse("translate -1 0.5 4 cube").objects.at(0);
    expectNear(transformPoint(s.worldFromObject, {0, 0, 0}), {-1, 0.5, 4});
    expectInversePair(s);
}

TEST(SdlReader, RotateTurnsAboutANormalisedAxis) {
    for (const char* text : {"rotate 90 0 0 1 sphere", "rotate 90 0 0 5 sphere"}) {
        const SceneObject s = parse(text).objects.at(0);
        expectNear(transformPoint(s.worldFromObject, {1, 0, 0}), {0, 1, 0});
        expectNear(transformPoint(s.worldFromObject, {0, 0, 2}), {0, 0, 2});
        expectInversePair(s);
    }
    // Right-handed about +x: y goes to z.
    const SceneObject x = parse("rotate 90 1 0 0 sphere").objects.at(0);
    expectNear(transformPoint(x.worldFromObject, {0, 1, 0}), {0, 0, 1});
}

TEST(SdlReader, RotateThenTranslateMovesAlongTheTurnedAxis) {
    // M = R * T: the translation happens in the rotated frame.
    const SceneObject s = parse("rotate 90 0 0 1 translate 1 0 0 sphere").objects.at(0);
    expectNear(transformPoint(s.worldFromObject, {0, 0, 0}), {0, 1, 0});
    expectInversePair(s);
}

TEST(SdlReader, ScaleAlone) {
    const SceneObject s = parse("scale 2 -3 0.25 sphere").objects.at(0);
    expectNear(transformPoint(s.worldFromObject, {1, 1, 1}), {2, -3, 0.25});
    expectInversePair(s);
}

TEST(SdlReader, LongChainsKeepAnExactInverse) {
    const SceneObject s = parse(
                              "translate 3 -2 7 rotate 33 1 2 3 scale 0.5 3 2 rotate -71 0 1 1 "
                              "translate 0.3 0.3 -9 scale 1.5 0.25 1 rotate 12 -1 0 0.5 sphere")
                              .objects.at(0);
    expectInversePair(s);
}

TEST(SdlReader, PushPopSaveTheTransformOnly) {
    const Scene scene = parse(
        "translate 1 0 0 push translate 0 5 0 diffuse 0.1 0.2 0.3 sphere pop cube\n"
        "push scale 2 2 2 push identityAffine plane pop square pop");
    ASSERT_EQ(scene.objects.size(), 4u);
    expectNear(transformPoint(scene.objects[0].worldFromObject, {0, 0, 0}), {1, 5, 0});
    // pop restores both matrices...
    expectNear(transformPoint(scene.objects[1].worldFromObject, {0, 0, 0}), {1, 0, 0});
    expectNear(transformPoint(scene.objects[1].objectFromWorld, {1, 0, 0}), {0, 0, 0});
    // ...but not the material, which is global state.
    EXPECT_EQ(scene.objects[1].material.diffuse, glm::dvec3(0.1, 0.2, 0.3));
    // identityAffine resets the current transform, not the saved ones.
    EXPECT_EQ(scene.objects[2].worldFromObject, glm::dmat4(1.0));
    EXPECT_EQ(scene.objects[2].objectFromWorld, glm::dmat4(1.0));
    expectNear(transformPoint(scene.objects[3].worldFromObject, {1, 1, 1}), {3, 2, 2});
}

TEST(SdlReader, TransformErrors) {
    EXPECT_ERROR("push pop\n  pop", "t.sdl:2:3: error: 'pop' without a matching 'push'");
    EXPECT_ERROR("sphere\nscale 1 0 1",
                 "t.sdl:2:1: error: scale factor 0 makes the transform singular");
    EXPECT_ERROR("scale 0 0 0", "t.sdl:1:1: error: scale factor 0");
    EXPECT_ERROR("\n\n rotate 30 0 0 0", "t.sdl:3:2: error: rotate axis 0 0 0");
}

// ---- materials --------------------------------------------------------------

TEST(SdlReader, MaterialIsCopiedIntoEachShapeWhenMade) {
    const Scene scene = parse(
        "sphere\n"
        "ambient 0.1 0.2 0.3 diffuse 0.4 0.5 0.6 specular 0.7 0.8 0.9 emissive 1 0 0.5\n"
        "specularExponent 30 reflectivity 0.25 transparency 0.5 speedOfLight 0.75\n"
        "specularFraction 0.125 surfaceRoughness 0.0625 texture 2 parameters 3 1.5 -2 4\n"
        "cube\n"
        "diffuse 0 0 0 defaultMaterials square");
    ASSERT_EQ(scene.objects.size(), 3u);
    const Material defaults;
    EXPECT_EQ(scene.objects[0].material.diffuse, defaults.diffuse);
    const Material& m = scene.objects[1].material;
    EXPECT_EQ(m.ambient, glm::dvec3(0.1, 0.2, 0.3));
    EXPECT_EQ(m.diffuse, glm::dvec3(0.4, 0.5, 0.6));
    EXPECT_EQ(m.specular, glm::dvec3(0.7, 0.8, 0.9));
    EXPECT_EQ(m.emissive, glm::dvec3(1, 0, 0.5));
    EXPECT_EQ(m.specularExponent, 30);
    EXPECT_EQ(m.reflectivity, 0.25);
    EXPECT_EQ(m.transparency, 0.5);
    EXPECT_EQ(m.speedOfLight, 0.75);
    EXPECT_EQ(m.specularFraction, 0.125);
    EXPECT_EQ(m.surfaceRoughness, 0.0625);
    EXPECT_EQ(m.texture, 2);
    EXPECT_EQ(m.textureParameters, (std::vector<double>{1.5, -2, 4}));
    // defaultMaterials goes back to Material{} in every field.
    const Material& reset = scene.objects[2].material;
    EXPECT_EQ(reset.ambient, defaults.ambient);
    EXPECT_EQ(reset.diffuse, defaults.diffuse);
    EXPECT_EQ(reset.specular, defaults.specular);
    EXPECT_EQ(reset.emissive, defaults.emissive);
    EXPECT_EQ(reset.specularExponent, defaults.specularExponent);
    EXPECT_EQ(reset.reflectivity, defaults.reflectivity);
    EXPECT_EQ(reset.speedOfLight, defaults.speedOfLight);
    EXPECT_EQ(reset.texture, 0);
    EXPECT_TRUE(reset.textureParameters.empty());
}

TEST(SdlReader, MakePixmapResolvesItsFileAgainstTheSceneFolder) {
    const Scene scene = parseSdl("makePixmap 2 wood.bmp", "dir/sub/t.sdl", {});
    ASSERT_EQ(scene.pixmaps.size(), 1u);
    EXPECT_EQ(scene.pixmaps[0].index, 2);
    EXPECT_EQ(fs::path(scene.pixmaps[0].file), fs::path("dir/sub/wood.bmp"));
    EXPECT_EQ(scene.pixmaps[0].loc.str(), "dir/sub/t.sdl:1:1");
}

// ---- shapes -----------------------------------------------------------------

TEST(SdlReader, EveryShapeKeywordMakesItsShape) {
    const Scene scene = parse(
        "sphere plane square cube cylinder cone taperedCylinder 0.3 torus teapot tetrahedron\n"
        "octahedron dodecahedron icosahedron buckyball diamond mesh pawn.3vn extrude arch.dat");
    const ShapeType expected[] = {
        ShapeType::Sphere,          ShapeType::Plane,
        ShapeType::Square,          ShapeType::Cube,
        ShapeType::Cylinder,        ShapeType::Cone,
        ShapeType::TaperedCylinder, ShapeType::Torus,
        ShapeType::Teapot,          ShapeType::Tetrahedron,
        ShapeType::Octahedron,      ShapeType::Dodecahedron,
        ShapeType::Icosahedron,     ShapeType::Buckyball,
        ShapeType::Diamond,         ShapeType::Mesh,
        ShapeType::Extrude,
    };
    ASSERT_EQ(scene.objects.size(), std::size(expected));
    for (size_t i = 0; i < std::size(expected); ++i)
        EXPECT_EQ(scene.objects[i].type, expected[i]) << i;
    EXPECT_EQ(scene.objects[4].taper, 1);    // cylinder
    EXPECT_EQ(scene.objects[5].taper, 0);    // cone
    EXPECT_EQ(scene.objects[6].taper, 0.3);  // taperedCylinder 0.3
    EXPECT_EQ(scene.objects[0].taper, 1);
    EXPECT_EQ(scene.objects[15].file, "pawn.3vn");
    EXPECT_EQ(scene.objects[16].file, "arch.dat");
    EXPECT_EQ(scene.objects[7].loc.str(), "t.sdl:1:60");  // torus
    EXPECT_EQ(scene.objects[10].loc.str(), "t.sdl:2:1");  // octahedron
}

TEST(SdlReader, MeshAndExtrudeFilesAreResolvedButNotRead) {
    const Scene scene = parseSdl("mesh pawn.3vn extrude ../hlArch.dat", "a/b/t.sdl", {});
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(fs::path(scene.objects[0].file), fs::path("a/b/pawn.3vn"));
    EXPECT_EQ(fs::path(scene.objects[1].file), fs::path("a/b/../hlArch.dat"));
    EXPECT_ERROR("mesh", "t.sdl:1:1: error: 'mesh' is missing a file name");
    EXPECT_ERROR("mesh }", "t.sdl:1:6: error: expected a file name");
}

TEST(SdlReader, BooleansTakeTheNextTwoObjects) {
    const Scene scene = parse(
        "union sphere translate 1 0 0 cube plane\n"
        "difference intersection cone sphere push scale 2 2 2 cube pop square");
    ASSERT_EQ(scene.objects.size(), 4u);
    const SceneObject& u = scene.objects[0];
    EXPECT_EQ(u.type, ShapeType::Union);
    EXPECT_EQ(u.loc.str(), "t.sdl:1:1");
    ASSERT_EQ(u.operands.size(), 2u);
    EXPECT_EQ(u.operands[0].type, ShapeType::Sphere);
    EXPECT_EQ(u.operands[1].type, ShapeType::Cube);
    // Statements between operands act as anywhere else.
    expectNear(transformPoint(u.operands[1].worldFromObject, {0, 0, 0}), {1, 0, 0});
    EXPECT_EQ(scene.objects[1].type, ShapeType::Plane);

    const SceneObject& d = scene.objects[2];
    EXPECT_EQ(d.type, ShapeType::Difference);
    ASSERT_EQ(d.operands.size(), 2u);
    EXPECT_EQ(d.operands[0].type, ShapeType::Intersection);
    ASSERT_EQ(d.operands[0].operands.size(), 2u);
    EXPECT_EQ(d.operands[0].operands[0].type, ShapeType::Cone);
    EXPECT_EQ(d.operands[0].operands[1].type, ShapeType::Sphere);
    EXPECT_EQ(d.operands[1].type, ShapeType::Cube);
    EXPECT_TRUE(d.operands[1].operands.empty());
    EXPECT_EQ(scene.objects[3].type, ShapeType::Square);
}

TEST(SdlReader, BooleanWithoutTwoObjectsIsAnError) {
    EXPECT_ERROR("sphere\n  union cube", "t.sdl:2:3: error: 'union' needs two objects");
    EXPECT_ERROR("intersection", "t.sdl:1:1: error: 'intersection' needs two objects");
    EXPECT_ERROR("cube difference sphere union cube",
                 "t.sdl:1:24: error: 'union' needs two objects");
}

TEST(SdlReader, DeeplyNestedBooleansDoNotOverflowTheStack) {
    std::string nested;
    for (int i = 0; i < 500; ++i) nested += "union sphere ";
    const Scene scene = parse(nested + "cube");
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].operands.at(1).type, ShapeType::Union);
    std::string tooDeep;
    for (int i = 0; i < 100000; ++i) tooDeep += "union ";
    // Refused at the first boolean beyond kMaxCsgDepth (scene_limits_test.cpp).
    EXPECT_ERROR(tooDeep, "t.sdl:1:6001: error: 'union' nests booleans 1001 deep");
}

// ---- def / use ----------------------------------------------------------------

TEST(SdlReader, UsePastesTextSoATransformInADefMovesLaterShapes) {
    const Scene scene = parse(
        "def step { translate 1 0 0 }\n"
        "def ball { push scale 0.5 0.5 0.5 sphere pop }\n"
        "use step use step use ball\n"
        "cube");
    ASSERT_EQ(scene.objects.size(), 2u);
    expectNear(transformPoint(scene.objects[0].worldFromObject, {1, 0, 0}), {2.5, 0, 0});
    // The def's translate changed the caller's state, after the def's push/pop.
    expectNear(transformPoint(scene.objects[1].worldFromObject, {0, 0, 0}), {2, 0, 0});
    // A pasted shape's place is where it was written.
    EXPECT_EQ(scene.objects[0].loc.str(), "t.sdl:2:35");
    expectInversePair(scene.objects[0]);
}

TEST(SdlReader, DefsAndUsesMayStandBetweenArguments) {
    const Scene scene = parse(
        "def xy { 1 2 } def mat { diffuse 0.5 0.5 0.5 }\n"
        "translate use xy 3 use mat sphere");
    expectNear(transformPoint(scene.objects.at(0).worldFromObject, {0, 0, 0}), {1, 2, 3});
    EXPECT_EQ(scene.objects.at(0).material.diffuse, glm::dvec3(0.5));
}

TEST(SdlReader, LaterDefReplacesEarlierOne) {
    const Scene scene = parse("def s { sphere } use s def s { cube } use s");
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].type, ShapeType::Sphere);
    EXPECT_EQ(scene.objects[1].type, ShapeType::Cube);
}

TEST(SdlReader, ErrorInsideADefNamesTheDefAndTheUse) {
    const std::string message = errorOf("def bad { light 1 x 3 1 1 1 }\nsphere\n use bad");
    EXPECT_EQ(message,
              "t.sdl:1:19: error: expected a number after 'light', found 'x'\n"
              "t.sdl:3:2: note: in text pasted by 'use bad'");
    const std::string nested =
        errorOf("def inner { bogus }\ndef outer { cube use inner }\nuse outer");
    EXPECT_EQ(nested,
              "t.sdl:1:13: error: unknown keyword 'bogus'\n"
              "t.sdl:2:18: note: in text pasted by 'use inner'\n"
              "t.sdl:3:1: note: in text pasted by 'use outer'");
}

TEST(SdlReader, DefUseErrors) {
    EXPECT_ERROR("sphere\ndef a { push\n  { sphere }", "t.sdl:2:7: error: '{' is never closed");
    EXPECT_ERROR("def a { sphere }\n sphere }", "t.sdl:2:9: error: '}' without a matching '{'");
    EXPECT_ERROR("sphere\n\n  use missing", "t.sdl:3:3: error: 'use missing': no def named");
    EXPECT_ERROR("def a { cube use a }\nuse a", "t.sdl:1:14: error: recursive 'use a' (a -> a)");
    EXPECT_ERROR("def a { use b }\ndef b { sphere use a }\nuse a",
                 "t.sdl:2:16: error: recursive 'use a' (a -> b -> a)");
    EXPECT_ERROR("{ sphere }", "t.sdl:1:1: error: '{' outside a def");
}

TEST(SdlReader, ExponentialPastingHitsTheDefaultLimit) {
    // 2^40 pastes of `identityAffine` if nothing stopped it.
    std::string text = "def a0 { identityAffine }\n";
    for (int i = 1; i <= 40; ++i)
        text += "def a" + std::to_string(i) + " { use a" + std::to_string(i - 1) + " use a" +
                std::to_string(i - 1) + " }\n";
    text += "\nuse a40\n";
    const std::string message = errorOf(text);
    EXPECT_NE(message.find("would paste more than 5000000 tokens"), std::string::npos) << message;
    EXPECT_NE(message.find("t.sdl:43:1: note: in text pasted by 'use a40'"), std::string::npos)
        << message.substr(0, 400);
}

// ---- numbers and arguments -------------------------------------------------------

TEST(SdlReader, MalformedNumbersNameThePlaceAndTheKeyword) {
    EXPECT_ERROR("sphere\n\nlight abc 1 1 1 1 1",
                 "t.sdl:3:7: error: expected a number after 'light', found 'abc'");
    EXPECT_ERROR("translate 1.2.3 0 0", "t.sdl:1:11: error: expected a number after 'translate'");
    EXPECT_ERROR("light 1 2 sphere 1 1 1", "t.sdl:1:11: error: expected a number after 'light'");
    EXPECT_ERROR("cube\n  diffuse nan 0 0", "t.sdl:2:11: error:");
    EXPECT_ERROR("cube\n  diffuse nan 0 0", "'nan'");
    EXPECT_ERROR("specular 1 1 inf", "t.sdl:1:14: error:");
    EXPECT_ERROR("background 0 1e999 0", "t.sdl:1:14: error: number '1e999'");
    EXPECT_ERROR("background 0 1e999 0", "out of range");
}

TEST(SdlReader, MissingArgumentAtEndOfFileIsReportedAtTheKeyword) {
    EXPECT_ERROR("sphere\n light 1 2 3 1 1", "t.sdl:2:2: error: 'light' is missing a number");
    EXPECT_ERROR("rotate 45", "t.sdl:1:1: error: 'rotate' is missing a number (end of file)");
    EXPECT_ERROR("cube taperedCylinder", "t.sdl:1:6: error: 'taperedCylinder' is missing");
}

TEST(SdlReader, NumbersInTheFormsOldFilesUse) {
    const Scene scene = parse("light +1 .5 -4.75071e-009 1. 2.5E-1 -0");
    EXPECT_EQ(scene.lights.at(0).position, glm::dvec3(1, 0.5, -4.75071e-9));
    EXPECT_EQ(scene.lights.at(0).color, glm::dvec3(1, 0.25, 0));
}

// ---- strict and lenient ------------------------------------------------------------

TEST(SdlReader, StrictModeRefusesUnknownWords) {
    EXPECT_ERROR("sphere\nexponent 50", "t.sdl:2:1: error: unknown keyword 'exponent'");
    EXPECT_ERROR("light 1 2 3 1 1 1 7", "t.sdl:1:19: error: expected a keyword, found the number");
    EXPECT_ERROR("Sphere", "unknown keyword 'Sphere'");  // keywords are case sensitive
    // Binary junk is quoted as \xNN: a NUL would cut the message short.
    EXPECT_ERROR(std::string("sphere\nab\0\xff\xfe", 12),
                 "t.sdl:2:1: error: unknown keyword 'ab\\x00\\xff\\xfe'");
}

TEST(SdlReader, LenientModeSkipsUnknownWordsAndTheirNumbersWithAWarning) {
    std::vector<std::string> warnings;
    const Scene scene =
        parse("sphere\n  exponent 50 60 cube\nfoo diffuse 1 1 1 bar 3 square\n", true, &warnings);
    ASSERT_EQ(scene.objects.size(), 3u);
    EXPECT_EQ(scene.objects[1].type, ShapeType::Cube);
    EXPECT_EQ(scene.objects[2].material.diffuse, glm::dvec3(1));
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warnings[0],
              "t.sdl:2:3: warning: unknown keyword 'exponent' skipped (with 2 numbers after it)");
    EXPECT_EQ(warnings[1],
              "t.sdl:3:1: warning: unknown keyword 'foo' skipped (with 0 numbers after it)");
    EXPECT_EQ(warnings[2],
              "t.sdl:3:19: warning: unknown keyword 'bar' skipped (with 1 number after it)");
    // Warnings may be dropped, but the skipping is the same.
    EXPECT_EQ(parse("exponent 5 sphere", true).objects.size(), 1u);
}

TEST(SdlReader, LenientModeStillRefusesStrayBracesAndBadArguments) {
    SdlOptions lenient;
    lenient.lenient = true;
    EXPECT_NE(errorOf("sphere }", lenient).find("t.sdl:1:8: error: '}' without a matching '{'"),
              std::string::npos);
    EXPECT_NE(errorOf("light 1 x 1 1 1 1", lenient).find("t.sdl:1:9: error:"), std::string::npos);
}

// Hill's course files write `texture -1`: lenient reads an unknown code as
// none, with a warning at the word; strict refuses it there, naming the codes.
TEST(SdlReader, LenientModeReadsAnUnknownTextureCodeAsNone) {
    std::vector<std::string> warnings;
    const Scene scene =
        parse("texture 1 sphere\n  texture -1 cube\ntexture 2 square\n", true, &warnings);
    ASSERT_EQ(scene.objects.size(), 3u);
    EXPECT_EQ(scene.objects[0].material.texture, 1);
    EXPECT_EQ(scene.objects[1].material.texture, 0);
    EXPECT_EQ(scene.objects[2].material.texture, 2);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(
        warnings[0],
        "t.sdl:2:3: warning: texture -1 is not one of 0 none, 1 checkerboard, 2 wood, 3 image; "
        "drawn without a texture (as texture 0)");
    EXPECT_EQ(parse("texture 7.5 sphere", true).objects.at(0).material.texture,
              0);  // warnings dropped
    EXPECT_ERROR(
        "sphere\n  texture -1 cube",
        "t.sdl:2:3: error: texture -1 is not one of 0 none, 1 checkerboard, 2 wood, 3 image");
}

// ---- camera extension ---------------------------------------------------------------

TEST(SdlReader, CameraPartsInAnyOrderEachOptional) {
    const Scene scene = parse("camera fov 40 up 0 0 1 eye 1 2 3 look 4 5 6 sphere");
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(scene.camera->look, glm::dvec3(4, 5, 6));
    EXPECT_EQ(scene.camera->up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(scene.camera->fovDegrees, 40);
    EXPECT_EQ(scene.objects.size(), 1u);  // the camera statement ended at `sphere`

    const Scene partial = parse("camera eye 0 0 9");
    ASSERT_TRUE(partial.camera.has_value());
    EXPECT_EQ(partial.camera->eye, glm::dvec3(0, 0, 9));
    EXPECT_EQ(partial.camera->look, Camera{}.look);
    EXPECT_EQ(partial.camera->fovDegrees, Camera{}.fovDegrees);
}

TEST(SdlReader, CameraFovMustBeBetween0And180) {
    EXPECT_ERROR("sphere\ncamera eye 1 1 1 fov 0", "t.sdl:2:22: error: camera fov 0 is outside");
    EXPECT_ERROR("camera fov 180", "t.sdl:1:12: error:");
    EXPECT_ERROR("camera fov -5", "t.sdl:1:12: error:");
    EXPECT_EQ(parse("camera fov 179.5").camera->fovDegrees, 179.5);
    EXPECT_ERROR("camera eye 1 2", "t.sdl:1:8: error: 'eye' is missing a number");
}

// ---- text forms -------------------------------------------------------------------

TEST(SdlReader, CrlfAndLatin1InCommentsAreFine) {
    const Scene scene = parse("! caf\xe9 \x96 old file\r\nlight 1 2 3 1 1 1\r\n\r\n  sphere\r\n");
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].loc.str(), "t.sdl:4:3");
    EXPECT_EQ(scene.lights.size(), 1u);
}

// ---- files ------------------------------------------------------------------------

class SdlFileTest : public ::testing::Test {
protected:
    test::TempFolder scratch_{"vkray-sdl-reader"};
    const fs::path folder_ = scratch_.path();
};

TEST_F(SdlFileTest, LoadsAFileAndResolvesMeshesNextToIt) {
    const fs::path file = folder_ / "scene.sdl";
    std::ofstream(file) << "mesh pawn.3vn\nfoo\n";
    const std::string message = [&] {
        try {
            loadSdlFile(file.string(), {});
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    }();
    EXPECT_EQ(message, file.string() + ":2:1: error: unknown keyword 'foo'");

    std::vector<std::string> warnings;
    const Scene scene = loadSdlFile(file.string(), {true}, &warnings);
    EXPECT_EQ(scene.path, file.string());
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(fs::path(scene.objects[0].file), folder_ / "pawn.3vn");
    EXPECT_EQ(warnings.size(), 1u);
}

TEST_F(SdlFileTest, MissingFileOrFolderIsAnErrorNamingThePath) {
    const std::string missing = (folder_ / "no_such.sdl").string();
    try {
        loadSdlFile(missing, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  missing + ": error: cannot read scene file: No such file or directory");
    }
    try {
        loadSdlFile(folder_.string(), {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(folder_.string() + ": error: cannot read"),
                  std::string::npos)
            << e.what();
    }
}

TEST(SdlReader, EveryErrorOfAFileIsReportedAtItsPlace) {
    const std::string path = VKRAY_SOURCE_DIR "/tests/data/three_errors.sdl";
    try {
        loadSdlFile(path, {});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  path + ":3:15: error: expected a number after 'translate', found 'x'\n" + path +
                      ":5:1: error: scale factor 0 makes the transform singular\n" + path +
                      ":6:1: error: 'pop' without a matching 'push'");
    }
}

TEST(SdlReader, AStatementInErrorIsSkippedUpToTheNextKeyword) {
    // The numbers after the bad one belong to the statement in error: they
    // are not reported again as stray numbers.
    EXPECT_EQ(errorOf("translate 1 x 3 4\nsphere\n"),
              "t.sdl:1:13: error: expected a number after 'translate', found 'x'");
    EXPECT_EQ(errorOf("pop\npop\n"),
              "t.sdl:1:1: error: 'pop' without a matching 'push'\n"
              "t.sdl:2:1: error: 'pop' without a matching 'push'");
}

}  // namespace
}  // namespace vkray
