// Boxes, the slab test and the binned-SAH BVH: hand-derived slab answers
// (boundaries, infinite inverses, flat boxes, corner touches), structural
// invariants, and traversal against brute force on random scenes.
#include "scene/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <glm/geometric.hpp>
#include <limits>
#include <random>
#include <vector>

namespace vkray {
namespace {

// CPU time of this thread: timings that other processes (ctest -j) do not skew.
double threadSeconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

constexpr double kInf = std::numeric_limits<double>::infinity();

glm::dvec3 inverse(const glm::dvec3& d) {
    return 1.0 / d;
}

const Aabb kCube{glm::dvec3(-1), glm::dvec3(1)};

// ---- Aabb ------------------------------------------------------------------------

TEST(Aabb, DefaultIsEmptyAndGrows) {
    Aabb box;
    EXPECT_TRUE(box.empty());
    EXPECT_FALSE(box.finite());
    EXPECT_EQ(box.surfaceArea(), 0);
    box.grow(glm::dvec3(1, 2, 3));
    EXPECT_FALSE(box.empty());
    EXPECT_TRUE(box.finite());  // a point is a finite, non-empty box
    box.grow(Aabb{glm::dvec3(0, 0, 0), glm::dvec3(2, 2, 4)});
    EXPECT_EQ(box.lo, glm::dvec3(0, 0, 0));
    EXPECT_EQ(box.hi, glm::dvec3(2, 2, 4));
    EXPECT_EQ(box.centroid(), glm::dvec3(1, 1, 2));
    // 2 (2*2 + 2*4 + 4*2) = 40
    EXPECT_EQ(box.surfaceArea(), 40);
    box.grow(Aabb{});  // an empty box changes nothing
    EXPECT_EQ(box.hi, glm::dvec3(2, 2, 4));
}

TEST(Aabb, UnboundedIsNotFinite) {
    EXPECT_FALSE((Aabb{glm::dvec3(-kInf), glm::dvec3(kInf)}.finite()));
    EXPECT_FALSE((Aabb{glm::dvec3(0), glm::dvec3(1, 1, kInf)}.finite()));
    EXPECT_TRUE((Aabb{glm::dvec3(0), glm::dvec3(0, 1, 0)}.finite()));
}

TEST(Aabb, HitFromOutsideInsideAndMisses) {
    double t = -1;
    // From x = -5 along +x: enters the cube's x = -1 face at t = 4.
    EXPECT_TRUE(intersectAabb(kCube, {-5, 0, 0}, inverse({1, 0, 0}), 0, kInf, &t));
    EXPECT_EQ(t, 4);
    // Diagonal from (-3, -3, -3) along (1, 1, 1): enters at t = 2.
    EXPECT_TRUE(intersectAabb(kCube, {-3, -3, -3}, inverse({1, 1, 1}), 0, kInf, &t));
    EXPECT_EQ(t, 2);
    // From the centre: the entry is the ray's own tMin.
    EXPECT_TRUE(intersectAabb(kCube, {0, 0, 0}, inverse({0.3, -0.2, 0.9}), 0, kInf, &t));
    EXPECT_EQ(t, 0);
    // Passing beside, pointing away, beyond tMax, and tMin past the exit (t = 6).
    EXPECT_FALSE(intersectAabb(kCube, {-5, 1.5, 0}, inverse({1, 0, 0}), 0, kInf));
    EXPECT_FALSE(intersectAabb(kCube, {5, 0, 0}, inverse({1, 0, 0}), 0, kInf));
    EXPECT_FALSE(intersectAabb(kCube, {-5, 0, 0}, inverse({1, 0, 0}), 0, 3.5));
    EXPECT_FALSE(intersectAabb(kCube, {-5, 0, 0}, inverse({1, 0, 0}), 6.5, kInf));
    EXPECT_TRUE(intersectAabb(kCube, {-5, 0, 0}, inverse({1, 0, 0}), 5.5, kInf, &t));
    EXPECT_EQ(t, 5.5);
    // An empty tMin..tMax interval never hits.
    EXPECT_FALSE(intersectAabb(kCube, {0, 0, 0}, inverse({1, 0, 0}), 2, 1));
}

TEST(Aabb, AxisParallelRaysOnSlabBoundariesHit) {
    // d = (1, 0, 0): 1/0 = +inf on y and z; the origin's y sits exactly on the
    // box's y = 1 (then y = -1) face, so (1 - 1) * inf = NaN must count as inside.
    double t = -1;
    EXPECT_TRUE(intersectAabb(kCube, {-5, 1, 0}, inverse({1, 0, 0}), 0, kInf, &t));
    EXPECT_EQ(t, 4);
    EXPECT_TRUE(intersectAabb(kCube, {-5, -1, 0}, inverse({1, 0, 0}), 0, kInf, &t));
    EXPECT_EQ(t, 4);
    // Along an edge (y = 1 and z = -1 at once).
    EXPECT_TRUE(intersectAabb(kCube, {-5, 1, -1}, inverse({1, 0, 0}), 0, kInf, &t));
    EXPECT_EQ(t, 4);
    // -0 gives -inf: from x = +5 along -x with d.y = -0, still on the y = 1 face.
    EXPECT_TRUE(intersectAabb(kCube, {5, 1, 0}, inverse({-1, -0.0, 0}), 0, kInf, &t));
    EXPECT_EQ(t, 4);
    EXPECT_TRUE(intersectAabb(kCube, {5, -1, 0}, inverse({-1, -0.0, 0}), 0, kInf, &t));
    // Just outside the face the same rays miss.
    EXPECT_FALSE(
        intersectAabb(kCube, {-5, std::nextafter(1.0, 2.0), 0}, inverse({1, 0, 0}), 0, kInf));
    EXPECT_FALSE(
        intersectAabb(kCube, {5, std::nextafter(-1.0, -2.0), 0}, inverse({-1, -0.0, 0}), 0, kInf));
}

TEST(Aabb, FlatBoxesAreHitWithoutPadding) {
    // A square's box: zero thickness in z.
    const Aabb flat{glm::dvec3(-1, -1, 0), glm::dvec3(1, 1, 0)};
    double t = -1;
    EXPECT_TRUE(intersectAabb(flat, {0.5, 0.25, 5}, inverse({0, 0, -1}), 0, kInf, &t));
    EXPECT_EQ(t, 5);
    EXPECT_TRUE(
        intersectAabb(flat, {0, 0, -2}, inverse(glm::normalize(glm::dvec3(0.1, 0.2, 1))), 0, kInf));
    // In the box's own plane: NaN on z, counts as inside; enters at x = -1.
    EXPECT_TRUE(intersectAabb(flat, {-5, 0, 0}, inverse({1, 0, 0}), 0, kInf, &t));
    EXPECT_EQ(t, 4);
    // Parallel, a hair above: a miss.
    EXPECT_FALSE(intersectAabb(flat, {-5, 0, 1e-300}, inverse({1, 0, 0}), 0, kInf));
    // A point box is hit by a ray through the point.
    const Aabb point{glm::dvec3(1, 2, 3), glm::dvec3(1, 2, 3)};
    EXPECT_TRUE(intersectAabb(point, {1, 2, 0}, inverse({0, 0, 1}), 0, kInf, &t));
    EXPECT_EQ(t, 3);
}

TEST(Aabb, CornerTouchesAreConservative) {
    // Box [0, 1]^3 and lines o + d t through its corner (1, 1, 0) at t = 2,
    // with dx > 0, dy < 0, dz > 0: the x slab ends at t = 2 and the y and z
    // slabs begin there, so the box is touched in that one point. 1/d is
    // inexact: for dx = 49, 98 * fl(1/49) = 2 - 2^-52 while the y slab starts
    // at exactly 2, so without the far side's growth by 2 gamma(3) (pbrt) the
    // touch would be a miss.
    const Aabb unit{glm::dvec3(0), glm::dvec3(1)};
    int hits = 0, cases = 0;
    for (const int dx : {3, 49, 98, 103}) {
        for (const int dy : {-5, -9, -17}) {
            for (const int dz : {7, 19, 23}) {
                const glm::dvec3 d(dx, dy, dz);
                const glm::dvec3 origin = glm::dvec3(1, 1, 0) - 2.0 * d;  // exact
                double t = -1;
                ++cases;
                if (intersectAabb(unit, origin, inverse(d), 0, kInf, &t)) {
                    ++hits;
                    EXPECT_NEAR(t, 2, 1e-14);
                }
            }
        }
    }
    EXPECT_EQ(hits, cases);
}

// ---- BVH ---------------------------------------------------------------------------

std::vector<Aabb> randomBoxes(std::size_t count, std::uint32_t seed, double spread = 100,
                              double maxSize = 2) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> position(-spread, spread), size(0.01, maxSize);
    std::vector<Aabb> boxes;
    boxes.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const glm::dvec3 lo(position(rng), position(rng), position(rng));
        boxes.push_back(Aabb{lo, lo + glm::dvec3(size(rng), size(rng), size(rng))});
    }
    return boxes;
}

