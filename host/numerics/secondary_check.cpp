#include "numerics/secondary_check.h"

#include "shaders/layout.h"
#include "util/error.h"
#include "util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

namespace vkray::numerics {

namespace {

QVec toQuad(const glm::dvec3& v) {
    return {Quad(v.x), Quad(v.y), Quad(v.z)};
}
BVec exact(const QVec& v) {
    return {Bounded(v.x), Bounded(v.y), Bounded(v.z)};
}

// Crossings nearer the feeler's origin than this share of the primary t are
// the origin's own surface, or one coincident with it within the scene's own
// rounding (a square laid on a cube's face through rotate -90, whose double
// cosine is 6e-17, crosses it 7e-17 away): the oracle's tie tolerance, as
// for primary hits (oracle.h, closestHit).
const Quad kOwnSurface = Quad(1e-9);

// What the exact feeler from a point meets before the light: the object it
// leaves, and the others; each Yes, No or Uncertain (within the oracle's bounds).
struct FeelerTruth {
    Meets metLeft = Meets::No, metOther = Meets::No;
    Meets met() const {
        if (metLeft == Meets::Yes || metOther == Meets::Yes) return Meets::Yes;
        return metLeft == Meets::Uncertain || metOther == Meets::Uncertain ? Meets::Uncertain
                                                                           : Meets::No;
    }
};

FeelerTruth exactFeeler(const Scene& scene, int left, const BVec& from, const QVec& light,
                        const Quad& tiny) {
    const QVec toLight = light - valueOf(from);
    const Quad distance = length(toLight);
    const OracleRay ray{from, exact(toLight / distance)};
    FeelerTruth truth;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Meets m = meets(scene.objects[i], ray, tiny, distance);
        Meets& slot = int(i) == left ? truth.metLeft : truth.metOther;
        if (m == Meets::Yes || (m == Meets::Uncertain && slot == Meets::No)) slot = m;
    }
    return truth;
}

// Snell's law for unit d and the unit normal n facing it, eta = c2 / c1.
QVec refract(const QVec& d, const QVec& n, const Quad& eta) {
    const Quad c = -dot(d, n);
    const Quad k = 1 - eta * eta * (1 - c * c);
    return eta * d + (eta * c - sqrt(k)) * n;
}

}  // namespace

OriginFootprint originFootprintOf(Precision precision) {
    switch (precision) {
    case Precision::Naive: return {0, 2 * 1e-4};      // NAIVE_EPSILON
    case Precision::Robust: return {2 * 0x1p-18, 0};  // OFFSET_SCALE, OFFSET_GENERIC_SCALE
    case Precision::Fp64: return {2 * 0x1p-47, 0};    // OFFSET_DOUBLE_*
    }
    return {};
}

