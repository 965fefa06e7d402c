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

void expectValid(const std::vector<Aabb>& prims, const pt::BvhBuildOptions& options = {}) {
    const pt::Bvh bvh = pt::buildBvh(prims, options);
    const pt::WideBvh wide = pt::collapseToWide(bvh);
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

TEST(WideBvh, LeavesTooBigForAChildWordAreRefused) {
    pt::BvhBuildOptions o;
    o.maxLeafSize = 100;
    // Identical boxes cannot be split by SAH: leaves as big as allowed.
    const pt::Bvh bvh = pt::buildBvh(std::vector<Aabb>(50, randomBoxes(1, 2, 0.1f)[0]), o);
    ASSERT_GT(bvh.nodes[0].count, BVH4_MAX_LEAF_PRIMITIVES);
    EXPECT_THROW(pt::collapseToWide(bvh), std::length_error);
}

} // namespace
