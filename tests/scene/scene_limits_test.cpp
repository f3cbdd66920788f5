// Numbers a renderer in float cannot take: absurd values in a scene, in a
// transform they compose, in a mesh file, and degenerate directions (a zero
// rotation axis, a camera whose eye is its look point or whose up is along
// the view); and trees of booleans too deep to walk. Each is refused at its
// place, whichever renderer follows.
#include <gtest/gtest.h>

#include <functional>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <string>

#include "render/camera.h"
#include "scene/mesh_file.h"
#include "scene/sdl_reader.h"
#include "support/error_of.h"
#include "util/error.h"

namespace vkray {
namespace {

std::string sceneError(const std::string& text) {
    return errorOf([&] { parseSdl(text, "n.sdl", {}); });
}

std::string cameraError(const std::string& text) {
    return errorOf([&] {
        const Scene scene = parseSdl(text, "n.sdl", {});
        makeCameraBasis(scene.camera.value_or(autoCamera(scene)), 64, 48);
    });
}

TEST(SceneNumbers, NumberBeyondTheLimitIsRefusedWhereItStands) {
    EXPECT_EQ(sceneError("sphere\ntranslate 1 1e39 0\nsphere\n"),
              "n.sdl:2:13: error: number '1e39' after 'translate' is beyond vkray's limit of 1e18 "
              "for scene numbers (the GPU computes in float)");
    EXPECT_NE(sceneError("light 0 0 1e19 1 1 1\n").find("n.sdl:1:11: error: number '1e19'"),
              std::string::npos);
    EXPECT_NE(sceneError("diffuse -2e30 0 0\n").find("n.sdl:1:9: error:"), std::string::npos);
    // At the limit itself: accepted.
    EXPECT_EQ(sceneError("translate 1e18 -1e18 0 sphere\n"), "(no error)");
}

TEST(SceneNumbers, TransformWhoseInverseOverflowsFloatIsRefusedAtItsStatement) {
    // 1e-39 is a fine number, but M^-1 would hold 1e39 (float's largest is 3.4e38).
    EXPECT_EQ(sceneError("sphere\n  scale 1 1e-39 1\nsphere\n"),
              "n.sdl:2:3: error: 'scale' makes the inverse transform hold 1e+39, beyond vkray's "
              "limit of 1e18 (the GPU computes in float); use factors and offsets nearer 1 (e.g. "
              "scale the whole scene's units)");
    // Each factor is moderate; together they are not (1e10 * 1e10 = 1e20 in M).
    EXPECT_NE(sceneError("scale 1e10 1 1\nscale 1e10 1 1\ncube\n")
                  .find("n.sdl:2:1: error: 'scale' makes the transform hold 1e+20"),
              std::string::npos);
    // A translation scaled up by an earlier scale.
    EXPECT_NE(sceneError("scale 1e9 1e9 1e9\ntranslate 0 0 1e10\nsphere\n")
                  .find("n.sdl:2:1: error: 'translate' makes the transform hold 1e+19"),
              std::string::npos);
    // A subnormal factor: 1 / s is infinite in double already.
    EXPECT_NE(sceneError("scale 1e-310 1 1\n").find("n.sdl:1:1: error: 'scale' makes the inverse"),
              std::string::npos);
}

TEST(SceneNumbers, LargeButSaneTransformsAreKept) {
    const Scene scene = parseSdl("scale 1e-6 1e6 1 translate 1e6 0 0 sphere\n", "n.sdl", {});
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_DOUBLE_EQ(scene.objects[0].objectFromWorld[1][1], 1e-6);
}

TEST(SceneNumbers, RotationAboutATinyOrHugeAxisIsTheRotationAboutItsDirection) {
    const Scene unit = parseSdl("rotate 30 1 2 0 sphere\n", "n.sdl", {});
    for (const char* axis : {"1e-200 2e-200 0", "1e-320 2e-320 0", "1e17 2e17 0"}) {
        const Scene scaled = parseSdl(std::string("rotate 30 ") + axis + " sphere\n", "n.sdl", {});
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) {
                EXPECT_NEAR(scaled.objects[0].worldFromObject[c][r],
                            unit.objects[0].worldFromObject[c][r], 1e-15)
                    << axis;
                EXPECT_NEAR(scaled.objects[0].objectFromWorld[c][r],
                            unit.objects[0].objectFromWorld[c][r], 1e-15)
                    << axis;
            }
    }
    EXPECT_EQ(sceneError("sphere\n rotate 45 0 0 0\n"),
              "n.sdl:2:2: error: rotate axis 0 0 0 has no direction");
}

TEST(SceneNumbers, CameraEyeAtItsLookPointIsRefusedAtTheCamera) {
    EXPECT_EQ(cameraError("sphere\ncamera eye 1 2 3 look 1 2 3\n"),
              "n.sdl:2:1: error: camera: eye and look are the same point (1, 2, 3); move one of "
              "them");
    // So close that eye - look underflows a naive length: still a direction.
    EXPECT_EQ(cameraError("sphere\ncamera eye 1e-300 0 5 look 0 0 5\n"), "(no error)");
}

TEST(SceneNumbers, CameraUpZeroOrAlongTheViewIsRefusedAtTheCamera) {
    EXPECT_EQ(cameraError("camera eye 0 0 5 up 0 0 0\nsphere\n"),
              "n.sdl:1:1: error: camera: the up vector is zero; use e.g. up 0 1 0");
    EXPECT_EQ(cameraError("sphere\ncamera eye 0 5 0 look 0 0 0\n"),
              "n.sdl:2:1: error: camera: the up vector (0, 1, 0) is parallel to the view "
              "direction (0, -5, 0); choose another up");
    // The last `camera` of several is the one named.
    EXPECT_NE(cameraError("camera eye 0 0 5\nsphere\ncamera up 0 0 -2\n").find("n.sdl:3:1: error"),
              std::string::npos);
}

TEST(SceneNumbers, CameraFromTheCommandLineIsCheckedToo) {
    Camera camera;
    camera.eye = camera.look = glm::dvec3(4, 4, 4);
    EXPECT_EQ(errorOf([&] { makeCameraBasis(camera, 8, 8); }),
              "camera: eye and look are the same point (4, 4, 4); move one of them");
    camera.eye = glm::dvec3(1e39, 0, 0);
    EXPECT_NE(errorOf([&] { makeCameraBasis(camera, 8, 8); }).find("within 1e18"),
              std::string::npos);
}

TEST(SceneNumbers, MeshAndOutlineCoordinatesBeyondTheLimitAreRefusedInTheirFile) {
    EXPECT_EQ(errorOf([] { parse3vn("1 0 0\n0 2e18 0\n", "m.3vn"); }),
              "m.3vn:2:3: error: the number '2e18' for vertex 0 (y) is beyond vkray's limit of "
              "1e18 (the GPU computes in float)");
    EXPECT_NE(errorOf([] {
                  parseOutline("3\n0 0\n1 0\n0 -1e30\n", "o.dat");
              }).find("o.dat:4:3: error: the number '-1e30'"),
              std::string::npos);
}

std::string nestedUnions(int depth) {
    std::string text;
    for (int i = 0; i < depth; ++i) text += "union sphere\n";
    return text + "sphere\n";
}

TEST(SceneLimits, BooleansNestAtMostTheLimitDeep) {
    // Found by hand, not by the fuzzer: 20 000 nested unions overflowed the
    // stack (in the CPU reference, the GPU packer, the camera's framing).
    EXPECT_EQ(sceneError(nestedUnions(kMaxCsgDepth)), "(no error)");
    EXPECT_EQ(sceneError(nestedUnions(kMaxCsgDepth + 1)),
              "n.sdl:1001:1: error: 'union' nests booleans 1001 deep, beyond vkray's limit of "
              "1000; combine the objects in a balanced tree, or in fewer booleans");
    // Pasted by def/use: the same limit, at the pasted word (and where it was pasted).
    std::string text =
        "def u { intersection cube }\ndef v { use u use u use u use u use u "
        "use u use u use u use u use u }\n";
    for (int i = 0; i < 101; ++i) text += "use v ";  // 1010 open intersections
    const std::string message = sceneError(text + "\ncube\n");
    EXPECT_NE(message.find("n.sdl:1:9: error: 'intersection' nests booleans 1001 deep"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("note: in text pasted by 'use u'"), std::string::npos) << message;
}

}  // namespace
}  // namespace vkray