SecondaryStats checkSecondaryRays(const Scene& scene, const CameraBasis& camera,
                                  const std::vector<OraclePixel>& oracle,
                                  const std::vector<StressSample>& samples, Arithmetic a,
                                  const OriginFootprint& footprint, int threads) {
    if (oracle.size() != samples.size()) throw Error("internal: oracle and samples differ in size");
    const BVec eye = exact(toQuad(camera.eye));
    const int lights = int(std::min<size_t>(scene.lights.size(), gpu::STRESS_MAX_LIGHTS));
    std::atomic<size_t> feelerPixels{0}, acne{0}, shadowFlips{0}, shadowEdges{0}, refracted{0},
        exitErrors{0};
    std::mutex failedLock;
    std::vector<size_t> failed;
    constexpr size_t kChunk = 256;
    const auto checkChunk = [&](size_t chunk) {
        std::vector<size_t> mine;
        {
            const size_t first = chunk * kChunk;
            for (size_t i = first; i < std::min(first + kChunk, oracle.size()); ++i) {
                const OraclePixel& o = oracle[i];
                const StressSample& s = samples[i];
                if (o.setAside[a] || o.hit.id < 0 || s.object != o.hit.id || !std::isfinite(s.t))
                    continue;
                const BVec direction = exact(o.direction);
                const BVec point = eye + Bounded(o.hit.t, o.hit.tBound) * direction;
                const BVec modePoint = eye + Bounded(Quad(s.t)) * direction;
                const Quad tiny = kOwnSurface * o.hit.t;
                // The mode's origin footprint at this point, along the normal.
                const QVec fromEye = o.hit.t * o.direction;
                const double largest =
                    double(std::max({abs(fromEye.x), abs(fromEye.y), abs(fromEye.z)}));
                const double scale =
                    genericScaleAlong(scene.objects[size_t(o.hit.id)], o.hit.genericNormal);
                const Quad reach =
                    Quad(footprint.relative * std::max(largest, scale) + footprint.absolute);
                bool traced = false, selfHit = false, flip = false, edge = false;
                for (int l = 0; l < lights; ++l) {
                    const QVec light = toQuad(scene.lights[size_t(l)].position);
                    if (!s.feelerTraced(l) || !(dot(o.hit.normal, light - valueOf(point)) > 0))
                        continue;
                    traced = true;
                    const FeelerTruth truth = exactFeeler(scene, o.hit.id, point, light, tiny);
                    if (truth.met() == Meets::Uncertain) {  // the oracle cannot tell: not compared
                        edge = true;
                        continue;
                    }
                    // Acne: met the surface it left, which the exact feeler certainly never meets.
                    if (s.feelerMetLeft(l) && truth.metLeft == Meets::No) selfHit = true;
                    if (s.feelerMetLeft(l) || s.feelerMet(l) == (truth.met() == Meets::Yes))
                        continue;
                    // A verdict the other objects decide differently from the mode's own
                    // hit point, or from the exact one moved by the origin footprint, lies
                    // on a shadow's edge (the object left is acne's to judge).
                    bool onEdge = exactFeeler(scene, o.hit.id, modePoint, light, tiny).metOther !=
                                  truth.metOther;
                    for (const Quad& side : {Quad(1), Quad(-1)}) {
                        if (onEdge) break;
                        const BVec moved = point + Bounded(side * reach) * exact(o.hit.normal);
                        onEdge = exactFeeler(scene, o.hit.id, moved, light, tiny).metOther !=
                                 truth.metOther;
                    }
                    (onEdge ? edge : flip) = true;
                }
                feelerPixels += traced;
                acne += selfHit;
                shadowFlips += flip;
                shadowEdges += edge && !flip;
                if (selfHit || flip) mine.push_back(i);
                if (!s.refractedTraced || !o.hit.entering) continue;
                // The exact refracted ray, entering from air: eta = c_object / 1.
                const SceneObject& object = scene.objects[size_t(o.hit.id)];
                const QVec inward = normalize(
                    refract(o.direction, o.hit.normal, Quad(object.material.speedOfLight)));
                const OracleHit exit = closestHit(scene, {point, exact(inward)}, tiny);
                if (exit.id < 0 || exit.uncertain)
                    continue;  // no way through, or the oracle cannot tell
                ++refracted;
                const QVec exitPoint = o.hit.t * o.direction + exit.t * inward;  // from the eye
                const QVec modeExit = toQuad(s.refractedPoint);
                const bool good = s.refractedObject == exit.id && Quad(s.refractedT) > exit.t / 2 &&
                                  length(modeExit - exitPoint) <= Quad(1e-3) * o.hit.t;
                exitErrors += !good;
                if (!good && (mine.empty() || mine.back() != i)) mine.push_back(i);
            }
        }
        const std::lock_guard<std::mutex> hold(failedLock);
        failed.insert(failed.end(), mine.begin(), mine.end());
    };
    parallelFor((oracle.size() + kChunk - 1) / kChunk, checkChunk, threads);
    std::sort(failed.begin(), failed.end());
    return {feelerPixels, acne, shadowFlips, shadowEdges, refracted, exitErrors, failed};
}

}  // namespace vkray::numerics