bool contains(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) &&
           glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

// Checks the documented layout and returns the subtree's height in nodes.
int checkSubtree(const Bvh& bvh, std::span<const Aabb> boxes, std::uint32_t index, int maxLeafSize,
                 std::vector<int>& seen) {
    const BvhNode& node = bvh.nodes.at(index);
    if (node.leaf()) {
        EXPECT_LE(node.count, std::uint32_t(maxLeafSize));
        EXPECT_LE(std::size_t(node.first) + node.count, bvh.order.size());
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
            ++seen.at(bvh.order[k]);
            EXPECT_TRUE(contains(node.bounds, boxes[bvh.order[k]]));
        }
        return 1;
    }
    const std::uint32_t left = index + 1, right = node.first;
    EXPECT_GT(right, left);
    EXPECT_LT(right, bvh.nodes.size());
    EXPECT_TRUE(contains(node.bounds, bvh.nodes[left].bounds));
    EXPECT_TRUE(contains(node.bounds, bvh.nodes[right].bounds));
    return 1 + std::max(checkSubtree(bvh, boxes, left, maxLeafSize, seen),
                        checkSubtree(bvh, boxes, right, maxLeafSize, seen));
}

void checkInvariants(const Bvh& bvh, std::span<const Aabb> boxes, int maxLeafSize) {
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_EQ(bvh.order.size(), boxes.size());
    std::vector<int> seen(boxes.size(), 0);
    const int height = checkSubtree(bvh, boxes, 0, maxLeafSize, seen);
    EXPECT_EQ(height, bvh.depth);
    EXPECT_LE(bvh.depth, kMaxBvhDepth);
    // order is a permutation: each primitive in exactly one leaf.
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
}

