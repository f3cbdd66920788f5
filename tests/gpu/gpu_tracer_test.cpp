// Analytic answers from the real shader: a 1x1 image's only ray goes exactly
// from the eye through the look point, so a chosen ray can be traced on the GPU.
#include "support/gpu_fixture.h"

#include "render/camera.h"
#include "render/render_progress.h"
#include "render/tile_schedule.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace vkray {
namespace {

// Float on the GPU against exact answers: relative error bound for depth.
constexpr double kDepthTolerance = 2e-6;

SceneObject placed(ShapeType type, const glm::dmat4& worldFromObject) {
    SceneObject object;
    object.type = type;
    object.worldFromObject = worldFromObject;
    object.objectFromWorld = glm::inverse(worldFromObject);
    return object;
}

// Traces the single ray eye -> look in a 1x1 image.
Frame traceOne(const Scene& scene, glm::dvec3 eye, glm::dvec3 look, glm::dvec3 up = {0, 0, 1}) {
    Camera camera;
    camera.eye = eye;
    camera.look = look;
    camera.up = up;
    return test::renderOnGpu(scene, makeCameraBasis(camera, 1, 1), {1, 1, 1});
}

TEST(GpuTracer, RayMeetsGenericPlaneAtTheAnalyticPoint) {
    // The ray (4,1,3) + (-3,-5,-3) t meets z = 0 at t = 1, point (1,-4,0). The
    // GPU traces the unit ray, so its depth is |(-3,-5,-3)| = sqrt(43).
    Scene scene;
    scene.objects.push_back(placed(ShapeType::Plane, glm::dmat4(1.0)));
    Frame f = traceOne(scene, {4, 1, 3}, {1, -4, 0}, {0, 1, 0});
    EXPECT_EQ(f.id[0], 0);
    EXPECT_NEAR(f.depth[0], std::sqrt(43.0), kDepthTolerance * std::sqrt(43.0));
    EXPECT_NEAR(f.normal[0].z, 1.0, 1e-6);  // the ray comes from z > 0
}

TEST(GpuTracer, TransformedSphereHitAtHandComputedPoint) {
    // M = T(1,2,3) R_z(90) S(2,1,1): the generic point (-1,0,0) becomes
    // S -> (-2,0,0), R -> (0,-2,0), T -> (1,0,3). Looking from (1,-10,3) along
    // +y the first hit is that point, at distance 10, normal (0,-1,0).
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), {1, 2, 3});
    m = glm::rotate(m, glm::radians(90.0), {0, 0, 1});
    m = glm::scale(m, {2, 1, 1});
    Scene scene;
    scene.objects.push_back(placed(ShapeType::Sphere, m));
    Frame f = traceOne(scene, {1, -10, 3}, {1, 0, 3});
    EXPECT_EQ(f.id[0], 0);
    EXPECT_NEAR(f.depth[0], 10.0, 10 * kDepthTolerance);
    EXPECT_NEAR(f.normal[0].y, -1.0, 1e-6);
}

TEST(GpuTracer, CubeFacesAndNormals) {
    Scene scene;
    scene.objects.push_back(placed(ShapeType::Cube, glm::dmat4(1.0)));
    const glm::dvec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const glm::dvec3& axis : axes) {
        for (double sign : {-1.0, 1.0}) {
            const glm::dvec3 eye = 5.0 * sign * axis;
            const glm::dvec3 up = axis.y == 0 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
            Frame f = traceOne(scene, eye, {0, 0, 0}, up);
            EXPECT_NEAR(f.depth[0], 4.0, 4 * kDepthTolerance);
            EXPECT_NEAR(glm::dot(glm::dvec3(f.normal[0]), sign * axis), 1.0, 1e-6);
        }
    }
}

TEST(GpuTracer, SquareEdgesInsideAndOutside) {
    Scene scene;
    scene.objects.push_back(placed(ShapeType::Square, glm::dmat4(1.0)));
    // Straight down the z axis at x = 0.999 (inside), and x = 1.001 (outside).
    Frame inside = traceOne(scene, {0.999, 0, 5}, {0.999, 0, 0}, {0, 1, 0});
    EXPECT_EQ(inside.id[0], 0);
    EXPECT_NEAR(inside.depth[0], 5.0, 5 * kDepthTolerance);
    Frame outside = traceOne(scene, {1.001, 0, 5}, {1.001, 0, 0}, {0, 1, 0});
    EXPECT_EQ(outside.id[0], -1);
    EXPECT_TRUE(std::isinf(outside.depth[0]));
}

