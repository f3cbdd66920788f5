#include "gpu/gpu_scene.h"

#include "image/image_io.h"
#include "scene/pixmaps.h"
#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"
#include "util/error.h"

#include <algorithm>
#include <cstring>

namespace vkray::gpu {

namespace {

vec4 toVec4(const glm::dvec3& v, double w = 0) {
    return {float(v.x), float(v.y), float(v.z), float(w)};
}

float bitsAsFloat(uint bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

uint floatBits(float f) {
    uint bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits;
}

// The texture's parameters with the defaults of docs/shading.md, "Textures", for
// those the scene leaves out; an image texture's pixmap as its slot in
// Scene::pixmaps (loadPixmaps has checked that it exists).
vec4 packTexture(const Scene& scene, const Material& m) {
    const auto parameter = [&](size_t i, double fallback) {
        return i < m.textureParameters.size() ? float(m.textureParameters[i]) : float(fallback);
    };
    switch (uint(m.texture)) {
    case TEXTURE_CHECKERBOARD:
        return {parameter(0, 0.5), parameter(1, 0), parameter(2, 0), parameter(3, 0)};
    case TEXTURE_WOOD:
        return {parameter(0, 0.1), parameter(1, 0.55), parameter(2, 0.35), parameter(3, 0.15)};
    case TEXTURE_IMAGE: {
        const Pixmap* pixmap = findPixmap(scene, pixmapIndexOf(m));
        if (!pixmap || !pixmap->image)
            throw Error(formatDiagnostic(m.textureLoc, nullptr, "error",
                                         "texture 3 names no loaded pixmap"));
        return {bitsAsFloat(uint(pixmap - scene.pixmaps.data())), 0, 0, 0};
    }
    default: return {0, 0, 0, 0};
    }
}

// What a walk reads of the object (GpuObjectGeometry) and its material.
struct PackedObject {
    GpuObjectGeometry geometry;
    GpuMaterial material;
};

PackedObject packObject(const Scene& scene, const SceneObject& object) {
    PackedObject packed{};
    GpuObjectGeometry& g = packed.geometry;
    // M^-1 was composed in double from exact inverses; only now rounded to float.
    const glm::dmat4& inv = object.objectFromWorld;
    for (int row = 0; row < 3; ++row)
        g.objectFromWorld[row] = {float(inv[0][row]), float(inv[1][row]), float(inv[2][row]),
                                  float(inv[3][row])};
    const Material& m = object.material;
    const uint kind = gpuKindOf(object.type);
    uint parameter = 0;
    if (kind == KIND_TAPERED_CYLINDER) parameter = floatBits(float(object.taper));
    if (kind == KIND_MESH) parameter = uint(object.mesh);
    uint follow = 0;
    if (scene.maxRecursionDepth > 0 && m.reflectivity > scene.minReflectivity)
        follow |= FOLLOW_REFLECTION;
    if (scene.maxRecursionDepth > 0 && m.transparency > scene.minTransparency)
        follow |= FOLLOW_REFRACTION;
    g.shape = {kind, parameter, follow, floatBits(float(m.transparency))};
    GpuMaterial& material = packed.material;
    material.ambient = toVec4(m.ambient);
    material.diffuse = toVec4(m.diffuse);
    material.specular = toVec4(m.specular, m.specularExponent);
    material.emissive = toVec4(m.emissive);
    material.material = {float(m.reflectivity), float(m.transparency), float(m.speedOfLight),
                         bitsAsFloat(uint(m.texture))};
    material.texture = packTexture(scene, m);
    return packed;
}

// The fp64 variant's copy of M^-1, unrounded.
GpuDoubleObject packDoubleObject(const SceneObject& object) {
    GpuDoubleObject g{};
    const glm::dmat4& inv = object.objectFromWorld;
    for (int row = 0; row < 3; ++row)
        g.objectFromWorld[row] = {inv[0][row], inv[1][row], inv[2][row], inv[3][row]};
    if (gpuKindOf(object.type) == KIND_TAPERED_CYLINDER) g.parameters.x = object.taper;
    return g;
}

// The BVH in the shader's layout (layout.h, GpuBvhNode): the root first,
// then each interior node's two children side by side, placed breadth first.
std::vector<GpuBvhNode> packBvh(const Bvh& bvh) {
    std::vector<GpuBvhNode> packed;
    if (bvh.nodes.empty()) return packed;
    packed.reserve(bvh.nodes.size());
    const auto entry = [](const BvhNode& node) {
        if (node.leaf() && (node.count > BVH_LEAF_MAX || node.first > BVH_FIRST_MAX))
            throw Error("internal: a BVH leaf beyond the shader's bounds (" +
                        std::to_string(node.count) + " entries from " + std::to_string(node.first) +
                        ")");
        return GpuBvhNode{toVec4(node.bounds.lo, bitsAsFloat(node.leaf() ? node.first : 0)),
                          toVec4(node.bounds.hi, bitsAsFloat(node.count))};
    };
    packed.push_back(entry(bvh.nodes[0]));
    // (packed index, node index) of the interior nodes whose children are still to place.
    std::vector<std::pair<std::size_t, std::uint32_t>> pending{{0, 0}};
    for (std::size_t next = 0; next < pending.size(); ++next) {
        const auto [at, index] = pending[next];
        const BvhNode& node = bvh.nodes[index];
        if (node.leaf()) continue;
        const std::uint32_t children[2] = {index + 1, node.first};
        const std::size_t first = packed.size();
        if (first > BVH_FIRST_MAX)
            throw Error("internal: a BVH beyond the shader's node index bound");
        packed[at].lo.w = bitsAsFloat(uint(first));
        for (int k = 0; k < 2; ++k) {
            pending.emplace_back(packed.size(), children[k]);
            packed.push_back(entry(bvh.nodes[children[k]]));
        }
    }
    return packed;
}

std::string located(const SceneObject& object, const std::string& message) {
    return formatDiagnostic(object.loc, nullptr, "error", message);
}

// A mesh is convex when every vertex lies on the inner side of every face.
bool isConvex(const TriangleMesh& mesh) {
    const double scale = glm::length(mesh.bounds.hi - mesh.bounds.lo);
    for (const TriangleMesh::Triangle& t : mesh.triangles) {
        const glm::dvec3 a = mesh.positions[t.position[0]];
        const glm::dvec3 n =
            glm::cross(mesh.positions[t.position[1]] - a, mesh.positions[t.position[2]] - a);
        const double length = glm::length(n);
        if (length == 0) continue;
        for (const glm::dvec3& p : mesh.positions)
            if (glm::dot(p - a, n) / length > 1e-9 * scale) return false;
    }
    return true;
}

// Packs boolean trees as GpuCsgNodes in post order, each followed by its
// leaves again, in the same order (the shader's loop over the primitives
// then turns once a primitive, not once a node); the primitives are objects
// after the scene's own.
class CsgPacker {
public:
    CsgPacker(const Scene& scene, GpuScene& packed) : scene_(scene), packed_(packed) {}

    // Packs the tree of boolean `object`; returns its first node's index.
    uint pack(const SceneObject& object) {
        const uint first = uint(packed_.csgNodes.size());
        const uint leaves = emit(object, object, false);
        if (leaves > CSG_MAX_LEAVES)
            throw Error(located(object, std::string("this '") + shapeKeyword(object.type) +
                                            "' has " + std::to_string(leaves) +
                                            " primitives; the GPU evaluates trees of at most " +
                                            std::to_string(CSG_MAX_LEAVES) +
                                            " (split the tree or render with --cpu)"));
        packed_.csgNodes[first].node.z = uint(packed_.csgNodes.size()) - first;
        packed_.csgNodes[first].node.w = leaves;
        packed_.csgNodes.insert(packed_.csgNodes.end(), leaves_.begin(), leaves_.end());
        leaves_.clear();
        return first;
    }

private:
    // Emits `node`'s subtree in post order; returns its primitives. `turned`:
    // the subtree is subtracted in an odd number of differences, so its
    // surfaces bound the result from outside them.
    uint emit(const SceneObject& node, const SceneObject& root, bool turned) {
        if (isBoolean(node.type)) {
            const uint a = emit(node.operands.at(0), root, turned);
            const uint b =
                emit(node.operands.at(1), root, turned != (node.type == ShapeType::Difference));
            const uint op = node.type == ShapeType::Union          ? CSG_UNION
                            : node.type == ShapeType::Intersection ? CSG_INTERSECTION
                                                                   : CSG_DIFFERENCE;
            packed_.csgNodes.push_back({{op, 0, 0, 0}});
            return a + b;
        }
        requireInside(node, root);
        const GpuCsgNode leaf{{CSG_LEAF, uint(packed_.objects.size()), 0, turned ? 1u : 0u}};
        packed_.csgNodes.push_back(leaf);
        leaves_.push_back(leaf);
        const PackedObject primitive = packObject(scene_, node);
        packed_.objects.push_back(primitive.geometry);
        packed_.materials.push_back(primitive.material);
        packed_.doubleObjects.push_back(packDoubleObject(node));
        return 1;
    }

    // Refuses an operand without an inside, and a mesh whose spans the GPU's
    // first and last crossing would not give (a concave one).
    void requireInside(const SceneObject& leaf, const SceneObject& root) {
        const std::string op = shapeKeyword(root.type);
        if (gpuKindOf(leaf.type) == KIND_SQUARE)
            throw Error(
                located(leaf, "'square' has no inside and cannot be an operand of '" + op + "'"));
        if (gpuKindOf(leaf.type) != KIND_MESH) return;
        const TriangleMesh& mesh = *scene_.meshes.at(size_t(leaf.mesh));
        if (!mesh.closed)
            throw Error(located(
                leaf, "'" + std::string(shapeKeyword(leaf.type)) +
                          "' is not a closed surface and cannot be an operand of '" + op + "'"));
        if (!isConvex(mesh))
            throw Error(located(leaf, "'" + std::string(shapeKeyword(leaf.type)) +
                                          "' is not convex; the GPU takes only convex meshes "
                                          "in CSG (render with --cpu)"));
    }

    const Scene& scene_;
    GpuScene& packed_;
    std::vector<GpuCsgNode> leaves_;  // the tree's leaves in order, copied after its nodes
};

void packMeshes(const Scene& scene, GpuScene& packed) {
    for (const auto& mesh : scene.meshes) {
        const uint firstNode = uint(packed.meshNodes.size());
        const uint firstTriangle = uint(packed.triangles.size());
        packed.meshes.push_back({{firstNode, firstTriangle, uint(mesh->triangles.size()), 0}});
        const std::vector<GpuBvhNode> nodes = packBvh(mesh->bvh);
        packed.meshNodes.insert(packed.meshNodes.end(), nodes.begin(), nodes.end());
        // Triangles in leaf order, so that a leaf's range is contiguous.
        for (std::uint32_t index : mesh->bvh.order) {
            const TriangleMesh::Triangle& t = mesh->triangles[index];
            GpuTriangle g{};
            vec4* corners[3] = {&g.p0, &g.p1, &g.p2};
            vec4* normals[3] = {&g.n0, &g.n1, &g.n2};
            for (int k = 0; k < 3; ++k) {
                *corners[k] = toVec4(mesh->positions[t.position[k]]);
                *normals[k] = toVec4(mesh->normals[t.normal[k]]);
            }
            packed.triangles.push_back(g);
        }
    }
}

// A mesh object's BVH in world space: its mesh's nodes and leaves, each
// box refitted around `boxes` (its triangles', in the mesh's leaf order):
// linear in the triangles, where a new build is not (1.1-1.5 s for a
// million), and a render with another eye or a moved object builds it anew.
Bvh refittedBvh(const Bvh& mesh, const std::vector<Aabb>& boxes) {
    Bvh refitted;
    refitted.nodes = mesh.nodes;
    refitted.depth = mesh.depth;
    // Children come after their parent: from the last node back.
    for (std::size_t n = refitted.nodes.size(); n-- > 0;) {
        BvhNode& node = refitted.nodes[n];
        node.bounds = Aabb{};
        if (node.leaf()) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                node.bounds.grow(boxes[k]);
        } else {
            node.bounds.grow(refitted.nodes[n + 1].bounds);
            node.bounds.grow(refitted.nodes[node.first].bounds);
        }
    }
    return refitted;
}

// Places every mesh object's triangles in world space (layout.h, after
// GpuTriangle; VKRAY_WORLD_TRIANGLES) at the front of packed.triangles, each
// object's in its mesh's leaf order, the meshes' own triangles after them.
// Their BVH is each object's mesh BVH refitted in world space, under a BVH
// over the objects (a new build over all the triangles where that would be
// too deep for the shader's stack). Returns it joined to `objects` (which
// leaves the mesh objects out), its leaves indexing from `first` on: the
// shader's triangleFirst.
Bvh placeTrianglesInWorld(const Scene& scene, const Bvh& objects, std::uint32_t first,
                          GpuScene& packed) {
    std::vector<std::uint32_t> meshObjects;
    std::size_t count = 0;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        if (isBoolean(object.type) || gpuKindOf(object.type) != KIND_MESH) continue;
        if (scene.meshes.at(size_t(object.mesh))->triangles.empty()) continue;
        meshObjects.push_back(std::uint32_t(i));
        count += scene.meshes[size_t(object.mesh)]->triangles.size();
    }
    std::vector<GpuTriangle> world;
    std::vector<Aabb> boxes;  // of the corners as the shader gets them, rounded
    world.reserve(count);
    boxes.reserve(count);
    std::vector<Bvh> subtrees;
    std::vector<std::uint32_t> offsets;
    std::vector<Aabb> roots;
    for (const std::uint32_t i : meshObjects) {
        const SceneObject& object = scene.objects[i];
        const TriangleMesh& mesh = *scene.meshes[size_t(object.mesh)];
        // Where packMeshes put this mesh's triangles, in its leaf order, once
        // the world's go first.
        const uint own = uint(count) + packed.meshes.at(size_t(object.mesh)).range.y;
        const std::size_t offset = world.size();
        for (std::size_t k = 0; k < mesh.bvh.order.size(); ++k) {
            const TriangleMesh::Triangle& t = mesh.triangles[mesh.bvh.order[k]];
            GpuTriangle g{};
            vec4* corners[3] = {&g.p0, &g.p1, &g.p2};
            Aabb box;
            for (int c = 0; c < 3; ++c) {
                const glm::dvec4 p =
                    object.worldFromObject * glm::dvec4(mesh.positions[t.position[c]], 1.0);
                *corners[c] = toVec4(glm::dvec3(p));
                box.grow(glm::dvec3(corners[c]->x, corners[c]->y, corners[c]->z));
            }
            g.p0.w = bitsAsFloat(i);
            g.p1.w = bitsAsFloat(own + uint(k));
            world.push_back(g);
            boxes.push_back(box);
        }
        offsets.push_back(std::uint32_t(offset));
        subtrees.push_back(refittedBvh(
            mesh.bvh, std::vector<Aabb>(boxes.begin() + std::ptrdiff_t(offset), boxes.end())));
        roots.push_back(subtrees.back().nodes[0].bounds);
    }
    Bvh triangles = nestBvhs(buildBvh(roots, 1), subtrees, offsets);
    if (triangles.depth > kMaxBvhDepth) {
        triangles = buildBvh(boxes);
        std::vector<GpuTriangle> ordered;
        ordered.reserve(count);
        for (const std::uint32_t index : triangles.order) ordered.push_back(world[index]);
        world = std::move(ordered);
    }
    world.insert(world.end(), packed.triangles.begin(), packed.triangles.end());
    packed.triangles = std::move(world);
    for (GpuMesh& mesh : packed.meshes) mesh.range.y += uint(count);
    return joinBvhs(objects, triangles, first);
}

}  // namespace

