// `vkray features SCENE` as a user runs it: the report for known scenes,
// worked out by hand from the scene files, and its key is the one `render`
// compiles.
#include "support/cli_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>

namespace {

using vkray::test::RunResult;
using vkray::test::vkray;
using Features = vkray::test::CliTest;

const std::string kScenes = VKRAY_SOURCE_DIR "/scenes/";

// The text after "label: " on the report's line for `label`.
std::string field(const std::string& output, const std::string& label) {
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind(label + ": ", 0) == 0) return line.substr(label.size() + 2);
    return "(no " + label + " line)";
}

// The buffer lines ("  1 objects  storage  480 bytes (5 x 96)"), squeezed to single spaces.
std::vector<std::string> buffers(const std::string& output) {
    std::vector<std::string> result;
    const size_t start = output.find("buffers:\n");
    if (start == std::string::npos) return result;
    std::istringstream lines(output.substr(start + 9));
    for (std::string line; std::getline(lines, line) && line.rfind("  ", 0) == 0;)
        result.push_back(
            std::regex_replace(line.substr(line.find_first_not_of(' ')), std::regex(" +"), " "));
    return result;
}

TEST_F(Features, DefaultSceneReport) {
    // default.sdl: a plane, a sphere, a cube, an ellipsoid (sphere) and a
    // square; three lights; 4 bounded objects, so no object BVH.
    RunResult run = vkray("features " + kScenes + "default.sdl");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_EQ(field(run.output, "scene"), kScenes + "default.sdl (5 objects, 3 lights)");
    EXPECT_EQ(field(run.output, "shapes"), "2 sphere, 1 plane, 1 square, 1 cube");
    EXPECT_EQ(field(run.output, "booleans"), "none");
    EXPECT_EQ(field(run.output, "meshes"), "none");
    EXPECT_EQ(field(run.output, "object BVH"),
              "no (4 bounded objects; more than 8, or two with a mesh, get one); each object "
              "tested in turn, "
              "the loop unrolled over the 5, each test its object's shape's code alone");
    EXPECT_EQ(field(run.output, "lights"), "3");
    EXPECT_EQ(field(run.output, "shadows"), "yes (3 lights, 5 objects)");
    EXPECT_EQ(field(run.output, "reflection"),
              "no (no object has reflectivity > minReflectivity 0.5 (highest 0))");
    EXPECT_EQ(field(run.output, "variant"), "sphere+plane+square+cube+shadows");
    EXPECT_EQ(field(run.output, "AOVs"),
              "object id; depth and normal with render --aov (variant "
              "sphere+plane+square+cube+shadows+aovs)");
    EXPECT_EQ(field(run.output, "defines"),
              "VKRAY_SHAPE_SPHERE=1 VKRAY_SHAPE_PLANE=1 VKRAY_SHAPE_SQUARE=1 VKRAY_SHAPE_CUBE=1 "
              "VKRAY_SHADOWS=1 VKRAY_LIGHTS=1 VKRAY_OBJECTS=5 VKRAY_OBJECT_KINDS=1u,0u,3u,0u,2u "
              "(every other variant flag 0)");
    // GpuObjectGeometry is 4 vec4 (64 bytes), GpuMaterial 6 (96), GpuLight 2
    // (32), FrameParams 9 (144).
    const std::vector<std::string> expected{
        "0 frame storage 144 bytes",
        "21 tile storage 48 bytes",
        "1 objects texels 320 bytes (5 x 64)",
        "18 materials texels 480 bytes (5 x 96)",
        "2 lights texels 96 bytes (3 x 32)",
        "3 pixels texels one tile of 32-byte pixels",
        "20 ray groups texels one tile's workgroups, 4 bytes each",
        // Feelers but no secondary rays, one sample: no ray pauses, no progress.
        "16 dispatch status storage 16 bytes",
    };
    EXPECT_EQ(buffers(run.output), expected) << run.output;
}

