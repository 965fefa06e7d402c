// The BVH builder's internals, shared by its three files: bvh.cpp (the build's outline and the
// assembly of the final node array), bvh_top_phase.cpp (the top levels, split by all threads
// together) and bvh_task_phase.cpp (the subtrees under them, one task per thread). The file
// comment of bvh.cpp describes the phases.
#pragma once
#include "accel/bvh.h"
#include "accel/bvh_binning.h"
#include "accel/bvh_simd.h"
#include "accel/huge_page_allocator.h"

#include <cstdint>
#include <span>
#include <vector>

namespace pt::bvh_detail {

// Nodes with at most this many primitives are built as independent tasks. A fixed constant (not
// derived from the thread count) so that the node layout never depends on the thread count.
constexpr uint32_t kTaskPrims = 4096;
// Top-phase nodes are binned and scattered in units of this many primitives, one thread each.
// Merging bins uses min/max and integer sums, which are exact, so the size changes nothing in
// the tree; it only trades load balance against per-unit overhead.
constexpr uint32_t kUnitPrims = 16384;
// Nodes with at most this many primitives use an exact SAH sweep instead of binning (see
// sweepSplit). At most 255 (sort indices are bytes).
constexpr int kSweepPrims = 16;
// Nodes with at most this many primitives are binned with kFewBins bins: the per-node cost of
// resetting and sweeping bins dominates there, and fewer bins lose little.
constexpr int kFewBinsPrims = 64;
constexpr int kFewBins = 8;

inline float boxArea(const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 d = hi - lo;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

struct WorkItem {
    uint32_t slot;  // index of this node in the node vector being filled (bounds already set)
    uint32_t begin; // primitive range [begin, end) in the PrimRef array
    uint32_t end;
    int depth;
    Box4 centroids; // bounds of the primitives' centroids (set for nodes that may be binned)
};

class Builder {
public:
    Builder(std::span<const Aabb> primBounds, const BvhBuildOptions& o);
    void run(Bvh& out);

private:
    struct Task {
        WorkItem work;
        bool inAlt; // its primitives lie in alt_ (moved to refs_ when the task starts)
    };

    // ---- top phase (bvh_top_phase.cpp) ----
    // Splits `root` level by level; nodes of at most kTaskPrims primitives (and the root itself
    // if it is that small) are handed back as tasks.
    void buildTop(std::vector<BvhNode>& nodes, const WorkItem& root, std::vector<Task>& tasks, int& maxDepth);

    // ---- task phase (bvh_task_phase.cpp) ----
    // Builds one task's subtree depth-first into `local`, whose node 0 is the task's root (a
    // copy of `root`, the top phase's node for it).
    void buildTask(const Task& task, const BvhNode& root, std::vector<BvhNode>& local, int& maxDepth);
    uint32_t partition(uint32_t begin, uint32_t end, int axis, int splitBin, Box4& leftCentroids, Box4& rightCentroids);
    bool sweepSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, uint32_t& mid);
    bool binnedSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, Box4& lc, Box4& rc, uint32_t& mid);
    void processNode(std::vector<BvhNode>& nodes, const WorkItem& item, std::vector<WorkItem>& stack, int& maxDepth);

    // ---- both phases and the result (bvh.cpp) ----
    double sahCost(const BvhNodeArray& nodes, uint32_t primCount) const;

    // Relative SAH cost of a split whose children's sum of area * count is `cost`. A zero-area node
    // (points or a line) makes every split free, and then only the leaf size limit splits it.
    float splitCost(float cost, float nodeArea) const {
        return traversalCost_ + intersectCost_ * (nodeArea > 0.0f ? cost / nodeArea : 0.0f);
    }

    std::span<const Aabb> input_;
    HugeArray<PrimRef> refs_; // the primitives, permuted; leaves index ranges of it
    HugeArray<PrimRef> alt_;  // the top phase's second buffer (it scatters between the two)
    int bins_ = 16;
    uint32_t maxLeaf_ = 4;
    float traversalCost_ = 1.0f;
    float intersectCost_ = 1.0f;
    int threads_ = 1;
};

} // namespace pt::bvh_detail
