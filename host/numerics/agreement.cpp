// The margin rule (see agreement.h).
#include "numerics/agreement.h"

#include "reference/shading.h"
#include "util/error.h"
#include "util/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <map>

namespace vkray {

namespace {

constexpr double kFloatBound = 64 * 0x1p-24;
constexpr double kDoubleBound = 64 * 0x1p-53;

// Float's rounding of a depth or a normal's component, with the room the
// colours get: the reference's own are in double, a Frame's in float.
constexpr double kDepthTolerance = 1e-4;  // relative
constexpr double kNormalTolerance = 1e-3;

double colorError(const glm::vec3& a, const glm::vec3& b) {
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
        if (std::isnan(a[c]) != std::isnan(b[c])) return 1e30;
        if (std::isnan(a[c])) continue;
        const double scale = std::max(1.0, double(std::abs(b[c])));
        worst = std::max(worst, std::abs(double(a[c]) - double(b[c])) / scale);
    }
    return worst;
}

// How far float's rounding moves a hit's depth and normal on its own, no
// decision turned (where both renderers hit the same object): the depth by
// the bound of the object's reach from the eye, more at grazing incidence
// (t = distance / cos); the normal by the float bound of its generic reach,
// times M's condition (M^-T takes it to the world).
struct Rooms {
    double depth = 0, normal = 0;
};

bool depthsDiffer(float a, float b, const Rooms& rooms) {
    if (std::isinf(a) || std::isinf(b)) return a != b;
    return std::abs(double(a) - double(b)) >
           kDepthTolerance * std::abs(double(b)) + 1e-5 + rooms.depth;
}

bool normalsDiffer(const glm::vec3& a, const glm::vec3& b, const Rooms& rooms) {
    const glm::vec3 d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z}) > std::max(kNormalTolerance, rooms.normal);
}

// M's condition, bounded above: the Frobenius norms of M and M^-1.
double conditionOf(const SceneObject& object) {
    if (!object.operands.empty()) {
        double c = 1;
        for (const SceneObject& operand : object.operands) c = std::max(c, conditionOf(operand));
        return c;
    }
    double m = 0, inverse = 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
            m += object.worldFromObject[c][r] * object.worldFromObject[c][r];
            inverse += object.objectFromWorld[c][r] * object.objectFromWorld[c][r];
        }
    return std::sqrt(m * inverse);
}

// |M^-1 eye| (at least 1), the largest over a boolean's primitives.
double genericReachOf(const SceneObject& object, const glm::dvec3& eye) {
    if (!object.operands.empty()) {
        double g = 1;
        for (const SceneObject& operand : object.operands)
            g = std::max(g, genericReachOf(operand, eye));
        return g;
    }
    const glm::dvec3 generic(object.objectFromWorld * glm::dvec4(eye, 1));
    return std::max({std::abs(generic.x), std::abs(generic.y), std::abs(generic.z), 1.0});
}

struct Difference {
    bool color = false, id = false, depth = false, normal = false;
    bool any() const { return color || id || depth || normal; }
};

Difference differenceAt(const Frame& gpu, const Frame& cpu, std::size_t i, double threshold,
                        const Rooms& rooms) {
    Difference d;
    d.color = colorError(gpu.color[i], cpu.color[i]) > threshold;
    d.id = gpu.id[i] != cpu.id[i];
    if (!d.id && gpu.id[i] >= 0) {
        d.depth = depthsDiffer(gpu.depth[i], cpu.depth[i], rooms);
        d.normal = normalsDiffer(gpu.normal[i], cpu.normal[i], rooms);
    }
    return d;
}