TEST_F(Features, MeshSceneBindsMeshAndBvhBuffers) {
    // meshes.sdl: a plane, a 3VN mesh (16 triangles), an extruded outline
    // (12) and 10 balls: 12 bounded objects, so the object BVH; two meshes.
    // In the textbook mode each mesh is walked in its own space, entered by
    // the objects' walk; in the robust mode their triangles go into the
    // object BVH in world space.
    for (const bool world : {false, true}) {
        SCOPED_TRACE(world ? "robust" : "naive");
        RunResult run =
            vkray("features " + kScenes + "meshes.sdl" + (world ? "" : " --precision naive"));
        ASSERT_EQ(run.status, 0) << run.output;
        EXPECT_EQ(field(run.output, "shapes"), "10 sphere, 1 plane, 1 mesh, 1 extrude");
        EXPECT_EQ(field(run.output, "meshes"),
                  world ? "2 (28 triangles); the mesh objects' 28 triangles in the object BVH, "
                          "placed in world space"
                        : "2 (28 triangles); each mesh walked in its own space (world space "
                          "takes opaque meshes near the eye, up to 2097152 triangles, in the "
                          "robust mode)");
        EXPECT_EQ(field(run.output, "object BVH").substr(0, 24), "yes (12 bounded objects;");
        EXPECT_EQ(field(run.output, "variant"),
                  world ? "sphere+plane+mesh+shadows+bvh+world-triangles"
                        : "sphere+plane+mesh+shadows+bvh");
        EXPECT_EQ(field(run.output, "defines"),
                  std::string("VKRAY_SHAPE_SPHERE=1 VKRAY_SHAPE_PLANE=1 VKRAY_SHAPE_MESH=1 "
                              "VKRAY_SHADOWS=1 VKRAY_LIGHTS=1 VKRAY_OBJECT_BVH=1 ") +
                      (world ? "VKRAY_WORLD_TRIANGLES=1" : "VKRAY_PRECISION_NAIVE=1") +
                      " (every other variant flag 0)");
        const std::vector<std::string> lines = buffers(run.output);
        std::vector<std::string> bound;
        for (const std::string& line : lines)
            bound.push_back(line.substr(0, std::min(line.find(" storage"), line.find(" texels"))));
        std::vector<std::string> expected{"0 frame",
                                          "21 tile",
                                          "1 objects",
                                          "18 materials",
                                          "2 lights",
                                          "3 pixels",
                                          "20 ray groups",
                                          "16 dispatch status",
                                          "5 object BVH nodes",
                                          "6 object BVH index",
                                          "7 meshes",
                                          "9 triangles"};
        // The meshes' BVH nodes follow the objects' in 5, one walk taking
        // both; apart in 8 where only a mesh in CSG would walk them.
        if (world) expected.insert(expected.end() - 1, "8 mesh BVH nodes");
        EXPECT_EQ(bound, expected) << run.output;
        // 10 balls + mesh + extrusion in the BVH's index, then the plane; in
        // world space the balls and the plane, the 28 triangles and their
        // copies in world space in 9.
        for (const char* line :
             world ? std::vector<const char*>{"6 object BVH index texels 44 bytes (11 x 4)",
                                              "9 triangles texels 5376 bytes (56 x 96)"}
                   : std::vector<const char*>{"6 object BVH index texels 52 bytes (13 x 4)",
                                              "9 triangles texels 2688 bytes (28 x 96)"})
            EXPECT_NE(std::find(lines.begin(), lines.end(), line), lines.end()) << line << "\n"
                                                                                << run.output;
    }
}

TEST_F(Features, FeelersTakeHintsInABvhWithoutPlanes) {
    // tests/data/shadow_hints.sdl: 14 bounded objects, three lights, no plane.
    RunResult run = vkray("features " VKRAY_SOURCE_DIR "/tests/data/shadow_hints.sdl");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_EQ(field(run.output, "shadows"),
              "yes (3 lights, 14 objects); each feeler's walk first tests what stopped the "
              "feeler toward the same light two pixels above");
    EXPECT_NE(field(run.output, "defines").find("VKRAY_FEELER_HINTS=1"), std::string::npos)
        << run.output;
}

