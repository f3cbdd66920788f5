#include "app/random_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace vkray {

namespace {

// splitmix64: a fixed sequence on every platform (std's distributions are not).
class Draw {
public:
    explicit Draw(std::uint64_t seed) : state_(seed * 0x9e3779b97f4a7c15ull + 0x632be59bd9b4e019ull) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double unit() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
    int below(int n) { return int(next() % std::uint64_t(n)); }
    bool chance(double p) { return unit() < p; }
    // A magnitude spread evenly in log between lo and hi.
    double logRange(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }

private:
    std::uint64_t state_;
};

std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

std::string triple(double a, double b, double c) { return num(a) + " " + num(b) + " " + num(c); }

const char* const kPlainShapes[] = {"sphere", "cube", "cylinder", "cone", "torus",
                                    "tetrahedron", "octahedron", "dodecahedron", "icosahedron",
                                    "square"};
const double kTapers[] = {-1, -0.5, 0, 0.3, 1, 2};

// A convex pyramid in Hill's 3VN: 5 vertices, 5 face normals, 5 faces.
std::string pyramid3vn() {
    return "5 5 5\n"
           "-1 0 -1  1 0 -1  1 0 1  -1 0 1  0 1.5 0\n"
           "0 -1 0  0 0.5547 -0.83205  0.83205 0.5547 0  0 0.5547 0.83205  -0.83205 0.5547 0\n"
           "4 0 1 2 3  0 0 0 0\n"
           "3 0 4 1  1 1 1\n"
           "3 1 4 2  2 2 2\n"
           "3 2 4 3  3 3 3\n"
           "3 3 4 0  4 4 4\n";
}

class SceneWriter {
public:
    SceneWriter(Draw& draw, const SceneEnvelope& envelope) : d_(draw), env_(envelope) {}

    // A material: every word now and then, secondary rays above Hill's
    // thresholds (minReflectivity and minTransparency 0.5) or well below.
    std::string material(bool textured) {
        std::string m = "ambient " + triple(d_.range(0, .3), d_.range(0, .3), d_.range(0, .3)) +
                        " diffuse " + triple(d_.range(.1, .9), d_.range(.1, .9), d_.range(.1, .9));
        m += d_.chance(.5) ? " specular " + triple(d_.range(0, .8), d_.range(0, .8), d_.range(0, .8)) +
                                 " specularExponent " + num(d_.logRange(1, 200))
                           : " specular 0 0 0";
        m += d_.chance(.15) ? " emissive " + triple(d_.range(0, .4), d_.range(0, .4), d_.range(0, .4))
                            : " emissive 0 0 0";
        m += " reflectivity " + num(d_.chance(.3) ? d_.range(.6, .95) : d_.range(0, .3));
        m += " transparency " + num(d_.chance(.25) ? d_.range(.6, .95) : d_.range(0, .3));
        m += " speedOfLight " + num(d_.range(.5, 1.2));
        if (textured) {
            // Checkerboard (1) or wood (2): size or ring width, then the odd colour.
            m += " texture " + std::string(d_.chance(.5) ? "1" : "2") + " parameters 4 " +
                 num(d_.logRange(.25, 2)) + " " + triple(d_.unit(), d_.unit(), d_.unit());
        } else {
            m += " texture 0";
        }
        return m + "\n";
    }

    // A transform placing a generic shape of size ~`size` at `at`: rotation
    // about a random axis, scales whose ratio stays above the envelope's
    // squash, sometimes a second rotation after the squash (a shear).
    // `squashed` says whether the scales differ.
    std::string placement(const std::array<double, 3>& at, double size, bool* squashed = nullptr) {
        std::string t = "translate " + triple(at[0], at[1], at[2]);
        t += " rotate " + num(d_.range(-180, 180)) + " " + axis();
        std::array<double, 3> s{size, size, size};
        const bool squash = d_.chance(.4);
        if (squashed) *squashed = squash;
        if (squash) {
            const double squash = d_.chance(.3) ? env_.smallestSquash : d_.logRange(.2, 1);
            s[size_t(d_.below(3))] *= std::max(squash, env_.smallestSquash);
            s[size_t(d_.below(3))] *= d_.range(.5, 2);
        }
        t += " scale " + triple(s[0], s[1], s[2]);
        if (d_.chance(.2)) t += " rotate " + num(d_.range(-90, 90)) + " " + axis();
        return t;
    }

