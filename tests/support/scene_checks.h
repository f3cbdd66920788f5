// Small checks the scene tests share: counting shapes, placing a generic
// point in the world, comparing points exactly enough for hand-worked
// transforms, and the folder of the repository's own test scenes.
#pragma once

#include "scene/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <string>

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray::test {

// The repository's own scenes and meshes (tests/data), with a trailing '/'.
inline const std::string kTestData = VKRAY_SOURCE_DIR "/tests/data/";

inline long countOf(const Scene& scene, ShapeType type) {
    return std::count_if(scene.objects.begin(), scene.objects.end(),
                         [type](const SceneObject& o) { return o.type == type; });
}

inline glm::dvec3 worldPoint(const SceneObject& object, const glm::dvec3& p) {
    return glm::dvec3(object.worldFromObject * glm::dvec4(p, 1.0));
}

// Transforms worked out by hand agree to 1e-12 in each coordinate.
inline void expectNear(const glm::dvec3& actual, const glm::dvec3& expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-12);
    EXPECT_NEAR(actual.y, expected.y, 1e-12);
    EXPECT_NEAR(actual.z, expected.z, 1e-12);
}

}  // namespace vkray::test
