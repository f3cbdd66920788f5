#include "bench/embree_tracer.h"

#include "reference/object_intersect.h"
#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"
#include "util/error.h"
#include "util/parallel_for.h"
#include "util/stopwatch.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

namespace vkray::bench {

struct EmbreeTracer::Impl {
    const Scene& scene;
    RTCDevice device = nullptr;
    RTCScene rtcScene = nullptr;
    std::vector<std::vector<int>> objectOfPrimitive;  // [geomID][primID] -> object index
    std::vector<int> userObjects;                     // user primitive -> object index
    std::vector<int> unbounded;                       // tested apart, for every ray
    std::size_t spheres = 0, triangles = 0;
    double buildSeconds = 0;

    explicit Impl(const Scene& s) : scene(s) {}
    ~Impl() {
        if (rtcScene) rtcReleaseScene(rtcScene);
        if (device) rtcReleaseDevice(device);
    }
    void check(const char* what) const {
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE)
            throw Error(std::string("Embree: ") + what + " failed");
    }
};

namespace {

// A sphere placed by rotation, uniform scale and translation stays a sphere:
// its centre and radius. Anything else (an ellipsoid) is not.
bool similarity(const glm::dmat4& m, glm::dvec3& centre, double& radius) {
    const glm::dvec3 c0(m[0]), c1(m[1]), c2(m[2]);
    const double r = glm::length(c0);
    const double tolerance = 1e-9 * r;
    if (std::abs(glm::length(c1) - r) > tolerance || std::abs(glm::length(c2) - r) > tolerance ||
        std::abs(glm::dot(c0, c1)) > tolerance * r || std::abs(glm::dot(c0, c2)) > tolerance * r ||
        std::abs(glm::dot(c1, c2)) > tolerance * r)
        return false;
    centre = glm::dvec3(m[3]);
    radius = r;
    return true;
}

// The cube [-1, 1]^3 as 12 triangles.
void cubeTriangles(std::vector<glm::dvec3>& corners, std::vector<std::uint32_t>& indices) {
    for (int i = 0; i < 8; ++i) corners.push_back({i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1});
    // Two triangles per face: (x = -1, x = +1, y = -1, y = +1, z = -1, z = +1).
    const std::uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                       {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const auto& f : faces)
        for (std::uint32_t k : {f[0], f[1], f[2], f[0], f[2], f[3]}) indices.push_back(k);
}

float down(double x) {
    return std::nextafter(float(x), -std::numeric_limits<float>::infinity());
}
float up(double x) {
    return std::nextafter(float(x), std::numeric_limits<float>::infinity());
}

void userBounds(const RTCBoundsFunctionArguments* args) {
    const auto& impl = *static_cast<const EmbreeTracer::Impl*>(args->geometryUserPtr);
    const SceneObject& object = impl.scene.objects[size_t(impl.userObjects[args->primID])];
    const Aabb box = worldBounds(object, impl.scene);
    *args->bounds_o = {down(box.lo.x), down(box.lo.y), down(box.lo.z), 0,
                       up(box.hi.x),   up(box.hi.y),   up(box.hi.z),   0};
}

// The CPU reference's intersection of the object, for each active ray.
void userIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto& impl = *static_cast<const EmbreeTracer::Impl*>(args->geometryUserPtr);
    const int index = impl.userObjects[args->primID];
    const SceneObject& object = impl.scene.objects[size_t(index)];
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const reference::Ray r{{RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                                RTCRayN_org_z(ray, args->N, i)},
                               {RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i),
                                RTCRayN_dir_z(ray, args->N, i)}};
        const auto h = reference::intersectObject(impl.scene, object, index, r,
                                                  RTCRayN_tnear(ray, args->N, i));
        if (!h || h->t >= RTCRayN_tfar(ray, args->N, i)) continue;
        RTCRayN_tfar(ray, args->N, i) = float(h->t);
        RTCHitN_Ng_x(hit, args->N, i) = float(h->normal.x);
        RTCHitN_Ng_y(hit, args->N, i) = float(h->normal.y);
        RTCHitN_Ng_z(hit, args->N, i) = float(h->normal.z);
        RTCHitN_u(hit, args->N, i) = 0;
        RTCHitN_v(hit, args->N, i) = 0;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_instID(hit, args->N, i, 0) = RTC_INVALID_GEOMETRY_ID;
    }
}

}  // namespace

