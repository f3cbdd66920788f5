// The scene that a file's statements describe (pbrt's ParserTarget): the SDL
// reader checks each statement's words and numbers and tells the builder what
// it says; the builder keeps what lasts between statements (the current
// transform and its push/pop stack, the current material, booleans waiting
// for their operands) and makes the Scene. Its errors are thrown at the
// statement's word, with file:line:col.
#pragma once

#include <glm/mat4x4.hpp>
#include <vector>

#include "scene/scene.h"
#include "scene/sdl_lexer.h"

namespace vkray {

class SceneBuilder {
public:
    // Lights, background and the other scene-wide settings, pixmaps, camera:
    // set on the scene directly.
    Scene& scene() { return scene_; }
    // The material the next shapes get.
    Material& material() { return material_; }
    void defaultMaterials() { material_ = Material{}; }

    // M <- M * forward, M^-1 <- inverse * M^-1 (`inverse` is forward's exact
    // inverse). Throws at `word` when an entry of either passes
    // kMaxSceneMagnitude.
    void transform(const Token& word, const glm::dmat4& forward, const glm::dmat4& inverse);
    void push();
    void pop(const Token& word);  // throws at `word` without a matching push
    void identityAffine();

    // A shape statement's object (type, place, taper or file set): it gets
    // the current transform and material, and goes to the boolean waiting
    // for an operand, or to the scene.
    void shape(SceneObject object, const Token& word);

    // The scene, once every statement is told; throws at a boolean still
    // waiting for its operands.
    Scene finish();

private:
    void deliver(SceneObject object, const Token& word);

    // The current transform: M (object -> world) and M^-1 kept beside it,
    // each composed from exact inverses rather than by inverting M.
    struct Transform {
        glm::dmat4 worldFromObject{1.0};
        glm::dmat4 objectFromWorld{1.0};
    };

    Scene scene_;
    Material material_;
    Transform current_;
    std::vector<Transform> saved_;  // push / pop
    // Booleans still waiting for their operands, innermost last. Kept here
    // rather than on the call stack so that `union union union ...` cannot
    // overflow it.
    struct OpenBoolean {
        SceneObject object;
        Token word;
    };
    std::vector<OpenBoolean> openBooleans_;
};

}  // namespace vkray
