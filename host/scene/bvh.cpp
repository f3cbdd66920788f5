#include "scene/bvh.h"

#include "util/error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <glm/common.hpp>
#include <utility>

namespace vkray {

// ---- Aabb ----------------------------------------------------------------------

bool Aabb::finite() const {
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(lo[axis]) || !std::isfinite(hi[axis])) return false;
    return !empty();
}

void Aabb::grow(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Aabb::grow(const Aabb& box) {
    lo = glm::min(lo, box.lo);
    hi = glm::max(hi, box.hi);
}

double Aabb::surfaceArea() const {
    if (empty()) return 0;
    const glm::dvec3 extent = hi - lo;
    return 2 * (extent.x * extent.y + extent.y * extent.z + extent.z * extent.x);
}

// ---- slab test -----------------------------------------------------------------

namespace {

// pbrt's gamma(n) for double: a bound on n successive roundings.
constexpr double gammaBound(int n) {
    constexpr double unitRoundoff = 0.5 * std::numeric_limits<double>::epsilon();
    return n * unitRoundoff / (1 - n * unitRoundoff);
}

// Each slab distance (bound - o) * inv is off by at most gamma(3) relative;
// growing the far distance by twice that keeps the test conservative
// (pbrt-v4, Bounds3::IntersectP; docs/numerics-background.md, "Conservative bounds").
constexpr double kFarGrowth = 2 * gammaBound(3);

}  // namespace

bool intersectAabb(const Aabb& box, const glm::dvec3& origin, const glm::dvec3& invDirection,
                   double tMin, double tMax, double* tEntry) {
    double tNear = tMin;
    double tFar = tMax;
    for (int axis = 0; axis < 3; ++axis) {
        // A ray parallel to the slab (inv = +-inf) starting on its boundary
        // gives 0 * inf = NaN here. Ordering by the sign of inv (not by
        // comparing the two values) and letting the comparisons below skip
        // NaN makes that slab pass: the boundary belongs to the closed box.
        double slabNear = (box.lo[axis] - origin[axis]) * invDirection[axis];
        double slabFar = (box.hi[axis] - origin[axis]) * invDirection[axis];
        if (std::signbit(invDirection[axis])) std::swap(slabNear, slabFar);
        slabFar *= slabFar > 0 ? 1 + kFarGrowth : 1 - kFarGrowth;  // outward, inf stays inf
        if (slabNear > tNear) tNear = slabNear;
        if (slabFar < tFar) tFar = slabFar;
        if (tNear > tFar) return false;
    }
    if (!(tNear <= tFar)) return false;  // NaN tMin/tMax
    if (tEntry) *tEntry = tNear;
    return true;
}

// ---- binned SAH build --------------------------------------------------------------

namespace {

constexpr int kBinCount = 16;
// SAH costs, relative to one primitive test: visiting a node (a box test)
// costs about as much as one primitive test (a triangle or a quadric).
constexpr double kTraversalCost = 1.0;

int ceilLog2(std::size_t n) {
    return n <= 1 ? 0 : int(std::bit_width(n - 1));
}

struct Split {
    int axis = -1;
    int binCount = 0;
    int bin = 0;  // primitives in bins [0, bin] go left
    double cost = std::numeric_limits<double>::infinity();
    std::size_t leftCount = 0;
};

class BvhBuilder {
public:
    // The primitives are copied into one array that the build partitions in
    // place: every pass then reads memory in order, not through `order`.
    BvhBuilder(std::span<const Aabb> boxes, int maxLeafSize)
        : maxLeafSize_(std::max(1, maxLeafSize)) {
        primitives_.reserve(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i)
            primitives_.push_back(Primitive{boxes[i], boxes[i].centroid(), std::uint32_t(i)});
    }

    Bvh build() {
        Bvh bvh;
        bvh_ = &bvh;
        if (primitives_.empty()) return bvh;
        // A balanced tree has about 2n / maxLeafSize nodes; SAH trees often more.
        bvh.nodes.reserve(2 * primitives_.size() / std::size_t(maxLeafSize_) + 16);
        buildNode(0, primitives_.size(), 1);
        bvh.order.reserve(primitives_.size());
        for (const Primitive& primitive : primitives_) bvh.order.push_back(primitive.index);
        return bvh;
    }

private:
    // Builds the subtree over primitives_[begin, end) at `depth` (the root is 1).
    // Invariant: depth + ceilLog2(count) <= kMaxBvhDepth, which median splits
    // keep (each halves the count) and which the SAH may use up.
    void buildNode(std::size_t begin, std::size_t end, int depth) {
        const std::size_t nodeIndex = bvh_->nodes.size();
        bvh_->nodes.emplace_back();
        bvh_->depth = std::max(bvh_->depth, depth);

        Aabb bounds, centroidBounds;
        for (std::size_t i = begin; i < end; ++i) {
            bounds.grow(primitives_[i].box);
            centroidBounds.grow(primitives_[i].centroid);
        }
        bvh_->nodes[nodeIndex].bounds = bounds;
        const std::size_t count = end - begin;

        std::size_t middle = begin;
        const bool sahAllowed = depth + ceilLog2(count) < kMaxBvhDepth;
        const Split split = sahAllowed ? bestSplit(begin, end, bounds, centroidBounds) : Split{};
        if (split.axis >= 0) {
            // Leaf when allowed and no split pays for its traversal.
            const double leafCost = double(count);
            if (count <= std::size_t(maxLeafSize_) && leafCost <= split.cost) {
                makeLeaf(nodeIndex, begin, count);
                return;
            }
            middle = partitionAt(begin, end, split, centroidBounds);
        } else {
            if (count <= std::size_t(maxLeafSize_)) {
                makeLeaf(nodeIndex, begin, count);
                return;
            }
            middle = medianSplit(begin, end, centroidBounds);
        }
        buildNode(begin, middle, depth + 1);
        bvh_->nodes[nodeIndex].first = std::uint32_t(bvh_->nodes.size());
        buildNode(middle, end, depth + 1);
    }

    void makeLeaf(std::size_t nodeIndex, std::size_t begin, std::size_t count) {
        bvh_->nodes[nodeIndex].first = std::uint32_t(begin);
        bvh_->nodes[nodeIndex].count = std::uint32_t(count);
    }

    static int binOf(double centroid, double lo, double scale, int binCount) {
        const int bin = int((centroid - lo) * scale);
        return std::clamp(bin, 0, binCount - 1);
    }

    // The cheapest split between bins on any axis, in SAH cost relative to a
    // primitive test; axis -1 when the centroids coincide (nothing to bin).
    Split bestSplit(std::size_t begin, std::size_t end, const Aabb& bounds,
                    const Aabb& centroidBounds) const {
        struct Bin {
            Aabb bounds;
            std::size_t count = 0;
        };
        Split best;
        const double parentArea = bounds.surfaceArea();
        // Small nodes need no more bins than primitives (most nodes are small).
        const int binCount = int(std::min<std::size_t>(kBinCount, end - begin));
        for (int axis = 0; axis < 3; ++axis) {
            const double lo = centroidBounds.lo[axis];
            const double extent = centroidBounds.hi[axis] - lo;
            const double scale = binCount / extent;
            // Nothing to bin; and a denormal or overflowing extent would make
            // the bin index NaN or huge (its int conversion undefined).
            if (!(extent > 0 && std::isfinite(extent) && std::isfinite(scale))) continue;
            std::array<Bin, kBinCount> bins;
            for (std::size_t i = begin; i < end; ++i) {
                Bin& bin = bins[binOf(primitives_[i].centroid[axis], lo, scale, binCount)];
                bin.bounds.grow(primitives_[i].box);
                ++bin.count;
            }
            // Sweep from the right to get each suffix's area and count.
            std::array<double, kBinCount> rightArea{};
            std::array<std::size_t, kBinCount> rightCount{};
            Aabb right;
            std::size_t countRight = 0;
            for (int b = binCount - 1; b > 0; --b) {
                right.grow(bins[b].bounds);
                countRight += bins[b].count;
                rightArea[b] = right.surfaceArea();
                rightCount[b] = countRight;
            }
            Aabb left;
            std::size_t countLeft = 0;
            for (int b = 0; b < binCount - 1; ++b) {
                left.grow(bins[b].bounds);
                countLeft += bins[b].count;
                if (countLeft == 0 || rightCount[b + 1] == 0) continue;
                const double weighted = left.surfaceArea() * double(countLeft) +
                                        rightArea[b + 1] * double(rightCount[b + 1]);
                // Flat or point-like nodes have no area: compare the counts alone.
                const double cost = parentArea > 0 ? kTraversalCost + weighted / parentArea
                                                   : kTraversalCost + double(end - begin) / 2;
                const auto imbalance = [&](std::size_t leftCount) {
                    const std::size_t total = end - begin;
                    return leftCount > total - leftCount ? 2 * leftCount - total
                                                         : total - 2 * leftCount;
                };
                // Equal costs (flat inputs): take the more balanced split.
                if (cost < best.cost ||
                    (cost == best.cost && imbalance(countLeft) < imbalance(best.leftCount))) {
                    best = Split{axis, binCount, b, cost, countLeft};
                }
            }
        }
        return best;
    }

    std::size_t partitionAt(std::size_t begin, std::size_t end, const Split& split,
                            const Aabb& centroidBounds) {
        const double lo = centroidBounds.lo[split.axis];
        const double scale = split.binCount / (centroidBounds.hi[split.axis] - lo);
        const auto first = primitives_.begin();
        const auto middle = std::partition(
            first + std::ptrdiff_t(begin), first + std::ptrdiff_t(end), [&](const Primitive& p) {
                return binOf(p.centroid[split.axis], lo, scale, split.binCount) <= split.bin;
            });
        return std::size_t(middle - first);
    }

    // Halves the range by centroid along the widest axis (by position in the
    // range when all centroids coincide), so the depth grows by log2 only.
    std::size_t medianSplit(std::size_t begin, std::size_t end, const Aabb& centroidBounds) {
        const glm::dvec3 extent = centroidBounds.hi - centroidBounds.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const std::size_t middle = begin + (end - begin) / 2;
        if (extent[axis] > 0) {
            const auto first = primitives_.begin();
            std::nth_element(first + std::ptrdiff_t(begin), first + std::ptrdiff_t(middle),
                             first + std::ptrdiff_t(end),
                             [&](const Primitive& a, const Primitive& b) {
                                 return a.centroid[axis] < b.centroid[axis];
                             });
        }
        return middle;
    }

    struct Primitive {
        Aabb box;
        glm::dvec3 centroid;
        std::uint32_t index;
    };

    int maxLeafSize_;
    std::vector<Primitive> primitives_;
    Bvh* bvh_ = nullptr;
};

}  // namespace

Bvh buildBvh(std::span<const Aabb> boxes, int maxLeafSize) {
    return BvhBuilder(boxes, maxLeafSize).build();
}

Bvh nestBvhs(const Bvh& top, std::span<const Bvh> subtrees,
             std::span<const std::uint32_t> leafOffsets) {
    Bvh nested;
    // Depth first, as buildBvh lays nodes out: a node's first child follows
    // it, its second child's index is set once that child is placed.
    const auto place = [&](auto& self, std::uint32_t index, int depth) -> void {
        const BvhNode& node = top.nodes[index];
        if (node.leaf()) {
            if (node.count != 1) throw Error("internal: nestBvhs: a top leaf of several subtrees");
            const std::uint32_t which = top.order[node.first];
            const Bvh& subtree = subtrees[which];
            const std::uint32_t shift = std::uint32_t(nested.nodes.size());
            for (BvhNode inner : subtree.nodes) {
                inner.first += inner.leaf() ? leafOffsets[which] : shift;
                nested.nodes.push_back(inner);
            }
            nested.depth = std::max(nested.depth, depth - 1 + subtree.depth);
            return;
        }
        const std::size_t at = nested.nodes.size();
        nested.nodes.push_back(BvhNode{node.bounds, 0, 0});
        self(self, index + 1, depth + 1);
        nested.nodes[at].first = std::uint32_t(nested.nodes.size());
        self(self, node.first, depth + 1);
    };
    if (!top.nodes.empty()) place(place, 0, 1);
    return nested;
}

Bvh joinBvhs(const Bvh& first, const Bvh& second, std::uint32_t secondOffset) {
    Bvh joined;
    joined.order = first.order;
    const bool both = !first.nodes.empty() && !second.nodes.empty();
    if (both) {
        BvhNode root;
        root.bounds = first.nodes[0].bounds;
        root.bounds.grow(second.nodes[0].bounds);
        root.first = std::uint32_t(1 + first.nodes.size());
        joined.nodes.push_back(root);
    }
    // Interior nodes name their second child by index: moved with the node.
    const auto append = [&](const Bvh& bvh, std::uint32_t leafOffset) {
        const std::uint32_t shift = std::uint32_t(joined.nodes.size());
        for (BvhNode node : bvh.nodes) {
            node.first += node.leaf() ? leafOffset : shift;
            joined.nodes.push_back(node);
        }
    };
    append(first, 0);
    append(second, secondOffset);
    joined.depth = std::max(first.depth, second.depth) + (both ? 1 : 0);
    return joined;
}

}  // namespace vkray
