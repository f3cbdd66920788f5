// `extrude file.dat`: a 2D outline swept from z = 0 to z = 1 into a closed
// prism. The caps are triangulated by ear clipping, with a uniform grid over
// the vertices that can block an ear, so large outlines stay fast.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <string>

#include "scene/triangle_mesh.h"
#include "util/error.h"

namespace vkray {

namespace {

using Point = glm::dvec2;

// Self-intersection tests and ear clipping are quadratic at worst; a hostile
// outline (up to kMaxOutlinePoints) must fail in about a second, not hang.
constexpr std::uint64_t kMaxWork = 400'000'000;

// Twice the signed area of triangle (a, b, c): > 0 when counter-clockwise.
double orient(const Point& a, const Point& b, const Point& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

double signedArea(const std::vector<Point>& polygon) {
    double twice = 0;
    for (std::size_t i = 0, n = polygon.size(); i < n; ++i) {
        const Point& p = polygon[i];
        const Point& q = polygon[(i + 1) % n];
        twice += p.x * q.y - q.x * p.y;
    }
    return twice / 2;
}

class WorkBudget {
public:
    explicit WorkBudget(const std::string& path) : path_(path) {}
    void spend(std::uint64_t work) {
        used_ += work;
        if (used_ > kMaxWork) throw Error(path_ + ": error: the outline is too complex to extrude");
    }

private:
    const std::string& path_;
    std::uint64_t used_ = 0;
};

// The points without repeats: consecutive equal points (and a last point
// equal to the first) add nothing but zero-length edges.
std::vector<Point> withoutRepeats(const std::vector<Point>& points) {
    std::vector<Point> kept;
    kept.reserve(points.size());
    for (const Point& p : points)
        if (kept.empty() || p != kept.back()) kept.push_back(p);
    while (kept.size() > 1 && kept.back() == kept.front()) kept.pop_back();
    return kept;
}

bool onSegment(const Point& a, const Point& b, const Point& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

// Closed segments [a, b] and [c, d] share a point (crossing, touching or overlapping).
bool segmentsMeet(const Point& a, const Point& b, const Point& c, const Point& d) {
    const double d1 = orient(c, d, a), d2 = orient(c, d, b);
    const double d3 = orient(a, b, c), d4 = orient(a, b, d);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    return (d1 == 0 && onSegment(c, d, a)) || (d2 == 0 && onSegment(c, d, b)) ||
           (d3 == 0 && onSegment(a, b, c)) || (d4 == 0 && onSegment(a, b, d));
}

// True when the closed polygon has no two edges that meet other than
// neighbours at their shared corner (and those do not fold back onto each
// other). A sweep over x: each edge is tested only against the edges whose
// x-range overlaps its own.
bool isSimplePolygon(const std::vector<Point>& polygon, WorkBudget& budget) {
    const std::size_t n = polygon.size();
    if (n < 3 || signedArea(polygon) == 0) return false;
    const auto minX = [&](std::size_t edge) {
        return std::min(polygon[edge].x, polygon[(edge + 1) % n].x);
    };
    const auto maxX = [&](std::size_t edge) {
        return std::max(polygon[edge].x, polygon[(edge + 1) % n].x);
    };
    std::vector<std::size_t> edges(n);
    for (std::size_t i = 0; i < n; ++i) edges[i] = i;
    std::sort(edges.begin(), edges.end(),
              [&](std::size_t a, std::size_t b) { return minX(a) < minX(b); });
    budget.spend(n * 32);  // the sort
    std::vector<std::size_t> active;
    for (const std::size_t edge : edges) {
        const double left = minX(edge);
        std::erase_if(active, [&](std::size_t other) { return maxX(other) < left; });
        budget.spend(active.size() + 1);
        const Point& a = polygon[edge];
        const Point& b = polygon[(edge + 1) % n];
        for (const std::size_t other : active) {
            const Point& c = polygon[other];
            const Point& d = polygon[(other + 1) % n];
            const bool otherFollows = other == (edge + 1) % n;
            const bool otherPrecedes = edge == (other + 1) % n;
            if (otherFollows || otherPrecedes) {
                // Neighbours share a corner; they must not run back over each other.
                const Point first = otherFollows ? b - a : d - c;
                const Point second = otherFollows ? d - c : b - a;
                if (first.x * second.y - first.y * second.x == 0 && glm::dot(first, second) < 0)
                    return false;
                continue;
            }
            if (segmentsMeet(a, b, c, d)) return false;
        }
        active.push_back(edge);
    }
    return true;
}

// Hill's quad strip p0 p1 | p2 p3 | ...: its outline runs up the even points
// and back down the odd ones.
std::vector<Point> quadStripBoundary(const std::vector<Point>& points) {
    std::vector<Point> boundary;
    boundary.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); i += 2) boundary.push_back(points[i]);
    for (std::size_t i = points.size() - 1; i < points.size(); i -= 2)
        boundary.push_back(points[i]);
    return boundary;
}

// Ear clipping of a simple counter-clockwise polygon: n - 2 triangles, each
// counter-clockwise. Only vertices that start reflex or straight can lie in
// an ear (convex ones stay convex as ears are cut), so only they go into the grid.
class EarClipper {
public:
    EarClipper(const std::vector<Point>& polygon, WorkBudget& budget)
        : polygon_(polygon),
          budget_(budget),
          next_(polygon.size()),
          previous_(polygon.size()),
          removed_(polygon.size(), false) {
        const std::size_t n = polygon.size();
        for (std::size_t i = 0; i < n; ++i) {
            next_[i] = (i + 1) % n;
            previous_[i] = (i + n - 1) % n;
        }
        buildGrid();
    }

