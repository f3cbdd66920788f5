#include "bench/bench_scenes.h"

#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <memory>
#include <random>

namespace vkray::bench {

namespace {

SceneObject placed(ShapeType type, const glm::dmat4& worldFromObject) {
    SceneObject object;
    object.type = type;
    object.worldFromObject = worldFromObject;
    object.objectFromWorld = glm::inverse(worldFromObject);
    object.material.specular = {0.3, 0.3, 0.3};
    object.material.specularExponent = 20;
    return object;
}

}  // namespace

Scene randomSpheres(int n) {
    Scene scene;
    scene.lights.push_back({{50, 80, 60}, {1, 1, 1}, {}});
    const double side = 4 * std::cbrt(double(n));
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> coordinate(-side / 2, side / 2);
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 centre(coordinate(random), coordinate(random), coordinate(random));
        scene.objects.push_back(placed(ShapeType::Sphere, glm::translate(glm::dmat4(1.0), centre)));
    }
    // One sphere alone sits at a random point: look at it, from close enough
    // that it fills a good part of the image like the larger fields do.
    const glm::dvec3 look =
        n == 1 ? glm::dvec3(scene.objects[0].worldFromObject[3]) : glm::dvec3(0);
    const double distance = n == 1 ? 3.5 : side * 1.7;
    scene.camera =
        Camera{look + distance * glm::normalize(glm::dvec3(1.2, 0.9, 1.2)), look, {0, 1, 0}, 60};
    return scene;
}

Scene uvSphereMesh(int rings) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->name = "uv sphere";
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i) {
        for (int j = 0; j <= rings; ++j) {
            const double theta = pi * i / rings, phi = 2 * pi * j / rings;
            const glm::dvec3 p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                               std::cos(theta));
            mesh->positions.push_back(p);
            mesh->normals.push_back(p);
        }
    }
    const auto at = [&](int i, int j) { return std::uint32_t(i * (rings + 1) + j); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < rings; ++j) {
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1),
                                d = at(i, j + 1);
            mesh->triangles.push_back({{a, b, c}, {a, b, c}});
            mesh->triangles.push_back({{a, c, d}, {a, c, d}});
        }
    }
    finishMesh(*mesh);
    Scene scene;
    scene.lights.push_back({{5, 8, 6}, {1, 1, 1}, {}});
    scene.meshes.push_back(mesh);
    SceneObject object = placed(ShapeType::Mesh, glm::dmat4(1.0));
    object.mesh = 0;
    scene.objects.push_back(object);
    scene.camera = Camera{{2.2, 1.2, 2.4}, {0, 0, 0}, {0, 1, 0}, 45};
    return scene;
}

Scene missedSpheres(int n) {
    // No light: no variant here has shadows, so 1 and 8 spheres differ only
    // in the sphere tests.
    Scene scene;
    for (int i = 0; i < n; ++i) {
        // This camera's rays are at most 50 degrees off -z (60 degrees high,
        // 16:9 at most): their lines pass a centre at x = 1000 at a distance
        // of at least 1000 sin(40 degrees) = 640, never within 1.
        const glm::dvec3 centre(1000, 3.0 * i, 0);
        scene.objects.push_back(placed(ShapeType::Sphere, glm::translate(glm::dmat4(1.0), centre)));
    }
    scene.camera = Camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60};
    return scene;
}

Scene sdlScene(const std::string& path) {
    return loadScene(path, {true}, nullptr);
}

}  // namespace vkray::bench
