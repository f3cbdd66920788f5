#include "app/random_scene.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include "image/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace vkray {

namespace {

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

// Six significant digits, or every digit where a place matters to far less
// than 1e-6 of its size (the near view's huge object and eye).
std::string num(double v, bool precise = false) {
    char text[32];
    std::snprintf(text, sizeof text, precise ? "%.17g" : "%.6g", v);
    return text;
}

// What the scene reader reads back from num(v): every figure below is
// computed from the scene as written.
double written(double v, bool precise = false) {
    return std::strtod(num(v, precise).c_str(), nullptr);
}
dvec3 written(dvec3 v, bool precise = false) {
    return {written(v.x, precise), written(v.y, precise), written(v.z, precise)};
}

std::string triple(dvec3 v, bool precise = false) {
    return num(v.x, precise) + " " + num(v.y, precise) + " " + num(v.z, precise);
}

const char* const kPlainShapes[] = {"sphere",      "cube",        "cylinder",   "cone",
                                    "torus",       "tetrahedron", "octahedron", "dodecahedron",
                                    "icosahedron", "square"};
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

struct Rotation {
    double degrees = 0;
    dvec3 axis{0, 1, 0};
};

// R^T v for the scene reader's `rotate degrees axis` (glm::rotate).
dvec3 unrotate(const Rotation& r, dvec3 v) {
    const glm::dmat4 m =
        glm::rotate(glm::dmat4(1.0), glm::radians(r.degrees), glm::normalize(r.axis));
    return dvec3(glm::transpose(m) * glm::dvec4(v, 0.0));
}

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

// Whether a view from inside may stand at the shape's generic origin: a
// point well inside it (or, for the torus, in the hole). That of a
// cylinder, cone, square or the pyramid lies on its surface: an eye there
// sees hits at t = 0.
bool centredSolid(const std::string& shape) {
    return shape == "sphere" || shape == "cube" || shape == "torus" || shape == "tetrahedron" ||
           shape == "octahedron" || shape == "dodecahedron" || shape == "icosahedron" ||
           shape == "buckyball";
}

// One to four lights around and above a scene of `extent`.
std::string drawLights(Draw& d, double extent) {
    std::string lines;
    const int lights = 1 + d.below(4);
    for (int i = 0; i < lights; ++i) {
        lines += "light " + triple(d.vec({-3, 0, -3}, {3, 4, 3}) * extent);
        lines += " " + triple(d.vec(.2, 1)) + "\n";
    }
    return lines;
}

// The far view's eye: `direction` times the distance at which the farthest
// object (in object sizes) is `reach` of the envelope's farthestEye away,
// never nearer than `nearest` nor farther than the CPU reference's limit.
double farDistance(const std::vector<Placed>& objects, dvec3 direction, double size, double reach,
                   const EnvelopeLimits& env, double nearest) {
    const auto farthest = [&](double distance) {
        double most = 0;
        for (const Placed& p : objects)
            most = std::max(most, p.eyeInSizes(direction * distance, size));
        return most / env.farthestEye;
    };
    double lo = nearest, hi = env.farthestWorldEye * (1 - 1e-5);  // its six digits may round up
    if (farthest(lo) >= reach) return lo;
    if (farthest(hi) <= reach) return hi;
    for (int i = 0; i < 80; ++i) {
        const double mid = std::sqrt(lo * hi);
        (farthest(mid) > reach ? hi : lo) = mid;
    }
    return lo;
}

// The render settings: the image size, --block, --spp and --seed.
void drawSettings(Draw& d, RandomScene& r) {
    const int sizes[][2] = {{24, 18}, {32, 24}, {40, 30}};
    const int* size = sizes[d.below(3)];
    r.width = size[0];
    r.height = size[1];
    r.block = d.chance(.2) ? 2 + d.below(2) : 1;
    const int spps[] = {1, 1, 1, 2, 4, 9, 16};
    r.spp = d.chance(.02) ? 256 : spps[d.below(7)];
    r.sampleSeed = std::uint32_t(d.next());
}

// Out to `most` (a figure of the envelope, above `least`): three draws in ten
// at its last factor of two, the rest spread evenly in log.
double toward(Draw& d, double least, double most) {
    return d.chance(.3) ? most * d.range(.5, 1) : d.logRange(least, most);
}

// A lone object as the envelope's sweeps (scripts/envelope.sh) place it, in
// random directions, colours and lights: a sphere far away, plain or
// checkered, filling the view; a cube, sphere, icosahedron or teapot
// squashed after its rotation (`scale a b r rotate ...`) or before it
// (`rotate ... scale a b r`), seen from 4 to 7 away; a huge sphere, cylinder
// or torus seen from close above; a mirror floor scaled by 1e7 with a ball.
void loneScene(Draw& d, const EnvelopeLimits& env, RandomScene& r) {
    r.lone = true;
    const auto colour = [&](double lo, double hi) { return triple(d.vec(lo, hi)); };
    std::string material = "ambient " + colour(0, .3);
    material += " diffuse " + colour(.2, .9);
    if (d.chance(.5)) {
        material += " specular " + colour(0, .8);
        material += " specularExponent " + num(d.logRange(1, 200));
    } else {
        material += " specular 0 0 0";
    }
    material += " reflectivity 0 transparency 0";
    std::string head = "background " + colour(0, 1);
    head += "\nglobalAmbient " + colour(0, .4) + "\n";
    const dvec3 direction = glm::normalize(d.vec(-1, 1) + dvec3(0, 0, 1e-3));
    const int kind = d.below(7);
    dvec3 eye, look(0.0), light;
    double fov = 40;
    std::string objects;
    bool precise = false;
    if (kind <= 1) {
        // A unit sphere at the origin from D radii, filling the view; or
        // checkered with cells s, D / s up to the envelope's per cell.
        const bool checkered = kind == 1;
        const double cell =
            written(d.chance(.3) ? .05 : d.logRange(.05, .5));  // the sweep's cells: 0.05
        const double most =
            checkered ? std::min(env.farthestEye, env.farthestPerCell * cell) : env.farthestEye;
        const double distance = toward(d, 2, std::min(most, env.farthestWorldEye * (1 - 1e-5)));
        eye = written(direction * distance);
        // Looking a little beside the centre: looking at it, the image is
        // symmetric and pixels on the silhouette come in eights at the same
        // distance from its middle, so one rounding is drawn eight times.
        look = written(d.vec(-.3, .3));
        r.reach.eye = glm::length(eye);
        r.reach.worldEye = r.reach.eye;
        fov = written(glm::degrees(2 * std::asin(1 / r.reach.eye)) * d.range(1.05, 1.5));
        light = eye + distance * d.vec({-1, 1, -1}, {1, 4, 1});
        if (checkered) {
            material += " texture 1 parameters 4 " + num(cell) + " " + colour(0, 1);
            r.reach.perCell = r.reach.eye / cell;
        }
        objects = material + "\nsphere\n";
        r.genericEye.push_back(r.reach.eye);
    } else if (kind <= 3) {
        // Squashed after its rotation (kind 2: every generic coordinate mixes
        // the stretched axis in) or before it (kind 3).
        const char* shapes[] = {"cube", "sphere", "icosahedron", "teapot"};
        const int shape = d.below(4);
        const bool after = kind == 2;
        const double smallest = after ? env.smallestSquash : env.smallestInnerSquash;
        const double ratio = written(1 / toward(d, 1, 1 / smallest));
        const double a = d.range(1, 2), b = d.range(1, 2);
        const dvec3 scale = written(dvec3(a, b, ratio * std::max(a, b)));
        const Rotation rotation{written(d.range(-180, 180)), written(direction)};
        const std::string rotate = "rotate " + num(rotation.degrees) + " " + triple(rotation.axis);
        const std::string squash = "scale " + triple(scale);
        const dvec3 from = glm::normalize(d.vec(-1, 1) + dvec3(0, 0, 1e-3));
        eye = written(from * d.range(4, 7));
        light = eye * 1.5 + dvec3(0, 4, 0);
        look = written(d.vec(-.3, .3));
        objects = material + " texture 0\npush " +
                  (after ? squash + " " + rotate : rotate + " " + squash) + " " + shapes[shape] +
                  " pop\n";
        // M^-1 eye: S^-1 R^T eye after the rotation, R^T S^-1 eye before it.
        const dvec3 generic =
            after ? unrotate(rotation, eye / scale) : unrotate(rotation, eye) / scale;
        r.reach.generic = glm::length(generic);
        r.genericEye.push_back(r.reach.generic);
        (after ? r.reach.squash : r.reach.innerSquash) = scale.z / std::max(scale.x, scale.y);
        r.reach.worldEye = glm::length(eye);
    } else if (kind <= 5) {
        // A huge sphere, cylinder or torus seen from H above: R / H to the
        // envelope's for the sphere; the cylinder and the torus to the
        // figures measured for them (radius 3000 from 0.07; tube 500 from 0.05).
        const int shape = kind == 4 ? 0 : 1 + d.below(2);
        const double ratioLimit =
            shape == 0 ? env.largestNearRatio
                       : std::min(env.largestNearRatio, shape == 1 ? 3000 / 0.07 : 500 / 0.05);
        const double radius = written(d.logRange(100, 1e5), true);
        const double ratio = toward(d, 10, ratioLimit);
        const double height = radius / ratio;
        precise = true;
        if (shape == 0) {
            // Not straight over the top: looking level from there, the view
            // would be symmetric about its middle column, each horizon pixel
            // twice.
            const dvec3 tilt = d.vec({-.05, 1, -.05}, {.05, 1, .05});
            eye = (radius + height) * glm::normalize(tilt);
            objects = material + " texture 0\npush scale " + triple(dvec3(radius), true) +
                      " sphere pop\n";
            r.genericEye.push_back((radius + height) / radius);
        } else if (shape == 1) {
            // The wall x^2 + y^2 = R^2 of a long cylinder along z.
            eye = dvec3(0, radius + height, 0);
            objects = material + " texture 0\npush translate 0 0 " + num(-5 * radius, true) +
                      " scale " + num(radius, true) + " " + num(radius, true) + " " +
                      num(10 * radius, true) + " cylinder pop\n";
            r.genericEye.push_back(glm::length(dvec3(0, eye.y / radius, 5.0 / 10.0)));
        } else {
            // The outer equator of a torus of tube radius R (its centre circle 4 R).
            eye = dvec3(0, radius + height, 0);
            objects = material + " texture 0\npush translate 0 " + num(-4 * radius, true) +
                      " 0 rotate 90 0 1 0 scale " + triple(dvec3(4 * radius), true) +
                      " torus pop\n";
            r.genericEye.push_back((eye.y + 4 * radius) / (4 * radius));
        }
        eye = written(eye, true);
        look = eye + d.vec({-3, -.2, -3}, {3, 0, 3});
        light = eye + d.vec({-100, 50, -100}, {100, 200, 100});
        fov = written(d.range(30, 70));
        r.reach.nearRatio = ratio;
        r.reach.worldEye = glm::length(eye);
    } else {
        // A mirror floor (a plane scaled by 1e7) seen from 0.1 to 1 above, a
        // ball on it.
        const double height = written(d.logRange(.1, 1));
        eye = dvec3(0, height, 0);
        look = d.vec({1, 0, 1}, {4, 0, 4});
        light = d.vec({-4, 3, -4}, {4, 8, 4});
        const dvec3 ball = written(look + dvec3(0, .4, 0));
        objects = "diffuse " + colour(.2, .9);
        objects += " reflectivity " + num(d.range(.6, .95)) +
                   "\npush rotate -90 1 0 0 scale 1e7 1e7 1e7 plane pop\n" + material +
                   " texture 0\npush translate " + triple(ball) + " scale 0.4 0.4 0.4 sphere pop\n";
        r.genericEye.push_back(height / 1e7);
        r.genericEye.push_back(glm::length(eye - ball) / 0.4);
        r.reach.worldEye = height;
    }
    r.sdl = "camera eye " + triple(eye, precise) + " look " + triple(look, precise) +
            " up 0 1 0 fov " + num(fov) + "\n" + head + "light " + triple(light, precise) + " " +
            colour(.5, 1) + "\n" + objects;
}

// The solids a boolean takes on the GPU: every shape but the teapot (an
// open mesh: GPU CSG takes closed convex meshes only) and the square (no
// inside), with their inside spans along a ray (a torus and an hourglass
// two, every other solid one).
struct Solid {
    const char* word;
    int spans;
};
const Solid kSolids[] = {{"sphere", 1},
                         {"cube", 1},
                         {"cylinder", 1},
                         {"cone", 1},
                         {"torus", 2},
                         {"taperedCylinder -1", 2},
                         {"taperedCylinder -0.5", 2},
                         {"taperedCylinder 0", 1},
                         {"taperedCylinder 2", 1},
                         {"tetrahedron", 1},
                         {"octahedron", 1},
                         {"dodecahedron", 1},
                         {"icosahedron", 1},
                         {"buckyball", 1},
                         {"mesh pyramid.3vn", 1}};
constexpr int kSolidCount = int(sizeof kSolids / sizeof kSolids[0]);

// A small pixmap: a few texels a side, each its own colour or a two-colour
// checker, as a PNG file.
std::string pixmapPng(Draw& d) {
    Image image;
    image.width = 2 + d.below(15);
    image.height = 2 + d.below(15);
    image.channels = 3;
    const bool checker = d.chance(.5);
    const dvec3 a = d.vec(0, 1), b = d.vec(0, 1);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const dvec3 c = checker ? ((x + y) % 2 ? a : b) : d.vec(0, 1);
            for (int k = 0; k < 3; ++k) image.pixels.push_back(float(c[k]));
        }
    return pngBytes(image);
}

