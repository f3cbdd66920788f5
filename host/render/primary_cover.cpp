#include "render/primary_cover.h"

#include "scene/scene_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <deque>

namespace vkray {

namespace {

// The angle by which a shader's primary ray may stray from the exact one
// (float camera basis and image point: a few 1e-7) and its object tests may
// still meet an object's box beyond the exact ray's reach, with a wide margin.
constexpr double kAngleMargin = 1e-4;

int cellsOf(int pixels) {
    return (pixels + PrimaryCover::kCell - 1) / PrimaryCover::kCell;
}

// The pixels a render's samples lie in: the image rounded up to whole blocks
// (a block at the edge looks through its centre, which may lie beyond it).
int extentOf(int pixels, int block) {
    return (pixels + block - 1) / block * block;
}

}  // namespace

PrimaryCover::PrimaryCover(const RenderSettings& settings)
    : width_(extentOf(settings.width, settings.block)),
      height_(extentOf(settings.height, settings.block)),
      cellsX_(cellsOf(width_)),
      cellsY_(cellsOf(height_)) {
    coverAll();
}

void PrimaryCover::coverAll() {
    sums_.assign(size_t(cellsX_ + 1) * size_t(cellsY_ + 1), 0);
    for (int y = 1; y <= cellsY_; ++y)
        for (int x = 1; x <= cellsX_; ++x)
            sums_[size_t(y) * size_t(cellsX_ + 1) + size_t(x)] = x * y;
}

PrimaryCover::PrimaryCover(const CoverShapes& shapes, const CameraBasis& camera,
                           const RenderSettings& settings)
    : PrimaryCover(settings) {
    if (shapes.unbounded || shapes.planes.size() > kMostPlanes) return;
    // The image point (px, py), in pixels of the W x H image, looks along
    // d = -n + sx T A u + sy T v, sx = 2 px / W - 1, sy = 1 - 2 py / H
    // (render/camera.h).
    const double tanY = camera.tanHalfFov, tanX = camera.tanHalfFov * camera.aspect;
    const double w = settings.width, h = settings.height;
    // A pixel is at least 2 tanX / W of the tangent plane; an angle of
    // kAngleMargin moves a point by at most kAngleMargin (1 + tanX^2 + tanY^2) there.
    const double margin = std::max(1.0, kAngleMargin * (1 + tanX * tanX + tanY * tanY) *
                                            std::max(w / (2 * tanX), h / (2 * tanY)));
    std::vector<std::int32_t> marks(size_t(cellsX_ + 1) * size_t(cellsY_ + 1), 0);
    const auto at = [&](int x, int y) -> std::int32_t& {
        return marks[size_t(y) * size_t(cellsX_ + 1) + size_t(x)];
    };
    const auto markPixels = [&](double x0, double y0, double x1, double y1) {
        x0 -= margin, y0 -= margin, x1 += margin, y1 += margin;
        if (x1 < 0 || y1 < 0 || x0 >= width_ || y0 >= height_) return;
        const int cx0 = std::clamp(int(std::floor(x0 / kCell)), 0, cellsX_ - 1);
        const int cy0 = std::clamp(int(std::floor(y0 / kCell)), 0, cellsY_ - 1);
        const int cx1 = std::clamp(int(std::floor(x1 / kCell)), 0, cellsX_ - 1) + 1;
        const int cy1 = std::clamp(int(std::floor(y1 / kCell)), 0, cellsY_ - 1) + 1;
        ++at(cx0, cy0), --at(cx1, cy0), --at(cx0, cy1), ++at(cx1, cy1);
    };
    for (const Aabb& box : shapes.boxes) {
        if (box.empty()) continue;
        double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
        int behind = 0;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? box.hi.x : box.lo.x,
                               (corner & 2) ? box.hi.y : box.lo.y,
                               (corner & 4) ? box.hi.z : box.lo.z);
            const glm::dvec3 q = p - camera.eye;
            const double depth = -glm::dot(q, camera.n);
            if (!(depth > 0)) {
                ++behind;
                continue;
            }
            const double px = (glm::dot(q, camera.u) / (depth * tanX) + 1) * w / 2;
            const double py = (1 - glm::dot(q, camera.v) / (depth * tanY)) * h / 2;
            x0 = std::min(x0, px), x1 = std::max(x1, px);
            y0 = std::min(y0, py), y1 = std::max(y1, py);
        }
        if (behind == 8) continue;  // primary rays only go forward from the eye
        if (behind > 0 || !std::isfinite(x0 + x1 + y0 + y1)) {
            return;  // the box reaches the eye's plane: it may be anywhere in the image
        }
        markPixels(x0, y0, x1, y1);
    }
    // Covered cells: the marks summed up to each.
    std::vector<std::uint8_t> covered(size_t(cellsX_) * size_t(cellsY_));
    std::vector<std::int32_t> row(size_t(cellsX_ + 1), 0);
    for (int y = 0; y < cellsY_; ++y) {
        std::int32_t run = 0;
        for (int x = 0; x < cellsX_; ++x) {
            run += at(x, y);
            row[size_t(x)] += run;
            covered[size_t(y) * size_t(cellsX_) + size_t(x)] = row[size_t(x)] > 0;
        }
    }
    // A plane meets the ray of image point (px, py) where (N . d) and the
    // eye's side s = N . eye + c differ in sign; N . d is affine in (px, py),
    // so a cell whose four corners all look away from the plane (with margin)
    // shows none of it.
    for (const WorldPlane& plane : shapes.planes) {
        const double side = glm::dot(plane.normal, camera.eye) + plane.offset;
        const double a0 = -glm::dot(plane.normal, camera.n) -
                          tanX * glm::dot(plane.normal, camera.u) +
                          tanY * glm::dot(plane.normal, camera.v);
        const double ax = 2 * tanX * glm::dot(plane.normal, camera.u) / w;
        const double ay = -2 * tanY * glm::dot(plane.normal, camera.v) / h;
        const double slack = kAngleMargin * glm::length(plane.normal) * (1 + tanX + tanY);
        if (!(side != 0) || !std::isfinite(side + a0 + ax + ay)) return;  // the eye on it
        const double sign = side > 0 ? 1 : -1;
        for (int y = 0; y < cellsY_; ++y)
            for (int x = 0; x < cellsX_; ++x) {
                std::uint8_t& cell = covered[size_t(y) * size_t(cellsX_) + size_t(x)];
                if (cell) continue;
                double least = INFINITY;  // of sign (N . d) over the cell's corners
                for (int corner = 0; corner < 4; ++corner) {
                    const double px = double(x + (corner & 1)) * kCell;
                    const double py = double(y + (corner >> 1)) * kCell;
                    least = std::min(least, sign * (a0 + ax * px + ay * py));
                }
                if (!(least > slack)) cell = 1;
            }
    }
    sums_.assign(size_t(cellsX_ + 1) * size_t(cellsY_ + 1), 0);
    for (int y = 0; y < cellsY_; ++y)
        for (int x = 0; x < cellsX_; ++x)
            sums_[size_t(y + 1) * size_t(cellsX_ + 1) + size_t(x + 1)] =
                covered[size_t(y) * size_t(cellsX_) + size_t(x)] +
                sums_[size_t(y) * size_t(cellsX_ + 1) + size_t(x + 1)] +
                sums_[size_t(y + 1) * size_t(cellsX_ + 1) + size_t(x)] -
                sums_[size_t(y) * size_t(cellsX_ + 1) + size_t(x)];
}

