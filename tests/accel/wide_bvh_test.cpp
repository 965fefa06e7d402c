// Host tests of the four-wide collapse (src/accel/wide_bvh.cpp): the wide tree holds every
// primitive exactly once, every child box bounds its whole subtree, the stack need and depth it
// reports are what its structure implies, and closest hits through it match brute force.
#include "accel/wide_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using pt::Aabb;
using pt::gpu::GpuBvh4Node;

std::vector<Aabb> randomBoxes(size_t n, uint32_t seed, float size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), e(0.0f, size);
    std::vector<Aabb> boxes(n);
    for (Aabb& b : boxes) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        b.grow(c - glm::vec3(e(rng), e(rng), e(rng)));
        b.grow(c + glm::vec3(e(rng), e(rng), e(rng)));
    }
    return boxes;
}

Aabb slotBox(const GpuBvh4Node& n, int slot) {
    Aabb b;
    b.lo = glm::vec3(n.loX[slot], n.loY[slot], n.loZ[slot]);
    b.hi = glm::vec3(n.hiX[slot], n.hiY[slot], n.hiZ[slot]);
    return b;
}

bool contains(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

struct Walk {
    std::vector<int> seen; // per BVH-ordered primitive: how many leaves hold it
    int depth = 0, stackNeed = 0, nodesVisited = 0;
};

// Walks the subtree of wide node `index` inside `bound`, checking boxes and ordering; returns
// (depth, stack need) of the subtree as the definitions in wide_bvh.h have them.
std::pair<int, int> walk(const pt::WideBvh& wide, const pt::Bvh& bvh, const std::vector<Aabb>& prims, uint32_t index,
    const Aabb& bound, Walk& w) {
    ++w.nodesVisited;
    const GpuBvh4Node& n = wide.nodes.at(index);
    int used = 0, depth = 1, need = 0;
    bool emptySeen = false;
    for (int slot = 0; slot < 4; ++slot) {
        const uint32_t c = n.child[slot];
        if (c == BVH4_EMPTY) {
            emptySeen = true;
            EXPECT_TRUE(slotBox(n, slot).empty()) << "unused slot of node " << index << " has a box";
            continue;
        }
        EXPECT_FALSE(emptySeen) << "node " << index << ": a used slot after an unused one";
        ++used;
        const Aabb box = slotBox(n, slot);
        EXPECT_TRUE(contains(bound, box)) << "child box of node " << index << " outside its parent's";
        if (pt::isWideLeaf(c)) {
            const uint32_t first = pt::wideLeafFirst(c), count = pt::wideLeafCount(c);
            for (uint32_t i = first; i < first + count; ++i) {
                ++w.seen.at(i);
                EXPECT_TRUE(contains(box, prims[bvh.primOrder[i]])) << "primitive " << i << " outside its leaf box";
            }
        } else {
            EXPECT_GT(c, index) << "child before its parent (not preorder)";
            const auto [d, s] = walk(wide, bvh, prims, c, box, w);
            depth = std::max(depth, d + 1);
            need = std::max(need, s);
        }
    }
    EXPECT_GE(used, 1);
    return {depth, need + used - 1};
}

void expectValid(const std::vector<Aabb>& prims, const pt::BvhBuildOptions& options = {},
    const pt::WideCollapseOptions& collapse = {}) {
    const pt::Bvh bvh = pt::buildBvh(prims, options);
    const pt::WideBvh wide = pt::collapseToWide(bvh, collapse);
    if (prims.empty()) {
        EXPECT_TRUE(wide.nodes.empty());
        return;
    }
    Walk w;
    w.seen.assign(prims.size(), 0);
    Aabb everything;
    everything.grow(glm::vec3(-std::numeric_limits<float>::max()));
    everything.grow(glm::vec3(std::numeric_limits<float>::max()));
    const auto [depth, need] = walk(wide, bvh, prims, 0, everything, w);
    EXPECT_EQ(size_t(w.nodesVisited), wide.nodes.size()) << "nodes not reachable from the root";
    for (size_t i = 0; i < prims.size(); ++i)
        ASSERT_EQ(w.seen[i], 1) << "primitive " << i << " in " << w.seen[i] << " leaves";
    EXPECT_EQ(depth, wide.depth);
    EXPECT_EQ(need, wide.stackNeed);
    // Each wide level consumes at least one binary level, usually two.
    EXPECT_LE(wide.depth, bvh.maxDepth + 1);
    const Aabb root = pt::wideNodeBounds(wide.nodes[0]);
    EXPECT_EQ(root.lo, bvh.nodes[0].lo);
    EXPECT_EQ(root.hi, bvh.nodes[0].hi);
}

TEST(WideBvh, EmptyOneAndFewPrimitives) {
    for (size_t n : {0, 1, 2, 3, 4, 5, 7, 9, 17}) {
        SCOPED_TRACE(n);
        expectValid(randomBoxes(n, 3 + uint32_t(n), 0.1f));
    }
    const pt::WideBvh one = pt::collapseToWide(pt::buildBvh(randomBoxes(1, 1, 0.1f)));
    ASSERT_EQ(one.nodes.size(), 1u);
    EXPECT_TRUE(pt::isWideLeaf(one.nodes[0].child[0]));
    EXPECT_EQ(one.nodes[0].child[1], BVH4_EMPTY);
    EXPECT_EQ(one.stackNeed, 0);
}

TEST(WideBvh, StructureOfLargeTreesAndLeafSizes) {
    for (int leaf : {1, 2, 4, 16}) {
        SCOPED_TRACE(leaf);
        pt::BvhBuildOptions o;
        o.maxLeafSize = leaf;
        expectValid(randomBoxes(20000, 11, 0.01f), o);
        pt::WideCollapseOptions bigLeaves;
        bigLeaves.maxLeafSize = 16;
        bigLeaves.primitiveCost = 0.05f;
        expectValid(randomBoxes(20000, 12, 0.01f), o, bigLeaves);
    }
    // Identical boxes: the builder's fallback splits, one long range.
    expectValid(std::vector<Aabb>(5000, randomBoxes(1, 5, 0.1f)[0]));
}

TEST(WideBvh, HalvesTheDepthAndTheInnerNodes) {
    const pt::Bvh bvh = pt::buildBvh(randomBoxes(100000, 21, 0.005f));
    const pt::WideBvh wide = pt::collapseToWide(bvh);
    const size_t binaryInner = (bvh.nodes.size() - 1) / 2;
    std::printf("[          ] binary: %zu nodes, depth %d; wide: %zu nodes, depth %d, stack need %d\n",
        bvh.nodes.size(), bvh.maxDepth, wide.nodes.size(), wide.depth, wide.stackNeed);
    // A wide node absorbs up to three binary inner nodes, fewer where its children are leaves
    // (measured: 0.51 of them here).
    EXPECT_LE(double(wide.nodes.size()), 0.6 * double(binaryInner));
    EXPECT_LE(wide.depth, (bvh.maxDepth + 1) * 3 / 4);
    EXPECT_LE(wide.stackNeed, TRAVERSAL_STACK_SIZE);
}

// SAH cost of a wide tree under the collapse's cost model, relative to the root's area: the
// root node, then every child slot (a node or a leaf of n primitives).
double wideSahCost(const pt::WideBvh& wide, const pt::WideCollapseOptions& o) {
    const double rootArea = pt::wideNodeBounds(wide.nodes.at(0)).surfaceArea();
    double cost = o.nodeCost * rootArea;
    for (const GpuBvh4Node& n : wide.nodes)
        for (int slot = 0; slot < 4; ++slot) {
            const uint32_t c = n.child[slot];
            if (c == BVH4_EMPTY) continue;
            const double area = slotBox(n, slot).surfaceArea();
            cost +=
                pt::isWideLeaf(c) ? area * (o.leafCost + o.primitiveCost * pt::wideLeafCount(c)) : area * o.nodeCost;
        }
    return cost / rootArea;
}

// The least cost by exhaustive search: every way to cover a node's subtree with at most four
// wide children (each a binary subtree made a leaf or, recursively at its best, a wide node).
class BruteForceCollapse {
public:
    BruteForceCollapse(const pt::Bvh& bvh, const pt::WideCollapseOptions& o) : bvh_(bvh), o_(o) {}

    double asNode(uint32_t n) const {
        const pt::BvhNode& node = bvh_.nodes[n];
        double best = std::numeric_limits<double>::infinity();
        for (const auto& left : covers(node.leftOrFirst))
            for (const auto& right : covers(node.leftOrFirst + 1)) {
                if (left.size() + right.size() > 4) continue;
                double c = 0.0;
                for (uint32_t m : left) c += asChild(m);
                for (uint32_t m : right) c += asChild(m);
                best = std::min(best, c);
            }
        return area(n) * o_.nodeCost + best;
    }

private:
    double area(uint32_t n) const {
        Aabb b;
        b.lo = bvh_.nodes[n].lo;
        b.hi = bvh_.nodes[n].hi;
        return b.surfaceArea();
    }
    uint32_t count(uint32_t n) const {
        const pt::BvhNode& node = bvh_.nodes[n];
        return node.count != 0 ? node.count : count(node.leftOrFirst) + count(node.leftOrFirst + 1);
    }
    double asChild(uint32_t n) const {
        const double leaf = area(n) * (o_.leafCost + o_.primitiveCost * count(n));
        if (bvh_.nodes[n].count != 0) return leaf;
        return count(n) <= uint32_t(o_.maxLeafSize) ? std::min(leaf, asNode(n)) : asNode(n);
    }
    // Every set of at most four disjoint subtrees that together hold n's primitives.
    std::vector<std::vector<uint32_t>> covers(uint32_t n) const {
        std::vector<std::vector<uint32_t>> out{{n}};
        const pt::BvhNode& node = bvh_.nodes[n];
        if (node.count != 0) return out;
        for (const auto& left : covers(node.leftOrFirst))
            for (const auto& right : covers(node.leftOrFirst + 1)) {
                if (left.size() + right.size() > 4) continue;
                std::vector<uint32_t> both = left;
                both.insert(both.end(), right.begin(), right.end());
                out.push_back(both);
            }
        return out;
    }

    const pt::Bvh& bvh_;
    pt::WideCollapseOptions o_;
};

TEST(WideBvh, CollapseIsTheLeastCostOneUnderItsModel) {
    const pt::WideCollapseOptions models[] = {{1.0f, 0.0f, 1.0f, 4}, {1.0f, 0.5f, 1.0f, 4}, {1.0f, 0.0f, 0.3f, 8},
        {1.0f, 0.0f, 2.0f, 2}, {0.2f, 1.0f, 1.0f, 16}};
    for (uint32_t seed = 1; seed <= 40; ++seed) {
        const size_t n = 9 + seed % 8; // more than any model's leaf below 16: the root is a node
        pt::BvhBuildOptions binary;
        binary.maxLeafSize = 1 + int(seed % 3);
        const std::vector<Aabb> prims = randomBoxes(n, 100 + seed, 0.2f);
        const pt::Bvh bvh = pt::buildBvh(prims, binary);
        for (const pt::WideCollapseOptions& model : models) {
            if (n <= size_t(model.maxLeafSize)) continue;
            SCOPED_TRACE(::testing::Message() << "seed " << seed << ", leaf cost " << model.leafCost
                                              << ", primitive cost " << model.primitiveCost);
            const pt::WideBvh wide = pt::collapseToWide(bvh, model);
            const double rootArea = pt::wideNodeBounds(wide.nodes[0]).surfaceArea();
            const double best = BruteForceCollapse(bvh, model).asNode(0) / rootArea;
            EXPECT_NEAR(wideSahCost(wide, model), best, 1e-5 * best);
        }
    }
}

TEST(WideBvh, LeavesGatherSmallSubtreesUpToTheirLimit) {
    pt::BvhBuildOptions binary;
    binary.maxLeafSize = 1;
    const std::vector<Aabb> prims = randomBoxes(20000, 31, 0.01f);
    const pt::Bvh bvh = pt::buildBvh(prims, binary);
    for (int leaf : {1, 3, 8}) {
        pt::WideCollapseOptions o;
        o.maxLeafSize = leaf;
        o.primitiveCost = 0.1f; // cheap primitives: leaves as big as allowed pay
        const pt::WideBvh wide = pt::collapseToWide(bvh, o);
        uint32_t largest = 0;
        for (const GpuBvh4Node& node : wide.nodes)
            for (int slot = 0; slot < 4; ++slot)
                if (pt::isWideLeaf(node.child[slot])) largest = std::max(largest, pt::wideLeafCount(node.child[slot]));
        EXPECT_EQ(largest, uint32_t(leaf));
    }
}

TEST(WideBvh, LeavesTooBigForAChildWordAreRefused) {
    pt::BvhBuildOptions o;
    o.maxLeafSize = 100;
    // Identical boxes cannot be split by SAH: leaves as big as allowed.
    const pt::Bvh bvh = pt::buildBvh(std::vector<Aabb>(50, randomBoxes(1, 2, 0.1f)[0]), o);
    ASSERT_GT(bvh.nodes[0].count, BVH4_MAX_LEAF_PRIMITIVES);
    EXPECT_THROW(pt::collapseToWide(bvh), std::length_error);
}

} // namespace
