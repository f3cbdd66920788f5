// Small helpers shared by the CPU reference's tests: exact affine matrices,
// objects, vector comparisons, seeded random numbers and test meshes.
#pragma once

#include "scene/scene.h"
#include "scene/triangle_mesh.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <random>

namespace vkray::reference::test {

inline void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tol) {
    EXPECT_NEAR(actual.x, expected.x, tol);
    EXPECT_NEAR(actual.y, expected.y, tol);
    EXPECT_NEAR(actual.z, expected.z, tol);
}

// The two vectors point the same way (unit vectors within tol).
inline void expectSameDirection(const glm::dvec3& actual, const glm::dvec3& expected, double tol) {
    expectNear(glm::normalize(actual), glm::normalize(expected), tol);
}

// glm is column-major: m[column][row].
inline glm::dmat4 translation(const glm::dvec3& t) {
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(t, 1);
    return m;
}

inline glm::dmat4 scaling(const glm::dvec3& s) {
    glm::dmat4 m(1.0);
    m[0][0] = s.x;
    m[1][1] = s.y;
    m[2][2] = s.z;
    return m;
}

inline SceneObject makeObject(ShapeType type, const glm::dmat4& worldFromObject = glm::dmat4(1.0),
                              const glm::dmat4& objectFromWorld = glm::dmat4(1.0)) {
    SceneObject o;
    o.type = type;
    o.worldFromObject = worldFromObject;
    o.objectFromWorld = objectFromWorld;
    return o;
}

// A shape moved by t and scaled by s (M = T S, M^-1 = S^-1 T^-1).
inline SceneObject placed(ShapeType type, const glm::dvec3& t, const glm::dvec3& s = {1, 1, 1}) {
    return makeObject(type, translation(t) * scaling(s), scaling(1.0 / s) * translation(-t));
}

inline SceneObject boolean(ShapeType type, SceneObject a, SceneObject b) {
    SceneObject o = makeObject(type);
    o.operands = {std::move(a), std::move(b)};
    return o;
}

// Seeded random numbers: each test names its seed, so a failure repeats.
class Random {
public:
    explicit Random(std::uint64_t seed) : engine_(seed) {}
    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(engine_);
    }
    // A uniformly distributed unit vector.
    glm::dvec3 direction() {
        const double z = uniform(-1, 1), phi = uniform(0, 2 * std::numbers::pi);
        const double rho = std::sqrt(1 - z * z);
        return {rho * std::cos(phi), rho * std::sin(phi), z};
    }
    glm::dvec3 inBox(const glm::dvec3& lo, const glm::dvec3& hi) {
        return {uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
    }
    int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(engine_); }

private:
    std::mt19937_64 engine_;
};

// A closed UV sphere of radius 1: `rings` bands of latitude, `segments` of
// longitude, wound counter-clockwise seen from outside, with the exact unit
// normals at the corners. 2 * segments * (rings - 1) triangles.
inline TriangleMesh tessellatedSphere(int rings, int segments) {
    TriangleMesh mesh;
    mesh.name = "test sphere";
    const auto vertex = [&](int ring, int segment) -> std::uint32_t {
        if (ring == 0) return 0;
        if (ring == rings) return 1;
        return std::uint32_t(2 + (ring - 1) * segments + segment % segments);
    };
    mesh.positions.push_back({0, 0, 1});
    mesh.positions.push_back({0, 0, -1});
    for (int ring = 1; ring < rings; ++ring) {
        const double theta = std::numbers::pi * ring / rings;
        for (int segment = 0; segment < segments; ++segment) {
            const double phi = 2 * std::numbers::pi * segment / segments;
            mesh.positions.push_back({std::sin(theta) * std::cos(phi),
                                      std::sin(theta) * std::sin(phi), std::cos(theta)});
        }
    }
    mesh.normals = mesh.positions;  // a unit sphere's normal is its point
    const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        mesh.triangles.push_back({{a, b, c}, {a, b, c}});
    };
    for (int ring = 0; ring < rings; ++ring) {
        for (int segment = 0; segment < segments; ++segment) {
            const std::uint32_t a = vertex(ring, segment), b = vertex(ring, segment + 1);
            const std::uint32_t c = vertex(ring + 1, segment), d = vertex(ring + 1, segment + 1);
            if (ring > 0) add(a, c, b);  // z decreases with the ring: c, d lie below
            if (ring < rings - 1) add(b, c, d);
        }
    }
    mesh.closed = true;
    finishMesh(mesh);
    return mesh;
}

}  // namespace vkray::reference::test
