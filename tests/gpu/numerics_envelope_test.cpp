// The numerics envelope (docs/numerics.md, "Envelope"): scenes at the edges
// of what each precision mode draws as the CPU reference does, each pinned
// with the bound `render --check` asks (colour within 0.02 on all but 0.1 %
// of the pixels, object ids on 99.9 %), most with ids equal everywhere. The
// scenes are tests/data/envelope/*.sdl; each file's header gives its figures.
#include "support/frame_difference.h"
#include "support/gpu_fixture.h"

#include "reference/reference_tracer.h"

#include <gtest/gtest.h>

#include <string>

namespace vkray {
namespace {

const std::string kEnvelopeDir = test::kDataDir + "/envelope/";

struct Renders {
    Frame gpu, cpu;
};

// The scene file `name` of tests/data/envelope at 160x120 (render --check's
// usual size), on the GPU in `precision` and with the CPU reference.
Renders renderBoth(const std::string& name, Precision precision) {
    const Scene scene = loadScene(kEnvelopeDir + name, {}, nullptr);
    const RenderSettings settings{160, 120};
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    gpu::GpuTracer tracer(test::gpuContext(),
                          {.shaderDirectory = test::kShaderDir, .precision = precision});
    return {tracer.render(scene, camera, settings), reference::render(scene, camera, settings)};
}

// `render --check`'s bound: colour within 0.02 on all but 0.1 % of the
// pixels, and object ids on all but `idShare` of them (0: everywhere).
void expectAgreement(const std::string& name, Precision precision, double idShare = 0) {
    SCOPED_TRACE(name + " --precision " + precisionName(precision));
    const Renders r = renderBoth(name, precision);
    const test::FrameDifference d = test::frameDifference(r.gpu, r.cpu, 0.02);
    const double pixels = double(r.cpu.pixelCount());
    EXPECT_LE(double(d.ids), idShare * pixels) << d.ids << " pixels have another object";
    EXPECT_LE(double(d.over), 0.001 * pixels)
        << d.over << " pixels differ by more than 0.02 (largest " << d.maxColor << ")";
}

const char* const kSquashedShapes[] = {"cube", "sphere", "icosahedron", "teapot"};

// A sphere of radius 2000 seen from 0.1 above: the secondary rays' offset
// sized from the eye's distance alone was below the sphere's own generic
// rounding (~u x 2000 in the world), and the shadow feelers re-met the
// sphere: 5.4 % of the pixels wrongly shadowed in robust, 6.3 % in fp64.
TEST(NumericsEnvelope, HugeSphereSeenFromCloseHasNoShadowAcneInRobust) {
    expectAgreement("huge_sphere_near.sdl", Precision::Robust);
}

TEST(NumericsEnvelope, HugeSphereSeenFromCloseHasNoShadowAcneInFp64) {
    expectAgreement("huge_sphere_near.sdl", Precision::Fp64);
}

// The offset's floor from the object's own scale is 0 for planes and
// squares, whose distance from a point is generic z alone (rounded like the
// eye's height): a mirror floor scaled by 1e7 would otherwise lift every
// reflected ray 64 u x 1e7 = 38 units off it (2.3 % of these pixels off).
TEST(NumericsEnvelope, MirrorFloorScaledBy1e7ReflectsFromItsSurface) {
    expectAgreement("huge_mirror_floor.sdl", Precision::Robust);
    expectAgreement("huge_mirror_floor.sdl", Precision::Fp64);
}

// A checkered unit sphere (cells 0.05) seen from 8000 radii. fp64 took the
// texture point from float M^-1 p, whose O(1) result cancels out of
// coordinates of ~8000: 0.19 % of the pixels on the wrong side of a cell
// border. Now o + t d on the intersection's generic ray, in double.
TEST(NumericsEnvelope, FarCheckeredSphereAgreesInFp64) {
    expectAgreement("far_checker_8000.sdl", Precision::Fp64);
}

// Robust locates a point to ~u |M^-1 eye| generic units (its ray's float
// direction and generic eye): its textures agree while distance / cell
// <= 2e4, here 1000 radii with cells of 0.05.
TEST(NumericsEnvelope, CheckeredSphereAtRobustsTextureLimitAgrees) {
    expectAgreement("far_checker_1000.sdl", Precision::Robust);
}

// A squash applied after a rotation (the outermost transform) mixes the
// stretched axis into every generic coordinate; robust agrees down to 1e-4
// (ids as render --check asks: 99.9 %), fp64 at 1e-5 (and beyond) exactly.
TEST(NumericsEnvelope, OutermostSquashAtRobustsLimitAgrees) {
    for (const char* shape : kSquashedShapes)
        expectAgreement(std::string("squash_outer_1e-4_") + shape + ".sdl", Precision::Robust,
                        0.001);
}

TEST(NumericsEnvelope, OutermostSquashOf1e5AgreesInFp64) {
    for (const char* shape : kSquashedShapes)
        expectAgreement(std::string("squash_outer_1e-5_") + shape + ".sdl", Precision::Fp64);
}

// Applied before the rotation (innermost, written last) the stretch stays in
// one generic coordinate: robust agrees at 1e-8, ids equal.
TEST(NumericsEnvelope, InnermostSquashOf1e8AgreesInRobust) {
    for (const char* shape : kSquashedShapes)
        expectAgreement(std::string("squash_inner_1e-8_") + shape + ".sdl", Precision::Robust);
}

// Seen from 2000 away, a secondary ray's origin moves 0.0076 off the
// surface; moved along the normal, reflected and shadow rays ran beside the
// exact ones and every reflected and shadow edge moved with them (21 pixels
// off in robust). Stepped along the rays themselves, none is, in either mode.
TEST(NumericsEnvelope, MirroredAndShadowedEdgesSeenFromAfarStayPut) {
    for (const Precision precision : {Precision::Robust, Precision::Fp64}) {
        SCOPED_TRACE(precisionName(precision));
        const Renders r = renderBoth("far_mirror_edges.sdl", precision);
        const test::FrameDifference d = test::frameDifference(r.gpu, r.cpu, 0.02);
        EXPECT_EQ(d.ids, 0u);
        EXPECT_EQ(d.over, 0u) << "largest difference " << d.maxColor;
    }
}

// A refracted ray starts a step inside its solid (2^-18 of its distance from
// the eye in robust) and leaks through the solid's edges where it is thinner
// than that: a glass cone squashed by r has a rim of angle ~r. Robust holds
// to r = 0.1 seen from ~10 (smallest scale / distance 0.017); fp64, whose
// step is 2^-47 of the distance, to 1e-4 and beyond.
TEST(NumericsEnvelope, FlatGlassConeAtRobustsLimitAgrees) {
    expectAgreement("thin_glass_cone_0.1.sdl", Precision::Robust);
}

TEST(NumericsEnvelope, FlatGlassConeOf1e4AgreesInFp64) {
    expectAgreement("thin_glass_cone_1e-4.sdl", Precision::Fp64);
}

}  // namespace
}  // namespace vkray
