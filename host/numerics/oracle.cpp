#include "numerics/oracle.h"

#include "util/error.h"
#include "util/file_loc.h"
#include "util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace vkray::numerics {

namespace {

BVec exactVec(const glm::dvec3& v) {
    return {Bounded(v.x), Bounded(v.y), Bounded(v.z)};
}

// The generic ray of an object: A origin + b and A direction, A and b the
// rows of the scene's double M^-1 (glm stores columns: m[column][row]).
void toGeneric(const SceneObject& object, const OracleRay& ray, BVec& o, BVec& d) {
    const glm::dmat4& m = object.objectFromWorld;
    for (int row = 0; row < 3; ++row) {
        const Bounded a0(m[0][row]), a1(m[1][row]), a2(m[2][row]);
        o[row] = a0 * ray.origin.x + a1 * ray.origin.y + a2 * ray.origin.z + Bounded(m[3][row]);
        d[row] = a0 * ray.direction.x + a1 * ray.direction.y + a2 * ray.direction.z;
    }
}

// A^T n: a generic normal's world direction (normals are covectors).
BVec toWorldNormal(const SceneObject& object, const BVec& n) {
    const glm::dmat4& m = object.objectFromWorld;
    BVec w;
    for (int column = 0; column < 3; ++column)
        w[column] =
            Bounded(m[column][0]) * n.x + Bounded(m[column][1]) * n.y + Bounded(m[column][2]) * n.z;
    return w;
}

double taperOf(const SceneObject& object) {
    if (object.type == ShapeType::Cylinder) return 1;
    if (object.type == ShapeType::Cone) return 0;
    return object.taper;
}

bool oracleShape(ShapeType type) {
    switch (type) {
    case ShapeType::Sphere:
    case ShapeType::Plane:
    case ShapeType::Square:
    case ShapeType::Cube:
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder:
    case ShapeType::Torus: return true;
    default: return false;
    }
}

// A ball about the generic origin holding the shape (0: unbounded), and the
// size of the generic coordinates a hit's t depends on (oracle.h, "extent").
double boundingRadius(const SceneObject& object) {
    switch (object.type) {
    case ShapeType::Sphere: return 1;
    case ShapeType::Cube: return std::sqrt(3.0);
    case ShapeType::Torus: return kTorusMajorRadius + kTorusTubeRadius;
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: {
        const double s = taperOf(object);
        return std::sqrt(2 * std::max(1.0, s * s) + 1);
    }
    default: return 0;  // plane, square
    }
}

double extentOf(const SceneObject& object) {
    return object.type == ShapeType::Square ? 0 : boundingRadius(object);
}

// The line certainly passes farther than twice the bounding radius from the
// generic origin (a cull, in plain float128: what it tests is generous).
bool certainlyMisses(const SceneObject& object, const BVec& o, const BVec& d) {
    const double radius = boundingRadius(object);
    if (radius == 0) return false;
    const QVec ov = valueOf(o), dv = valueOf(d);
    const Quad along = dot(ov, dv) / dot(dv, dv);
    const QVec foot = ov - along * dv;
    return dot(foot, foot) > Quad(4 * radius * radius);
}

ExactCrossings genericCrossings(const SceneObject& object, const BVec& o, const BVec& d) {
    switch (object.type) {
    case ShapeType::Sphere: return sphereCrossings(o, d);
    case ShapeType::Plane: return planeCrossings(o, d, false);
    case ShapeType::Square: return planeCrossings(o, d, true);
    case ShapeType::Cube: return cubeCrossings(o, d);
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: return taperedCylinderCrossings(o, d, taperOf(object));
    case ShapeType::Torus: return torusCrossings(o, d, kTorusMajorRadius, kTorusTubeRadius);
    default: throw Error("internal: the oracle has no intersector for this shape");
    }
}

QVec unit(const BVec& v, bool& degenerate) {
    const QVec value = valueOf(v);
    const Quad size = sqrt(dot(value, value));
    degenerate = !(size > 4 * errorOf(v));  // no direction the oracle can be sure of
    return degenerate ? QVec{} : value / size;
}

QVec perturbed(const QVec& d, const glm::dvec3& axis, double angle) {
    return normalize(d + Quad(angle) * QVec{Quad(axis.x), Quad(axis.y), Quad(axis.z)});
}

double norm(const glm::dvec3& v) {
    return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

// alphaO, alphaD, |o|, |d| of oracle.h for an object and a world ray, in double.
struct GenericSizes {
    double alphaO = 0, alphaD = 0, lengthO = 0, lengthD = 0;
    glm::dvec3 d{0};
};

GenericSizes genericSizes(const SceneObject& object, const glm::dvec3& eye, const glm::dvec3& w) {
    const glm::dmat4& m = object.objectFromWorld;
    GenericSizes g;
    glm::dvec3 aO(0), aD(0), o(0);
    for (int row = 0; row < 3; ++row) {
        for (int j = 0; j < 3; ++j) {
            aO[row] += std::abs(m[j][row] * eye[j]);
            aD[row] += std::abs(m[j][row] * w[j]);
            o[row] += m[j][row] * eye[j];
            g.d[row] += m[j][row] * w[j];
        }
        aO[row] += std::abs(m[3][row]);
        o[row] += m[3][row];
    }
    g.alphaO = norm(aO);
    g.alphaD = norm(aD);
    g.lengthO = norm(o);
    g.lengthD = norm(g.d);
    return g;
}

// The footprint's angle (oracle.h) for an object seen along w, in arithmetic `a`.
double footprint(const SceneObject& object, const glm::dvec3& eye, const glm::dvec3& w, int a) {
    const GenericSizes g = genericSizes(object, eye, w);
    const double lengthO = std::max(g.lengthO, 1e-300);
    const double world = a == kDoubleAsWritten ? kUnitRoundoff[a] * g.alphaO / lengthO : 0;
    return kFootprintMultiple *
           (kUnitRoundoff[a] * (2 + extentOf(object) / lengthO + g.alphaD / g.lengthD) + world);
}

Conditioning conditioningAt(const SceneObject& object, const glm::dvec3& eye, const glm::dvec3& w,
                            const OracleHit& hit) {
    const GenericSizes g = genericSizes(object, eye, w);
    const double t = double(hit.t);
    const glm::dvec3 n = toDvec3(hit.genericNormal);
    const double cosine = std::abs(glm::dot(n, g.d)) / g.lengthD;
    const glm::dmat4& m = object.objectFromWorld;
    double frobenius = 0;
    glm::dvec3 world(0);
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) {
            frobenius += m[column][row] * m[column][row];
            world[column] += m[column][row] * n[row];
        }
    const double J = std::sqrt(frobenius) / norm(world);
    const double along = t * g.lengthD * cosine;  // t |n.d|
    const double turn = J * hit.curvature * t * g.lengthD * (1 + cosine);
    Conditioning c;
    c.t = (g.lengthO + t * (g.alphaD + g.lengthD) + extentOf(object)) / along;
    c.tWorld = g.alphaO / along;
    c.normal = J + turn * c.t;
    c.normalWorld = turn * c.tWorld;
    return c;
}

}  // namespace

