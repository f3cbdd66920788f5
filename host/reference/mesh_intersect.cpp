// Watertight ray/triangle intersection (Woop, Benthin, Wald, JCGT 2(1), 2013;
// docs/numerics-background.md, "Watertight triangles") in double, and the mesh BVH walk.
//
// Why watertight: Moller-Trumbore measures each triangle from its own first
// corner, so two triangles round a shared edge differently and rays slip
// through (holes) or hit both (double hits). Here every triangle is tested in
// one frame per ray (translated to the ray's origin, sheared so the ray is
// the z axis): whether the ray passes left or right of an edge is the sign of
// a 2D cross product of the edge's two sheared corners. The same corners give
// the same numbers in every triangle, and the neighbour, walking the edge the
// other way, computes exactly the negated value. So the edge tests of
// neighbours never disagree, and the even-odd spans of a closed mesh stay
// consistent.
#include "reference/mesh_intersect.h"

#include "reference/bvh_walk.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace vkray::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The largest finite t: BVH boxes are clipped to it rather than to +-inf,
// which keeps a slab test of a ray parallel to a box face free of inf - inf.
constexpr double kFar = std::numeric_limits<double>::max();

// a b - c d with the sign always right: the rounding error of c d is
// recovered exactly by fma, and the result is within 2 ulps (Kahan;
// docs/numerics-background.md, "Compensated products").
double differenceOfProducts(double a, double b, double c, double d) {
    const double cd = c * d;
    const double error = std::fma(-c, d, cd);
    return std::fma(a, b, -cd) + error;
}

struct Sheared {
    double x, y, z;
};

// Edge function of the sheared corners P, Q about the ray (the origin):
// positive when the ray passes on one side, negative on the other. Plain
// double first (exactly antisymmetric in P, Q); a 0 is recomputed with the
// exact sign, and a true 0 (the ray exactly through the edge) is decided as
// if the ray were moved by (eps, eps^2) for an infinitesimal eps, which gives
// the sign of (P.y - Q.y), else of (Q.x - P.x): still antisymmetric, so
// exactly one of the two triangles at an edge (or one of a fan around a
// vertex) takes the ray.
double edgeFunction(const Sheared& p, const Sheared& q, double* tieSign) {
    double e = p.x * q.y - p.y * q.x;
    if (e == 0) e = differenceOfProducts(p.x, q.y, p.y, q.x);
    *tieSign = e;
    if (e == 0) *tieSign = p.y != q.y ? p.y - q.y : q.x - p.x;
    return e;
}

}  // namespace

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin) {
    const glm::dvec3& d = ray.direction;
    const glm::dvec3 a = glm::abs(d);
    kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    valid = a[kz] > 0 && std::isfinite(a[kz]);
    kx = (kz + 1) % 3;
    ky = (kx + 1) % 3;
    // Swapping two axes mirrors the frame; together with the sign of d_kz it
    // makes the determinant below positive exactly when the ray meets the
    // front of the triangle (the side its right-handed normal points to).
    if (d[kz] < 0) std::swap(kx, ky);
    shearX = d[kx] / d[kz];
    shearY = d[ky] / d[kz];
    shearZ = 1 / d[kz];
}

std::optional<TriangleHit> intersectTriangle(const WatertightRay& ray, const glm::dvec3& p0,
                                             const glm::dvec3& p1, const glm::dvec3& p2,
                                             double tMin, double tMax) {
    if (!ray.valid) return std::nullopt;
    const auto shear = [&ray](const glm::dvec3& corner) {
        const glm::dvec3 p = corner - ray.origin;
        return Sheared{p[ray.kx] - ray.shearX * p[ray.kz], p[ray.ky] - ray.shearY * p[ray.kz],
                       ray.shearZ * p[ray.kz]};
    };
    const Sheared a = shear(p0), b = shear(p1), c = shear(p2);

    // u, v, w: twice the signed areas of (ray, b, c), (ray, c, a), (ray, a, b),
    // each the weight of the opposite corner.
    double su, sv, sw;
    const double u = edgeFunction(c, b, &su);
    const double v = edgeFunction(a, c, &sv);
    const double w = edgeFunction(b, a, &sw);
    if ((su < 0 || sv < 0 || sw < 0) && (su > 0 || sv > 0 || sw > 0)) return std::nullopt;
    const double det = u + v + w;
    if (det == 0) return std::nullopt;  // seen edge-on: the ray lies in the triangle's plane

    const double t = (u * a.z + v * b.z + w * c.z) / det;
    if (!(t > tMin && t < tMax)) return std::nullopt;
    return TriangleHit{t, u / det, v / det, w / det, det > 0};
}

