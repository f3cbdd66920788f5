// The built-in solids. Hill's programs read tetra.3vn, octa.3vn, ... which
// users do not have; vkray makes them from the solids' known vertex
// coordinates (their convex hull, one flat normal per face). All are centred
// at the origin with circumradius 1 (every vertex at distance 1 for the
// Platonic solids and the buckyball; the diamond's girdle at distance 1):
//
//   tetrahedron   4 triangles   vertices (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1) / sqrt 3
//   octahedron    8 triangles   vertices on the axes: (+-1,0,0), (0,+-1,0), (0,0,+-1)
//   icosahedron  20 triangles   cyclic permutations of (0, +-1, +-phi) / sqrt(1 + phi^2)
//   dodecahedron 36 triangles   (+-1,+-1,+-1) and cyclic permutations of
//                               (0, +-1/phi, +-phi), / sqrt 3; 12 pentagons, 3 triangles each
//   buckyball   116 triangles   truncated icosahedron: the points 1/3 and 2/3 along each
//                               edge of the icosahedron above, scaled to radius 1; its 12
//                               pentagons (3 triangles) face the icosahedron's vertices,
//                               its 20 hexagons (4 triangles) the icosahedron's faces
//   diamond      30 triangles   a simplified octagonal brilliant, table up (+y): girdle
//                               octagon of radius 1 in y = 0 (corners at 45k degrees from
//                               +x toward +z), table octagon of radius 0.55 in y = 0.3
//                               (corners at 45k + 22.5 degrees), culet point (0, -0.86, 0).
//                               Crown 16 triangles, pavilion 8, table 6. The proportions of a
//                               round brilliant: table 55 %, crown 15 %, pavilion 43 % of
//                               the girdle's diameter.
//
// (phi = (1 + sqrt 5) / 2.) The teapot is in teapot.cpp.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "scene/triangle_mesh.h"
#include "util/error.h"

namespace vkray {

namespace {

constexpr double kPhi = std::numbers::phi;

// Scales the points about the origin so the farthest is at distance 1.
std::vector<glm::dvec3> withCircumradiusOne(std::vector<glm::dvec3> points) {
    double radius = 0;
    for (const glm::dvec3& p : points) radius = std::max(radius, glm::length(p));
    for (glm::dvec3& p : points) p /= radius;
    return points;
}

// (x, y, z), (y, z, x), (z, x, y) for each sign combination of the nonzero parts.
void addCyclicPermutations(std::vector<glm::dvec3>& points, glm::dvec3 base) {
    for (int signs = 0; signs < 8; ++signs) {
        glm::dvec3 p = base;
        bool repeat = false;
        for (int axis = 0; axis < 3; ++axis) {
            if (signs & (1 << axis)) {
                if (p[axis] == 0) repeat = true;  // -0 is +0: that combination is made already
                p[axis] = -p[axis];
            }
        }
        if (repeat) continue;
        points.emplace_back(p.x, p.y, p.z);
        points.emplace_back(p.y, p.z, p.x);
        points.emplace_back(p.z, p.x, p.y);
    }
}

std::vector<glm::dvec3> icosahedronVertices() {
    std::vector<glm::dvec3> points;
    addCyclicPermutations(points, {0, 1, kPhi});
    return withCircumradiusOne(points);
}

std::vector<glm::dvec3> solidVertices(ShapeType type) {
    std::vector<glm::dvec3> points;
    switch (type) {
    case ShapeType::Tetrahedron: points = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}; break;
    case ShapeType::Octahedron:
        points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        break;
    case ShapeType::Icosahedron: return icosahedronVertices();
    case ShapeType::Dodecahedron:
        for (int signs = 0; signs < 8; ++signs)
            points.emplace_back(signs & 1 ? -1 : 1, signs & 2 ? -1 : 1, signs & 4 ? -1 : 1);
        addCyclicPermutations(points, {0, 1 / kPhi, kPhi});
        break;
    case ShapeType::Buckyball: {
        const std::vector<glm::dvec3> icosahedron = icosahedronVertices();
        double edge = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < icosahedron.size(); ++i)
            for (std::size_t j = i + 1; j < icosahedron.size(); ++j)
                edge = std::min(edge, glm::distance(icosahedron[i], icosahedron[j]));
        for (std::size_t i = 0; i < icosahedron.size(); ++i) {
            for (std::size_t j = i + 1; j < icosahedron.size(); ++j) {
                if (glm::distance(icosahedron[i], icosahedron[j]) > edge * (1 + 1e-9)) continue;
                points.push_back((2.0 * icosahedron[i] + icosahedron[j]) / 3.0);
                points.push_back((icosahedron[i] + 2.0 * icosahedron[j]) / 3.0);
            }
        }
        break;
    }
    case ShapeType::Diamond: {
        constexpr double kTableRadius = 0.55, kCrownHeight = 0.3, kPavilionDepth = 0.86;
        constexpr double kStep = std::numbers::pi / 4;
        for (int k = 0; k < 8; ++k)
            points.emplace_back(std::cos(k * kStep), 0.0, std::sin(k * kStep));
        for (int k = 0; k < 8; ++k) {
            const double angle = (k + 0.5) * kStep;
            points.emplace_back(kTableRadius * std::cos(angle), kCrownHeight,
                                kTableRadius * std::sin(angle));
        }
        points.emplace_back(0.0, -kPavilionDepth, 0.0);
        return points;  // the girdle is at radius 1 already
    }
    default: throw Error(std::string("'") + shapeKeyword(type) + "' is not a built-in solid");
    }
    return withCircumradiusOne(points);
}