GpuScene packScene(const Scene& scene, const ShaderFeatures& features) {
    GpuScene packed;
    packed.objects.reserve(scene.objects.size());
    packed.materials.reserve(scene.objects.size());
    packed.doubleObjects.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects) {
        if (!isBoolean(object.type) && gpuKindOf(object.type) == KIND_MESH &&
            (object.mesh < 0 || size_t(object.mesh) >= scene.meshes.size()))
            throw Error(located(
                object, std::string("'") + shapeKeyword(object.type) + "' has no geometry loaded"));
        const PackedObject p = packObject(scene, object);
        packed.objects.push_back(p.geometry);
        packed.materials.push_back(p.material);
        packed.doubleObjects.push_back(packDoubleObject(object));
    }
    for (const Light& light : scene.lights)
        packed.lights.push_back({toVec4(light.position), toVec4(light.color)});

    CsgPacker csg(scene, packed);
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (isBoolean(scene.objects[i].type))
            packed.objects[i].shape.y = csg.pack(scene.objects[i]);

    if (features.kinds[KIND_MESH]) packMeshes(scene, packed);

    if (features.has(Shading::Pixmaps)) {
        // Every pixmap's rgb texels, one after the other (a dropped one is empty).
        for (const Pixmap& pixmap : scene.pixmaps) {
            const uint first = uint(packed.texels.size());
            if (!pixmap.image) {
                packed.pixmaps.push_back({{first, 0, 0, 0}});
                continue;
            }
            const Image& image = *pixmap.image;
            if (image.channels != 3)
                throw Error("internal: pixmap " + std::to_string(pixmap.index) + " has " +
                            std::to_string(image.channels) + " channels, not 3");
            packed.pixmaps.push_back({{first, uint(image.width), uint(image.height), 0}});
            packed.texels.insert(packed.texels.end(), image.pixels.begin(), image.pixels.end());
        }
    }

    if (features.objectBvh) {
        const bool worldTriangles = placesTrianglesInWorld(features);
        ObjectBvh objects =
            buildObjectBvh(scene, worldTriangles ? MeshObjects::Apart : MeshObjects::In);
        packed.objectIndex.assign(objects.bvh.order.begin(), objects.bvh.order.end());
        packed.unboundedFirst = uint(packed.objectIndex.size());
        packed.unboundedCount = uint(objects.unbounded.size());
        packed.objectIndex.insert(packed.objectIndex.end(), objects.unbounded.begin(),
                                  objects.unbounded.end());
        if (worldTriangles)
            objects.bvh =
                placeTrianglesInWorld(scene, objects.bvh, uint(packed.objectIndex.size()), packed);
        packed.objectNodes = packBvh(objects.bvh);
        // featuresOf asks for the BVH only with bounded objects: the root exists.
        if (packed.objectNodes.empty()) throw Error("internal: an object BVH without nodes");
        packed.objectBvh = std::move(objects.bvh);
        // One walk takes the objects' BVH and the meshes' (trace.comp's
        // VKRAY_MESH_INSTANCES): their nodes in one array, the meshes' after.
        if (meshNodesWithObjects(features)) {
            const uint first = uint(packed.objectNodes.size());
            for (GpuMesh& mesh : packed.meshes) mesh.range.x += first;
            packed.objectNodes.insert(packed.objectNodes.end(), packed.meshNodes.begin(),
                                      packed.meshNodes.end());
            packed.meshNodes.clear();
        }
    }
    return packed;
}