// Visits the primitives of every leaf the ray's [0, tMax] reaches; `visit`
// may shorten tMax (closest hit). Children nearer first, like the shader.
template <class Visit>
void traverse(const Bvh& bvh, const glm::dvec3& origin, const glm::dvec3& direction, double& tMax,
              Visit visit) {
    if (bvh.nodes.empty()) return;
    const glm::dvec3 inv = inverse(direction);
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode& node = bvh.nodes[stack.back()];
        const std::uint32_t index = stack.back();
        stack.pop_back();
        if (!intersectAabb(node.bounds, origin, inv, 0, tMax)) continue;
        if (node.leaf()) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                visit(bvh.order[k], tMax);
            continue;
        }
        stack.push_back(node.first);
        stack.push_back(index + 1);
    }
}

TEST(Bvh, NoBoxesGiveNoNodes) {
    const Bvh bvh = buildBvh({});
    EXPECT_TRUE(bvh.nodes.empty());
    EXPECT_TRUE(bvh.order.empty());
    EXPECT_EQ(bvh.depth, 0);
}

TEST(Bvh, OneBoxIsOneLeaf) {
    const std::vector<Aabb> boxes = {Aabb{glm::dvec3(1), glm::dvec3(2)}};
    const Bvh bvh = buildBvh(boxes);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_TRUE(bvh.nodes[0].leaf());
    EXPECT_EQ(bvh.nodes[0].count, 1u);
    EXPECT_EQ(bvh.nodes[0].first, 0u);
    EXPECT_EQ(bvh.order, std::vector<std::uint32_t>{0});
    EXPECT_EQ(bvh.depth, 1);
    EXPECT_EQ(bvh.nodes[0].bounds.lo, glm::dvec3(1));
}

TEST(Bvh, TwoFarBoxesAreSplit) {
    // Leaf cost 2 against 1 + (6 + 6) / (2 * (11*1 + 1*1 + 1*11)) = 1.26: split.
    const std::vector<Aabb> boxes = {Aabb{glm::dvec3(0), glm::dvec3(1)},
                                     Aabb{glm::dvec3(10, 0, 0), glm::dvec3(11, 1, 1)}};
    const Bvh bvh = buildBvh(boxes);
    ASSERT_EQ(bvh.nodes.size(), 3u);
    EXPECT_FALSE(bvh.nodes[0].leaf());
    EXPECT_EQ(bvh.nodes[0].first, 2u);
    checkInvariants(bvh, boxes, 4);
}