// A boolean operand `depth` levels deep: a solid placed inside its parent, or
// (while depth lasts) a boolean of two. `spans` is what the tree may still
// add to a ray's span list (GPU CSG keeps 8 a list): a tree of four solids
// at most, two spans each, always fits.
std::string operand(Draw& d, SceneWriter& w, int depth, int& spans, bool first) {
    std::string t = first ? "  "
                          : "  push translate " + triple(d.vec(-.8, .8)) + " scale " +
                                triple(d.vec(.4, 1)) + " ";
    if (!first && d.chance(.4)) {
        const Rotation r{written(d.range(-180, 180)), w.axis()};
        t += "rotate " + num(r.degrees) + " " + triple(r.axis) + " ";
    }
    if (d.chance(.2)) t = "diffuse " + triple(d.vec(.1, .9)) + "\n" + t;
    const char* ops[] = {"union", "intersection", "difference"};
    if (depth > 0 && spans >= 2 && d.chance(.5)) {
        t += std::string(ops[d.below(3)]) + "\n";
        t += operand(d, w, depth - 1, spans, true);
        t += operand(d, w, depth - 1, spans, false);
    } else {
        int pick = d.below(kSolidCount);
        if (kSolids[pick].spans > spans) pick = 0;  // the sphere
        spans -= kSolids[pick].spans;
        if (std::string(kSolids[pick].word).starts_with("mesh")) w.usesMesh = true;
        t += std::string(kSolids[pick].word) + "\n";
    }
    return first ? t : t + "  pop\n";
}

