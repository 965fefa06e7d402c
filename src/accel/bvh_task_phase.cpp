// The BVH build's task phase (see bvh.cpp): every node of at most kTaskPrims primitives is the
// root of a subtree one thread builds depth-first on its own: binned SAH for the bigger nodes,
// an exact SAH sweep for the smallest.
#include "accel/bvh_builder.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace pt::bvh_detail {

void Builder::buildTask(const Task& task, const BvhNode& root, std::vector<BvhNode>& ln, int& maxDepth) {
    WorkItem item = task.work;
    if (task.inAlt) std::memcpy(&refs_[item.begin], &alt_[item.begin], sizeof(PrimRef) * (item.end - item.begin));
    ln.reserve(2 * size_t(item.end - item.begin));
    ln.push_back(root);
    item.slot = 0;
    std::vector<WorkItem> stack{item};
    while (!stack.empty()) {
        const WorkItem w = stack.back();
        stack.pop_back();
        processNode(ln, w, stack, maxDepth);
    }
}

// Branch-free Lomuto partition on the cached bin key (which side an element goes to is
// unpredictable, so a branchy partition pays a mispredict for about every other element).
// The children's centroid bounds are collected on the way (saving them a pass of their own).
uint32_t Builder::partition(
    uint32_t begin, uint32_t end, int axis, int splitBin, Box4& leftCentroids, Box4& rightCentroids) {
    const int shift = 8 * axis;
    Box4 cl, cr;
    uint32_t l = begin;
    for (uint32_t i = begin; i < end; ++i) {
        const PrimRef t = refs_[i];
        refs_[i] = refs_[l];
        refs_[l] = t;
        const bool left = int((t.binKeys >> shift) & 0xffu) < splitBin;
        addCentroidToSide(centroidOf(loadLo(t), loadHi(t)), left, cl, cr);
        l += uint32_t(left);
    }
    leftCentroids = cl;
    rightCentroids = cr;
    return l;
}

// Exact SAH for small nodes: every object partition along each axis, in centroid order (ties
// in range order, so it is deterministic). Binning has a fixed cost per node (resetting and
// sweeping 3 * bins bins) that would dominate down here, where most of the nodes are; the
// exact sweep is cheaper and finds better splits. Identical centroids need no special case:
// all costs tie and the most balanced split (the range median) wins. Returns false for a leaf.
bool Builder::sweepSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, uint32_t& mid) {
    const int n = int(item.end - item.begin);
    if (n == 2) {
        // The most common case, short-cut: the same decision and order as the general code
        // below (every axis offers the same partition, so axis 0 wins the tie).
        PrimRef& a = refs_[item.begin];
        PrimRef& b = refs_[item.begin + 1];
        Box4 ba, bb;
        ba.grow(a);
        bb.grow(b);
        if (maxLeaf_ >= 2 && intersectCost_ * 2.0f <= splitCost(ba.area() + bb.area(), nodeArea)) return false;
        float ca[4], cb[4];
        store(ca, centroidOf(ba.lo, ba.hi));
        store(cb, centroidOf(bb.lo, bb.hi));
        if (cb[0] < ca[0]) {
            std::swap(a, b);
            std::swap(ba, bb);
        }
        lb = ba;
        rb = bb;
        mid = item.begin + 1;
        return true;
    }
    std::array<PrimRef, kSweepPrims> tmp;
    std::array<std::array<float, kSweepPrims>, 3> cen;
    std::array<std::array<uint8_t, kSweepPrims>, 3> order;
    std::array<float, kSweepPrims> rightArea;
    for (int i = 0; i < n; ++i) {
        tmp[i] = refs_[item.begin + i];
        float c[4];
        store(c, centroidOf(loadLo(tmp[i]), loadHi(tmp[i])));
        for (int a = 0; a < 3; ++a) cen[a][i] = c[a];
    }
    const int nPadded = (n + 3) & ~3;
    for (int a = 0; a < 3; ++a)
        for (int i = n; i < nPadded; ++i) cen[a][i] = kInf;
    int bestAxis = 0, bestK = 0, bestImbalance = 0;
    float bestCost = kInf;
    for (int a = 0; a < 3; ++a) {
        auto& o = order[a];
        const auto& key = cen[a];
        // Sort by rank counting: O(n^2) but branch-free and 4-wide, which beats a comparison
        // sort at these sizes. Ties are ranked by range position.
        for (int i = 0; i < n; ++i) o[rankOf(key.data(), nPadded, i)] = uint8_t(i);
        Box4 acc;
        for (int k = n - 1; k >= 1; --k) {
            acc.grow(tmp[o[k]]);
            rightArea[k] = acc.area();
        }
        acc = Box4{};
        for (int k = 1; k < n; ++k) {
            acc.grow(tmp[o[k - 1]]);
            const float cost = acc.area() * float(k) + rightArea[k] * float(n - k);
            const int imbalance = std::abs(2 * k - n);
            // Branch-free update: which split wins is unpredictable.
            const bool better = (cost < bestCost) | ((cost == bestCost) & (imbalance < bestImbalance));
            bestAxis = better ? a : bestAxis;
            bestK = better ? k : bestK;
            bestCost = better ? cost : bestCost;
            bestImbalance = better ? imbalance : bestImbalance;
        }
    }
    if (uint32_t(n) <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(bestCost, nodeArea)) return false;
    const auto& o = order[bestAxis];
    for (int j = 0; j < n; ++j) {
        refs_[item.begin + j] = tmp[o[j]];
        (j < bestK ? lb : rb).grow(tmp[o[j]]);
    }
    mid = item.begin + uint32_t(bestK);
    return true;
}