double genericScaleAlong(const SceneObject& object, const QVec& genericNormal) {
    const glm::dmat4& m = object.objectFromWorld;
    const glm::dvec3 n = toDvec3(genericNormal);
    glm::dvec3 world(0);
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) world[column] += m[column][row] * n[row];
    return extentOf(object) / norm(world);
}

OracleRay exactRay(const glm::dvec3& origin, const glm::dvec3& direction) {
    return {exactVec(origin), exactVec(direction)};
}

std::vector<WorldCrossing> objectCrossings(const SceneObject& object, const OracleRay& ray) {
    BVec o, d;
    toGeneric(object, ray, o, d);
    std::vector<WorldCrossing> out;
    if (certainlyMisses(object, o, d)) return out;
    const ExactCrossings c = genericCrossings(object, o, d);
    for (int i = 0; i < c.count; ++i) {
        const ExactCrossing& x = c.at[size_t(i)];
        bool degenerate = false, genericDegenerate = false;
        const QVec world = unit(toWorldNormal(object, x.normal), degenerate);
        const QVec generic = unit(x.normal, genericDegenerate);
        const CrossingKind kind = degenerate || genericDegenerate ? CrossingKind::Edge : x.kind;
        out.push_back({x.t, x.tBound, world, generic, x.curvature, kind});
    }
    return out;
}

OracleHit closestHit(const Scene& scene, const OracleRay& ray, const Quad& tMin) {
    OracleHit best;
    const QVec direction = valueOf(ray.direction);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        for (const WorldCrossing& c : objectCrossings(scene.objects[i], ray)) {
            if (!(c.t + c.tBound > tMin)) continue;
            const bool straddles = !(c.t - c.tBound > tMin);  // at tMin, within its bracket
            // Nearer beyond the tie tolerance wins; a tie keeps the lower index (met first).
            if (best.id < 0 || c.t < best.t * (1 - Quad(1e-9))) {
                best.t = c.t;
                best.tBound = c.tBound;
                best.normal = c.normal;
                best.genericNormal = c.genericNormal;
                best.curvature = c.curvature;
                best.id = int(i);
                best.uncertain = straddles || c.kind != CrossingKind::Crossing;
            }
            break;  // the first crossing after tMin is this object's hit
        }
    }
    best.entering = best.id >= 0 && dot(best.normal, direction) < 0;
    if (best.id >= 0 && dot(best.normal, direction) > 0) best.normal = -best.normal;
    return best;
}

