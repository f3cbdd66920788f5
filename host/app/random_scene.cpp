#include "app/random_scene.h"

#include "app/random_scene_draw.h"
#include "app/random_scene_open.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vkray {

namespace {

using namespace random_scene;

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
