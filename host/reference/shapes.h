// Generic shapes for the CPU reference, each in its own object space (Hill
// ch. 14), derived from the implicit equations in double precision. The ray
// is not normalised in object space, so a root t is also the world t.
//
// Every closed shape also reports where the ray is inside it: a sorted list
// of spans [enter, exit] (CSG combines them). Its nearest hit is then simply
// the first span end with t > tMin, so hit and spans can never disagree.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <optional>

namespace vkray::reference {

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;  // need not be unit length
};

// A hit in generic space: t along the ray, and the outward generic normal
// (not normalised). Meshes also give the triangle's own normal, which decides
// which side the ray is on (the interpolated normal may lean past the
// silhouette); zero for every other shape, whose normal is its own.
struct GenericHit {
    double t;
    glm::dvec3 normal;
    glm::dvec3 geometricNormal{0};
};

// The ray is inside the solid for enter.t <= t <= exit.t (closed). An end at
// +-inf (a half-space) has a zero normal and is never a hit.
struct GenericSpan {
    GenericHit enter, exit;
};

// The spans of one primitive along a ray, sorted and disjoint. Two are enough
// for every analytic shape here (the torus; an hourglass tapered cylinder),
// so they live inline: no allocation per ray.
class SpanPair {
public:
    void push(const GenericSpan& span) { spans_[count_++] = span; }
    std::size_t size() const { return count_; }
    bool empty() const { return count_ == 0; }
    const GenericSpan& operator[](std::size_t i) const { return spans_[i]; }
    const GenericSpan* begin() const { return spans_.data(); }
    const GenericSpan* end() const { return spans_.data() + count_; }

private:
    std::array<GenericSpan, 2> spans_{};
    std::size_t count_ = 0;
};

// The first span end strictly after tMin (the interval (tMin, +inf) is open
// at tMin): entering the solid, or leaving it when the ray starts inside.
std::optional<GenericHit> firstBoundary(const SpanPair& spans, double tMin);

// Each intersect* returns the nearest hit with t > tMin, or nothing.

// Unit sphere x^2 + y^2 + z^2 <= 1.
std::optional<GenericHit> intersectSphere(const Ray& ray, double tMin);
SpanPair sphereSpans(const Ray& ray);

// Plane z = 0, normal +z. As a solid (CSG) it is the half-space z <= 0, so
// its spans may reach -inf or +inf.
std::optional<GenericHit> intersectPlane(const Ray& ray, double tMin);
SpanPair planeSpans(const Ray& ray);

// The part of z = 0 with |x|, |y| <= 1. A surface without an inside: no spans.
std::optional<GenericHit> intersectSquare(const Ray& ray, double tMin);

// Cube [-1, 1]^3.
std::optional<GenericHit> intersectCube(const Ray& ray, double tMin);
SpanPair cubeSpans(const Ray& ray);

// Hill's generic tapered cylinder: axis z from 0 to 1, radius 1 at z = 0 and
// s at z = 1 (cylinder s = 1, cone s = 0), closed by the disks z = 0 (radius
// 1) and z = 1 (radius s; a point when s = 0). The solid is
//     0 <= z <= 1  and  x^2 + y^2 <= rho(z)^2,  rho(z) = 1 + (s - 1) z.
// Outward normals: wall (x, y, -(s - 1) rho(z)), caps -z and +z, the apex +z.
// For s < 0 the two nappes meet inside [0, 1]: an hourglass, up to two spans.
std::optional<GenericHit> intersectTaperedCylinder(const Ray& ray, double s, double tMin);
SpanPair taperedCylinderSpans(const Ray& ray, double s);

// The generic torus of scene.h: axis z, centre at the origin, radii
// R = kTorusMajorRadius (the tube's centre circle, in z = 0) and
// r = kTorusTubeRadius, i.e.
//     F(p) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) <= 0.
// torusRoots gives every crossing along the whole line (up to four), sorted
// by t, each with its outward normal grad F; see torus.cpp for the solver.
struct TorusRoots {
    std::array<GenericHit, 4> hits{};
    int count = 0;
};
TorusRoots torusRoots(const Ray& ray);
std::optional<GenericHit> intersectTorus(const Ray& ray, double tMin);
SpanPair torusSpans(const Ray& ray);

}  // namespace vkray::reference