    std::vector<std::array<std::size_t, 3>> triangulate() {
        std::vector<std::array<std::size_t, 3>> triangles;
        std::size_t remaining = polygon_.size();
        triangles.reserve(remaining - 2);
        std::size_t vertex = 0;
        std::size_t sinceLastClip = 0;
        while (remaining > 3) {
            budget_.spend(1);
            if (isEar(vertex) || sinceLastClip > remaining) {
                // After a whole lap without an ear (only rounding can cause
                // that in a simple polygon), the current vertex is cut anyway.
                triangles.push_back({previous_[vertex], vertex, next_[vertex]});
                const std::size_t after = next_[vertex];
                remove(vertex);
                --remaining;
                vertex = after;
                sinceLastClip = 0;
            } else {
                vertex = next_[vertex];
                ++sinceLastClip;
            }
        }
        triangles.push_back({previous_[vertex], vertex, next_[vertex]});
        return triangles;
    }

private:
    void buildGrid() {
        for (std::size_t i = 0; i < polygon_.size(); ++i) {
            lo_ = glm::min(lo_, polygon_[i]);
            hi_ = glm::max(hi_, polygon_[i]);
            if (orient(polygon_[previous_[i]], polygon_[i], polygon_[next_[i]]) <= 0)
                blockers_.push_back(i);
        }
        // About one blocker per cell, in a grid shaped like the outline's box.
        const Point extent = glm::max(hi_ - lo_, Point(1e-300));
        const double cells = std::max<double>(1, double(blockers_.size()));
        const double aspect = extent.x / extent.y;
        columns_ = std::clamp(int(std::sqrt(cells * aspect)), 1, 2048);
        rows_ = std::clamp(int(cells / columns_), 1, 2048);
        cellSize_ = extent / Point(columns_, rows_);
        cellStart_.assign(std::size_t(columns_ * rows_) + 1, 0);
        for (const std::size_t b : blockers_) ++cellStart_[cellOf(polygon_[b]) + 1];
        for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
        cellItems_.resize(blockers_.size());
        std::vector<std::size_t> fill(cellStart_.begin(), cellStart_.end() - 1);
        for (const std::size_t b : blockers_) cellItems_[fill[cellOf(polygon_[b])]++] = b;
    }

    int column(double x) const {
        return std::clamp(int((x - lo_.x) / cellSize_.x), 0, columns_ - 1);
    }
    int row(double y) const { return std::clamp(int((y - lo_.y) / cellSize_.y), 0, rows_ - 1); }
    std::size_t cellOf(const Point& p) const {
        return std::size_t(row(p.y)) * std::size_t(columns_) + std::size_t(column(p.x));
    }