namespace {

// Nearest first, then the lower triangle index: the same winner whatever
// order the triangles are tested in.
bool better(const MeshHit& hit, const std::optional<MeshHit>& best) {
    return !best || hit.t < best->t || (hit.t == best->t && hit.triangle < best->triangle);
}

std::optional<MeshHit> testTriangle(const TriangleMesh& mesh, const WatertightRay& ray,
                                    std::uint32_t index, double tMin, double tMax) {
    const TriangleMesh::Triangle& triangle = mesh.triangles[index];
    const std::optional<TriangleHit> hit = intersectTriangle(
        ray, mesh.positions[triangle.position[0]], mesh.positions[triangle.position[1]],
        mesh.positions[triangle.position[2]], tMin, tMax);
    if (!hit) return std::nullopt;
    return MeshHit{hit->t, index, *hit};
}

}  // namespace

std::optional<MeshHit> intersectMesh(const TriangleMesh& mesh, const Ray& ray, double tMin) {
    const WatertightRay prepared(ray);
    if (!prepared.valid) return std::nullopt;
    std::optional<MeshHit> best;
    // Boxes up to the best t so far, that t included: a tie may still go to a
    // lower-numbered triangle further on.
    const auto tMax = [&best] { return best ? best->t : kFar; };
    walkBvh(mesh.bvh, ray, tMin, tMax, [&](std::uint32_t index) {
        const std::optional<MeshHit> hit = testTriangle(mesh, prepared, index, tMin, kInf);
        if (hit && better(*hit, best)) best = hit;
    });
    return best;
}

std::optional<MeshHit> intersectMeshBruteForce(const TriangleMesh& mesh, const Ray& ray,
                                               double tMin) {
    const WatertightRay prepared(ray);
    std::optional<MeshHit> best;
    for (std::uint32_t index = 0; index < mesh.triangles.size(); ++index) {
        const std::optional<MeshHit> hit = testTriangle(mesh, prepared, index, tMin, kInf);
        if (hit && better(*hit, best)) best = hit;
    }
    return best;
}

std::vector<MeshHit> meshCrossings(const TriangleMesh& mesh, const Ray& ray) {
    std::vector<MeshHit> crossings;
    const WatertightRay prepared(ray);
    if (!prepared.valid) return crossings;
    walkBvh(
        mesh.bvh, ray, -kFar, [] { return kFar; },
        [&](std::uint32_t index) {
            const std::optional<MeshHit> hit = testTriangle(mesh, prepared, index, -kInf, kInf);
            if (hit) crossings.push_back(*hit);
        });
    std::sort(crossings.begin(), crossings.end(), [](const MeshHit& a, const MeshHit& b) {
        return a.t < b.t || (a.t == b.t && a.triangle < b.triangle);
    });
    return crossings;
}

GenericHit meshSurface(const TriangleMesh& mesh, const MeshHit& hit) {
    const TriangleMesh::Triangle& triangle = mesh.triangles[hit.triangle];
    const glm::dvec3& p0 = mesh.positions[triangle.position[0]];
    const glm::dvec3 geometric = glm::cross(mesh.positions[triangle.position[1]] - p0,
                                            mesh.positions[triangle.position[2]] - p0);
    const double weights[3] = {hit.crossing.b0, hit.crossing.b1, hit.crossing.b2};
    glm::dvec3 normal(0);
    for (int k = 0; k < 3; ++k) {
        if (triangle.normal[k] >= mesh.normals.size()) return {hit.t, geometric, geometric};
        normal += weights[k] * mesh.normals[triangle.normal[k]];
    }
    // Opposed corner normals can cancel: fall back to the flat normal.
    if (!(glm::dot(normal, normal) > 0)) normal = geometric;
    return {hit.t, normal, geometric};
}

std::vector<GenericSpan> meshSpans(const TriangleMesh& mesh, const Ray& ray) {
    const std::vector<MeshHit> crossings = meshCrossings(mesh, ray);
    std::vector<GenericSpan> spans;
    spans.reserve(crossings.size() / 2);
    // An odd count means a crossing was lost to rounding where the ray grazes
    // the surface; the unmatched last crossing is dropped.
    for (std::size_t i = 0; i + 1 < crossings.size(); i += 2)
        spans.push_back({meshSurface(mesh, crossings[i]), meshSurface(mesh, crossings[i + 1])});
    return spans;
}

}  // namespace vkray::reference