// A scene past every envelope, for `--precision auto`: up to three planes at
// any tilt, textured (checkers, wood, a pixmap) and seen to their horizons;
// booleans of every solid, booleans nested in them; glass of any thickness; squashes
// to 1e-6 between rotations and 1e-8 before one; eyes up to 2e5 times the
// scene away, low over a floor, grazing or inside. `vkray difftest` renders
// it in the mode auto chooses, or reports it not comparable where the scene
// passes fp64's envelope too (docs/testing.md).
void openScene(Draw& d, std::uint64_t seed, RandomScene& r) {
    r.open = true;
    EnvelopeLimits limits = envelopeOf(Precision::Fp64).scenes;
    limits.smallestSquash = 1e-6;
    limits.smallestInnerSquash = 1e-8;
    SceneWriter w(d, limits);
    std::string head = "background " + triple(d.vec(0, 1)) + "\n";
    head += "globalAmbient " + triple(d.vec(0, .4)) + "\n";
    head += "maxRecursionDepth " + std::to_string(d.chance(.2) ? d.below(9) : d.below(5)) + "\n";
    const double extent = d.logRange(1, 20);
    std::vector<Placed> objects;
    std::vector<dvec3> centres;  // of centred solids that are not squashed
    double floor = 0;            // the first level plane's height
    bool level = false;
    const int planes = d.chance(.5) ? 0 : 1 + d.below(3);
    for (int i = 0; i < planes; ++i) {
        Placed p;
        w.material(p, d.chance(.6), true);
        p.plane = true;
        p.at = written(d.vec({-extent, -2 * extent, -extent}, {extent, 0, extent}));
        if (i == 0 && d.chance(.6)) {
            p.rotation = {-90, dvec3(1, 0, 0)};
            level = true;
            floor = p.at.y;
        } else {
            p.rotation = {written(d.range(-180, 180)), w.axis()};
        }
        objects.push_back(p);
    }
    const int count = d.chance(.3) ? 9 + d.below(16) : 1 + d.below(8);
    for (int i = 0; i < count; ++i) {
        const dvec3 at = d.vec(-extent, extent);
        const double size = extent * d.logRange(.05, .5);
        Placed p;
        w.material(p, d.chance(.3), true);
        w.placement(p, at, size);
        if (d.chance(.3)) {
            const char* ops[] = {"union", "intersection", "difference"};
            int spans = 8;
            const int depth = d.chance(.35) ? 1 : 0;  // a boolean nested in it, or none
            p.boolean = true;
            p.body = std::string(ops[d.below(3)]) + "\n";
            p.body += operand(d, w, depth, spans, true);
            p.body += operand(d, w, depth, spans, false);
        } else {
            p.body = w.primitive(true);
            if (p.squashAxis < 0 && centredSolid(p.body)) centres.push_back(p.at);
        }
        objects.push_back(p);
    }

    const std::string lightLines = drawLights(d, extent);

    dvec3 eye(0.0), look(0.0);
    double fov = d.range(15, 80);
    int view = d.below(10);
    if (view == 8 && !level) view = 0;
    if (view == 9 && centres.empty()) view = 0;
    if (view < 5) {
        const double r0 = extent * d.range(2.5, 6);
        eye = d.vec({-1, .2, -1}, {1, 1, 1}) * r0;
        if (std::abs(eye.x) + std::abs(eye.z) < 1e-3) eye.x = r0;
    } else if (view < 7) {
        const dvec3 direction = glm::normalize(d.vec({-1, .1, 1}, {1, 1, 1}));
        const double distance = extent * d.logRange(6, 2e5);
        eye = direction * distance;
        fov = glm::degrees(2 * std::atan(extent * d.range(.5, 2.5) / distance));
    } else if (view < 8) {
        eye = dvec3(extent * 3, extent * d.range(-.2, .2), extent * 3);
    } else if (view < 9) {
        // Low over the floor, looking level: its horizon across the view.
        eye = dvec3(extent * d.range(-1, 1), floor + extent * d.logRange(1e-3, .5),
                    extent * d.range(2, 4));
        look = dvec3(eye.x * .5, eye.y - extent * d.range(0, .3), -extent);
    } else {
        eye = centres[size_t(d.below(int(centres.size())))];
        look = eye + d.vec(-1, 1);
    }
    eye = written(eye);
    fov = written(fov);

    if (glm::length(written(look) - eye) < 1e-6 * extent) look = eye + dvec3(0, 0, -extent);
    std::string sdl = "camera eye " + triple(eye) + " look " + triple(look) + " up 0 1 0 fov " +
                      num(fov) + "\n" + head;
    bool pixmap = false;
    for (const Placed& p : objects) {
        sdl += p.text();
        pixmap |= p.texture == 3;
        r.genericEye.push_back(p.genericEye(eye));
    }
    if (pixmap) {  // each seed's own, beside every other seed's scene
        const std::string name = "seed-" + std::to_string(seed) + "-pixmap.png";
        r.files.push_back({name, pixmapPng(d)});
        sdl += "makePixmap 0 " + name + "\n";
    }
    r.reach.worldEye = glm::length(eye);
    r.sdl = sdl + lightLines;
    if (w.usesMesh) r.files.push_back({"pyramid.3vn", pyramid3vn()});
    drawSettings(d, r);
}

}  // namespace