TEST(GpuTracer, EyeInsideSphereHitsTheFarSideFacingInward) {
    Scene scene;
    scene.objects.push_back(placed(ShapeType::Sphere, glm::dmat4(1.0)));
    Frame f = traceOne(scene, {0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    EXPECT_NEAR(f.depth[0], 1.0, kDepthTolerance);
    EXPECT_NEAR(f.normal[0].z, 1.0, 1e-6);  // (0,0,-1) outward, turned to face the ray
}

TEST(GpuTracer, ClosestOfSeveralObjectsWins) {
    Scene scene;
    for (double z : {-4.0, 2.0, -1.0})
        scene.objects.push_back(
            placed(ShapeType::Sphere, glm::translate(glm::dmat4(1.0), {0, 0, z})));
    Frame f = traceOne(scene, {0, 0, 10}, {0, 0, 0}, {0, 1, 0});
    EXPECT_EQ(f.id[0], 1);
    EXPECT_NEAR(f.depth[0], 7.0, 7 * kDepthTolerance);
}

TEST(GpuTracer, BlockFillsEachBlockWithOneRay) {
    Scene scene = parseSdl("sphere", "block.sdl", {});
    Camera camera;
    camera.eye = {0, 0, 4};
    const RenderSettings settings{37, 29, 4};  // sizes not a multiple of the block
    Frame f = test::renderOnGpu(scene, makeCameraBasis(camera, 37, 29), settings);
    for (int y = 0; y < 29; ++y)
        for (int x = 0; x < 37; ++x) {
            const size_t first = f.index(x - x % 4, y - y % 4);
            ASSERT_EQ(f.color[f.index(x, y)], f.color[first]) << x << "," << y;
            ASSERT_EQ(f.id[f.index(x, y)], f.id[first]);
        }
}

TEST(GpuTracer, TheDefaultTileSuitsTheDevice) {
    gpu::DeviceInfo device;
    device.type = "CPU";
    EXPECT_EQ(gpu::defaultTileSide(device), 256);
    device.type = "discrete GPU";
    EXPECT_EQ(gpu::defaultTileSide(device), 1024);
    device.type = "integrated GPU";
    EXPECT_EQ(gpu::defaultTileSide(device), 1024);
    // Unset, the tile side is the device's: lavapipe's 256 pixels give a
    // 600x300 image 3x2 tiles.
    Scene scene = parseSdl("sphere", "tiles.sdl", {});
    const RenderSettings settings{600, 300, 1};
    gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir});
    gpu::GpuRenderStats stats;
    tracer.render(scene, makeCameraBasis(Camera{}, 600, 300), settings, &stats);
    const uint expected = test::gpuContext().device().type == "CPU" ? 6u : 1u;
    EXPECT_EQ(stats.tiles, expected);
}

TEST(GpuTracer, TilesStitchIntoTheSameImage) {
    // Small tiles must give exactly the bytes of one big tile.
    Scene scene = parseSdl("push translate 0.3 0 0 sphere pop cube", "tiles.sdl", {});
    Camera camera;
    camera.eye = {3, 4, 5};
    const RenderSettings settings{50, 40, 1};
    const CameraBasis basis = makeCameraBasis(camera, 50, 40);
    gpu::GpuTracer big(test::gpuContext(), {.shaderDirectory = test::kShaderDir, .tileSize = 256});
    gpu::GpuTracer small(test::gpuContext(), {.shaderDirectory = test::kShaderDir, .tileSize = 16});
    gpu::GpuRenderStats bigStats, smallStats;
    Frame a = big.render(scene, basis, settings, &bigStats);
    Frame b = small.render(scene, basis, settings, &smallStats);
    EXPECT_EQ(bigStats.tiles, 1u);
    EXPECT_EQ(smallStats.tiles, 4u * 3u);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.id, b.id);
}