int PrimaryCover::cellCount(int cx0, int cy0, int cx1, int cy1) const {
    const auto s = [&](int x, int y) { return sums_[size_t(y) * size_t(cellsX_ + 1) + size_t(x)]; };
    return s(cx1, cy1) - s(cx0, cy1) - s(cx1, cy0) + s(cx0, cy0);
}

bool PrimaryCover::mayHit(int x0, int y0, int x1, int y1) const {
    x0 = std::clamp(x0, 0, width_), x1 = std::clamp(x1, 0, width_);
    y0 = std::clamp(y0, 0, height_), y1 = std::clamp(y1, 0, height_);
    if (x0 >= x1 || y0 >= y1) return false;
    return cellCount(x0 / kCell, y0 / kCell, cellsOf(x1), cellsOf(y1)) > 0;
}

double PrimaryCover::share() const {
    const int cells = cellsX_ * cellsY_;
    return cells > 0 ? double(cellCount(0, 0, cellsX_, cellsY_)) / cells : 1.0;
}

CoverShapes coverShapesOf(const Scene& scene, const Bvh* bvh, std::size_t most) {
    CoverShapes shapes;
    std::size_t bounded = 0;
    for (const SceneObject& object : scene.objects) {
        const Aabb box = worldBounds(object, scene);
        if (box.empty()) continue;  // can never be hit
        if (box.finite()) {
            ++bounded;
            if (!bvh || bounded <= most) shapes.boxes.push_back(box);
        } else if (object.type == ShapeType::Plane) {
            // The generic plane z = 0: row 2 of M^-1 applied to the world point.
            const glm::dmat4& m = object.objectFromWorld;
            shapes.planes.push_back({{m[0][2], m[1][2], m[2][2]}, m[3][2]});
        } else {
            shapes.unbounded = true;
        }
    }
    if (!bvh || bounded <= most || bvh->nodes.empty()) return shapes;
    // The shallowest cut of the BVH with at most `most` nodes: split the
    // frontier's interior nodes breadth first while it stays within `most`.
    shapes.boxes.clear();
    std::deque<std::uint32_t> frontier{0};
    std::vector<std::uint32_t> cut;
    while (!frontier.empty()) {
        const std::uint32_t i = frontier.front();
        frontier.pop_front();
        const BvhNode& node = bvh->nodes[i];
        if (node.leaf() || frontier.size() + cut.size() + 2 > most) {
            cut.push_back(i);
            continue;
        }
        frontier.push_back(i + 1);       // first child: the next node
        frontier.push_back(node.first);  // second child
    }
    for (const std::uint32_t i : cut) shapes.boxes.push_back(bvh->nodes[i].bounds);
    return shapes;
}

}  // namespace vkray