RandomScene randomScene(std::uint64_t seed, const Precision* precision) {
    RandomScene r;
    // Open or for a mode, decided by a draw of its own: the scenes drawn for
    // a mode are the seeds' scenes from before the open family was drawn.
    if (!precision && Draw(seed ^ 0x6f70656e5f736565ull).chance(.5)) {
        Draw d(seed);
        openScene(d, seed, r);
        return r;
    }
    Draw d(seed);
    // Naive mode is the textbook's float, expected to disagree: drawn only
    // when asked for.
    const Precision modes[] = {Precision::Robust, Precision::Robust, Precision::Fp64};
    r.precision = precision ? *precision : modes[d.below(3)];
    const SceneEnvelope envelope = envelopeOf(r.precision);
    if (r.precision != Precision::Naive && d.chance(.25)) {
        loneScene(d, envelope.lone, r);
        drawSettings(d, r);
        return r;
    }
    const EnvelopeLimits& env = envelope.scenes;
    SceneWriter w(d, env);

    std::string head;
    head += "background " + triple(d.vec(0, 1)) + "\n";
    head += "globalAmbient " + triple(d.vec(0, .4)) + "\n";
    const int depth = d.chance(.2) ? d.below(12) : d.below(5);
    head += "maxRecursionDepth " + std::to_string(depth) + "\n";

    // The view, drawn first: ordinary, far away, grazing the middle of the
    // scene, inside an object, or close above a huge object (near: one that
    // the envelope admits at all).
    int view = d.below(10);
    const bool near = env.largestNearRatio > 0 && view == 9 && d.chance(.5);

    // Objects around the origin in a box of `extent`; a plane now and then.
    const double extent = d.logRange(1, 20);
    const int count = d.chance(.3) ? 9 + d.below(16) : 1 + d.below(8);  // > 8: an object BVH
    std::vector<Placed> objects;
    std::vector<dvec3> centres;  // of centred solids that are not squashed
    for (int i = 0; i < count; ++i) {
        const dvec3 at = d.vec(-extent, extent);
        const double size = extent * d.logRange(.05, .5);
        Placed p;
        w.material(p, d.chance(.2));
        const int kind = d.below(20);
        if (kind == 0 && i == 0 && !near) {
            p.plane = true;
            p.at = written(dvec3(0, -extent, 0));
            p.rotation = {-90, dvec3(1, 0, 0)};
            // Untextured: near its horizon a plane's hits lie arbitrarily
            // far, and no mode places them to a cell there (docs/numerics.md,
            // "Envelope").
            p.texture = 0;
        } else if (kind <= 2) {
            // A boolean of two primitives (convex meshes only: the polyhedra).
            const char* ops[] = {"union", "intersection", "difference"};
            const char* solids[] = {"sphere", "cube",       "cylinder",
                                    "cone",   "octahedron", "taperedCylinder 0.5"};
            w.placement(p, at, size);
            p.boolean = true;
            p.body = ops[d.below(3)];
            p.body += std::string("\n  ") + solids[d.below(6)] + "\n";
            p.body += "  push translate " + triple(d.vec(-.8, .8));
            p.body += " scale " + triple(d.vec(.4, 1));
            p.body += std::string(" ") + solids[d.below(6)] + " pop\n";
        } else {
            w.placement(p, at, size);
            p.body = w.primitive(true);
            if (p.squashAxis < 0 && centredSolid(p.body)) centres.push_back(p.at);
        }
        objects.push_back(p);
    }

    const std::string lightLines = drawLights(d, extent);

    // The camera.
    dvec3 eye(0.0), look(0.0);
    double fov = d.range(15, 80);
    bool precise = false;
    if (view == 9 && centres.empty() && !near) view = 0;
    if (near) {
        // Close above the top of a huge sphere, or of a huge cylinder lying
        // along x, whose top is the scene's floor (y = -extent): R / H up to
        // the envelope's, the eye over the scene.
        const double radius = written(extent * d.logRange(10, 1000), true);
        const double ratio = d.chance(.3) ? env.largestNearRatio * d.range(.5, 1)
                                          : d.logRange(10, env.largestNearRatio);
        const double height = radius / ratio;
        const bool sphere = d.chance(.6);
        Placed huge;
        w.material(huge, d.chance(.2));
        huge.precise = true;
        const dvec3 foot = d.vec({-.5, 0, -.5}, {.5, 0, .5}) * extent;
        if (sphere) {
            huge.at = written(dvec3(0, -extent - radius, 0), true);
            huge.scale = dvec3(radius);
            huge.body = "sphere";
            const dvec3 up = glm::normalize(dvec3(foot.x, radius, foot.z));
            eye = huge.at + (radius + height) * up;
        } else {
            huge.at = written(dvec3(-radius, -extent - radius, 0), true);
            huge.rotation = {90, dvec3(0, 1, 0)};
            huge.scale = dvec3(radius, radius, 2 * radius);
            huge.body = "cylinder";
            const dvec3 up = glm::normalize(dvec3(0, radius, foot.z));
            eye = dvec3(foot.x, huge.at.y, 0) + (radius + height) * up;
        }
        r.reach.nearRatio = ratio;
        objects.insert(objects.begin(), huge);
        look = d.vec({-1, -.5, -1}, {1, .5, 1}) * extent;
        precise = true;
        // The eye is inside none of the others (within twice its size of its centre).
        std::erase_if(objects, [&](const Placed& p) {
            return !p.precise && !p.plane &&
                   glm::length(eye - p.at) <
                       2 * p.largestScale() * (p.boolean ? kBooleanChildStretch : 1);
        });
    } else if (view < 6) {
        const double r0 = extent * d.range(2.5, 6);
        eye = d.vec({-1, .2, -1}, {1, 1, 1}) * r0;
        if (std::abs(eye.x) + std::abs(eye.z) < 1e-3) eye.x = r0;
    } else if (view < 8) {
        // Far away, up to the envelope's distance, the view narrowed to the
        // scene (or a little more, or less): float's error grows with the
        // distance in object sizes, and shows where an object spans pixels.
        const dvec3 direction = glm::normalize(d.vec({-1, .1, 1}, {1, 1, 1}));
        const double reach = d.chance(.3) ? d.range(.5, 1) : d.logRange(1e-4, 1);
        const double distance = farDistance(objects, direction, extent, reach, env, 6 * extent);
        eye = direction * distance;
        fov = glm::degrees(2 * std::atan(extent * d.range(.5, 2.5) / distance));
    } else if (view < 9) {
        eye = dvec3(extent * 3, extent * d.range(-.2, .2), extent * 3);  // grazing the middle plane
    } else {
        // Inside (or at the heart of) an object; not a squashed one, whose
        // walls may lie closer to the eye than robust's offset can tell apart
        // (docs/numerics.md, "Envelope").
        eye = centres[size_t(d.below(int(centres.size())))];
        look = eye + d.vec(-1, 1);
    }
    eye = written(eye, precise);
    fov = written(fov);

    // Into the envelope: a squash is eased until |M^-1 eye| is within it (and
    // a refracting solid is thick enough), a texture's cells widened until
    // |M^-1 eye| / cell is.
    for (Placed& p : objects) {
        while (p.squashAxis >= 0 && p.silhouetteReach(eye, extent) > env.farthestGeneric)
            if (!p.ease()) break;
        while (p.thin() && p.thinPerDistance(eye) < env.thinnestPerDistance)
            if (!p.ease())
                p.transparency = 0.3;  // still too thin for its distance: clear, not glass
        if (p.texture != 0 && p.perCell(eye) > env.farthestPerCell)
            p.cell = written(p.cell * p.perCell(eye) / env.farthestPerCell * 1.01);
    }

    std::string sdl = "camera eye " + triple(eye, precise) + " look " + triple(look) +
                      " up 0 1 0 fov " + num(fov) + "\n" + head;
    for (const Placed& p : objects) {
        sdl += p.text();
        r.genericEye.push_back(p.genericEye(eye));
        if (p.precise) continue;  // the near view's huge object: its figure is R / H
        if (p.squashAxis >= 0) {
            r.reach.generic = std::max(r.reach.generic, p.silhouetteReach(eye, extent));
            double& squash = p.secondRotation ? r.reach.squash : r.reach.innerSquash;
            squash = std::min(squash, p.squash());
        } else {
            r.reach.eye = std::max(r.reach.eye, p.silhouetteReach(eye, extent));
        }
        if (p.texture != 0) r.reach.perCell = std::max(r.reach.perCell, p.perCell(eye));
        if (p.thin())
            r.reach.thinPerDistance = std::min(r.reach.thinPerDistance, p.thinPerDistance(eye));
    }
    r.reach.worldEye = glm::length(eye);
    r.sdl = sdl + lightLines;
    if (w.usesMesh) r.files.push_back({"pyramid.3vn", pyramid3vn()});
    drawSettings(d, r);
    return r;
}

}  // namespace vkray
