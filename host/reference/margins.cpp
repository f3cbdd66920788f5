// Decision margins by playing the bound on every ray (see margins.h).
#include "reference/margins.h"

#include "reference/scene_intersector.h"
#include "reference/shading.h"
#include "scene/scene_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace vkray::reference {

namespace {

bool textured(const SceneObject& object) {
    if (object.material.texture != 0) return true;
    return std::any_of(object.operands.begin(), object.operands.end(), textured);
}

bool anyTextured(const Scene& scene) {
    return std::any_of(scene.objects.begin(), scene.objects.end(), textured);
}

}  // namespace

struct MarginTracer::Plays {
    SceneIntersector intersector;
    std::vector<Aabb> boxes;
    std::vector<RayPerturbation> perturbations;
    std::vector<WhittedShader> shaders;  // the reference's own first
};

MarginTracer::MarginTracer(const Scene& scene, const CameraBasis& camera,
                           const RenderSettings& settings, const ErrorBound& bound)
    : camera_(camera), settings_(settings), plays_(new Plays{SceneIntersector(scene), {}, {}, {}}) {
    requireReferenceScene(scene);
    for (const SceneObject& object : scene.objects)
        plays_->boxes.push_back(worldBounds(object, scene));
    RayPerturbation base;
    base.boxes = &plays_->boxes;
    base.eye = camera.eye;
    base.bound = bound;
    // The GPU's own geometry, its steps off each surface landing where it
    // computes them, or the bound further or shorter along the new ray (a
    // reflection inside a buckyball left near an edge: the GPU's float step
    // landed outside the next face, where the same step in double stops
    // 6e-6 short of it).
    for (const int ahead : {0, 1, -1}) {
        RayPerturbation offsets = base;
        offsets.sideways = false;
        offsets.stepAhead = ahead;
        plays_->perturbations.push_back(offsets);
    }
    // The eight sides; in a textured scene each again with its textures
    // looked up where its hits are. The GPU's texture lookups and its rays
    // round apart: plays that moved both at once missed a sample whose
    // refracted ray's feeler passed a cube's edge the other way (the light's
    // float position, 5e4 from the eye) while the floor's texel stayed the
    // reference's (tests/data/difftest/feeler_past_an_edge_under_a_texel.sdl).
    for (const bool texturesAside : {true, false}) {
        if (!texturesAside && !anyTextured(scene)) continue;
        for (int side = 0; side < 8; ++side) {
            RayPerturbation p = base;
            p.angle = side * std::acos(-1.0) / 4;
            p.feelerSide = side % 2 == 0 ? 1 : -1;
            if (!texturesAside) p.bound.texture = 0;
            plays_->perturbations.push_back(p);
        }
    }
    RayPerturbation ties = base;
    ties.sideways = false;
    ties.runnerUp = true;
    plays_->perturbations.push_back(ties);
    plays_->shaders.emplace_back(scene, plays_->intersector);
    for (const RayPerturbation& p : plays_->perturbations)
        plays_->shaders.emplace_back(scene, plays_->intersector, &p);
}

MarginTracer::~MarginTracer() = default;

int MarginTracer::plays() const {
    return int(plays_->shaders.size());
}

PixelSpan MarginTracer::spanOf(int x, int y) const {
    PixelSpan span;
    const int end = sampleEnd(settings_);
    glm::dvec3 low(0), high(0);
    for (int k = settings_.firstSample; k < end; ++k) {
        const Ray ray{camera_.eye,
                      primaryDirection(camera_, settings_, jitteredSample(x, y, settings_, k))};
        glm::dvec3 least(std::numeric_limits<double>::infinity()), most(-least);
        for (const WhittedShader& shader : plays_->shaders) {
            std::optional<WorldHit> first;
            const glm::dvec3 c = shader.radiance(ray, 0, Medium{}, k == 0 ? &first : nullptr);
            least = glm::min(least, c);
            most = glm::max(most, c);
            if (k != 0) continue;
            if (first)
                span.firstHits.push_back(
                    {first->object, float(first->t), glm::vec3(first->normal)});
            else
                span.firstHits.push_back({-1, std::numeric_limits<float>::infinity(), {}});
        }
        low += least;
        high += most;
    }
    const double n = double(end - settings_.firstSample);
    span.low = glm::vec3(low / n);
    span.high = glm::vec3(high / n);
    return span;
}

}  // namespace vkray::reference