    bool isEar(std::size_t vertex) const {
        const std::size_t a = previous_[vertex], b = next_[vertex];
        const Point &pa = polygon_[a], &pv = polygon_[vertex], &pb = polygon_[b];
        const double turn = orient(pa, pv, pb);
        if (turn < 0) return false;
        if (turn == 0) return true;  // a straight corner: cutting it leaves the outline as it is
        const Point lo = glm::min(pa, glm::min(pv, pb));
        const Point hi = glm::max(pa, glm::max(pv, pb));
        for (int r = row(lo.y); r <= row(hi.y); ++r) {
            for (int c = column(lo.x); c <= column(hi.x); ++c) {
                const std::size_t cell = std::size_t(r) * std::size_t(columns_) + std::size_t(c);
                budget_.spend(cellStart_[cell + 1] - cellStart_[cell] + 1);
                for (std::size_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
                    const std::size_t p = cellItems_[k];
                    if (removed_[p] || p == a || p == vertex || p == b) continue;
                    const Point& q = polygon_[p];
                    if (q == pa || q == pv || q == pb) continue;
                    // Closed triangle: a blocker on an edge also blocks the ear.
                    if (orient(pa, pv, q) >= 0 && orient(pv, pb, q) >= 0 && orient(pb, pa, q) >= 0)
                        return false;
                }
            }
        }
        return true;
    }

    void remove(std::size_t vertex) {
        removed_[vertex] = true;
        next_[previous_[vertex]] = next_[vertex];
        previous_[next_[vertex]] = previous_[vertex];
    }

    const std::vector<Point>& polygon_;
    WorkBudget& budget_;
    std::vector<std::size_t> next_, previous_;
    std::vector<bool> removed_;
    std::vector<std::size_t> blockers_;
    Point lo_{std::numeric_limits<double>::infinity()};
    Point hi_{-std::numeric_limits<double>::infinity()};
    int columns_ = 1, rows_ = 1;
    Point cellSize_{1, 1};
    std::vector<std::size_t> cellStart_, cellItems_;
};

}  // namespace

TriangleMesh extrudeOutline(const Outline& outline) {
    WorkBudget budget(outline.path);
    std::vector<Point> polygon = withoutRepeats(outline.points);
    if (!isSimplePolygon(polygon, budget)) {
        std::vector<Point> strip;
        if (outline.points.size() >= 4 && outline.points.size() % 2 == 0)
            strip = withoutRepeats(quadStripBoundary(outline.points));
        if (strip.empty() || !isSimplePolygon(strip, budget)) {
            throw Error(outline.path +
                        ": error: the outline crosses or touches itself; extrude needs a simple "
                        "polygon (or Hill's quad strip: pairs of points, each pair a rung)");
        }
        polygon = std::move(strip);
    }
    if (signedArea(polygon) < 0) std::reverse(polygon.begin(), polygon.end());

    TriangleMesh mesh;
    mesh.name = std::filesystem::path(outline.path).filename().string();
    const std::size_t n = polygon.size();
    // positions: bottom ring (z = 0) then top ring (z = 1).
    mesh.positions.reserve(2 * n);
    for (const Point& p : polygon) mesh.positions.emplace_back(p.x, p.y, 0.0);
    for (const Point& p : polygon) mesh.positions.emplace_back(p.x, p.y, 1.0);
    const auto bottom = [](std::size_t i) { return std::uint32_t(i); };
    const auto top = [n](std::size_t i) { return std::uint32_t(n + i); };

    // Sides: for a counter-clockwise outline, (dy, -dx) points out of edge (dx, dy).
    mesh.normals.reserve(n + 2);
    mesh.triangles.reserve(2 * n + 2 * (n - 2));
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (i + 1) % n;
        const Point edge = polygon[j] - polygon[i];
        const auto normal = std::uint32_t(mesh.normals.size());
        mesh.normals.push_back(glm::normalize(glm::dvec3(edge.y, -edge.x, 0)));
        mesh.triangles.push_back({{bottom(i), bottom(j), top(j)}, {normal, normal, normal}});
        mesh.triangles.push_back({{bottom(i), top(j), top(i)}, {normal, normal, normal}});
    }
    const auto down = std::uint32_t(mesh.normals.size());
    mesh.normals.emplace_back(0, 0, -1);
    const auto up = std::uint32_t(mesh.normals.size());
    mesh.normals.emplace_back(0, 0, 1);
    for (const auto& [a, b, c] : EarClipper(polygon, budget).triangulate()) {
        mesh.triangles.push_back({{bottom(a), bottom(c), bottom(b)}, {down, down, down}});
        mesh.triangles.push_back({{top(a), top(b), top(c)}, {up, up, up}});
    }
    mesh.closed = true;  // by construction; tests check it with isClosedSurface
    finishMesh(mesh);
    return mesh;
}

}  // namespace vkray
