#pragma once
// The binary SAH tree (accel/bvh.h) collapsed into the four-wide tree the kernel traverses
// (GpuBvh4Node in shared/layout.h). On lavapipe every shader invocation is one SIMD lane, so a
// wide node does not test its boxes in parallel; what it saves is loop iterations (half the
// depth), stack traffic and divergence between lanes, which is where a binary traversal's time
// went (bench/RESULTS.md, "Wide BVH").
#include "accel/bvh.h"
#include "shared/layout.h"

#include <vector>

namespace pt {

struct WideBvh {
    std::vector<gpu::GpuBvh4Node> nodes; // empty for a tree over no primitives
    int depth = 0;                       // nodes on the longest root-to-leaf path (0 when empty)
    int stackNeed = 0;                   // most entries a traversal ever holds on its stack: over root-to-leaf
                                         // paths, the sum of (children - 1) of the nodes on the path
};

// The collapse's SAH cost model, per unit of surface area relative to the root's: a wide node
// visited (its four box tests), a leaf entered, a primitive tested.
struct WideCollapseOptions {
    float nodeCost = 1.0f;
    float leafCost = 0.0f;
    float primitiveCost = 1.0f;
    int maxLeafSize = 4; // primitives a leaf gathers from the binary tree's subtrees (binary leaves
                         // bigger than this stay as they are)
};

// Collapses `bvh` (as buildBvh returns it, primitives in bvh.primOrder order) into the wide tree
// of least SAH cost under `options`: each wide child is a binary subtree, kept as a wide node or
// made one leaf of all its primitives. Leaves are contiguous primitive ranges. Throws
// std::length_error when a leaf holds more than BVH4_MAX_LEAF_PRIMITIVES primitives or the tree
// more than BVH4_FIRST_MASK.
WideBvh collapseToWide(const Bvh& bvh, const WideCollapseOptions& options = {});

// Union of a wide node's child boxes (empty slots contribute nothing): the root's is the
// tree's bounds.
Aabb wideNodeBounds(const gpu::GpuBvh4Node& node);

// Decoded child word.
inline bool isWideLeaf(uint32_t child) { return child != BVH4_EMPTY && (child & BVH4_LEAF_BIT) != 0; }
inline uint32_t wideLeafFirst(uint32_t child) { return child & BVH4_FIRST_MASK; }
inline uint32_t wideLeafCount(uint32_t child) { return ((child >> BVH4_COUNT_SHIFT) & 15u) + 1u; }

} // namespace pt
