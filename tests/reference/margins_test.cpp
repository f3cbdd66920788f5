// Decision margins: the bound played on a ray flips exactly the decisions
// within it (a silhouette, a tie), worked out by hand, and nothing else.
#include "reference/margins.h"

#include "reference/scene_intersector.h"
#include "reference/shading.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace vkray::reference {
namespace {

Scene sceneOf(const std::string& text) {
    Scene scene = parseSdl(text, "margins.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    return scene;
}

// The objects the ray (0, height, 10) -> -z first meets, over the eight
// sides of a bound of `position` of its reach.
std::vector<int> idsMet(const Scene& scene, double height, double position, bool runnerUp) {
    const SceneIntersector intersector(scene);
    std::vector<Aabb> boxes;
    for (const SceneObject& object : scene.objects) boxes.push_back(worldBounds(object, scene));
    std::vector<int> ids;
    for (int side = 0; side < 8; ++side) {
        RayPerturbation p;
        p.eye = {0, height, 10};
        p.boxes = &boxes;
        p.bound.position = position;
        p.angle = side * std::acos(-1.0) / 4;
        p.sideways = !runnerUp;
        p.runnerUp = runnerUp;
        const WhittedShader shader(scene, intersector, &p);
        std::optional<WorldHit> hit;
        shader.radiance({{0, height, 10}, {0, 0, -1}}, 0, Medium{}, &hit);
        ids.push_back(hit ? hit->object : -1);
    }
    return ids;
}

bool has(const std::vector<int>& ids, int id) {
    return std::find(ids.begin(), ids.end(), id) != ids.end();
}

TEST(Margins, ASilhouetteWithinTheBoundFlipsAndOneBeyondItDoesNot) {
    // A unit sphere seen from 10 along z: the ray's reach is |M^-1 eye| = 10
    // times M's scale bound (its Frobenius norm, sqrt 3), so robust's bound,
    // 64 u = 2^-18 of it, is 6.6e-5. A ray passing 1e-5 above the silhouette
    // meets the sphere on the side toward it; one passing 1e-4 above does on
    // no side.
    const Scene scene = sceneOf("sphere\n");
    const double bound = 0x1p-18;
    const std::vector<int> near = idsMet(scene, 1 + 1e-5, bound, false);
    EXPECT_TRUE(has(near, 0));
    EXPECT_TRUE(has(near, -1));
    const std::vector<int> far = idsMet(scene, 1 + 1e-4, bound, false);
    EXPECT_FALSE(has(far, 0));
    // Through the middle, every side meets it.
    EXPECT_FALSE(has(idsMet(scene, 0, bound, false), -1));
}

TEST(Margins, ATieWithinTheBoundGoesToTheRunnerUpInItsPlay) {
    // Two unit spheres, the second 1e-6 behind the first along the ray: the
    // first (index 0) is met at 9, the second at 9 + 1e-6, within the bound
    // (6.6e-5, of the reach 17.3); 1e-3 behind, it is not.
    EXPECT_TRUE(has(idsMet(sceneOf("sphere\ntranslate 0 0 -1e-6 sphere\n"), 0, 0x1p-18, true), 1));
    EXPECT_FALSE(has(idsMet(sceneOf("sphere\ntranslate 0 0 -1e-3 sphere\n"), 0, 0x1p-18, true), 1));
}

TEST(Margins, APixelInsideAnObjectHasOneValueAndOneId) {
    // Lit, diffuse and plain: every play of a ray through the sphere's middle
    // sees the same object at the same depth, and a colour within float's
    // reach of the reference's.
    const Scene scene = sceneOf(
        "light 5 5 10 1 1 1\n"
        "diffuse 0.8 0.3 0.2 sphere\n");
    const Camera camera{{0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 30, {}};
    const RenderSettings settings{9, 9, 1};
    const CameraBasis basis = makeCameraBasis(camera, 9, 9);
    const MarginTracer margins(scene, basis, settings, {0x1p-18, 0x1p-18, 0x1p-18, 0x1p-18, 0});
    const PixelSpan span = margins.spanOf(4, 4);
    ASSERT_EQ(span.firstHits.size(), std::size_t(margins.plays()));
    EXPECT_EQ(margins.plays(), 13);  // untextured: no plays with the textures unmoved
    for (const PixelSpan::FirstHit& hit : span.firstHits) {
        EXPECT_EQ(hit.id, 0);
        EXPECT_NEAR(hit.depth, 9, 1e-4);
    }
    for (int c = 0; c < 3; ++c) EXPECT_LT(span.high[c] - span.low[c], 1e-3) << c;
    EXPECT_GT(span.low.r, 0.1f);
}

}  // namespace
}  // namespace vkray::reference