// Whether the span holds the GPU's value: each colour channel within the
// span's, the id one the reference gives in some play, and the depth and
// normal within those of the plays that hit that object.
bool explains(const reference::PixelSpan& span, const Frame& gpu, std::size_t i,
              const Difference& d, double threshold, const Rooms& rooms) {
    for (int c = 0; c < 3; ++c) {
        const double g = gpu.color[i][c];
        if (std::isnan(g)) return false;
        const double low = span.low[c], high = span.high[c];
        const double room = threshold * std::max({1.0, std::abs(low), std::abs(high)});
        if (g < low - room || g > high + room) return false;
    }
    bool idMet = false, depthMet = !d.depth, normalMet = !d.normal;
    for (const reference::PixelSpan::FirstHit& hit : span.firstHits) {
        if (hit.id != gpu.id[i]) continue;
        idMet = true;
        if (!depthMet) depthMet = !depthsDiffer(gpu.depth[i], hit.depth, rooms);
        if (!normalMet) normalMet = !normalsDiffer(gpu.normal[i], hit.normal, rooms);
    }
    if (d.depth || d.normal) {
        // Between the plays' values counts too: the GPU's rounding lands anywhere.
        float low = gpu.depth[i], high = gpu.depth[i];
        glm::vec3 nLow(1e30f), nHigh(-1e30f);
        bool any = false;
        for (const reference::PixelSpan::FirstHit& hit : span.firstHits) {
            if (hit.id != gpu.id[i]) continue;
            if (!any) low = high = hit.depth;
            any = true;
            low = std::min(low, hit.depth);
            high = std::max(high, hit.depth);
            nLow = glm::min(nLow, hit.normal);
            nHigh = glm::max(nHigh, hit.normal);
        }
        const double g = gpu.depth[i];
        const double room = kDepthTolerance * std::abs(g) + 1e-5 + rooms.depth;
        if (any && g >= low - room && g <= high + room) depthMet = true;
        const glm::vec3 n = gpu.normal[i];
        const float normalRoom = float(std::max(kNormalTolerance, rooms.normal));
        if (any && glm::all(glm::greaterThanEqual(n, nLow - normalRoom)) &&
            glm::all(glm::lessThanEqual(n, nHigh + normalRoom)))
            normalMet = true;
    }
    return idMet && depthMet && normalMet;
}

}  // namespace

reference::ErrorBound errorBoundOf(Precision precision) {
    reference::ErrorBound bound;
    bound.position = precision == Precision::Fp64 ? kDoubleBound : kFloatBound;
    bound.primaryTilt = bound.position;
    // Shading is float in every mode: the shaded point (where secondary rays
    // leave, in the eye's frame), the normal (their directions), the textures.
    bound.secondaryTilt = kFloatBound;
    bound.secondaryPosition = kFloatBound;
    bound.texture = kFloatBound;
    bound.absolute = precision == Precision::Naive ? 1e-4 : 0;
    return bound;
}

Agreement judgeAgreement(const Scene& scene, const CameraBasis& camera,
                         const RenderSettings& settings, Precision precision, const Frame& gpu,
                         const Frame& cpu, const AgreementOptions& options) {
    if (gpu.width != cpu.width || gpu.height != cpu.height)
        throw Error("compare: the GPU's frame is " + std::to_string(gpu.width) + "x" +
                    std::to_string(gpu.height) + ", the CPU reference's " +
                    std::to_string(cpu.width) + "x" + std::to_string(cpu.height));
    Agreement a;
    a.pixels = gpu.pixelCount();
    a.verdicts.assign(a.pixels, PixelVerdict::Same);
    const int block = std::max(settings.block, 1);
    const reference::ErrorBound bound = errorBoundOf(precision);
    std::vector<double> reaches, genericReaches, conditions;
    for (const SceneObject& object : scene.objects) {
        reaches.push_back(reference::reachOf(scene, object, camera.eye));
        genericReaches.push_back(genericReachOf(object, camera.eye));
        conditions.push_back(conditionOf(object));
    }
    const auto roomsAt = [&](int x, int y, std::size_t i) {
        Rooms rooms;
        const int id = cpu.id[i];
        if (id < 0 || std::size_t(id) >= reaches.size()) return rooms;
        const glm::dvec3 d = primaryDirection(
            camera, settings, jitteredSample(x - x % block, y - y % block, settings, 0));
        const double cosine = std::abs(glm::dot(d, glm::dvec3(cpu.normal[i])));
        rooms.depth =
            (bound.position * reaches[std::size_t(id)] + bound.absolute) / std::max(cosine, 1e-6);
        rooms.normal =
            bound.secondaryTilt * genericReaches[std::size_t(id)] * conditions[std::size_t(id)];
        return rooms;
    };
    // The differing pixels, by the block whose ray they show.
    std::map<std::pair<int, int>, std::vector<std::size_t>> byBlock;
    std::vector<Difference> differences(a.pixels);
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            const std::size_t i = gpu.index(x, y);
            const double error = colorError(gpu.color[i], cpu.color[i]);
            if (error > a.largest) {
                a.largest = error;
                a.largestX = x;
                a.largestY = y;
            }
            const Difference d =
                differenceAt(gpu, cpu, i, options.colorThreshold, roomsAt(x, y, i));
            if (!d.any()) continue;
            differences[i] = d;
            ++a.differing;
            a.colors += d.color;
            a.ids += d.id;
            a.depths += d.depth;
            a.normals += d.normal;
            byBlock[{x - x % block, y - y % block}].push_back(i);
        }
    if (!byBlock.empty()) {
        const reference::MarginTracer margins(scene, camera, settings, errorBoundOf(precision));
        std::vector<std::pair<std::pair<int, int>, std::vector<std::size_t>>> blocks(
            byBlock.begin(), byBlock.end());
        parallelFor(
            blocks.size(),
            [&](std::size_t b) {
                const auto& [origin, pixels] = blocks[b];
                const reference::PixelSpan span = margins.spanOf(origin.first, origin.second);
                for (const std::size_t i : pixels)
                    a.verdicts[i] = explains(span, gpu, i, differences[i], options.colorThreshold,
                                             roomsAt(int(i % std::size_t(gpu.width)),
                                                     int(i / std::size_t(gpu.width)), i))
                                        ? PixelVerdict::SetAside
                                        : PixelVerdict::Unexplained;
            },
            options.threads);
    }
    for (std::size_t i = 0; i < a.pixels; ++i) {
        if (a.verdicts[i] == PixelVerdict::SetAside) ++a.setAside;
        if (a.verdicts[i] != PixelVerdict::Unexplained) continue;
        ++a.unexplained;
        if (a.firstUnexplained.size() < 5)
            a.firstUnexplained.emplace_back(int(i % std::size_t(gpu.width)),
                                            int(i / std::size_t(gpu.width)));
    }
    a.passed = 100.0 * double(a.unexplained) <= options.allowedPercent * double(a.pixels);
    return a;
}