EmbreeTracer::EmbreeTracer(const Scene& scene, int threads) : impl_(std::make_unique<Impl>(scene)) {
    Impl& m = *impl_;
    const Stopwatch build;
    const std::string config = "threads=" + std::to_string(threads);
    m.device = rtcNewDevice(config.c_str());
    if (!m.device) throw Error("Embree: rtcNewDevice(\"" + config + "\") failed");
    m.rtcScene = rtcNewScene(m.device);

    std::vector<float> sphereData;  // x y z r
    std::vector<int> sphereObjects, triangleObjects;
    std::vector<float> vertices;
    std::vector<std::uint32_t> indices;
    const auto addTriangles = [&](int index, const glm::dmat4& m4,
                                  const std::vector<glm::dvec3>& positions,
                                  const std::vector<std::uint32_t>& corners) {
        const std::uint32_t base = std::uint32_t(vertices.size() / 3);
        for (const glm::dvec3& p : positions) {
            const glm::dvec3 w = glm::dvec3(m4 * glm::dvec4(p, 1.0));
            vertices.insert(vertices.end(), {float(w.x), float(w.y), float(w.z)});
        }
        for (std::uint32_t c : corners) indices.push_back(base + c);
        triangleObjects.insert(triangleObjects.end(), corners.size() / 3, index);
    };
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        glm::dvec3 centre;
        double radius;
        if (object.type == ShapeType::Sphere &&
            similarity(object.worldFromObject, centre, radius)) {
            sphereData.insert(sphereData.end(),
                              {float(centre.x), float(centre.y), float(centre.z), float(radius)});
            sphereObjects.push_back(int(i));
        } else if (object.type == ShapeType::Cube) {
            std::vector<glm::dvec3> corners;
            std::vector<std::uint32_t> cube;
            cubeTriangles(corners, cube);
            addTriangles(int(i), object.worldFromObject, corners, cube);
        } else if (!isBoolean(object.type) && isMeshShape(object.type)) {
            const TriangleMesh& mesh = reference::meshOf(scene, object);
            std::vector<std::uint32_t> corners;
            corners.reserve(mesh.triangles.size() * 3);
            for (const auto& t : mesh.triangles)
                corners.insert(corners.end(), t.position, t.position + 3);
            addTriangles(int(i), object.worldFromObject, mesh.positions, corners);
        } else if (worldBounds(object, scene).finite()) {
            m.userObjects.push_back(int(i));
        } else {
            m.unbounded.push_back(int(i));
        }
    }

    const auto attach = [&](RTCGeometry geometry, std::vector<int> objects) {
        rtcCommitGeometry(geometry);
        const unsigned id = rtcAttachGeometry(m.rtcScene, geometry);
        rtcReleaseGeometry(geometry);
        if (m.objectOfPrimitive.size() <= id) m.objectOfPrimitive.resize(id + 1);
        m.objectOfPrimitive[id] = std::move(objects);
    };
    if (!sphereObjects.empty()) {
        RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        auto* data = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                    4 * sizeof(float), sphereObjects.size()));
        std::copy(sphereData.begin(), sphereData.end(), data);
        m.spheres = sphereObjects.size();
        attach(g, std::move(sphereObjects));
    }
    if (!triangleObjects.empty()) {
        RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              vertices.size() / 3));
        std::copy(vertices.begin(), vertices.end(), v);
        auto* t = static_cast<std::uint32_t*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(std::uint32_t), indices.size() / 3));
        std::copy(indices.begin(), indices.end(), t);
        m.triangles = triangleObjects.size();
        attach(g, std::move(triangleObjects));
    }
    if (!m.userObjects.empty()) {
        RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, unsigned(m.userObjects.size()));
        rtcSetGeometryUserData(g, &m);
        rtcSetGeometryBoundsFunction(g, userBounds, &m);
        rtcSetGeometryIntersectFunction(g, userIntersect);
        attach(g, m.userObjects);
    }
    m.check("building the geometry");
    rtcCommitScene(m.rtcScene);
    m.check("rtcCommitScene");
    m.buildSeconds = build.seconds();
}

EmbreeTracer::~EmbreeTracer() = default;

double EmbreeTracer::buildSeconds() const {
    return impl_->buildSeconds;
}