TEST(Bvh, RandomBoxesKeepInvariantsAndAreAllReachable) {
    for (const int maxLeafSize : {1, 4, 8}) {
        const std::vector<Aabb> boxes = randomBoxes(5000, 7u + std::uint32_t(maxLeafSize));
        const Bvh bvh = buildBvh(boxes, maxLeafSize);
        checkInvariants(bvh, boxes, maxLeafSize);
        // A ray through each box's centre, from outside everything, reaches it.
        std::mt19937 rng(99);
        std::normal_distribution<double> gaussian;
        int unreachable = 0;
        for (std::uint32_t i = 0; i < boxes.size(); ++i) {
            const glm::dvec3 d =
                glm::normalize(glm::dvec3(gaussian(rng), gaussian(rng), gaussian(rng)));
            const glm::dvec3 origin = boxes[i].centroid() - 500.0 * d;
            bool found = false;
            double tMax = kInf;
            traverse(bvh, origin, d, tMax, [&](std::uint32_t p, double&) { found |= p == i; });
            unreachable += found ? 0 : 1;
        }
        EXPECT_EQ(unreachable, 0) << "maxLeafSize " << maxLeafSize;
    }
}

// Checks that every interior node of `bvh` holds its two children's boxes
// and calls leafEntry(node, k) for each entry k of each leaf.
template <class LeafEntry>
void forEachLeafEntry(const Bvh& bvh, LeafEntry leafEntry) {
    for (std::uint32_t i = 0; i < bvh.nodes.size(); ++i) {
        const BvhNode& node = bvh.nodes[i];
        if (node.leaf()) {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k) leafEntry(node, k);
            continue;
        }
        ASSERT_LT(node.first, bvh.nodes.size());
        EXPECT_TRUE(contains(node.bounds, bvh.nodes[i + 1].bounds));
        EXPECT_TRUE(contains(node.bounds, bvh.nodes[node.first].bounds));
    }
}

// Two BVHs under one root: every primitive of each in exactly one leaf of
// the joined tree, the second's leaves numbered from the offset on, every
// box inside its parent's; with one side empty, the other alone.
TEST(Bvh, JoinedTreesKeepEachSidesLeaves) {
    const std::vector<Aabb> first = randomBoxes(300, 1), second = randomBoxes(500, 2, 20, 0.5);
    const Bvh a = buildBvh(first), b = buildBvh(second);
    constexpr std::uint32_t kOffset = 1000;
    const Bvh joined = joinBvhs(a, b, kOffset);
    ASSERT_EQ(joined.nodes.size(), 1 + a.nodes.size() + b.nodes.size());
    EXPECT_EQ(joined.order, a.order);
    EXPECT_EQ(joined.depth, std::max(a.depth, b.depth) + 1);
    std::vector<int> seenFirst(first.size(), 0), seenSecond(second.size(), 0);
    forEachLeafEntry(joined, [&](const BvhNode& node, std::uint32_t k) {
        if (k >= kOffset) {
            const std::uint32_t p = b.order.at(k - kOffset);
            ++seenSecond[p];
            EXPECT_TRUE(contains(node.bounds, second[p]));
        } else {
            const std::uint32_t p = a.order.at(k);
            ++seenFirst[p];
            EXPECT_TRUE(contains(node.bounds, first[p]));
        }
    });
    const auto once = [](const std::vector<int>& seen) {
        return std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; });
    };
    EXPECT_TRUE(once(seenFirst));
    EXPECT_TRUE(once(seenSecond));
    const Bvh alone = joinBvhs(Bvh{}, b, kOffset);
    ASSERT_EQ(alone.nodes.size(), b.nodes.size());
    EXPECT_EQ(alone.depth, b.depth);
    EXPECT_TRUE(alone.order.empty());
    EXPECT_EQ(alone.nodes[0].first,
              b.nodes[0].leaf() ? b.nodes[0].first + kOffset : b.nodes[0].first);
    EXPECT_EQ(joinBvhs(a, Bvh{}, kOffset).nodes.size(), a.nodes.size());
}

