#include "numerics/oracle.h"

#include "scene/error.h"
#include "scene/file_loc.h"

#include <atomic>
#include <cmath>
#include <thread>

namespace vkray::numerics {

namespace {

// The generic ray of an object: M^-1 (o, 1) and M^-1 (d, 0), in long double
// from the scene's double M^-1 (glm stores columns: m[column][row]).
void toGeneric(const SceneObject& object, const OracleRay& ray, RVec& o, RVec& d) {
    const glm::dmat4& m = object.objectFromWorld;
    for (int row = 0; row < 3; ++row) {
        o[row] = Real(m[0][row]) * ray.origin.x + Real(m[1][row]) * ray.origin.y +
                 Real(m[2][row]) * ray.origin.z + Real(m[3][row]);
        d[row] = Real(m[0][row]) * ray.direction.x + Real(m[1][row]) * ray.direction.y +
                 Real(m[2][row]) * ray.direction.z;
    }
}

// Normals are covectors: (M^-1)^T n.
RVec toWorldNormal(const SceneObject& object, const RVec& n) {
    const glm::dmat4& m = object.objectFromWorld;
    RVec w;
    for (int column = 0; column < 3; ++column)
        w[column] = Real(m[column][0]) * n.x + Real(m[column][1]) * n.y + Real(m[column][2]) * n.z;
    return normalize(w);
}

Real taperOf(const SceneObject& object) {
    if (object.type == ShapeType::Cylinder) return 1;
    if (object.type == ShapeType::Cone) return 0;
    return Real(object.taper);
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

RVec perturbed(const RVec& d, const glm::dvec3& axis, double angle) {
    return normalize(d + Real(angle) * RVec{Real(axis.x), Real(axis.y), Real(axis.z)});
}

}  // namespace

Crossings<Real> objectCrossings(const SceneObject& object, const OracleRay& ray) {
    RVec o, d;
    toGeneric(object, ray, o, d);
    Crossings<Real> c;
    switch (object.type) {
    case ShapeType::Sphere: c = sphereCrossings(o, d); break;
    case ShapeType::Plane: c = planeCrossings(o, d, false); break;
    case ShapeType::Square: c = planeCrossings(o, d, true); break;
    case ShapeType::Cube: c = cubeCrossings(o, d); break;
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: c = taperedCylinderCrossings(o, d, taperOf(object)); break;
    case ShapeType::Torus:
        c = torusCrossings(o, d, Real(kTorusMajorRadius), Real(kTorusTubeRadius));
        break;
    default: throw Error("internal: the oracle has no intersector for this shape");
    }
    for (int i = 0; i < c.count; ++i) c.at[i].normal = toWorldNormal(object, c.at[i].normal);
    return c;
}

OracleHit closestHit(const Scene& scene, const OracleRay& ray) {
    OracleHit best;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Crossings<Real> c = objectCrossings(scene.objects[i], ray);
        for (int k = 0; k < c.count; ++k) {
            const Real t = c.at[k].t;
            if (!(t > 0)) continue;
            // Nearer beyond the tie tolerance wins; a tie keeps the lower index (met first).
            if (best.id < 0 || t < best.t * (1 - Real(1e-9))) {
                best.t = t;
                best.normal = c.at[k].normal;
                best.id = int(i);
            }
            break;  // the first crossing after 0 is this object's hit
        }
    }
    if (best.id >= 0 && dot(best.normal, ray.direction) > 0) best.normal = -best.normal;
    return best;
}

OracleRay primaryRay(const CameraBasis& camera, const RenderSettings& settings, Real px, Real py) {
    const Real sx = 2 * px / Real(settings.width) - 1;
    const Real sy = 1 - 2 * py / Real(settings.height);
    const auto r = [](const glm::dvec3& v) { return RVec{Real(v.x), Real(v.y), Real(v.z)}; };
    const Real tanHalf = Real(camera.tanHalfFov);
    const RVec d = -r(camera.n) + (sx * tanHalf * Real(camera.aspect)) * r(camera.u) +
                   (sy * tanHalf) * r(camera.v);
    return {r(camera.eye), normalize(d)};
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
    std::vector<OraclePixel> pixels(size_t(settings.width) * size_t(settings.height));
    std::atomic<int> nextRow{0};
    auto worker = [&] {
        for (int y = nextRow++; y < settings.height; y = nextRow++) {
            for (int x = 0; x < settings.width; ++x) {
                OraclePixel& p = pixels[size_t(y) * size_t(settings.width) + size_t(x)];
                const OracleRay ray = primaryRay(camera, settings, Real(x) + Real(0.5), Real(y) + Real(0.5));
                p.hit = closestHit(scene, ray);
                p.direction = ray.direction;
                for (int band = 0; band < 2; ++band) {
                    for (const glm::dvec3& axis : {camera.u, -camera.u, camera.v, -camera.v}) {
                        const OracleRay turned{ray.origin, perturbed(ray.direction, axis, kBandAngle[band])};
                        const OracleHit h = closestHit(scene, turned);
                        if (h.id != p.hit.id) {
                            p.silhouette[band] = true;
                            continue;
                        }
                        if (h.id < 0) continue;
                        p.tSpread[band] = std::max(p.tSpread[band], double(std::abs(h.t - p.hit.t)));
                        p.normalSpread[band] = std::max(
                            p.normalSpread[band], angleBetween(toDvec3(h.normal), toDvec3(p.hit.normal)));
                    }
                }
            }
        }
    };
    int count = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (int i = 1; i < count; ++i) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    return pixels;
}

}  // namespace vkray::numerics
