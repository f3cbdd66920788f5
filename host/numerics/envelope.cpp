#include "numerics/envelope.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/scene_geometry.h"

namespace vkray {

namespace {

// The largest singular value of a 3x3 matrix: power iteration on A^T A from
// its longest column (never orthogonal to the top singular vector unless
// the matrix is zero). A lower bound that converges from below; the figures
// it feeds are compared with limits orders of magnitude apart.
double largestSingularValue(const glm::dmat3& a) {
    glm::dvec3 v = a[0];
    for (int c = 1; c < 3; ++c)
        if (glm::length(a[c]) > glm::length(v)) v = a[c];
    if (!(glm::length(v) > 0)) return 0;
    v = glm::transpose(a) * v;
    double sigma = 0;
    for (int i = 0; i < 64; ++i) {
        const double length = glm::length(v);
        if (!(length > 0)) return 0;
        v /= length;
        const glm::dvec3 image = a * v;
        sigma = glm::length(image);
        v = glm::transpose(a) * image;
    }
    return sigma;
}

bool textured(const Material& m) {
    return (m.texture == 1 || m.texture == 2) && !m.textureParameters.empty() &&
           m.textureParameters[0] > 0;
}

std::string figure(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2g", value);
    return text;
}

class Measure {
public:
    Measure(const Scene& scene, const CameraBasis& camera, const EnvelopeLimits& limits)
        : scene_(scene), camera_(camera), limits_(limits) {
        for (double sx : {-1.0, 1.0})
            for (double sy : {-1.0, 1.0})
                corners_.push_back(
                    glm::normalize(-camera.n + sx * camera.tanHalfFov * camera.aspect * camera.u +
                                   sy * camera.tanHalfFov * camera.v));
    }

    void object(const SceneObject& o) {
        for (const SceneObject& operand : o.operands) object(operand);
        if (o.type == ShapeType::Plane) return plane(o);
        const std::optional<Aabb> box = genericBounds(o, scene_);
        if (!box || box->empty()) return;
        const glm::dvec3 centre = 0.5 * (box->lo + box->hi);
        const glm::dvec3 half = 0.5 * (box->hi - box->lo);
        const double size = std::max({half.x, half.y, half.z});
        if (!(size > 0)) return;
        const glm::dvec3 eye = glm::dvec3(o.objectFromWorld * glm::dvec4(camera_.eye, 1));
        const glm::dmat3 linear(o.worldFromObject);
        const double largest = largestSingularValue(linear);
        const double smallest = 1 / largestSingularValue(glm::dmat3(o.objectFromWorld));
        const double squash = largest > 0 ? smallest / largest : 1;
        const double reach = glm::length(eye - centre) / size;
        if (squash < 0.5) {
            over(o, "squashed to " + figure(squash) + " of its largest scale", squash,
                 limits_.smallestSquash, true);
            over(o,
                 "squashed and seen from " + figure(reach) + " of its generic sizes (|M^-1 eye|)",
                 reach, limits_.farthestGeneric, false);
            // The squash sweeps looked from a few sizes: from farther, the
            // eye's own figure holds too, in world sizes (its largest scale).
            const glm::dvec3 where = glm::dvec3(o.worldFromObject * glm::dvec4(centre, 1));
            const double sizes = glm::length(camera_.eye - where) / (largest * size);
            over(o, "squashed and seen from " + figure(sizes) + " of its sizes", sizes,
                 limits_.farthestEye, false);
        } else {
            over(o, "seen from " + figure(reach) + " of its sizes", reach, limits_.farthestEye,
                 false);
        }
        if (textured(o.material)) {
            const double perCell = glm::length(eye) / o.material.textureParameters[0];
            over(o,
                 "textured and seen from " + figure(perCell) + " of its cells (|M^-1 eye| / cell)",
                 perCell, limits_.farthestPerCell, false);
        }
        if (o.material.transparency > scene_.minTransparency && o.type != ShapeType::Square &&
            limits_.thinnestPerDistance > 0) {
            const glm::dvec3 where = glm::dvec3(o.worldFromObject * glm::dvec4(centre, 1));
            const double distance =
                std::max(glm::length(camera_.eye - where), glm::length(where)) + largest * size;
            const double thin = smallest * size / distance;
            over(o, "refracting, " + figure(thin) + " thick for its distance", thin,
                 limits_.thinnestPerDistance, true);
        }
    }

    void eye() {
        const double distance = glm::length(camera_.eye);
        if (distance > limits_.farthestWorldEye)
            excesses.push_back({"the eye is " + figure(distance) + " from the world's origin",
                                FileLoc{}, distance, limits_.farthestWorldEye});
    }