// Binned SAH for the task phase's bigger nodes. Returns false for a leaf.
bool Builder::binnedSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, Box4& lc, Box4& rc, uint32_t& mid) {
    const uint32_t n = item.end - item.begin;
    const int binCount = n <= uint32_t(kFewBinsPrims) ? std::min(bins_, kFewBins) : bins_;
    V4 origin, scale;
    if (binTransform(item.centroids, binCount, origin, scale)) {
        Bins bins;
        binRange(refs_.get(), item.begin, item.end, origin, scale, binCount, bins);
        const Split split = findSplit(bins, binCount);
        if (split.axis >= 0) {
            if (n <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(split.cost, nodeArea)) return false;
            mid = partition(item.begin, item.end, split.axis, split.bin, lc, rc);
            // The children's boxes are the unions of their bins: every primitive's whole box
            // went into the bin its cached key names, so these are exact and tight.
            for (int i = 0; i < binCount; ++i)
                if (bins.count[split.axis][i] != 0)
                    (i < split.bin ? lb : rb).grow(bins.lo[split.axis][i], bins.hi[split.axis][i]);
            return true; // both sides are non-empty: findSplit only offers such splits
        }
    }
    if (n <= maxLeaf_) return false;
    // All centroids equal (or binning could not separate them): halve the range so that
    // leaves stay within maxLeafSize and the depth stays logarithmic.
    mid = item.begin + n / 2;
    for (uint32_t i = item.begin; i < mid; ++i) lb.grow(refs_[i]);
    for (uint32_t i = mid; i < item.end; ++i) rb.grow(refs_[i]);
    lc = rc = item.centroids;
    return true;
}

// Decides leaf or split for one node; on a split appends the two children (adjacent) and
// pushes them so that the left child is processed next (depth-first).
void Builder::processNode(
    std::vector<BvhNode>& nodes, const WorkItem& item, std::vector<WorkItem>& stack, int& maxDepth) {
    const uint32_t n = item.end - item.begin;
    Box4 lb, rb, lc, rc; // children's boxes and centroid bounds (the sweep's children need none)
    uint32_t mid = item.begin;
    bool split = false;
    if (n > 1) {
        const float nodeArea = boxArea(nodes[item.slot].lo, nodes[item.slot].hi);
        split = n <= uint32_t(kSweepPrims) ? sweepSplit(item, nodeArea, lb, rb, mid)
                                           : binnedSplit(item, nodeArea, lb, rb, lc, rc, mid);
    }
    if (!split) {
        nodes[item.slot].leftOrFirst = item.begin;
        nodes[item.slot].count = n;
        maxDepth = std::max(maxDepth, item.depth);
        return;
    }
    const uint32_t left = uint32_t(nodes.size());
    nodes.push_back(BvhNode{lb.lo3(), 0, lb.hi3(), 0});
    nodes.push_back(BvhNode{rb.lo3(), 0, rb.hi3(), 0});
    nodes[item.slot].leftOrFirst = left;
    nodes[item.slot].count = 0;
    stack.push_back(WorkItem{left + 1, mid, item.end, item.depth + 1, rc});
    stack.push_back(WorkItem{left, item.begin, mid, item.depth + 1, lc});
}

} // namespace pt::bvh_detail