// Subtrees nested under a BVH over their roots: every primitive of each in
// exactly one leaf, numbered from its subtree's offset on, every box inside
// its parent's, and as deep as the top's path to it and the subtree.
TEST(Bvh, NestedSubtreesKeepTheirLeaves) {
    std::vector<std::vector<Aabb>> boxes;
    std::vector<Bvh> subtrees;
    std::vector<Aabb> roots;
    std::vector<std::uint32_t> offsets;
    std::uint32_t offset = 0;
    for (std::uint32_t k = 0; k < 5; ++k) {
        boxes.push_back(randomBoxes(40 + 30 * k, 10 + k, 10 + 5.0 * k));
        subtrees.push_back(buildBvh(boxes.back()));
        roots.push_back(subtrees.back().nodes[0].bounds);
        offsets.push_back(offset);
        offset += std::uint32_t(boxes.back().size());
    }
    const Bvh top = buildBvh(roots, 1);
    const Bvh nested = nestBvhs(top, subtrees, offsets);
    std::size_t nodes = top.nodes.size() - 5;  // the top's leaves give way to the subtrees
    int deepest = 0;
    for (const Bvh& subtree : subtrees) {
        nodes += subtree.nodes.size();
        deepest = std::max(deepest, subtree.depth);
    }
    ASSERT_EQ(nested.nodes.size(), nodes);
    EXPECT_LE(nested.depth, top.depth - 1 + deepest);
    EXPECT_GE(nested.depth, deepest + 1);
    std::vector<int> seen(offset, 0);
    forEachLeafEntry(nested, [&](const BvhNode& node, std::uint32_t k) {
        const auto which = std::upper_bound(offsets.begin(), offsets.end(), k) - 1;
        const std::size_t tree = std::size_t(which - offsets.begin());
        const std::uint32_t p = subtrees[tree].order.at(k - *which);
        ++seen.at(k);
        EXPECT_TRUE(contains(node.bounds, boxes[tree][p]));
    });
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
}

// Smallest t > 0 where the ray meets the sphere, or inf.
double hitSphere(const glm::dvec3& centre, double radius, const glm::dvec3& origin,
                 const glm::dvec3& d) {
    const glm::dvec3 oc = origin - centre;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
    const double discriminant = b * b - c;  // d is unit length
    if (discriminant < 0) return kInf;
    const double root = std::sqrt(discriminant);
    if (-b - root > 0) return -b - root;
    if (-b + root > 0) return -b + root;
    return kInf;
}

TEST(Bvh, ClosestHitMatchesBruteForceOnTenThousandSpheres) {
    constexpr int kSpheres = 10'000, kRays = 10'000;
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> position(-50, 50), radius(0.05, 1.5);
    std::normal_distribution<double> gaussian;
    std::vector<glm::dvec3> centres(kSpheres);
    std::vector<double> radii(kSpheres);
    std::vector<Aabb> boxes(kSpheres);
    for (int i = 0; i < kSpheres; ++i) {
        centres[i] = {position(rng), position(rng), position(rng)};
        radii[i] = radius(rng);
        boxes[i] = Aabb{centres[i] - radii[i], centres[i] + radii[i]};
    }
    const Bvh bvh = buildBvh(boxes);
    checkInvariants(bvh, boxes, 4);
    int hits = 0;
    for (int r = 0; r < kRays; ++r) {
        // Half the rays start inside the cloud, half outside aiming through it.
        const glm::dvec3 d =
            glm::normalize(glm::dvec3(gaussian(rng), gaussian(rng), gaussian(rng)));
        const glm::dvec3 start(position(rng), position(rng), position(rng));
        const glm::dvec3 origin = r % 2 ? start : start - 120.0 * d;
        double bestT = kInf;
        int best = -1;
        for (int i = 0; i < kSpheres; ++i) {
            const double t = hitSphere(centres[i], radii[i], origin, d);
            if (t < bestT) bestT = t, best = i;
        }
        double tMax = kInf;
        int found = -1;
        traverse(bvh, origin, d, tMax, [&](std::uint32_t i, double& t) {
            const double candidate = hitSphere(centres[i], radii[i], origin, d);
            if (candidate < t) t = candidate, found = int(i);
        });
        ASSERT_EQ(found, best) << "ray " << r;
        ASSERT_EQ(tMax, bestT) << "ray " << r;
        hits += best >= 0 ? 1 : 0;
    }
    EXPECT_GT(hits, kRays / 10);  // the test sees hits, not only misses
}

