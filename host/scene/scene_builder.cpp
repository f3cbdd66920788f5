#include "scene/scene_builder.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace vkray {

void SceneBuilder::transform(const Token& word, const glm::dmat4& forward,
                             const glm::dmat4& inverse) {
    Transform next;
    next.worldFromObject = current_.worldFromObject * forward;  // M <- M * T
    next.objectFromWorld = inverse * current_.objectFromWorld;  // M^-1 <- T^-1 * M^-1
    // Both go to the renderers (M^-1 to the GPU in float): an entry beyond
    // kMaxSceneMagnitude (scale 1e-30: M^-1 holds 1e30) is refused here, at
    // the statement that made it, not rendered black.
    for (const glm::dmat4* matrix : {&next.worldFromObject, &next.objectFromWorld}) {
        for (int column = 0; column < 4; ++column) {
            for (int row = 0; row < 3; ++row) {
                const double entry = (*matrix)[column][row];
                if (std::abs(entry) <= kMaxSceneMagnitude) continue;
                char value[32];
                std::snprintf(value, sizeof value, "%.3g", entry);
                throwAt(word,
                        inQuotes(word.text) + " makes the " +
                            (matrix == &next.worldFromObject ? "transform" : "inverse transform") +
                            " hold " + value +
                            ", beyond vkray's limit of 1e18 (the GPU computes "
                            "in float); use factors and offsets nearer 1 (e.g. scale the whole "
                            "scene's units)");
            }
        }
    }
    current_ = next;
}

void SceneBuilder::push() {
    saved_.push_back(current_);
}

void SceneBuilder::pop(const Token& word) {
    if (saved_.empty()) throwAt(word, "'pop' without a matching 'push'");
    current_ = saved_.back();
    saved_.pop_back();
}

void SceneBuilder::identityAffine() {
    current_ = Transform{};
}

void SceneBuilder::shape(SceneObject object, const Token& word) {
    object.worldFromObject = current_.worldFromObject;
    object.objectFromWorld = current_.objectFromWorld;
    object.material = material_;
    deliver(std::move(object), word);
}

void SceneBuilder::deliver(SceneObject object, const Token& word) {
    // A boolean takes the next two objects made, whatever statements come
    // between them; a finished boolean is itself an object for the one around
    // it, or for the scene.
    if (isBoolean(object.type)) {
        // Every open boolean is one level of the tree it ends up in.
        if (openBooleans_.size() >= std::size_t(kMaxCsgDepth))
            throwAt(word, inQuotes(word.text) + " nests booleans " +
                              std::to_string(kMaxCsgDepth + 1) + " deep, beyond vkray's limit of " +
                              std::to_string(kMaxCsgDepth) +
                              "; combine the objects in a balanced tree, or in fewer booleans");
        openBooleans_.push_back(OpenBoolean{std::move(object), word});
        return;
    }
    while (!openBooleans_.empty()) {
        SceneObject& open = openBooleans_.back().object;
        open.operands.push_back(std::move(object));
        if (open.operands.size() < 2) return;
        object = std::move(open);
        openBooleans_.pop_back();
    }
    scene_.objects.push_back(std::move(object));
}

Scene SceneBuilder::finish() {
    if (!openBooleans_.empty()) {
        const Token& word = openBooleans_.back().word;
        throwAt(word,
                inQuotes(word.text) + " needs two objects after it; the file ends before them");
    }
    return std::move(scene_);
}

}  // namespace vkray