TEST_F(Features, ALoneObjectIsTestedAloneWhateverItsShape) {
    // A torus or a mesh among others keeps the loop over the run-time count;
    // alone, its test is the walk (no loop, its code once). An opaque mesh
    // alone goes into world space, in a BVH of its own (the next test).
    for (const char* shape : {"torus", "transparency 0.5 tetrahedron"}) {
        RunResult run =
            vkray("features " + scene("lone.sdl", std::string("light 2 3 4 1 1 1\n") + shape));
        ASSERT_EQ(run.status, 0) << run.output;
        EXPECT_EQ(field(run.output, "object BVH"),
                  "no (1 bounded objects; more than 8, or two with a mesh, get one); the one "
                  "object tested alone, with its shape's code only")
            << shape;
        EXPECT_NE(field(run.output, "defines").find("VKRAY_OBJECTS=1 VKRAY_OBJECT_KINDS="),
                  std::string::npos)
            << run.output;
    }
}

TEST_F(Features, ALoneOpaqueMeshNearTheEyeIsWalkedAsTrianglesInWorldSpace) {
    const std::string lone = "light 2 3 4 1 1 1\ncamera eye 3 2 4\ntetrahedron\n";
    RunResult run = vkray("features " + scene("lone.sdl", lone));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_EQ(field(run.output, "object BVH"),
              "yes (1 bounded objects; more than 8, or two with a mesh, get one; so do "
              "triangles in world space)");
    EXPECT_EQ(field(run.output, "variant"), "mesh+shadows+bvh+world-triangles");
    // From 1e5 away, over 4096 of the tetrahedron's sizes, its walk starts near
    // it in its own space instead.
    RunResult far =
        vkray("features " + scene("far.sdl", std::string(lone) + "camera eye 0 0 100000\n") +
              " --precision robust");
    ASSERT_EQ(far.status, 0) << far.output;
    EXPECT_EQ(field(far.output, "variant"), "mesh+shadows") << far.output;
}

TEST_F(Features, VariantAllCompilesEveryFeatureAndBindsTheirBuffers) {
    RunResult run = vkray("features " + kScenes + "default.sdl --variant all -D EXTRA=2");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_EQ(field(run.output, "variant"), "all shapes+all shading+blocks");
    EXPECT_EQ(field(run.output, "defines"),
              "VKRAY_SHAPE_SPHERE=1 VKRAY_SHAPE_PLANE=1 VKRAY_SHAPE_SQUARE=1 VKRAY_SHAPE_CUBE=1 "
              "VKRAY_SHAPE_TAPERED_CYLINDER=1 VKRAY_SHAPE_TORUS=1 VKRAY_SHAPE_MESH=1 VKRAY_CSG=1 "
              "VKRAY_SHADOWS=1 VKRAY_REFLECTION=1 VKRAY_REFRACTION=1 VKRAY_TEXTURES=1 "
              "VKRAY_PIXMAPS=1 VKRAY_ANTIALIAS=1 VKRAY_LIGHTS=1 VKRAY_BLOCKS=1 VKRAY_KEEP_TORI=1 "
              "EXTRA=2 (every other "
              "variant flag 0)");
    // The scene's own needs are still reported as the scene's.
    EXPECT_EQ(field(run.output, "reflection").substr(0, 3), "no ") << run.output;
    // The pending rays (maxRecursionDepth 3 + 1 entries), the mesh, CSG and
    // pixmap arrays are bound (empty: one element, as Vulkan wants).
    const std::vector<std::string> lines = buffers(run.output);
    ASSERT_EQ(lines.size(), 16u) << run.output;
    EXPECT_EQ(lines[9], "17 pending rays storage one tile of 4-entry stacks of 64-byte rays");
    EXPECT_EQ(lines[12],
              "9 triangles texels empty (one 96-byte element: Vulkan has no empty buffers)");
    EXPECT_EQ(lines[13],
              "10 CSG nodes texels empty (one 16-byte element: Vulkan has no empty buffers)");
    EXPECT_EQ(lines[15],
              "12 pixmap texels texels empty (one 4-byte element: Vulkan has no empty buffers)");
}

