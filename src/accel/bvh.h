#pragma once
#include "accel/huge_page_allocator.h"

#include <glm/glm.hpp>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace pt {

struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    void grow(const glm::vec3& p);
    void grow(const Aabb& b);
    glm::vec3 centroid() const; // meaningless for empty boxes
    float surfaceArea() const;  // 0 for empty boxes
    bool empty() const;
};

// Flattened node, depth-first order. Interior node: count == 0, its two children are
// nodes[leftOrFirst] and nodes[leftOrFirst + 1] (always adjacent). Leaf: count > 0 primitives
// primOrder[leftOrFirst .. leftOrFirst + count). The root is nodes[0]. For zero primitives nodes
// is empty (no node with an empty box exists). "Depth-first": children pairs are stored in the
// preorder of their parents (left subtree first), i.e. exactly where a sequential depth-first
// build allocates them, so a child always has a larger index than its parent.
// Layout is 32 bytes, two vec3+uint pairs; the kernel reads the four-wide collapse of this tree
// (accel/wide_bvh.h), not these nodes.
struct BvhNode {
    glm::vec3 lo;
    uint32_t leftOrFirst;
    glm::vec3 hi;
    uint32_t count;
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is two vec3+uint pairs");

// Default-initialising (no zero fill) and on huge pages from 2 MiB: huge_page_allocator.h.
using BvhNodeArray = std::vector<BvhNode, DefaultInitAllocator<BvhNode>>;

// Meshes placed several times (Scene::instances): kept once each under a tree over their
// placements (two levels), or copied into world space into the one tree (src/flatten/flat_instances.h).
enum class Instancing { Auto, Keep, Expand };

struct BvhBuildOptions {
    // Clamped to [2, 128]; nodes of at most kFewBinsPrims use kFewBins. 64 rather than 16: the
    // four-wide tree of a 1 M-triangle mesh traced 3-4% more paths per second for 12% more build
    // time (bench/RESULTS.md, "More SAH bins").
    int bins = 64;
    int maxLeafSize = 4; // clamped to >= 1; never exceeded
    float traversalCost = 1.0f;
    float intersectCost = 1.0f;
    int threads = 0; // 0 = hardware concurrency; the result does not depend on it
    // The triangle tree is stored with quantised nodes (accel/quantized_bvh.h) when its float
    // nodes would take more than this: about the size of a core's L2 cache, below which the
    // decoding costs more than the halved loads save (bench/RESULTS.md, "Quantised nodes").
    size_t quantizeOverBytes = size_t(1) << 20;
    Instancing instancing = Instancing::Auto;
    // Auto copies the instances into world space when that adds at most this many triangles:
    // below it one tree traced faster than two levels (no ray to map into each instance), above
    // it the copies' tree outgrew the caches and the meshes kept once traced faster, in less
    // memory (bench/RESULTS.md, "Instances").
    uint64_t expandInstancesUpTo = uint64_t(1) << 15;
};

struct Bvh {
    BvhNodeArray nodes;
    std::vector<uint32_t> primOrder; // leaf ranges index this; primOrder[i] = original primitive index
    // SAH cost of the tree relative to the root area:
    //   (sum over interior nodes traversalCost * area + sum over leaves intersectCost * count * area) / rootArea
    // If the root box has zero area every node is counted with the root's area.
    double sahCost = 0;
    int maxDepth = 0; // edges on the longest root-to-leaf path (0 for a single leaf);
                      // a push-far-child traversal needs at most this many stack entries
    double buildSeconds = 0;
};

// Builds over arbitrary primitives given their bounds (triangles now, spheres later).
// Bounds must be finite (|coordinate| < 1e38); they may be flat or points. Throws
// std::length_error above 2^31-1 primitives.
// The output (nodes, primOrder, sahCost, maxDepth) is identical for every options.threads value.
Bvh buildBvh(std::span<const Aabb> primBounds, const BvhBuildOptions& options = {});

} // namespace pt