// Every tile of tilesOf, handed out one at a time: the path of a schedule
// (MPI's), where the renderer keeps one tile in flight, not two.
class OneTileAtATime final : public TileSchedule {
public:
    void plan(int width, int height, int side) override { tiles_ = tilesOf(width, height, side); }
    std::optional<TileRect> next() override {
        if (next_ == tiles_.size()) return std::nullopt;
        return tiles_[next_++];
    }
    void finished(const TileRect&, const Frame&) override { ++finished_; }
    std::size_t finishedTiles() const { return finished_; }

private:
    std::vector<TileRect> tiles_;
    std::size_t next_ = 0, finished_ = 0;
};

TEST(GpuTracer, TwoTilesInFlightGiveTheBytesOfOneAtATime) {
    // Two tiles in flight, each dispatched several times (a low turn budget
    // pauses their rays), their re-dispatches interleaved: the image is that
    // of one tile at a time, byte for byte, AOVs included.
    Scene scene =
        parseSdl("light 4 4 4 1 1 1 push translate 0.3 0 0 sphere pop cube", "tiles.sdl", {});
    Camera camera;
    camera.eye = {3, 4, 5};
    const RenderSettings settings{50, 40, 1, 4};
    const CameraBasis basis = makeCameraBasis(camera, 50, 40);
    // Every tile dispatched, even those whose rays all miss.
    gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir,
                                               .tileSize = 16,
                                               .primaryCover = false,
                                               .turnBudget = 8});
    gpu::GpuRenderStats overlapped, sequential;
    const Frame a = tracer.render(scene, basis, settings, &overlapped);
    OneTileAtATime schedule;
    const Frame b = tracer.render(scene, basis, settings, &sequential, nullptr, &schedule);
    EXPECT_EQ(schedule.finishedTiles(), 12u);
    EXPECT_EQ(overlapped.tiles, 12u);
    EXPECT_GT(overlapped.dispatches, overlapped.tiles);  // the rays did pause
    EXPECT_EQ(overlapped.dispatches, sequential.dispatches);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.id, b.id);
}

TEST(GpuTracer, InterruptedWithTilesInFlightRendersAgain) {
    // The progress callback stops the render after its first tile, while the
    // second is still on the device: the pass waits for it before its
    // buffers go (ASan and the validation layers would see otherwise), and
    // the tracer renders the same frame again whole.
    Scene scene = parseSdl("push translate 0.3 0 0 sphere pop cube", "stop.sdl", {});
    Camera camera;
    camera.eye = {3, 4, 5};
    const CameraBasis basis = makeCameraBasis(camera, 50, 40);
    gpu::GpuTracer tracer(test::gpuContext(),
                          {.shaderDirectory = test::kShaderDir, .tileSize = 16});
    int calls = 0;
    EXPECT_THROW(tracer.render(scene, basis, {50, 40, 1}, nullptr,
                               [&calls](std::size_t, std::size_t) { return ++calls < 2; }),
                 Interrupted);
    EXPECT_EQ(calls, 2);  // the start, then the first tile
    gpu::GpuRenderStats stats;
    const Frame again = tracer.render(scene, basis, {50, 40, 1}, &stats);
    EXPECT_EQ(stats.tiles, 12u);
    EXPECT_EQ(again.id, test::renderOnGpu(scene, basis, {50, 40, 1}).id);
}

TEST(GpuTracer, DeviceTimeOfTheDispatchesLiesWithinTheRender) {
    // Each dispatch's timestamps are written on the device between its
    // submit and the fence the host waits on, so their sum lies within the
    // wall clock around all of them; it is there exactly when the queue has
    // timestamps (lavapipe's has).
    Scene scene = parseSdl("push translate 0.3 0 0 sphere pop cube", "timed.sdl", {});
    Camera camera;
    camera.eye = {3, 4, 5};
    gpu::GpuTracer tracer(
        test::gpuContext(),
        {.shaderDirectory = test::kShaderDir, .tileSize = 16, .primaryCover = false});
    gpu::GpuRenderStats stats;
    tracer.render(scene, makeCameraBasis(camera, 50, 40), {50, 40, 1}, &stats);
    ASSERT_EQ(stats.deviceSeconds.has_value(), test::gpuContext().device().timestampValidBits > 0);
    if (!stats.deviceSeconds) GTEST_SKIP() << "the device's queue has no timestamps";
    EXPECT_EQ(stats.dispatches, 12u);
    EXPECT_GT(*stats.deviceSeconds, 0.0);
    EXPECT_LE(*stats.deviceSeconds, stats.renderSeconds);
    // The stages of the loop lie within it, and preparation was timed.
    EXPECT_GT(stats.firstTileSeconds, 0.0);
    EXPECT_LE(stats.firstTileSeconds, stats.renderSeconds);
    EXPECT_GE(stats.readBackSeconds, 0.0);
    EXPECT_LE(stats.readBackSeconds, stats.renderSeconds);
    EXPECT_GT(stats.setupSeconds, 0.0);
    EXPECT_GE(stats.setupCpuSeconds, 0.0);
}