FrameParams packFrame(const Scene& scene, const GpuScene& packed, const CameraBasis& camera,
                      const RenderSettings& settings) {
    FrameParams f{};
    f.eye = toVec4(camera.eye, camera.tanHalfFov);
    f.cameraU = toVec4(camera.u, camera.aspect);
    f.cameraV = toVec4(camera.v);
    f.cameraN = toVec4(camera.n);
    f.background = toVec4(scene.background);
    f.globalAmbient = toVec4(scene.globalAmbient);
    f.image = {uint(settings.width), uint(settings.height), uint(settings.block),
               uint(scene.objects.size())};
    f.counts = {uint(scene.lights.size()), uint(packed.objectNodes.size()), packed.unboundedFirst,
                packed.unboundedCount};
    f.sampling = {uint(settings.spp), settings.seed, uint(scene.maxRecursionDepth),
                  uint(pendingRayEntries(scene))};
    return f;
}

GpuDoubleCamera packDoubleCamera(const CameraBasis& camera) {
    const auto row = [](const glm::dvec3& v, double w) { return dvec4{v.x, v.y, v.z, w}; };
    return {row(camera.eye, camera.tanHalfFov), row(camera.u, camera.aspect), row(camera.v, 0),
            row(camera.n, 0)};
}

}  // namespace vkray::gpu
