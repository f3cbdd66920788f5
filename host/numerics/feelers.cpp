// Compiled with -fno-tree-slp-vectorize (CMakeLists.txt): GCC 12's SLP
// vectoriser has been seen to drop a double -> float -> double rounding
// (NUMERICS.md section 9), and this file must round exactly as float does.
#include "numerics/feelers.h"

#include "scene/error.h"
#include "shaders/layout.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace vkray::numerics {

namespace {

using FVec = Vec3<float>;

template <typename T>
Vec3<T> toMode(const glm::dvec3& v) { return {T(v.x), T(v.y), T(v.z)}; }
template <typename T, typename U>
Vec3<T> toMode(const Vec3<U>& v) { return {T(v.x), T(v.y), T(v.z)}; }
RVec toReal(const glm::dvec3& v) { return {Real(v.x), Real(v.y), Real(v.z)}; }
template <typename T>
RVec toRealVec(const Vec3<T>& v) { return {Real(v.x), Real(v.y), Real(v.z)}; }

// An object's M^-1 as the GPU holds it: three rows of an affine map, in the
// mode's type T (float, or double for fp64).
template <typename T>
struct ModeObject {
    T rows[3][4];
    const SceneObject* object;

    explicit ModeObject(const SceneObject& o) : object(&o) {
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) rows[r][c] = T(o.objectFromWorld[c][r]);
    }
    Vec3<T> point(Vec3<T> p) const {
        Vec3<T> out;
        for (int r = 0; r < 3; ++r)
            out[r] = rows[r][0] * p.x + rows[r][1] * p.y + rows[r][2] * p.z + rows[r][3];
        return out;
    }
    Vec3<T> vector(Vec3<T> d) const {
        Vec3<T> out;
        for (int r = 0; r < 3; ++r) out[r] = rows[r][0] * d.x + rows[r][1] * d.y + rows[r][2] * d.z;
        return out;
    }
};

template <typename T>
Crossings<T> modeCrossings(const ModeObject<T>& f, Vec3<T> origin, Vec3<T> direction) {
    const Vec3<T> o = f.point(origin), d = f.vector(direction);
    switch (f.object->type) {
    case ShapeType::Sphere: return sphereCrossings(o, d);
    case ShapeType::Plane: return planeCrossings(o, d, false);
    case ShapeType::Square: return planeCrossings(o, d, true);
    case ShapeType::Cube: return cubeCrossings(o, d);
    case ShapeType::Cylinder: return taperedCylinderCrossings(o, d, T(1));
    case ShapeType::Cone: return taperedCylinderCrossings(o, d, T(0));
    case ShapeType::TaperedCylinder: return taperedCylinderCrossings(o, d, T(f.object->taper));
    case ShapeType::Torus:
        return torusCrossings(o, d, T(kTorusMajorRadius), T(kTorusTubeRadius));
    default: throw Error("internal: no intersector for this shape");
    }
}

// The first crossing with tMin < t < tMax, or -1.
template <typename T>
T firstCrossing(const Crossings<T>& c, T tMin, T tMax) {
    for (int i = 0; i < c.count; ++i)
        if (c.at[i].t > tMin && c.at[i].t < tMax) return c.at[i].t;
    return -1;
}

constexpr float kNaiveEpsilon = 1e-4f;  // shaders/precision.glsl NAIVE_EPSILON

// shaders/shade.glsl genericScaleAlong at a hit with world unit normal n on
// `object`: the world length along n of one generic unit, |g| / |(M^-1)^T g|
// for the generic normal g, which is |M^T n| (g is M^T n up to its length),
// times the generic shape's extent (shade.glsl genericExtent: 0 for a plane
// or square, max(1, |s|) for a tapered cylinder, else 1; the replay has no
// meshes). The shader computes it from g and the rows of M^-1, this from n
// and M: the same up to rounding.
template <typename T>
T genericScaleAlong(const SceneObject& object, Vec3<T> n) {
    const glm::dvec3 along = glm::transpose(glm::dmat3(object.worldFromObject)) *
                             glm::dvec3(double(n.x), double(n.y), double(n.z));
    const bool flat = object.type == ShapeType::Plane || object.type == ShapeType::Square;
    const bool tapered = object.type == ShapeType::TaperedCylinder;
    const double extent = flat ? 0.0 : tapered ? std::max(1.0, std::abs(object.taper)) : 1.0;
    return T(glm::length(along) / glm::length(glm::dvec3(double(n.x), double(n.y), double(n.z))) *
             extent);
}

// shaders/precision.glsl offsetOrigin's last step: `step` off the surface
// (along n), taken along the ray (unit direction a) as far as
// OFFSET_MAX_FORWARD steps do it, the rest along n. c = n . a in float, as the
// shader has it.
template <typename T>
Vec3<T> stepOff(Vec3<T> p, Vec3<float> n, Vec3<float> a, T step) {
    const float c = dot(n, a);
    const T forward = c > 0 ? std::min(step / T(c), T(gpu::OFFSET_MAX_FORWARD) * step) : T(0);
    return p + forward * toMode<T>(a) + std::max(step - forward * T(c), T(0)) * toMode<T>(n);
}