// A render without AOVs (`vkray render` without --aov) writes the colour
// and the object id of a render with them, byte for byte, and leaves depth
// and normal as Frame() made them: for one pass a pixel (with feelers or
// without), for blocks, and for rays that pause between dispatches (a
// mirror, several samples).
TEST(GpuTracer, WithoutAovsTheColourAndIdsAreThoseOfARenderWithThem) {
    const char* const scenes[] = {
        "push translate 0.3 0 0 sphere pop cube",
        "light 4 4 4 1 1 1 push translate 0.3 0 0 sphere pop cube",
        "light 4 4 4 1 1 1 reflectivity 0.7 push translate 0.3 0 0 sphere pop cube",
    };
    Camera camera;
    camera.eye = {3, 4, 5};
    const CameraBasis basis = makeCameraBasis(camera, 50, 40);
    const Frame untouched(50, 40);
    for (const char* sdl : scenes) {
        const Scene scene = parseSdl(sdl, "aovs.sdl", {});
        for (RenderSettings settings :
             {RenderSettings{50, 40, 1}, RenderSettings{50, 40, 3}, RenderSettings{50, 40, 1, 4}}) {
            // Tiles of 16 and a budget of 8 turns: every ray of the lit
            // scene pauses, so its pixels are written over several dispatches.
            gpu::GpuTracer tracer(
                test::gpuContext(),
                {.shaderDirectory = test::kShaderDir, .tileSize = 16, .turnBudget = 8});
            gpu::GpuRenderStats withStats, withoutStats;
            const Frame with = tracer.render(scene, basis, settings, &withStats);
            settings.aovs = false;
            const Frame without = tracer.render(scene, basis, settings, &withoutStats);
            const std::string what = std::string(sdl) + ", block " +
                                     std::to_string(settings.block) + ", spp " +
                                     std::to_string(settings.spp);
            EXPECT_EQ(with.color, without.color) << what;
            EXPECT_EQ(with.id, without.id) << what;
            EXPECT_NE(std::count(with.id.begin(), with.id.end(), -1), 2000) << what;
            EXPECT_EQ(without.depth, untouched.depth) << what;
            EXPECT_EQ(without.normal, untouched.normal) << what;
            EXPECT_NE(with.depth, untouched.depth) << what;
            EXPECT_EQ(withStats.variant.find("+aovs") != std::string::npos, true) << what;
            EXPECT_EQ(withoutStats.variant.find("+aovs"), std::string::npos) << what;
            EXPECT_EQ(withStats.dispatches, withoutStats.dispatches) << what;
        }
    }
}

