#include "scene/scene_geometry.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include "scene/mesh_import.h"
#include "scene/pixmaps.h"
#include "scene/triangle_mesh.h"
#include "util/error.h"
#include "util/stopwatch.h"

namespace vkray {

namespace {

namespace fs = std::filesystem;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::string whatFailed(const SceneObject& object) {
    const char* verb =
        object.type == ShapeType::Extrude ? "cannot extrude '" : "cannot load mesh '";
    return verb + writtenName(object.loc, object.file) + "'";
}

// The reader's own "PATH:line:col: error: ..." becomes a note under a warning.
std::string asNote(std::string message) {
    const std::size_t at = message.find(": error: ");
    if (at != std::string::npos) message.replace(at, 9, ": note: ");
    return message;
}

// One key per file however the scene spelled its path.
std::string fileKey(const std::string& path) {
    std::error_code error;
    const fs::path canonical = fs::weakly_canonical(path, error);
    return error ? fs::path(path).lexically_normal().string() : canonical.string();
}

class MeshLoader {
public:
    explicit MeshLoader(Scene& scene) : scene_(scene) {}

    // The index into scene.meshes, or the loader's message. What the mesh
    // file's reader warned of goes to `warnings` once, at the first object
    // that names the file.
    std::optional<int> meshFor(const SceneObject& object, std::string* failure,
                               std::vector<std::string>* warnings) {
        if (isBuiltInMesh(object.type)) {
            auto [where, added] = builtIns_.try_emplace(object.type, -1);
            if (added) where->second = add(builtInMesh(object.type));
            return where->second;
        }
        auto [where, added] = files_.try_emplace(fileKey(object.file));
        Loaded& loaded = where->second;
        if (added) {
            std::vector<std::string> said;
            const Stopwatch clock;
            try {
                loaded.mesh =
                    add(object.type == ShapeType::Extrude ? extrudeOutline(loadOutline(object.file))
                                                          : loadMeshFile(object.file, &said));
            } catch (const Error& e) {
                loaded.failure = e.what();
            }
            scene_.meshFileSeconds += clock.seconds();
            if (loaded.mesh)
                scene_.meshBvhSeconds += scene_.meshes[std::size_t(*loaded.mesh)]->bvhSeconds;
            if (warnings)
                for (const std::string& warning : said)
                    warnings->push_back(formatDiagnostic(
                        object.loc, nullptr, "warning",
                        "mesh '" + writtenName(object.loc, object.file) + "': " + warning));
        }
        if (loaded.mesh) return loaded.mesh;
        *failure = loaded.failure;
        return std::nullopt;
    }

private:
    struct Loaded {
        std::optional<int> mesh;
        std::string failure;
    };

    int add(TriangleMesh mesh) {
        scene_.meshes.push_back(std::make_shared<const TriangleMesh>(std::move(mesh)));
        return int(scene_.meshes.size()) - 1;
    }

    Scene& scene_;
    std::map<std::string, Loaded> files_;  // by fileKey: a failure is remembered too
    std::map<ShapeType, int> builtIns_;
};

// Sets `mesh` in the object and its operands. Strict: the first failure
// throws. Lenient: returns false after one warning per failure, naming the
// top-level boolean that is left out with it.
bool assignMeshes(SceneObject& object, const SceneObject& topLevel, MeshLoader& loader,
                  bool lenient, std::vector<std::string>* warnings) {
    bool loaded = true;
    for (SceneObject& operand : object.operands)
        loaded = assignMeshes(operand, topLevel, loader, lenient, warnings) && loaded;
    if (!isMeshShape(object.type)) return loaded;
    std::string failure;
    if (const std::optional<int> mesh = loader.meshFor(object, &failure, warnings)) {
        object.mesh = *mesh;
        return loaded;
    }
    if (!lenient)
        throw Error(formatDiagnostic(object.loc, nullptr, "error", whatFailed(object)) + "\n" +
                    failure);
    if (warnings) {
        const std::string leftOut =
            &object == &topLevel ? std::string("; left out")
                                 : std::string("; the '") + shapeKeyword(topLevel.type) + "' at " +
                                       topLevel.loc.str() + " that holds it is left out";
        warnings->push_back(
            formatDiagnostic(object.loc, nullptr, "warning", whatFailed(object) + leftOut) + "\n" +
            asNote(failure));
    }
    return false;
}

void collectUsedMeshes(const SceneObject& object, std::vector<bool>& used) {
    if (object.mesh >= 0) used[std::size_t(object.mesh)] = true;
    for (const SceneObject& operand : object.operands) collectUsedMeshes(operand, used);
}

void renumberMeshes(SceneObject& object, const std::vector<int>& newIndex) {
    if (object.mesh >= 0) object.mesh = newIndex[std::size_t(object.mesh)];
    for (SceneObject& operand : object.operands) renumberMeshes(operand, newIndex);
}

// Drops meshes only left-out objects used (a boolean's good operand).
void dropUnusedMeshes(Scene& scene) {
    std::vector<bool> used(scene.meshes.size(), false);
    for (const SceneObject& object : scene.objects) collectUsedMeshes(object, used);
    std::vector<int> newIndex(scene.meshes.size(), -1);
    std::vector<std::shared_ptr<const TriangleMesh>> kept;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        if (!used[i]) continue;
        newIndex[i] = int(kept.size());
        kept.push_back(std::move(scene.meshes[i]));
    }
    if (kept.size() == scene.meshes.size()) {
        scene.meshes = std::move(kept);
        return;
    }
    scene.meshes = std::move(kept);
    for (SceneObject& object : scene.objects) renumberMeshes(object, newIndex);
}

Aabb unboundedBox() {
    return Aabb{glm::dvec3(-kInfinity), glm::dvec3(kInfinity)};
}

}  // namespace