TEST_F(Features, SecondaryRaysFollowLightsThresholdsAndDepth) {
    // Two objects and a light: shadows. Reflectivity 0.6 > 0.5 but
    // transparency 0.4 <= minTransparency 0.5.
    RunResult lit = vkray("features " + scene("m.sdl",
                                              "light 1 2 3 1 1 1\nreflectivity 0.6\n"
                                              "transparency 0.4 sphere cube\n"));
    ASSERT_EQ(lit.status, 0) << lit.output;
    EXPECT_EQ(field(lit.output, "shadows"), "yes (1 light, 2 objects)");
    EXPECT_EQ(field(lit.output, "reflection"),
              "yes (2 objects with reflectivity > minReflectivity 0.5, maxRecursionDepth 3)");
    EXPECT_EQ(field(lit.output, "refraction"),
              "no (no object has transparency > minTransparency 0.5 (highest 0.4))");
    EXPECT_EQ(field(lit.output, "variant"), "sphere+cube+shadows+reflection");
    EXPECT_EQ(field(lit.output, "samples"), "1 per pixel (pixel centres, no antialiasing)");
    // A lower threshold turns refraction on; depth 0 turns both off.
    RunResult low =
        vkray("features " + scene("l.sdl", "minTransparency 0.1 transparency 0.4 sphere\n"));
    EXPECT_EQ(field(low.output, "refraction").substr(0, 4), "yes ") << low.output;
    EXPECT_EQ(field(low.output, "shadows"), "no (no lights)");
    RunResult flat = vkray("features " + scene("f.sdl",
                                               "maxRecursionDepth 0 light 1 2 3 1 1 1\n"
                                               "reflectivity 0.9 plane\n"));
    EXPECT_EQ(field(flat.output, "reflection"),
              "no (1 object with reflectivity > minReflectivity 0.5, but maxRecursionDepth 0)")
        << flat.output;
    EXPECT_EQ(field(flat.output, "shadows"),
              "no (one plane or square: no feeler can meet it again)");
    EXPECT_EQ(field(flat.output, "maxRecursionDepth"), "0");
    // --spp adds antialiasing; textures are listed by kind.
    RunResult textured =
        vkray("features " + scene("t.sdl", "texture 1 sphere texture 2 cube\n") + " --spp 4");
    EXPECT_EQ(field(textured.output, "textures"), "1 checkerboard, 1 wood") << textured.output;
    EXPECT_EQ(field(textured.output, "samples"), "4 per pixel (antialiasing)");
    EXPECT_EQ(field(textured.output, "variant"), "sphere+cube+textures+antialias");
}

TEST_F(Features, KeyIsTheOneRenderCompiles) {
    for (const char* variant : {"scene", "all"}) {
        RunResult features = vkray("features " + kScenes + "csg.sdl --variant " + variant);
        ASSERT_EQ(features.status, 0) << features.output;
        RunResult render = vkray("render " + kScenes + "csg.sdl --size 8x6 -o " + path("c.png") +
                                 " --variant " + variant);
        ASSERT_EQ(render.status, 0) << render.output;
        const std::string key = field(features.output, "key").substr(0, 16);
        EXPECT_NE(render.output.find(" variant " + key + " ("), std::string::npos)
            << features.output << render.output;
        EXPECT_NE(render.output.find("shader: " + field(features.output, "variant") + " variant"),
                  std::string::npos)
            << features.output << render.output;
    }
}

TEST_F(Features, BadInputIsAClearError) {
    RunResult missing = vkray("features " + path("none.sdl"));
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.output.find("none.sdl"), std::string::npos) << missing.output;
    RunResult strict = vkray("features " + scene("w.sdl", "sphere\nexponent 5\n"));
    EXPECT_EQ(strict.status, 1);
    EXPECT_NE(strict.output.find("w.sdl:2:1"), std::string::npos) << strict.output;
    RunResult lenient = vkray("features " + scene("w.sdl", "sphere\nexponent 5\n") + " --lenient");
    EXPECT_EQ(lenient.status, 0) << lenient.output;
    EXPECT_EQ(field(lenient.output, "shapes"), "1 sphere") << lenient.output;
    RunResult noScene = vkray("features");
    EXPECT_EQ(noScene.status, 1);
    EXPECT_NE(noScene.output.find("features: expected one scene file"), std::string::npos)
        << noScene.output;
    RunResult badFlag = vkray("features " + kScenes + "default.sdl --cpu");
    EXPECT_EQ(badFlag.status, 1);
    EXPECT_NE(badFlag.output.find("unknown option '--cpu'"), std::string::npos) << badFlag.output;
}

}  // namespace