std::string formatAgreement(const Agreement& a, const AgreementOptions& options) {
    const auto percent = [&](std::size_t n) { return 100.0 * double(n) / double(a.pixels); };
    char line[400];
    std::string text;
    std::snprintf(line, sizeof line,
                  "differing       %zu of %zu pixels (%.4g %%): colour %zu (above %.4g), ids %zu, "
                  "depth %zu, normals %zu\n",
                  a.differing, a.pixels, percent(a.differing), a.colors, options.colorThreshold,
                  a.ids, a.depths, a.normals);
    text += line;
    std::snprintf(line, sizeof line,
                  "set aside       %zu pixels (%.4g %%): within a decision's margin of the "
                  "mode's error bound\n",
                  a.setAside, percent(a.setAside));
    text += line;
    std::snprintf(line, sizeof line, "unexplained     %zu pixels (%.4g %%), allowed %.4g %%",
                  a.unexplained, percent(a.unexplained), options.allowedPercent);
    text += line;
    for (std::size_t k = 0; k < a.firstUnexplained.size(); ++k)
        text += (k == 0 ? ": at (" : ", (") + std::to_string(a.firstUnexplained[k].first) + ", " +
                std::to_string(a.firstUnexplained[k].second) + ")";
    text += a.unexplained > a.firstUnexplained.size() ? ", ...\n" : "\n";
    std::snprintf(line, sizeof line, "largest         %.4g at (%d, %d) (colour, unclamped)\n",
                  a.largest, a.largestX, a.largestY);
    text += line;
    text += a.passed ? "result          PASS\n" : "result          FAIL\n";
    return text;
}

Image agreementImage(const Frame& gpu, const Frame& cpu, const Agreement& a) {
    Image image{gpu.width, gpu.height, 3, std::vector<float>(gpu.pixelCount() * 3)};
    for (std::size_t i = 0; i < gpu.pixelCount(); ++i) {
        glm::vec3 c;
        if (a.verdicts[i] == PixelVerdict::SetAside) {
            c = {0.2f, 0.4f, 1.0f};
        } else if (a.verdicts[i] == PixelVerdict::Unexplained) {
            c = {1.0f, 0.1f, 0.1f};
        } else {
            const float grey = std::min(1.0f, 4.0f * float(colorError(gpu.color[i], cpu.color[i])));
            c = glm::vec3(grey);
        }
        for (int k = 0; k < 3; ++k) image.pixels[3 * i + std::size_t(k)] = c[k];
    }
    return image;
}

}  // namespace vkray