    std::string primitive(bool allowMesh) {
        const int pick = d_.below(allowMesh ? 14 : 12);
        if (pick < 10) return kPlainShapes[pick];
        if (pick == 10) return "taperedCylinder " + num(kTapers[d_.below(6)]);
        if (pick == 11) return "buckyball";
        if (pick == 12) return "teapot";
        usesMesh = true;
        return "mesh pyramid.3vn";
    }

    bool usesMesh = false;

private:
    std::string axis() {
        const double x = d_.range(-1, 1), y = d_.range(-1, 1), z = d_.range(-1, 1);
        return (std::abs(x) + std::abs(y) + std::abs(z) < 1e-3) ? "0 1 0" : triple(x, y, z);
    }
    Draw& d_;
    const SceneEnvelope& env_;
};

}  // namespace

SceneEnvelope envelopeOf(Precision precision) {
    // Inside docs/numerics.md, "Envelope": robust places a hit to about
    // u |M^-1 eye| of the object's size, so silhouettes hold while the eye's
    // generic coordinates stay below ~6e4 and texture cells while they stay
    // below ~2e4 cells. An eye up to 10 x farthestEye object sizes away, a
    // squash r and cells of at least 0.25 give |M^-1 eye| / cell <= 1.6e4
    // for robust; fp64 holds to 1e6 and squashes of 1e-10.
    switch (precision) {
    case Precision::Naive: return {20, 0.05};
    case Precision::Robust: return {20, 0.05};
    case Precision::Fp64: return {3000, 1e-4};
    }
    return {20, 0.05};
}