// shaders/precision.glsl offsetOrigin, per mode; `along` is the new ray's direction.
FVec offsetOrigin(Precision precision, FVec p, FVec n, FVec along, float genericScale) {
    return precision == Precision::Naive ? p + kNaiveEpsilon * n
                                         : offsetRayOriginRobust(p, n, along, genericScale);
}
Vec3<double> offsetOrigin(Precision, Vec3<double> p, Vec3<double> n, Vec3<double> along,
                          double genericScale) {
    // OFFSET_DOUBLE_* of shaders/precision.glsl
    constexpr double kScale = 0x1p-47, kNearOriginStep = 0x1p-45, kGenericScale = 0x1p-47;
    const double largest = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
    const double step = std::max(std::max(kScale * largest, kNearOriginStep), kGenericScale * genericScale);
    return stepOff(p, toMode<float>(n), normalize(toMode<float>(along)), step);
}

template <typename T>
T tMinOf(Precision precision) { return precision == Precision::Naive ? T(kNaiveEpsilon) : T(0); }

// What the replay of one pixel needs, in the mode's world and in the oracle's.
template <typename T>
struct PixelSetup {
    Vec3<T> p, n, d;  // the mode's hit point, normal (facing the ray), ray direction
    RVec pTrue, nTrue, dTrue;
    Real tTrue;      // the primary hit's distance
    const SceneObject* original;  // the object as the scene has it (for the oracle)
    size_t pixel;                 // its index, row-major
};

// The pixels both agree on (same object, outside the float band), with the
// mode's hit point: for a float mode from the t the GPU returned; for fp64,
// whose t reaches the host rounded to float, from the primary ray replayed
// in double (the shader keeps t and the hit point in double).
template <typename T, typename Visit>
void forAgreeingPixels(const Scene& scene, const CameraBasis& camera,
                       const std::vector<OraclePixel>& oracle,
                       const std::vector<ModeSample>& samples, Precision precision, Visit visit) {
    const GpuInputs mode = prepareGpuInputs(precision, scene, camera);
    std::vector<ModeObject<T>> objects;
    for (const SceneObject& object : mode.scene.objects) objects.emplace_back(object);
    const Vec3<T> eye = toMode<T>(mode.camera.eye);
    const RVec eyeTrue = toReal(camera.eye);
    for (size_t i = 0; i < oracle.size(); ++i) {
        const OraclePixel& o = oracle[i];
        const ModeSample& s = samples[i];
        if (o.silhouette[0] || o.hit.id < 0 || s.id != o.hit.id || !std::isfinite(s.t)) continue;
        PixelSetup<T> px;
        px.pixel = i;
        px.d = toMode<T>(o.direction);
        T t = T(s.t);
        if constexpr (!std::is_same_v<T, float>) {
            // The shader's choice: the object's first crossing beyond tMin.
            const T first = firstCrossing(modeCrossings(objects[size_t(s.id)], eye, px.d),
                                          tMinOf<T>(precision), std::numeric_limits<T>::infinity());
            if (first > 0) t = first;
        }
        px.p = eye + t * px.d;
        px.n = toMode<T>(s.normal);
        px.dTrue = o.direction;
        px.pTrue = eyeTrue + o.hit.t * o.direction;
        px.nTrue = o.hit.normal;
        px.tTrue = o.hit.t;
        px.original = &scene.objects[size_t(s.id)];
        visit(px, objects[size_t(s.id)], mode.scene);
    }
}

template <typename T>
FeelerStats shadowFeelerAcneIn(const Scene& scene, const CameraBasis& camera,
                               const std::vector<OraclePixel>& oracle,
                               const std::vector<ModeSample>& samples, Precision precision) {
    FeelerStats stats;
    forAgreeingPixels<T>(scene, camera, oracle, samples, precision,
                         [&](const PixelSetup<T>& px, const ModeObject<T>& object, const Scene& modeScene) {
        bool traced = false, failed = false;
        for (size_t l = 0; l < scene.lights.size(); ++l) {
            const Vec3<T> toLight = toMode<T>(modeScene.lights[l].position) - px.p;
            const RVec toLightTrue = toReal(scene.lights[l].position) - px.pTrue;
            if (!(dot(px.n, toLight) > 0) || !(dot(px.nTrue, toLightTrue) > 0)) continue;
            traced = true;
            // Unit direction: t and the fixed epsilon are world distances.
            const T distance = length(toLight);
            const Vec3<T> origin = offsetOrigin(precision, px.p, px.n, toLight,
                                                genericScaleAlong(*object.object, px.n));
            const T t = firstCrossing(modeCrossings(object, origin, toLight / distance),
                                      tMinOf<T>(precision), distance);
            if (t < 0) continue;
            // Acne only if the exact feeler is not shadowed by this surface at all:
            // a torus may shadow itself, and near its terminator, on the saddle
            // side, a grazing feeler meets it again a little further on. (The
            // exact origin's own crossing, at |t| ~ 1e-18, is not counted.)
            const Crossings<Real> truth = objectCrossings(*px.original, {px.pTrue, normalize(toLightTrue)});
            const Real tiny = Real(1e-6) * px.tTrue, far = length(toLightTrue);
            bool genuine = false;
            for (int k = 0; k < truth.count; ++k)
                genuine = genuine || (truth.at[k].t > tiny && truth.at[k].t < far);
            failed = failed || !genuine;
        }
        stats.traced += traced;
        stats.failed += failed;
        if (failed) stats.failedPixels.push_back(px.pixel);
    });
    return stats;
}