    std::vector<EnvelopeExcess> excesses;

private:
    // A textured plane: near its horizon its hits lie arbitrarily far, where
    // float's rounding moves them across cells (fp64 draws on the margin
    // rule's measure: docs/numerics.md, "Envelope"); without the horizon in view, its farthest
    // visible hit (a corner ray's: the view meets the plane in a convex patch) per cell, as for a
    // bounded object.
    void plane(const SceneObject& o) {
        if (!textured(o.material) && o.material.texture != 3) return;
        const glm::dvec3 eye = glm::dvec3(o.objectFromWorld * glm::dvec4(camera_.eye, 1));
        const glm::dmat3 inverse(o.objectFromWorld);
        int hits = 0;
        double farthest = 0;
        for (const glm::dvec3& d : corners_) {
            const glm::dvec3 g = inverse * d;
            if (!(eye.z * g.z < 0)) continue;
            ++hits;
            farthest = std::max(farthest, glm::length(eye + (-eye.z / g.z) * g));
        }
        if (hits == 0) return;
        if (hits < 4) {
            if (limits_.texturedHorizon) return;
            excesses.push_back(
                {subject(o) + "a textured plane with its horizon in view", o.loc, 0, 0});
            return;
        }
        if (textured(o.material))
            over(o,
                 "textured and seen to " + figure(farthest / o.material.textureParameters[0]) +
                     " of its cells (its farthest visible point)",
                 farthest / o.material.textureParameters[0], limits_.farthestPerCell, false);
    }

    void over(const SceneObject& o, const std::string& what, double value, double limit,
              bool below) {
        if (below ? value < limit : value > limit)
            excesses.push_back({subject(o) + what, o.loc, value, limit});
    }

    static std::string subject(const SceneObject& o) {
        return std::string("the '") + shapeKeyword(o.type) + "' at " + o.loc.str() + " is ";
    }

    const Scene& scene_;
    const CameraBasis& camera_;
    const EnvelopeLimits& limits_;
    std::vector<glm::dvec3> corners_;
};

}  // namespace

SceneEnvelope envelopeOf(Precision precision) {
    // docs/numerics.md, "Envelope". A lone object, as its sweeps measured:
    // robust to 1.6e4 radii seen from any direction (textures while
    // |M^-1 eye| / cell <= 5e3), a squash after the rotation to 1e-4 seen
    // from a few sizes, one before it to 1e-8, a huge sphere seen from close
    // to R / H = 1e7; fp64 to 1e6 radii (cells of 0.05 there), 1e-10,
    // R / H = 2e7.
    // Several objects, as `vkray difftest` measured them (secondary rays
    // between objects start an offset off the surface that grows with the
    // eye's distance). Every scene keeps the eye within 1e6 of the world's
    // origin, where the CPU reference's own hit points still clear its
    // offset. Glass is held to 5e3 times the offset its refracted rays start
    // at: robust's 2^-18 of the distance; fp64's is the CPU reference's 2^-32
    // (shading.cpp), not the shader's far smaller 2^-47. A textured plane's
    // horizon is fp64's: its floors to the horizon differ from the reference
    // only where the margin rule explains it (robust draws ten times the
    // pixels off there). Naive, the
    // textbook's float, keeps to ordinary views.
    const EnvelopeLimits naive{400, 400, 400, 1e6, 0.05, 0.05, 0, 0.02, false};
    switch (precision) {
    case Precision::Naive: return {naive, naive};
    case Precision::Robust:
        return {{2e3, 2e3, 2e3, 1e6, 2e-3, 2e-3, 1e5, 0.02, false},
                {1.6e4, 7 / 1e-8, 5e3, 1e6, 1e-4, 1e-8, 1e7, 0, false}};
    case Precision::Fp64:
        return {{1e6, 4.3e10, 2e7, 1e6, 1e-10, 1e-8, 2e7, 0.02 * 0x1p-14, true},
                {1e6, 7 / 1e-10, 2e7, 1e6, 1e-10, 1e-8, 2e7, 0, true}};
    }
    return {naive, naive};
}

std::vector<EnvelopeExcess> envelopeExcesses(const Scene& scene, const CameraBasis& camera,
                                             Precision precision) {
    const SceneEnvelope envelope = envelopeOf(precision);
    Measure measure(scene, camera, scene.objects.size() == 1 ? envelope.lone : envelope.scenes);
    for (const SceneObject& object : scene.objects) measure.object(object);
    measure.eye();
    return std::move(measure.excesses);
}

PrecisionChoice choosePrecision(const Scene& scene, const CameraBasis& camera) {
    PrecisionChoice choice;
    choice.outside = envelopeExcesses(scene, camera, Precision::Robust);
    if (choice.outside.empty()) return choice;
    choice.precision = Precision::Fp64;
    choice.beyondEvery = envelopeExcesses(scene, camera, Precision::Fp64);
    return choice;
}

std::string describe(const EnvelopeExcess& excess, Precision precision) {
    std::string text = excess.what;
    if (excess.limit > 0)
        text += std::string(", beyond ") + precisionName(precision) + "'s " + figure(excess.limit);
    else
        text += std::string(" (outside ") + precisionName(precision) + "'s envelope)";
    return text;
}

}  // namespace vkray
