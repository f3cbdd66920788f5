// Analytic answers from the real shader for the shapes beyond the four of
// the foundation: a 1x1 image's only ray goes exactly from the eye through the
// look point, so a chosen ray can be traced on the GPU.
#include "support/gpu_fixture.h"

#include "render/camera.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vkray {
namespace {

// The scene from SDL text, with its meshes built; then the ray eye -> look.
Frame traceOne(const std::string& sdl, glm::dvec3 eye, glm::dvec3 look, glm::dvec3 up = {0, 0, 1}) {
    return test::traceOneRay(sdl, "t.sdl", eye, look, up);
}

void expectHit(const Frame& f, int id, double depth, glm::dvec3 normal, double tolerance = 2e-6) {
    EXPECT_EQ(f.id[0], id);
    EXPECT_NEAR(f.depth[0], depth, tolerance * std::max(1.0, depth));
    EXPECT_NEAR(f.normal[0].x, normal.x, 1e-5);
    EXPECT_NEAR(f.normal[0].y, normal.y, 1e-5);
    EXPECT_NEAR(f.normal[0].z, normal.z, 1e-5);
}

TEST(GpuShapes, CylinderWallAndCaps) {
    // Wall: (3, 0, 0.5) toward -x meets x = 1 at distance 2.
    expectHit(traceOne("cylinder", {3, 0, 0.5}, {0, 0, 0.5}), 0, 2.0, {1, 0, 0});
    // Top cap z = 1 from above, bottom cap z = 0 from below.
    expectHit(traceOne("cylinder", {0.3, 0.2, 4}, {0.3, 0.2, 0}, {0, 1, 0}), 0, 3.0, {0, 0, 1});
    expectHit(traceOne("cylinder", {0.3, 0.2, -2}, {0.3, 0.2, 0}, {0, 1, 0}), 0, 2.0, {0, 0, -1});
    // Along the axis (A = B = 0): only the caps.
    expectHit(traceOne("cylinder", {0, 0, 5}, {0, 0, 0}, {0, 1, 0}), 0, 4.0, {0, 0, 1});
    // Above z = 1 it misses.
    EXPECT_EQ(traceOne("cylinder", {3, 0, 1.5}, {0, 0, 1.5}).id[0], -1);
}

TEST(GpuShapes, ConeAndTaperedCylinderWalls) {
    // taperedCylinder 0.5 at z = 0.5 has radius 0.75; the wall normal is
    // (x, y, -k rho) = (0.75, 0, 0.375) with k = -0.5: unit (2, 0, 1)/sqrt(5).
    expectHit(traceOne("taperedCylinder 0.5", {3, 0, 0.5}, {0, 0, 0.5}), 0, 2.25,
              glm::dvec3(2, 0, 1) / std::sqrt(5.0));
    // A cone (s = 0) at z = 0.5 has radius 0.5.
    expectHit(traceOne("cone", {0, -3, 0.5}, {0, 0, 0.5}), 0, 2.5,
              glm::dvec3(0, -1, 1) / std::sqrt(2.0));
    // Straight down at x = 0.9: a cone has no top cap; the wall (radius 1 - z)
    // is met at z = 0.1.
    EXPECT_EQ(traceOne("cone", {0.9, 0, 2}, {0.9, 0, 0}, {0, 1, 0}).id[0], 0);
}

TEST(GpuShapes, HourglassTaperMinusOne) {
    // s = -1: k = -2, rho(z) = 1 - 2z, radius |rho| = 1 at both ends, 0 at the
    // apex z = 1/2; the wall normal is (x, y, -k rho) = (x, y, 2 rho).
    const std::string hourglass = "taperedCylinder -1";
    // Upper nappe at z = 0.75: radius 0.5, normal (0.5, 0, -1), leaning down.
    expectHit(traceOne(hourglass, {3, 0, 0.75}, {0, 0, 0.75}), 0, 2.5,
              glm::dvec3(1, 0, -2) / std::sqrt(5.0));
    // Lower nappe at z = 0.25: radius 0.5, normal (0.5, 0, 1).
    expectHit(traceOne(hourglass, {3, 0, 0.25}, {0, 0, 0.25}), 0, 2.5,
              glm::dvec3(1, 0, 2) / std::sqrt(5.0));
    // The top cap (radius |s| = 1) from above, not the upper nappe beneath it.
    expectHit(traceOne(hourglass, {0.25, 0, 5}, {0.25, 0, 0}, {0, 1, 0}), 0, 4.0, {0, 0, 1});
    // From the waist (outside: 0.25 > |rho(0.5)| = 0) straight up: the upper
    // nappe's inside begins where 1 - 2z = -0.25, z = 0.625, normal (0.25, 0, -0.5).
    expectHit(traceOne(hourglass, {0.25, 0, 0.5}, {0.25, 0, 1}, {0, 1, 0}), 0, 0.125,
              glm::dvec3(1, 0, -2) / std::sqrt(5.0));
    // Through the waist sideways, 0.1 off the apex: nothing.
    EXPECT_EQ(traceOne(hourglass, {3, 0.1, 0.5}, {0, 0.1, 0.5}).id[0], -1);
}

TEST(GpuShapes, HourglassTaperMinusHalf) {
    // s = -0.5: k = -1.5, rho(z) = 1 - 1.5z, apex at z = 2/3, top cap radius 0.5.
    const std::string hourglass = "taperedCylinder -0.5";
    // Upper nappe at z = 0.8: rho = -0.2, normal (0.2, 0, -0.3).
    expectHit(traceOne(hourglass, {3, 0, 0.8}, {0, 0, 0.8}), 0, 2.8,
              glm::dvec3(2, 0, -3) / std::sqrt(13.0));
    // Top cap from above at x = 0.3; at x = 0.6 (beyond the cap) down to the
    // lower nappe at rho = 0.6, z = 4/15, normal (0.6, 0, 0.9).
    expectHit(traceOne(hourglass, {0.3, 0, 5}, {0.3, 0, 0}, {0, 1, 0}), 0, 4.0, {0, 0, 1});
    expectHit(traceOne(hourglass, {0.6, 0, 5}, {0.6, 0, 0}, {0, 1, 0}), 0, 5 - 4.0 / 15,
              glm::dvec3(2, 0, 3) / std::sqrt(13.0));
    // Bottom cap from below; from the waist (rho(0.5) = 0.25 < 0.3) up to the
    // upper nappe at rho = -0.3, z = 13/15, normal (0.3, 0, -0.45).
    expectHit(traceOne(hourglass, {0.3, 0, -1}, {0.3, 0, 0}, {0, 1, 0}), 0, 1.0, {0, 0, -1});
    expectHit(traceOne(hourglass, {0.3, 0, 0.5}, {0.3, 0, 1}, {0, 1, 0}), 0, 13.0 / 15 - 0.5,
              glm::dvec3(2, 0, -3) / std::sqrt(13.0));
}

TEST(GpuShapes, CsgOfAnHourglassHasTwoSpans) {
    // taperedCylinder -1 less the box z <= 0.45: a vertical line at x = 0.25
    // is inside the hourglass for z <= 0.375 and z >= 0.625, so from below it
    // passes the removed part and the waist and meets the upper nappe at
    // z = 0.625 (normal (0.25, 0, -0.5)); the cut face z = 0.45 is there only
    // within radius 0.1.
    const std::string cut =
        "difference taperedCylinder -1 push translate 0 0 -0.55 scale 2 2 1 cube pop";
    expectHit(traceOne(cut, {0.25, 0, -3}, {0.25, 0, 0}, {0, 1, 0}), 0, 3.625,
              glm::dvec3(1, 0, -2) / std::sqrt(5.0));
    expectHit(traceOne(cut, {0.05, 0, -3}, {0.05, 0, 0}, {0, 1, 0}), 0, 3.45, {0, 0, -1});
    expectHit(traceOne(cut, {0.25, 0, 5}, {0.25, 0, 0}, {0, 1, 0}), 0, 4.0, {0, 0, 1});
    // The hourglass within the slab 0.4 <= z <= 0.6: from the waist at x = 0.15
    // up, the second span begins at the upper nappe, 1 - 2z = -0.15.
    const std::string waist =
        "intersection taperedCylinder -1 push translate 0 0 0.5 scale 2 2 0.1 cube pop";
    expectHit(traceOne(waist, {0.15, 0, 0.5}, {0.15, 0, 1}, {0, 1, 0}), 0, 0.075,
              glm::dvec3(1, 0, -2) / std::sqrt(5.0));
    expectHit(traceOne(waist, {0.15, 0, -3}, {0.15, 0, 0}, {0, 1, 0}), 0, 3.4, {0, 0, -1});
}

TEST(GpuShapes, TorusAlongTheXAxis) {
    // (-3, 0, 0) + (1, 0, 0) t crosses the tube at x = -1.25: distance 1.75.
    expectHit(traceOne("torus", {-3, 0, 0}, {0, 0, 0}), 0, 1.75, {-1, 0, 0}, 1e-5);
    // Down the z axis, through the hole: a miss.
    EXPECT_EQ(traceOne("torus", {0, 0, 5}, {0, 0, 0}, {0, 1, 0}).id[0], -1);
    // From above onto the top of the tube at (1, 0, 0.25): distance 4.75.
    expectHit(traceOne("torus", {1, 0, 5}, {1, 0, 0}, {0, 1, 0}), 0, 4.75, {0, 0, 1}, 1e-5);
    // From far away (distance 1000) the root stays accurate.
    expectHit(traceOne("torus", {-1000, 0, 0}, {0, 0, 0}), 0, 998.75, {-1, 0, 0}, 1e-6);
}

TEST(GpuShapes, BuiltInCubeLikeMeshesAndTriangles) {
    // An octahedron with vertices at distance 1 on the axes: along -z from
    // (0, 0, 5) the apex (0, 0, 1) is hit at distance 4.
    const Frame f = traceOne("octahedron", {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    EXPECT_EQ(f.id[0], 0);
    EXPECT_NEAR(f.depth[0], 4.0, 1e-5);
    // Through the centre of the face x + y + z = 1 (at (1/3, 1/3, 1/3)) from far.
    const glm::dvec3 centre(1.0 / 3, 1.0 / 3, 1.0 / 3);
    const Frame g = traceOne("octahedron", centre * 10.0, centre, {0, 0, 1});
    EXPECT_NEAR(g.depth[0], glm::length(centre * 10.0 - centre), 1e-5);
    EXPECT_NEAR(g.normal[0].x, 1 / std::sqrt(3.0), 1e-5);
}

TEST(GpuShapes, CsgOfTwoSpheres) {
    // Spheres at x = 0 and x = 1 (radius 1), ray along -x from x = 5.
    const std::string spheres = " sphere push translate 1 0 0 sphere pop";
    expectHit(traceOne("union" + spheres, {5, 0, 0}, {0, 0, 0}), 0, 3.0, {1, 0, 0});
    // The lens: enters the first sphere's surface at x = 1.
    expectHit(traceOne("intersection" + spheres, {5, 0, 0}, {0, 0, 0}), 0, 4.0, {1, 0, 0});
    // Sphere minus sphere: from +x the ray enters the hollow; the first
    // surface of the result is the second sphere's at x = 0, normal turned to +x.
    expectHit(traceOne("difference" + spheres, {5, 0, 0}, {0, 0, 0}), 0, 5.0, {1, 0, 0});
    // From -x the first sphere is entered at x = -1 as usual.
    expectHit(traceOne("difference" + spheres, {-5, 0, 0}, {0, 0, 0}), 0, 4.0, {-1, 0, 0});
}

TEST(GpuShapes, CsgSphereCutByAPlane) {
    // sphere minus the half-space z <= 0: only the upper half remains. From
    // below along +z the ray passes the removed half and meets the cut face
    // z = 0 (normal -z, facing the ray) at distance 5.
    expectHit(traceOne("difference sphere plane", {0, 0, -5}, {0, 0, 0}, {0, 1, 0}), 0, 5.0,
              {0, 0, -1});
    expectHit(traceOne("difference sphere plane", {0, 0, 5}, {0, 0, 0}, {0, 1, 0}), 0, 4.0,
              {0, 0, 1});
}

TEST(GpuShapes, CsgRefusesASquareOperandWithItsPlace) {
    Scene scene = parseSdl("union sphere\n  square\n", "t.sdl", {});
    try {
        test::renderOnGpu(scene, makeCameraBasis(Camera{}, 4, 4), {4, 4, 1});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("t.sdl:2:3: error: 'square' has no inside"),
                  std::string::npos)
            << e.what();
    }
}

// A tree's primitives are the bits of one word in the shader: 32 are
// evaluated (five hourglasses, ten spans along a line, once beyond the GPU's
// span lists, among them), 33 are refused at the tree's place.
TEST(GpuShapes, CsgTreesOfUpTo32PrimitivesAreEvaluated) {
    auto unionOf = [](int count) {
        std::string sdl = "translate 0 0 -3\n";
        for (int k = 1; k < count; ++k) sdl += "union ";
        for (int k = 0; k < count; ++k)
            sdl += k < 5 ? " taperedCylinder -1"
                         : " push translate 0 0 -" + std::to_string(k) + " sphere pop";
        return sdl + "\n";
    };
    // Straight down the hourglasses' axis from above: the top one's cap at z = -2.
    expectHit(traceOne(unionOf(32), {0, 0, 5}, {0, 0, 0}, {0, 1, 0}), 0, 7.0, {0, 0, 1});
    try {
        test::renderOnGpu(parseSdl(unionOf(33), "t.sdl", {}), makeCameraBasis(Camera{}, 4, 4),
                          {4, 4, 1});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("t.sdl:2:1: error: this 'union' has 33 primitives"),
                  std::string::npos)
            << e.what();
    }
}

// A primitive subtracted twice bounds the result from its inside again: in
// a shell of radii 2 to 3 around a ball of radius 1 (the ball subtracted
// from the hollow, the hollow from the shell), a ray from the gap meets the
// ball's surface, whose normal faces it without turning.
TEST(GpuShapes, CsgNormalsTurnOncePerDifferenceTheyAreSubtractedIn) {
    const std::string shell =
        "difference push scale 3 3 3 sphere pop difference push scale 2 2 2 sphere pop sphere";
    expectHit(traceOne(shell, {0, 0, -1.5}, {0, 0, 0}, {0, 1, 0}), 0, 0.5, {0, 0, -1});
    expectHit(traceOne(shell, {0, 0, 1.5}, {0, 0, 0}, {0, 1, 0}), 0, 0.5, {0, 0, 1});
    // From the gap outward: the hollow's wall, its normal turned inward.
    expectHit(traceOne(shell, {0, 0, 1.5}, {0, 0, 5}, {0, 1, 0}), 0, 0.5, {0, 0, -1});
}

// A walk keeps the CSG objects it meets in a list of 8 and tests them after
// the others, a full list before it goes on. Twelve half-spaces z <= c (a
// plane minus a far sphere: unbounded, so all in the walk's first leaf, or
// in the loop over every object) are met by a ray straight down; the highest,
// the last object, is the hit: it is only reached after the list's first test.
TEST(GpuShapes, CsgObjectsBeyondAFullListOfThemAreTested) {
    std::string halfSpaces;
    for (int i = 0; i < 12; ++i)
        halfSpaces += "push translate 0 0 " + std::to_string(i) +
                      " difference plane push translate 50 50 -50 sphere pop pop\n";
    // Alone: the loop over every object; with ten spheres aside: the BVH walk.
    std::string spheres;
    for (int i = 0; i < 10; ++i)
        spheres += "push translate " + std::to_string(40 + 3 * i) + " 0 0 sphere pop\n";
    for (const std::string& sdl : {halfSpaces, halfSpaces + spheres}) {
        SCOPED_TRACE(sdl.size() > halfSpaces.size() ? "BVH walk" : "every object in turn");
        expectHit(traceOne(sdl, {0.25, 0.5, 100}, {0.25, 0.5, 0}, {0, 1, 0}), 11, 89.0, {0, 0, 1});
    }
}

TEST(GpuShapes, ObjectBvhFindsTheSameObjectsAsTestingEach) {
    // 40 spheres in a row (a BVH variant) against the same scene cut to
    // their first 8 (no BVH): the first 8 must be hit identically.
    std::string row, firstEight;
    for (int i = 0; i < 40; ++i) {
        const std::string sphere = "push translate " + std::to_string(3 * i) + " 0 0 sphere pop\n";
        row += sphere;
        if (i < 8) firstEight += sphere;
    }
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 centre(3 * i, 0, 0);
        const Frame withBvh = traceOne(row, centre + glm::dvec3(0, 0, 10), centre, {0, 1, 0});
        const Frame without =
            traceOne(firstEight, centre + glm::dvec3(0, 0, 10), centre, {0, 1, 0});
        EXPECT_EQ(withBvh.id[0], i);
        EXPECT_EQ(without.id[0], i);
        EXPECT_EQ(withBvh.depth[0], without.depth[0]);
    }
}

}  // namespace
}  // namespace vkray