TEST(Bvh, IdenticalBoxesStayWithinTheDepthLimit) {
    const std::vector<Aabb> boxes(20'000, Aabb{glm::dvec3(-1), glm::dvec3(1)});
    const Bvh bvh = buildBvh(boxes);
    checkInvariants(bvh, boxes, 4);
    // Centroids coincide: halving by position gives ceil(log2(20000 / 4)) + 1 = 14 levels.
    EXPECT_EQ(bvh.depth, 14);
    std::size_t reached = 0;
    double tMax = kInf;
    traverse(bvh, {0, 0, -5}, {0, 0, 1}, tMax, [&](std::uint32_t, double&) { ++reached; });
    EXPECT_EQ(reached, boxes.size());
}

TEST(Bvh, BoxesOnALineWithGrowingGapsStayWithinTheDepthLimit) {
    // Box i spans x in [2^i, 1.001 * 2^i] (i < 1000; y and z in [0, 1], so no
    // area overflows). 16 bins over the centroids put all but the last five
    // boxes into the first bin, so SAH alone would peel off a few per level
    // (a chain some 200 deep); the depth limit switches to median splits in time.
    std::vector<Aabb> boxes;
    for (int i = 0; i < 1000; ++i) {
        const double x = std::ldexp(1.0, i);
        boxes.push_back(Aabb{glm::dvec3(x, 0, 0), glm::dvec3(x * 1.001, 1, 1)});
    }
    for (const int maxLeafSize : {1, 4}) {
        const Bvh bvh = buildBvh(boxes, maxLeafSize);
        checkInvariants(bvh, boxes, maxLeafSize);
        EXPECT_LE(bvh.depth, kMaxBvhDepth);
        EXPECT_GT(bvh.depth, 30);  // the SAH chain was taken as far as allowed
        for (std::uint32_t i = 0; i < boxes.size(); ++i) {
            bool found = false;
            double tMax = kInf;
            const glm::dvec3 c = boxes[i].centroid();
            traverse(bvh, {c.x, c.y, -3}, {0, 0, 1}, tMax,
                     [&](std::uint32_t p, double&) { found |= p == i; });
            EXPECT_TRUE(found) << i;
        }
    }
}

TEST(Bvh, FlatBoxesBuild) {
    // All boxes in the plane z = 0 (squares) and all zero-size points: areas
    // are zero, so SAH compares counts; the tree must still be valid.
    std::vector<Aabb> flat = randomBoxes(2000, 5);
    for (Aabb& box : flat) box.hi.z = box.lo.z = 0;
    checkInvariants(buildBvh(flat), flat, 4);
    std::vector<Aabb> points;
    for (int i = 0; i < 1000; ++i) points.push_back(Aabb{glm::dvec3(i, 0, 0), glm::dvec3(i, 0, 0)});
    const Bvh bvh = buildBvh(points);
    checkInvariants(bvh, points, 4);
    EXPECT_LE(bvh.depth, 12);  // balanced: ceil(log2(1000 / 4)) + 1 = 9, a little slack
}

TEST(Bvh, ExtremeCoordinatesBuild) {
    // Centroids 1e-310 apart (16 / extent overflows) and boxes near +-1e308
    // (extents overflow): those axes cannot be binned; the build halves instead.
    std::vector<Aabb> tiny, huge;
    for (int i = 0; i < 100; ++i) {
        const glm::dvec3 p(i * 1e-312, 0, 0);
        tiny.push_back(Aabb{p, p});
        const double x = (i % 2 ? 1 : -1) * 1e308 * (1 - i * 1e-3);
        huge.push_back(Aabb{glm::dvec3(x, 0, 0), glm::dvec3(x, 1, 1)});
    }
    checkInvariants(buildBvh(tiny), tiny, 4);
    checkInvariants(buildBvh(huge), huge, 4);
}

// The build's time is printed, not asserted (the benchmark's to judge).
TEST(Bvh, BuildsOneHundredThousandBoxesIntoAShallowTree) {
    const std::vector<Aabb> boxes = randomBoxes(100'000, 11, 1000);
    const double start = threadSeconds();
    const Bvh bvh = buildBvh(boxes);
    const double seconds = threadSeconds() - start;
    std::printf("[ timing   ] BVH over 100000 boxes: %.3f s (CPU), %zu nodes, depth %d\n", seconds,
                bvh.nodes.size(), bvh.depth);
    EXPECT_LE(bvh.depth, 30);  // about log2(1e5) = 17 levels of halves
    checkInvariants(bvh, boxes, 4);
}

}  // namespace
}  // namespace vkray