Meets meets(const SceneObject& object, const OracleRay& ray, const Quad& tMin, const Quad& tMax) {
    bool uncertain = false;
    for (const WorldCrossing& c : objectCrossings(object, ray)) {
        const Quad lo = c.t - c.tBound, hi = c.t + c.tBound;
        if (hi <= tMin || lo >= tMax) continue;
        if (lo > tMin && hi < tMax && c.kind == CrossingKind::Crossing) return Meets::Yes;
        uncertain = true;
    }
    return uncertain ? Meets::Uncertain : Meets::No;
}

OracleRay primaryRay(const CameraBasis& camera, const RenderSettings& settings, double px,
                     double py) {
    const Bounded sx = Bounded(2.0) * Bounded(px) / Bounded(double(settings.width)) - Bounded(1.0);
    const Bounded sy = Bounded(1.0) - Bounded(2.0) * Bounded(py) / Bounded(double(settings.height));
    const Bounded tanHalf(camera.tanHalfFov);
    const BVec d = -exactVec(camera.n) +
                   (sx * tanHalf * Bounded(camera.aspect)) * exactVec(camera.u) +
                   (sy * tanHalf) * exactVec(camera.v);
    return {exactVec(camera.eye), d / length(d)};
}

void requireOracleScene(const Scene& scene) {
    for (const SceneObject& object : scene.objects)
        if (!oracleShape(object.type))
            throw Error(formatDiagnostic(
                object.loc, nullptr, "error",
                std::string("the stress oracle intersects spheres, planes, squares, cubes, "
                            "tapered cylinders and tori; '") +
                    shapeKeyword(object.type) +
                    "' is not one (`vkray report` measures any scene against the CPU "
                    "reference)"));
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return std::atan2(std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z),
                      a.x * b.x + a.y * b.y + a.z * b.z);
}

std::vector<OraclePixel> renderOracle(const Scene& scene, const CameraBasis& camera,
                                      const RenderSettings& settings, int threads) {
    requireOracleScene(scene);
    const int width = settings.width, height = settings.height;
    std::vector<OraclePixel> pixels(size_t(width) * size_t(height));
    const auto forEachRow = [&](const auto& work) {
        parallelFor(
            std::size_t(height),
            [&](std::size_t row) {
                const int y = int(row);
                for (int x = 0; x < width; ++x)
                    work(x, y, pixels[size_t(y) * size_t(width) + size_t(x)]);
            },
            threads);
    };
    // The hits.
    forEachRow([&](int x, int y, OraclePixel& p) {
        const OracleRay ray = primaryRay(camera, settings, x + 0.5, y + 0.5);
        p.hit = closestHit(scene, ray);
        p.direction = valueOf(ray.direction);
        if (p.hit.id >= 0)
            p.conditioning = conditioningAt(scene.objects[size_t(p.hit.id)], camera.eye,
                                            toDvec3(p.direction), p.hit);
    });
    // The set-aside, tried where the ids change.
    forEachRow([&](int x, int y, OraclePixel& p) {
        if (p.hit.uncertain) {
            for (bool& a : p.setAside) a = true;
            return;
        }
        std::vector<int> seen;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                const int id = pixels[size_t(ny) * size_t(width) + size_t(nx)].hit.id;
                if (std::find(seen.begin(), seen.end(), id) == seen.end()) seen.push_back(id);
            }
        if (seen.size() < 2) return;
        p.besideEdge = true;
        const glm::dvec3 w = toDvec3(p.direction);
        for (int a = 0; a < 3; ++a) {
            double angle = 0;
            for (int id : seen)
                if (id >= 0)
                    angle = std::max(angle, footprint(scene.objects[size_t(id)], camera.eye, w, a));
            for (const glm::dvec3& axis : {camera.u, -camera.u, camera.v, -camera.v}) {
                const QVec turned = perturbed(p.direction, axis, angle);
                const OracleRay ray{exactVec(camera.eye),
                                    {Bounded(turned.x), Bounded(turned.y), Bounded(turned.z)}};
                const OracleHit h = closestHit(scene, ray);
                if (h.id != p.hit.id || h.uncertain) {
                    p.setAside[a] = true;
                    break;
                }
            }
        }
    });
    return pixels;
}

}  // namespace vkray::numerics