std::string EmbreeTracer::contents() const {
    std::string text;
    const auto add = [&](std::size_t n, const char* what) {
        if (n) text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(impl_->spheres, "spheres");
    add(impl_->triangles, "triangles");
    add(impl_->userObjects.size(), "user primitives");
    add(impl_->unbounded.size(), "planes tested apart");
    return text;
}

std::string EmbreeTracer::version() {
    RTCDevice device = rtcNewDevice("threads=1");
    if (!device) return "(no device)";
    const auto property = [&](RTCDeviceProperty p) { return rtcGetDeviceProperty(device, p); };
    std::string text =
        std::to_string(property(RTC_DEVICE_PROPERTY_VERSION_MAJOR)) + "." +
        std::to_string(property(RTC_DEVICE_PROPERTY_VERSION_MINOR)) + "." +
        std::to_string(property(RTC_DEVICE_PROPERTY_VERSION_PATCH)) +
        " (native ray8: " + (property(RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) ? "yes" : "no") +
        ")";
    rtcReleaseDevice(device);
    return text;
}

std::vector<int> EmbreeTracer::trace(const CameraBasis& camera, int width, int height, int threads,
                                     bool packets) const {
    const Impl& m = *impl_;
    std::vector<int> ids(size_t(width) * size_t(height), -1);
    // The primary ray of pixel (x, y), as the reference builds it (in double).
    const auto direction = [&](int x, int y) {
        const PixelSample s = primarySample(x, y, 1);
        const double sx = 2 * s.px / width - 1, sy = 1 - 2 * s.py / height;
        return glm::normalize(-camera.n + sx * camera.tanHalfFov * camera.aspect * camera.u +
                              sy * camera.tanHalfFov * camera.v);
    };
    // Planes and the like: not in Embree's BVH (it needs finite boxes).
    const auto unboundedHit = [&](const glm::dvec3& d, float tFar, int id) {
        for (int index : m.unbounded) {
            const auto h = reference::intersectObject(m.scene, m.scene.objects[size_t(index)],
                                                      index, {camera.eye, d}, 0.0);
            if (h && h->t < tFar) {
                tFar = float(h->t);
                id = index;
            }
        }
        return id;
    };
    const auto objectOf = [&](unsigned geomID, unsigned primID) {
        return geomID == RTC_INVALID_GEOMETRY_ID ? -1 : m.objectOfPrimitive[geomID][primID];
    };
    // Two rows at a time: the height of an 8-ray packet of 4x2 rays.
    const auto rowPair = [&](std::size_t pair) {
        const int y0 = 2 * int(pair);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        if (packets) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        if (!packets) {
            for (int y = y0; y < std::min(y0 + 2, height); ++y)
                for (int x = 0; x < width; ++x) {
                    const glm::dvec3 d = direction(x, y);
                    RTCRayHit rh{};
                    rh.ray = {float(camera.eye.x),
                              float(camera.eye.y),
                              float(camera.eye.z),
                              0.f,
                              float(d.x),
                              float(d.y),
                              float(d.z),
                              0.f,
                              std::numeric_limits<float>::infinity(),
                              ~0u,
                              0,
                              0};
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rtcIntersect1(m.rtcScene, &context, &rh);
                    int id = objectOf(rh.hit.geomID, rh.hit.primID);
                    if (!m.unbounded.empty()) id = unboundedHit(d, rh.ray.tfar, id);
                    ids[size_t(y) * size_t(width) + size_t(x)] = id;
                }
            return;
        }
        for (int x0 = 0; x0 < width; x0 += 4) {
            alignas(32) RTCRayHit8 rh;
            alignas(32) int valid[8];
            glm::dvec3 dirs[8];
            for (int k = 0; k < 8; ++k) {
                const int x = x0 + k % 4, y = y0 + k / 4;
                valid[k] = x < width && y < height ? -1 : 0;
                const glm::dvec3 d = valid[k] ? direction(x, y) : glm::dvec3(0, 0, -1);
                dirs[k] = d;
                rh.ray.org_x[k] = float(camera.eye.x);
                rh.ray.org_y[k] = float(camera.eye.y);
                rh.ray.org_z[k] = float(camera.eye.z);
                rh.ray.tnear[k] = 0;
                rh.ray.dir_x[k] = float(d.x);
                rh.ray.dir_y[k] = float(d.y);
                rh.ray.dir_z[k] = float(d.z);
                rh.ray.time[k] = 0;
                rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
                rh.ray.mask[k] = ~0u;
                rh.ray.id[k] = unsigned(k);
                rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect8(valid, m.rtcScene, &context, &rh);
            for (int k = 0; k < 8; ++k) {
                if (!valid[k]) continue;
                int id = objectOf(rh.hit.geomID[k], rh.hit.primID[k]);
                if (!m.unbounded.empty()) id = unboundedHit(dirs[k], rh.ray.tfar[k], id);
                ids[size_t(y0 + k / 4) * size_t(width) + size_t(x0 + k % 4)] = id;
            }
        }
    };
    parallelFor(std::size_t(height + 1) / 2, rowPair, threads);
    m.check("tracing");
    return ids;
}

}  // namespace vkray::bench
