// --precision auto's analysis: each figure of docs/numerics.md's envelope
// taken from a scene and its camera, worked out by hand for the scenes
// below, and the choice it makes.
#include "numerics/envelope.h"

#include <gtest/gtest.h>

#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

namespace vkray {
namespace {

struct Seen {
    Scene scene;
    CameraBasis camera;
};

Seen seen(const std::string& text) {
    Seen s{parseSdl(text, "s.sdl", {}), {}};
    loadSceneGeometry(s.scene, false, nullptr);
    s.camera = makeCameraBasis(*s.scene.camera, 160, 120);
    return s;
}

std::vector<EnvelopeExcess> robust(const Seen& s) {
    return envelopeExcesses(s.scene, s.camera, Precision::Robust);
}

TEST(Envelope, OrdinaryScenesAreInsideRobusts) {
    const Seen s = seen(
        "camera eye 0 2 9 look 0 0 0\nlight 5 5 5 1 1 1\n"
        "sphere\npush translate 3 0 0 cube pop\npush rotate -90 1 0 0 plane pop\n");
    EXPECT_TRUE(robust(s).empty());
    const PrecisionChoice choice = choosePrecision(s.scene, s.camera);
    EXPECT_EQ(choice.precision, Precision::Robust);
    EXPECT_TRUE(choice.outside.empty());
}

// Two unit spheres seen from 1e4 (two objects: the scenes' 2e3 holds, not
// the lone object's 1.6e4): fp64, the far one named at its place.
TEST(Envelope, AnEyeFarInObjectSizesForcesFp64) {
    const Seen s = seen(
        "camera eye 0 0 10000 look 0 0 0 fov 0.01\nsphere\n"
        "push translate 3 0 0 sphere pop\n");
    const PrecisionChoice choice = choosePrecision(s.scene, s.camera);
    EXPECT_EQ(choice.precision, Precision::Fp64);
    ASSERT_EQ(choice.outside.size(), 2u);
    EXPECT_EQ(choice.outside[0].where.str(), "s.sdl:2:1");
    EXPECT_NEAR(choice.outside[0].figure, 1e4, 1);
    EXPECT_EQ(choice.outside[0].limit, 2e3);
    EXPECT_EQ(describe(choice.outside[0], Precision::Robust),
              "the 'sphere' at s.sdl:2:1 is seen from 1e+04 of its sizes, beyond robust's 2e+03");
    EXPECT_TRUE(choice.beyondEvery.empty()) << "fp64 holds to 1e6 sizes";
    // Alone, the same sphere is within the lone figure (1.6e4).
    EXPECT_TRUE(robust(seen("camera eye 0 0 10000 look 0 0 0 fov 0.01\nsphere\n")).empty());
}

// A squash of 1e-3 between two rotations (several objects: robust to 2e-3).
TEST(Envelope, SquashesAreTheSmallestOverTheLargestScale) {
    const Seen s = seen(
        "camera eye 0 0 5 look 0 0 0\nsphere\n"
        "push rotate 30 0 0 1 scale 1 1 0.001 rotate 40 1 0 0 cube pop\n");
    const std::vector<EnvelopeExcess> out = robust(s);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out[0].where.str(), "s.sdl:3:54");
    EXPECT_NEAR(out[0].figure, 1e-3, 1e-9);
    EXPECT_EQ(out[0].limit, 2e-3);
}

// A lone cube squashed to 0.15 (far inside robust's lone 1e-4) seen from
// 3e4 of its sizes (its largest scale 1): |M^-1 eye| is inside the lone
// 7e8, but the squash sweeps looked from a few sizes, and 3e4 sizes pass
// the lone 1.6e4 (difftest seed 7300263 drew such a cube 5.2e5 sizes away,
// and auto ran robust there: 3 pixels unexplained).
TEST(Envelope, ASquashedObjectFarAwayIsHeldToTheEyesFigureToo) {
    const Seen s = seen(
        "camera eye 30000 0 0 look 0 0 0 fov 0.01\n"
        "push rotate 30 0 1 0 scale 1 0.15 0.5 cube pop\n");
    const std::vector<EnvelopeExcess> out = robust(s);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].what, "the 'cube' at s.sdl:2:39 is squashed and seen from 3e+04 of its sizes");
    EXPECT_NEAR(out[0].figure, 3e4, 1);
    EXPECT_EQ(out[0].limit, 1.6e4);
    EXPECT_TRUE(envelopeExcesses(s.scene, s.camera, Precision::Fp64).empty());
}

// A checkered sphere 100 from the eye with cells of 0.01: |M^-1 eye| / cell
// = 1e4, beyond robust's 2e3, inside fp64's 2e7.
TEST(Envelope, TexturesCountTheirCellsAcrossTheEyesDistance) {
    const Seen s = seen(
        "camera eye 0 0 100 look 0 0 0\ncube\n"
        "texture 1 parameters 4 0.01 1 1 1 sphere\n");
    const std::vector<EnvelopeExcess> out = robust(s);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(out[0].figure, 1e4, 1e-6);
    EXPECT_TRUE(envelopeExcesses(s.scene, s.camera, Precision::Fp64).empty());
}

// A checkered floor: looking down at it, its farthest visible point counts;
// with its horizon in view it is outside robust's envelope, inside fp64's.
TEST(Envelope, ATexturedPlanesHorizonIsFp64s) {
    const std::string floor =
        "sphere\npush rotate -90 1 0 0 texture 1 parameters 4 1 1 1 1 plane pop\n";
    EXPECT_TRUE(robust(seen("camera eye 0 10 0.001 look 0 0 0 fov 40\n" + floor)).empty());
    const Seen level = seen("camera eye 0 2 9 look 0 2 0 fov 40\n" + floor);
    const PrecisionChoice choice = choosePrecision(level.scene, level.camera);
    EXPECT_EQ(choice.precision, Precision::Fp64);
    ASSERT_EQ(choice.outside.size(), 1u);
    EXPECT_EQ(choice.outside[0].where.str(), "s.sdl:3:54");
    EXPECT_EQ(describe(choice.outside[0], Precision::Robust),
              "the 'plane' at s.sdl:3:54 is a textured plane with its horizon in view (outside "
              "robust's envelope)");
    EXPECT_TRUE(choice.beyondEvery.empty());
    // Untextured, the horizon is no matter.
    EXPECT_TRUE(robust(seen("camera eye 0 2 9 look 0 2 0\nsphere\n"
                            "push rotate -90 1 0 0 plane pop\n"))
                    .empty());
}

// Glass whose thickness is under 0.02 of its distance; and the eye past 1e6
// from the origin, the CPU reference's own limit (in every mode).
TEST(Envelope, ThinGlassAndAFarEye) {
    const std::vector<EnvelopeExcess> glass =
        robust(seen("camera eye 0 0 10 look 0 0 0\ncube\n"
                    "transparency 0.9 push scale 1 1 0.01 sphere pop\n"));
    ASSERT_EQ(glass.size(), 1u);  // its squash of 0.01 is inside robust's 2e-3
    EXPECT_NEAR(glass[0].figure, 0.01 / 11, 1e-6);

    const Seen far = seen("camera eye 2000000 0 0 look 0 0 0 fov 0.0001\nsphere\n");
    const PrecisionChoice choice = choosePrecision(far.scene, far.camera);
    ASSERT_FALSE(choice.beyondEvery.empty());
    EXPECT_FALSE(choice.beyondEvery.back().where.known());
    EXPECT_EQ(choice.beyondEvery.back().limit, 1e6);
}

}  // namespace
}  // namespace vkray