std::optional<Aabb> genericBounds(const SceneObject& object, const Scene& scene) {
    switch (object.type) {
    case ShapeType::Sphere:
    case ShapeType::Cube: return Aabb{glm::dvec3(-1), glm::dvec3(1)};
    case ShapeType::Square: return Aabb{glm::dvec3(-1, -1, 0), glm::dvec3(1, 1, 0)};
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: {
        // Radius 1 at z = 0, |s| at z = 1 (a negative s mirrors the same surface).
        const double radius = std::max(1.0, std::abs(object.taper));
        return Aabb{glm::dvec3(-radius, -radius, 0), glm::dvec3(radius, radius, 1)};
    }
    case ShapeType::Torus: {
        const double outer = kTorusMajorRadius + kTorusTubeRadius;
        return Aabb{glm::dvec3(-outer, -outer, -kTorusTubeRadius),
                    glm::dvec3(outer, outer, kTorusTubeRadius)};
    }
    default:
        if (isMeshShape(object.type) && object.mesh >= 0 &&
            std::size_t(object.mesh) < scene.meshes.size())
            return scene.meshes[std::size_t(object.mesh)]->bounds;
        return std::nullopt;
    }
}

namespace {

// pbrt's bound on the rounding of a transformed point: gamma(3) times the
// sum of the magnitudes that went into each coordinate
// (docs/numerics-background.md, "Conservative bounds").
constexpr double kGamma3 = 3 * (0.5 * std::numeric_limits<double>::epsilon()) /
                           (1 - 3 * (0.5 * std::numeric_limits<double>::epsilon()));

Aabb transformedBox(const Aabb& box, const glm::dmat4& matrix) {
    if (box.empty()) return Aabb{};
    Aabb world;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                           corner & 4 ? box.hi.z : box.lo.z);
        const glm::dvec3 q = glm::dvec3(matrix * glm::dvec4(p, 1.0));
        glm::dvec3 error;
        for (int row = 0; row < 3; ++row) {
            // glm is column-major: matrix[column][row].
            error[row] =
                kGamma3 * (std::abs(matrix[0][row] * p.x) + std::abs(matrix[1][row] * p.y) +
                           std::abs(matrix[2][row] * p.z) + std::abs(matrix[3][row]));
        }
        world.grow(q - error);
        world.grow(q + error);
    }
    return world.finite() ? world : unboundedBox();  // overflow: no usable box
}

}  // namespace

void loadSceneGeometry(Scene& scene, bool lenient, std::vector<std::string>* warnings) {
    scene.meshes.clear();
    MeshLoader loader(scene);
    std::vector<SceneObject> kept;
    kept.reserve(scene.objects.size());
    bool anyLeftOut = false;
    for (SceneObject& object : scene.objects) {
        if (assignMeshes(object, object, loader, lenient, warnings)) {
            kept.push_back(std::move(object));
        } else {
            anyLeftOut = true;
        }
    }
    scene.objects = std::move(kept);
    if (anyLeftOut) dropUnusedMeshes(scene);
    loadPixmaps(scene, lenient, warnings);
}

Scene loadScene(const std::string& path, const SdlOptions& options,
                std::vector<std::string>* warnings) {
    Scene scene = loadSdlFile(path, options, warnings);
    loadSceneGeometry(scene, options.lenient, warnings);
    return scene;
}

Aabb worldBounds(const SceneObject& object, const Scene& scene) {
    if (isBoolean(object.type)) {
        if (object.operands.size() != 2) return unboundedBox();  // the reader never makes one
        const Aabb first = worldBounds(object.operands[0], scene);
        if (object.type == ShapeType::Difference) return first;
        const Aabb second = worldBounds(object.operands[1], scene);
        if (object.type == ShapeType::Union) {
            Aabb both = first;
            both.grow(second);
            return both;
        }
        const Aabb overlap{glm::max(first.lo, second.lo), glm::min(first.hi, second.hi)};
        return overlap.empty() ? Aabb{} : overlap;
    }
    const std::optional<Aabb> generic = genericBounds(object, scene);
    if (!generic) return unboundedBox();
    return transformedBox(*generic, object.worldFromObject);
}

ObjectBvh buildObjectBvh(const Scene& scene, MeshObjects meshes) {
    ObjectBvh result;
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> objectOf;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        if (meshes == MeshObjects::Apart && scene.objects[i].mesh >= 0) continue;
        const Aabb box = worldBounds(scene.objects[i], scene);
        if (box.empty()) continue;  // an empty intersection: no ray can hit it
        if (box.finite()) {
            boxes.push_back(box);
            objectOf.push_back(std::uint32_t(i));
        } else {
            result.unbounded.push_back(std::uint32_t(i));
        }
    }
    result.bvh = buildBvh(boxes);
    for (std::uint32_t& index : result.bvh.order) index = objectOf[index];
    return result;
}

}  // namespace vkray