const char* builtInName(ShapeType type) {
    switch (type) {
    case ShapeType::Tetrahedron: return "built-in tetrahedron";
    case ShapeType::Octahedron: return "built-in octahedron";
    case ShapeType::Dodecahedron: return "built-in dodecahedron";
    case ShapeType::Icosahedron: return "built-in icosahedron";
    case ShapeType::Buckyball: return "built-in buckyball";
    case ShapeType::Diamond: return "built-in diamond";
    default: return "built-in";
    }
}

}  // namespace

TriangleMesh convexPolyhedron(std::span<const glm::dvec3> vertices, const std::string& name) {
    struct Face {
        glm::dvec3 normal;  // outward, unit
        double offset;      // dot(normal, p) on the face
        std::vector<std::uint32_t> corners;
    };
    double scale = 0;
    for (const glm::dvec3& p : vertices) scale = std::max(scale, glm::length(p));
    const double tolerance = 1e-9 * std::max(scale, 1e-300);
    const std::size_t n = vertices.size();
    const auto onFace = [&](const Face& face, const glm::dvec3& p) {
        return std::abs(glm::dot(face.normal, p) - face.offset) <= tolerance;
    };

    std::vector<Face> faces;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            for (std::size_t k = j + 1; k < n; ++k) {
                const glm::dvec3 &a = vertices[i], &b = vertices[j], &c = vertices[k];
                if (std::any_of(faces.begin(), faces.end(), [&](const Face& face) {
                        return onFace(face, a) && onFace(face, b) && onFace(face, c);
                    }))
                    continue;
                const glm::dvec3 cross = glm::cross(b - a, c - a);
                if (glm::length(cross) <= tolerance * scale) continue;  // collinear
                Face face{glm::normalize(cross), 0, {}};
                face.offset = glm::dot(face.normal, a);
                double above = -std::numeric_limits<double>::infinity();
                double below = std::numeric_limits<double>::infinity();
                for (const glm::dvec3& p : vertices) {
                    const double height = glm::dot(face.normal, p) - face.offset;
                    above = std::max(above, height);
                    below = std::min(below, height);
                }
                if (above > tolerance && below < -tolerance) continue;  // not a supporting plane
                if (above > tolerance) {
                    face.normal = -face.normal;
                    face.offset = -face.offset;
                }
                for (std::size_t m = 0; m < n; ++m)
                    if (onFace(face, vertices[m])) face.corners.push_back(std::uint32_t(m));
                // Counter-clockwise seen from outside: by angle about the outward normal.
                glm::dvec3 centre{0};
                for (const std::uint32_t corner : face.corners) centre += vertices[corner];
                centre /= double(face.corners.size());
                const glm::dvec3 u = glm::normalize(vertices[face.corners[0]] - centre);
                const glm::dvec3 w = glm::cross(face.normal, u);
                const auto angle = [&](std::uint32_t corner) {
                    const glm::dvec3 d = vertices[corner] - centre;
                    return std::atan2(glm::dot(d, w), glm::dot(d, u));
                };
                std::sort(face.corners.begin(), face.corners.end(),
                          [&](std::uint32_t x, std::uint32_t y) { return angle(x) < angle(y); });
                faces.push_back(std::move(face));
            }
        }
    }

    TriangleMesh mesh;
    mesh.name = name;
    mesh.positions.assign(vertices.begin(), vertices.end());
    for (const Face& face : faces) {
        const auto normal = std::uint32_t(mesh.normals.size());
        mesh.normals.push_back(face.normal);
        for (std::size_t c = 1; c + 1 < face.corners.size(); ++c) {
            mesh.triangles.push_back({{face.corners[0], face.corners[c], face.corners[c + 1]},
                                      {normal, normal, normal}});
        }
    }
    mesh.closed = isClosedSurface(mesh.positions, mesh.triangles);
    finishMesh(mesh);
    return mesh;
}

TriangleMesh builtInMesh(ShapeType type) {
    if (type == ShapeType::Teapot) return utahTeapot();
    const std::vector<glm::dvec3> vertices = solidVertices(type);
    return convexPolyhedron(vertices, builtInName(type));
}

}  // namespace vkray
