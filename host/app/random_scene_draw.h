// The random scene generator's parts (random_scene.h): its seeded draws,
// the numbers as a scene writes them, one object's placement and material
// as written, and the pieces both families of scenes share.
#pragma once

#include "app/random_scene.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace vkray::random_scene {

using glm::dvec3;

// splitmix64: a fixed sequence on every platform (std's distributions are not).
// The seed is mixed before it starts the sequence: splitmix64 steps its state
// by a constant, so seeds a constant apart would start the same sequence a
// few draws apart (seed 51's scene was seed 26's, shifted by 25 draws).
class Draw {
public:
    explicit Draw(std::uint64_t seed) : state_(mix(seed + 0x632be59bd9b4e019ull)) {}
    std::uint64_t next() { return mix(state_ += 0x9e3779b97f4a7c15ull); }
    double unit() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
    int below(int n) { return int(next() % std::uint64_t(n)); }
    bool chance(double p) { return unit() < p; }
    // A magnitude spread evenly in log between lo and hi.
    double logRange(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
    // A point in the box lo..hi, its coordinates drawn in order. (Draws are
    // never two arguments of one call, nor two operands of one +: their
    // order would be the compiler's, and the scene of a seed with it.)
    dvec3 vec(dvec3 lo, dvec3 hi) {
        const double x = range(lo.x, hi.x), y = range(lo.y, hi.y);
        return {x, y, range(lo.z, hi.z)};
    }
    dvec3 vec(double lo, double hi) { return vec(dvec3(lo), dvec3(hi)); }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    std::uint64_t state_;
};

inline constexpr const char* kPlainShapes[] = {
    "sphere",      "cube",       "cylinder",     "cone",        "torus",
    "tetrahedron", "octahedron", "dodecahedron", "icosahedron", "square"};
inline constexpr double kTapers[] = {-1, -0.5, 0, 0.3, 1, 2};

struct Rotation {
    double degrees = 0;
    dvec3 axis{0, 1, 0};
};

// Six significant digits, or every digit where a place matters to far less
// than 1e-6 of its size (the near view's huge object and eye).
std::string num(double v, bool precise = false);

// What the scene reader reads back from num(v): every figure below is
// computed from the scene as written.
double written(double v, bool precise = false);
dvec3 written(dvec3 v, bool precise = false);

std::string triple(dvec3 v, bool precise = false);

// A convex pyramid in Hill's 3VN: 5 vertices, 5 face normals, 5 faces.
std::string pyramid3vn();

// R^T v for the scene reader's `rotate degrees axis` (glm::rotate).
dvec3 unrotate(const Rotation& r, dvec3 v);

// Whether a view from inside may stand at the shape's generic origin: a
// point well inside it (or, for the torus, in the hole). That of a
// cylinder, cone, square or the pyramid lies on its surface: an eye there
// sees hits at t = 0.
bool centredSolid(const std::string& shape);

// One to four lights around and above a scene of `extent`.
std::string drawLights(Draw& d, double extent);

// The render settings: the image size, --block, --spp and --seed.
void drawSettings(Draw& d, RandomScene& r);

// Out to `most` (a figure of the envelope, above `least`): three draws in ten
// at its last factor of two, the rest spread evenly in log.
double toward(Draw& d, double least, double most);

// A boolean's second primitive is scaled by 0.4 to 1 inside the boolean's
// placement: its generic coordinates are up to 1 / 0.4 times the boolean's.
constexpr double kBooleanChildStretch = 2.5;

// One object: `translate at rotate rotation scale scale [rotate second] body`.
struct Placed {
    dvec3 at{0.0};
    Rotation rotation;
    dvec3 scale{1.0};
    bool secondRotation = false;
    Rotation second;
    int squashAxis = -1;   // the axis squashed (-1: none)
    bool precise = false;  // written with every digit (the near view's huge object)
    bool plane = false, boolean = false;
    double transparency = 0;
    std::string body;      // the shape word(s), or the boolean's lines
    std::string material;  // every material word but transparency, speedOfLight and the texture
    double speedOfLight = 1;
    int texture = 0;  // 0 none, 1 checkerboard, 2 wood, 3 pixmap 0
    double cell = 1;  // the texture's cell size or ring width
    dvec3 odd{0.0};   // its odd cells' or rings' colour