template <typename T>
FeelerStats refractionExitErrorsIn(const Scene& scene, const CameraBasis& camera,
                                   const std::vector<OraclePixel>& oracle,
                                   const std::vector<ModeSample>& samples, Precision precision) {
    FeelerStats stats;
    constexpr double kEta = 1.0 / 1.5;  // from air into glass
    // From the mode's world (rebased for robust and fp64) back to the scene's.
    const glm::dvec3 shift = camera.eye - prepareGpuInputs(precision, scene, camera).camera.eye;
    forAgreeingPixels<T>(scene, camera, oracle, samples, precision,
                         [&](const PixelSetup<T>& px, const ModeObject<T>& object, const Scene&) {
        // Snell's law with n facing the incoming ray: t = eta d + (eta c - sqrt(k)) n.
        const auto refract = [](auto d, auto n, auto eta) {
            const auto c = -dot(d, n);
            const auto k = 1 - eta * eta * (1 - c * c);
            return eta * d + (eta * c - std::sqrt(k)) * n;
        };
        const Vec3<T> dIn = refract(px.d, px.n, T(kEta));
        const RVec dInTrue = refract(px.dTrue, px.nTrue, Real(kEta));
        // The exit the oracle finds: the first crossing beyond the entry point itself.
        const Crossings<Real> truth = objectCrossings(*px.original, {px.pTrue, dInTrue});
        Real exitTrue = -1;
        for (int k = 0; k < truth.count && exitTrue < 0; ++k)
            if (truth.at[k].t > Real(1e-6) * px.tTrue) exitTrue = truth.at[k].t;
        if (exitTrue < 0) return;  // grazing entry: no path through
        ++stats.traced;
        const Vec3<T> origin = offsetOrigin(precision, px.p, T(-1) * px.n, dIn,
                                            genericScaleAlong(*object.object, px.n));
        const T exit = firstCrossing(modeCrossings(object, origin, dIn), tMinOf<T>(precision),
                                     std::numeric_limits<T>::infinity());
        // Failed: no exit, the entry surface met again (t well short of the
        // exit), or an exit point off by more than 1e-3 of the eye's distance
        // (a pixel's footprint at 640 pixels and 60 degrees is 1.6e-3 of it).
        // Offsetting the origin moves the exit point by about the offset,
        // which is fine until the offset reaches a visible size.
        const RVec exitPoint = toReal(shift) + toRealVec(origin + exit * dIn);
        const RVec exitPointTrue = px.pTrue + exitTrue * dInTrue;
        const bool failed = !(exit > 0 && Real(exit) > exitTrue / 2 &&
                              length(exitPoint - exitPointTrue) <= Real(1e-3) * px.tTrue);
        stats.failed += failed;
        if (failed) stats.failedPixels.push_back(px.pixel);
    });
    return stats;
}

}  // namespace

Vec3<float> offsetRayOriginRobust(Vec3<float> p, Vec3<float> n, Vec3<float> along,
                                  float genericScale) {
    // shaders/layout.h: the shader's constants.
    const float largest = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
    const float step = largest < gpu::OFFSET_NEAR_ORIGIN ? gpu::OFFSET_NEAR_ORIGIN_STEP
                                                         : gpu::OFFSET_SCALE * largest;
    return stepOff(p, n, normalize(along), std::max(step, gpu::OFFSET_GENERIC_SCALE * genericScale));
}

FeelerStats shadowFeelerAcne(const Scene& scene, const CameraBasis& camera,
                             const std::vector<OraclePixel>& oracle,
                             const std::vector<ModeSample>& samples, Precision precision) {
    return precision == Precision::Fp64
               ? shadowFeelerAcneIn<double>(scene, camera, oracle, samples, precision)
               : shadowFeelerAcneIn<float>(scene, camera, oracle, samples, precision);
}

FeelerStats refractionExitErrors(const Scene& scene, const CameraBasis& camera,
                                 const std::vector<OraclePixel>& oracle,
                                 const std::vector<ModeSample>& samples, Precision precision) {
    return precision == Precision::Fp64
               ? refractionExitErrorsIn<double>(scene, camera, oracle, samples, precision)
               : refractionExitErrorsIn<float>(scene, camera, oracle, samples, precision);
}

}  // namespace vkray::numerics