// Workgroups whose primary rays can meet nothing are not dispatched
// (GpuRenderOptions::primaryCover): their pixels, written on the host, are
// the bytes the shader writes for a miss, AOVs included, with blocks, several
// samples, feelers and a floor whose horizon crosses the image.
TEST(GpuTracer, PixelsLeftToTheBackgroundAreThoseTheShaderWouldWrite) {
    const char* const scenes[] = {
        "background 0.1 0.2 0.3 push translate 0.3 0 0 scale 0.3 0.3 0.3 sphere pop "
        "push translate -1 0.5 0 scale 0.2 0.2 0.2 cube pop",
        "background 0.7 0.11 0.3 light 4 4 4 1 1 1 reflectivity 0.7 push translate 0.3 0 0 "
        "scale 0.3 0.3 0.3 sphere pop push translate 0 -1 0 rotate -90 1 0 0 plane pop",
    };
    Camera camera;
    camera.eye = {3, 1, 5};
    camera.look = {0, 0, 0};
    camera.up = {0, 1, 0};
    const CameraBasis basis = makeCameraBasis(camera, 70, 50);
    for (const char* sdl : scenes) {
        const Scene scene = parseSdl(sdl, "cover.sdl", {});
        // Without AOVs, and a later sample alone (`view`'s passes), the
        // depth and id of a miss stay as Frame() makes them.
        RenderSettings noAovs{70, 50, 1};
        noAovs.aovs = false;
        RenderSettings laterSample{70, 50, 1, 4};
        laterSample.firstSample = 2;
        laterSample.sampleCount = 1;
        for (const RenderSettings& settings : {RenderSettings{70, 50, 1}, RenderSettings{70, 50, 3},
                                               RenderSettings{70, 50, 1, 5}, noAovs, laterSample})
            // Tiles of one workgroup: most hold no ray that may meet an object,
            // and are read back between the others' dispatches.
            for (const int tileSize : {32, 8}) {
                gpu::GpuTracer covered(test::gpuContext(),
                                       {.shaderDirectory = test::kShaderDir, .tileSize = tileSize});
                gpu::GpuTracer whole(test::gpuContext(), {.shaderDirectory = test::kShaderDir,
                                                          .tileSize = tileSize,
                                                          .primaryCover = false});
                gpu::GpuRenderStats coveredStats, wholeStats;
                const Frame a = covered.render(scene, basis, settings, &coveredStats);
                const Frame b = whole.render(scene, basis, settings, &wholeStats);
                const std::string what =
                    std::string(sdl) + ", block " + std::to_string(settings.block) + ", spp " +
                    std::to_string(settings.spp) + ", first sample " +
                    std::to_string(settings.firstSample) + ", AOVs " +
                    std::to_string(settings.aovs) + ", tile " + std::to_string(tileSize);
                EXPECT_EQ(a.color, b.color) << what;
                EXPECT_EQ(a.id, b.id) << what;
                EXPECT_EQ(a.depth, b.depth) << what;
                EXPECT_EQ(a.normal, b.normal) << what;
                if (settings.block == 1) {  // the sky, and the corners the objects leave
                    EXPECT_LT(coveredStats.groupsTraced, coveredStats.groups) << what;
                }
                EXPECT_GT(coveredStats.groupsTraced, 0u) << what;
                EXPECT_EQ(wholeStats.groupsTraced, wholeStats.groups) << what;
                EXPECT_EQ(coveredStats.groups, wholeStats.groups) << what;
                EXPECT_EQ(coveredStats.rays, wholeStats.rays) << what;
            }
    }
}

TEST(GpuTracer, SamplesTracedOneAtATimeSumToTheWholeRender) {
    // `vkray view` traces the spp samples one a pass and sums them in order,
    // as the shader sums them within one dispatch: the mean is the very same
    // float. The scene has a mirror and glass, so samples take secondary rays.
    Scene scene = parseSdl(
        "camera eye 0 1 5 look 0 0 0 up 0 1 0 fov 40\nlight 3 4 5 1 1 1\n"
        "reflectivity 0.5 sphere\n"
        "reflectivity 0 transparency 0.8 speedOfLight 0.7 translate 1.2 0.3 1 scale 0.4 0.4 0.4 "
        "sphere\n",
        "samples.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    RenderSettings all{24, 18, 1, 5, 7};
    const CameraBasis camera = makeCameraBasis(*scene.camera, all.width, all.height);
    const Frame whole = test::renderOnGpu(scene, camera, all);
    std::vector<glm::vec3> sum(whole.pixelCount());
    for (int k = 0; k < all.spp; ++k) {
        RenderSettings one = all;
        one.firstSample = k;
        one.sampleCount = 1;
        const Frame part = test::renderOnGpu(scene, camera, one);
        for (size_t i = 0; i < part.pixelCount(); ++i) {
            sum[i] = k == 0 ? part.color[i] : sum[i] + part.color[i];
            if (k == 0)
                ASSERT_EQ(part.id[i], whole.id[i]);
            else
                ASSERT_EQ(part.id[i], -1) << "sample " << k << " gave AOVs";
        }
    }
    for (size_t i = 0; i < whole.pixelCount(); ++i) {
        const glm::vec3 mean = sum[i] / float(all.spp);
        ASSERT_EQ(mean.x, whole.color[i].x) << i;
        ASSERT_EQ(mean.y, whole.color[i].y) << i;
        ASSERT_EQ(mean.z, whole.color[i].z) << i;
    }
}

}  // namespace
}  // namespace vkray