    bool squashedBetweenRotations() const { return squashAxis >= 0 && secondRotation; }
    // Eases the squash a step (the smallest scale a quarter larger, at most
    // the largest); false when there is none left to ease.
    bool ease() {
        if (squash() >= 1) return false;
        const int smallest = scale.x <= std::min(scale.y, scale.z) ? 0 : scale.y <= scale.z ? 1 : 2;
        scale[smallest] = written(std::min(largestScale(), scale[smallest] * 1.25));
        return true;
    }
    double largestScale() const { return std::max(scale.x, std::max(scale.y, scale.z)); }
    double smallestScale() const { return std::min(scale.x, std::min(scale.y, scale.z)); }
    double squash() const { return smallestScale() / largestScale(); }
    // |M^-1 eye| (the second rotation, orthogonal, changes no length).
    double genericEye(dvec3 eye) const { return glm::length(unrotate(rotation, eye - at) / scale); }
    // The eye's distance in object sizes (a boolean's second primitive's);
    // a plane counts the scene's extent (`size`) as its size.
    double eyeInSizes(dvec3 eye, double size) const {
        return stretch() * glm::length(eye - at) / (plane ? size : largestScale());
    }
    // What float's error grows with (docs/numerics.md, "Envelope"): the
    // distance in object sizes, or |M^-1 eye| for a squashed object (among
    // several objects, a squash before the rotation counts too: a mesh's
    // watertight test rounds every generic coordinate at |M^-1 eye|).
    double silhouetteReach(dvec3 eye, double size) const {
        return squashAxis >= 0 ? stretch() * genericEye(eye) : eyeInSizes(eye, size);
    }
    double perCell(dvec3 eye) const { return stretch() * genericEye(eye) / cell; }
    // A refracting solid's smallest scale (a boolean's second primitive's:
    // at least 0.4 of its placement's) over its distance from the eye or from
    // the world's origin, whichever is larger (the GPU's secondary-ray offset
    // grows with the first, the CPU reference's with the second): a squash by
    // r makes its edges wedges of angle ~r, through whose tips refracted rays
    // leak where the solid is thinner than their offset.
    bool refracts() const { return transparency > 0.5; }  // Hill's minTransparency
    bool thin() const { return refracts() && !plane && body != "square"; }
    double thinPerDistance(dvec3 eye) const {
        const double distance = std::max(glm::length(eye - at), glm::length(at));
        return smallestScale() / stretch() / (distance + largestScale());
    }
    double stretch() const { return boolean ? kBooleanChildStretch : 1; }

    std::string text() const {
        std::string t =
            material + " transparency " + num(transparency) + " speedOfLight " + num(speedOfLight);
        if (texture == 0) {
            t += " texture 0\n";
        } else if (texture == 3) {
            t += " texture 3 parameters 1 0\n";
        } else {
            t += " texture " + std::to_string(texture) + " parameters 4 " + num(cell) + " " +
                 triple(odd) + "\n";
        }
        if (plane)
            return t + "push translate " + triple(at) + " rotate " + num(rotation.degrees) + " " +
                   triple(rotation.axis) + " plane pop\n";
        t += "push translate " + triple(at, precise) + " rotate " + num(rotation.degrees) + " " +
             triple(rotation.axis) + " scale " + triple(scale, precise);
        if (secondRotation) t += " rotate " + num(second.degrees) + " " + triple(second.axis);
        return t + " " + body + (boolean ? "pop\n" : " pop\n");
    }
};

class SceneWriter {
public:
    SceneWriter(Draw& draw, const EnvelopeLimits& envelope) : d_(draw), env_(envelope) {}

    // A material: every word now and then, secondary rays above Hill's
    // thresholds (minReflectivity and minTransparency 0.5) or well below.
    void material(Placed& p, bool textured, bool pixmap = false) {
        std::string m = "ambient " + triple(d_.vec(0, .3));
        m += " diffuse " + triple(d_.vec(.1, .9));
        if (d_.chance(.5)) {
            m += " specular " + triple(d_.vec(0, .8));
            m += " specularExponent " + num(d_.logRange(1, 200));
        } else {
            m += " specular 0 0 0";
        }
        m += d_.chance(.15) ? " emissive " + triple(d_.vec(0, .4)) : " emissive 0 0 0";
        m += " reflectivity " + num(d_.chance(.3) ? d_.range(.6, .95) : d_.range(0, .3));
        p.transparency = written(d_.chance(.25) ? d_.range(.6, .95) : d_.range(0, .3));
        p.material = m;
        p.speedOfLight = written(d_.range(.5, 1.2));
        if (textured && pixmap && d_.chance(.35)) {
            p.texture = 3;
        } else if (textured) {
            // Checkerboard (1) or wood (2): size or ring width, then the odd colour.
            p.texture = d_.chance(.5) ? 1 : 2;
            p.cell = written(d_.logRange(.25, 2));
            p.odd = written(d_.vec(0, 1));
        }
    }

    // A transform placing a generic shape of size ~`size` at `at`: rotation
    // about a random axis, sometimes a squash, sometimes a second rotation
    // after the squash (a shear). A squash before the only rotation (the
    // innermost transform) goes down to the envelope's inner squash, one
    // between two rotations to its squash (docs/numerics.md: the first
    // keeps the stretch in one generic coordinate, the second mixes it into
    // all three).
    void placement(Placed& p, dvec3 at, double size) {
        p.at = written(at);
        p.rotation = {written(d_.range(-180, 180)), axis()};
        dvec3 s(size);
        const bool squash = d_.chance(.4);
        p.secondRotation = d_.chance(squash ? .4 : .2);
        if (squash) {
            const double smallest =
                p.secondRotation ? env_.smallestSquash : env_.smallestInnerSquash;
            const double ratio = d_.chance(.5) ? d_.logRange(smallest, 1) : d_.logRange(.2, 1);
            p.squashAxis = d_.below(3);
            s[p.squashAxis] *= ratio;
            const int other = (p.squashAxis + 1 + d_.below(2)) % 3;  // stays within the ratio
            s[other] *= d_.range(.5, 1);
        }
        p.scale = written(s);
        if (p.secondRotation) p.second = {written(d_.range(-90, 90)), axis()};
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

    dvec3 axis() {
        const double x = d_.range(-1, 1), y = d_.range(-1, 1), z = d_.range(-1, 1);
        return (std::abs(x) + std::abs(y) + std::abs(z) < 1e-3) ? dvec3(0, 1, 0)
                                                                : written(dvec3(x, y, z));
    }

    bool usesMesh = false;

private:
    Draw& d_;
    const EnvelopeLimits& env_;
};

}  // namespace vkray::random_scene
