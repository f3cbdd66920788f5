#include "app/random_scene_open.h"

#include "image/image_io.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vkray::random_scene {

namespace {

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

}  // namespace

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

}  // namespace vkray::random_scene