RandomScene randomScene(std::uint64_t seed, const Precision* precision) {
    Draw d(seed);
    RandomScene r;
    // Naive mode is the textbook's float, expected to disagree: drawn only
    // when asked for.
    const Precision modes[] = {Precision::Robust, Precision::Robust, Precision::Fp64};
    r.precision = precision ? *precision : modes[d.below(3)];
    const SceneEnvelope env = envelopeOf(r.precision);
    SceneWriter w(d, env);

    std::string sdl;
    sdl += "background " + triple(d.unit(), d.unit(), d.unit()) + "\n";
    sdl += "globalAmbient " + triple(d.range(0, .4), d.range(0, .4), d.range(0, .4)) + "\n";
    const int depth = d.chance(.2) ? d.below(12) : d.below(5);
    sdl += "maxRecursionDepth " + std::to_string(depth) + "\n";

    // Objects around the origin in a box of `extent`; a plane now and then.
    const double extent = d.logRange(1, 20);
    const int objects = d.chance(.3) ? 9 + d.below(16) : 1 + d.below(8);  // > 8: an object BVH
    std::vector<std::array<double, 3>> centres;  // of centred solids that are not squashed
    for (int i = 0; i < objects; ++i) {
        const std::array<double, 3> at{d.range(-extent, extent), d.range(-extent, extent),
                                       d.range(-extent, extent)};
        const double size = extent * d.logRange(.05, .5);
        const bool textured = d.chance(.2);
        sdl += w.material(textured);
        const int kind = d.below(20);
        if (kind == 0 && i == 0) {
            sdl += "push translate 0 " + num(-extent) + " 0 rotate -90 1 0 0 plane pop\n";
        } else if (kind <= 2) {
            // A boolean of two primitives (convex meshes only: the polyhedra).
            const char* ops[] = {"union", "intersection", "difference"};
            const char* solids[] = {"sphere", "cube", "cylinder", "cone", "octahedron",
                                    "taperedCylinder 0.5"};
            sdl += "push " + w.placement(at, size) + " " + ops[d.below(3)] + "\n";
            sdl += "  " + std::string(solids[d.below(6)]) + "\n";
            sdl += "  push translate " + triple(d.range(-.8, .8), d.range(-.8, .8), d.range(-.8, .8)) +
                   " scale " + triple(d.range(.4, 1), d.range(.4, 1), d.range(.4, 1)) + " " +
                   solids[d.below(6)] + " pop\npop\n";
        } else {
            bool squashed = false;
            const std::string shape = w.primitive(true);
            sdl += "push " + w.placement(at, size, &squashed) + " " + shape + " pop\n";
            // A view from inside needs a point well inside (or, for the
            // torus, in the hole): the generic origin of the centred solids.
            // (That of a cylinder, cone, square or the pyramid lies on its
            // surface: an eye there sees hits at t = 0.)
            const bool centred = shape == "sphere" || shape == "cube" || shape == "torus" ||
                                 shape == "tetrahedron" || shape == "octahedron" ||
                                 shape == "dodecahedron" || shape == "icosahedron" ||
                                 shape == "buckyball";
            if (!squashed && centred) centres.push_back(at);
        }
    }

    // Lights: one to four, around and above.
    const int lights = 1 + d.below(4);
    for (int i = 0; i < lights; ++i)
        sdl += "light " + triple(d.range(-3, 3) * extent, d.range(0, 4) * extent, d.range(-3, 3) * extent) +
               " " + triple(d.range(.2, 1), d.range(.2, 1), d.range(.2, 1)) + "\n";

    // The camera: ordinary, far away, grazing the ground, or inside an object.
    std::array<double, 3> eye{}, look{0, 0, 0};
    int view = d.below(10);
    if (view == 9 && centres.empty()) view = 0;
    if (view < 6) {
        const double r0 = extent * d.range(2.5, 6);
        eye = {d.range(-1, 1) * r0, d.range(.2, 1) * r0, d.range(-1, 1) * r0};
        if (std::abs(eye[0]) + std::abs(eye[2]) < 1e-3) eye[0] = r0;
    } else if (view < 8) {
        const double r0 = extent * d.logRange(6, env.farthestEye / 2);
        eye = {r0 * d.range(-1, 1), r0 * d.range(.1, 1), r0};
    } else if (view < 9) {
        eye = {extent * 3, extent * d.range(-.2, .2), extent * 3};  // grazing the middle plane
    } else {
        // Inside (or at the heart of) an object; not a squashed one, whose
        // walls may lie closer to the eye than robust's offset can tell apart
        // (docs/numerics.md, "Envelope").
        eye = centres[size_t(d.below(int(centres.size())))];
        look = {eye[0] + d.range(-1, 1), eye[1] + d.range(-1, 1), eye[2] + d.range(-1, 1)};
    }
    const double fov = d.range(15, 80);
    sdl = "camera eye " + triple(eye[0], eye[1], eye[2]) + " look " + triple(look[0], look[1], look[2]) +
          " up 0 1 0 fov " + num(fov) + "\n" + sdl;

    r.sdl = sdl;
    if (w.usesMesh) {
        r.meshFile = "pyramid.3vn";
        r.meshText = pyramid3vn();
    }
    const int sizes[][2] = {{24, 18}, {32, 24}, {40, 30}};
    const int* size = sizes[d.below(3)];
    r.width = size[0];
    r.height = size[1];
    r.block = d.chance(.2) ? 2 + d.below(2) : 1;
    const int spps[] = {1, 1, 1, 2, 4, 9, 16};
    r.spp = d.chance(.02) ? 256 : spps[d.below(7)];
    r.sampleSeed = std::uint32_t(d.next());
    return r;
}

}  // namespace vkray
