// The BVH build's top phase (see bvh.cpp): the nodes above kTaskPrims primitives, split one
// level at a time by all threads together. Each node of a level is cut into units of
// kUnitPrims primitives; the units are binned in parallel, a node's unit bins merged (exactly)
// to choose its split, and the units then scatter their primitives between refs_ and alt_ (a
// stable partition) collecting the children's centroid bounds on the way.
#include "accel/bvh_builder.h"

#include "accel/bvh_parallel.h"

#include <algorithm>
#include <cstring>
#include <memory>

namespace pt::bvh_detail {

void Builder::buildTop(std::vector<BvhNode>& nodes, const WorkItem& root, std::vector<Task>& tasks, int& maxDepth) {
    struct Unit {
        uint32_t item, begin, end;
        uint32_t leftCount = 0; // primitives of this unit that go to the left child
        uint32_t leftDst = 0, rightDst = 0;
        Box4 centroids[2]; // of the primitives that went left [0] and right [1]
    };
    enum class Mode { Leaf, Binned, Halve };
    struct Decision {
        Mode mode = Mode::Leaf;
        int axis = 0, bin = 0;
        uint32_t leftCount = 0;
        Box4 lb, rb;
    };

    if (root.end - root.begin <= kTaskPrims) {
        tasks.push_back({root, false});
        return;
    }
    std::vector<WorkItem> frontier{root};
    for (int parity = 0; !frontier.empty(); parity ^= 1) {
        PrimRef* src = parity ? alt_.get() : refs_.get();
        PrimRef* dst = parity ? refs_.get() : alt_.get();
        const size_t items = frontier.size();

        std::vector<Unit> units;
        std::vector<size_t> firstUnit(items + 1);
        std::vector<V4> origin(items), scale(items);
        std::vector<char> binnable(items);
        for (size_t k = 0; k < items; ++k) {
            const WorkItem& w = frontier[k];
            binnable[k] = binTransform(frontier[k].centroids, bins_, origin[k], scale[k]);
            firstUnit[k] = units.size();
            const size_t chunks = (w.end - w.begin + kUnitPrims - 1) / kUnitPrims;
            for (size_t c = 0; c < chunks; ++c) {
                const auto [b, e] = chunkRange(w.begin, w.end, chunks, c);
                units.push_back(Unit{uint32_t(k), b, e});
            }
        }
        firstUnit[items] = units.size();

        // Bin every unit (uninitialised storage: binRange resets the bins it uses).
        std::unique_ptr<Bins[]> unitBins(new Bins[units.size()]);
        parallelFor(threads_, units.size(), [&](size_t u) {
            const Unit& un = units[u];
            if (binnable[un.item]) binRange(src, un.begin, un.end, origin[un.item], scale[un.item], bins_, unitBins[u]);
        });

        // Choose every item's split from its merged bins.
        std::vector<Decision> decisions(items);
        for (size_t k = 0; k < items; ++k) {
            const WorkItem& w = frontier[k];
            const uint32_t n = w.end - w.begin;
            Decision& d = decisions[k];
            Split split;
            Bins bins;
            if (binnable[k]) {
                bins = unitBins[firstUnit[k]];
                for (size_t u = firstUnit[k] + 1; u < firstUnit[k + 1]; ++u) bins.merge(unitBins[u], bins_);
                split = findSplit(bins, bins_);
            }
            const float nodeArea = boxArea(nodes[w.slot].lo, nodes[w.slot].hi);
            if (split.axis >= 0)
                d.mode = n <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(split.cost, nodeArea) ? Mode::Leaf
                                                                                                       : Mode::Binned;
            else
                d.mode = n <= maxLeaf_ ? Mode::Leaf : Mode::Halve;
            if (d.mode == Mode::Binned) {
                d.axis = split.axis;
                d.bin = split.bin;
                for (int i = 0; i < bins_; ++i)
                    if (bins.count[d.axis][i] != 0)
                        (i < d.bin ? d.lb : d.rb).grow(bins.lo[d.axis][i], bins.hi[d.axis][i]);
                for (size_t u = firstUnit[k]; u < firstUnit[k + 1]; ++u) {
                    uint32_t left = 0;
                    for (int i = 0; i < d.bin; ++i) left += unitBins[u].count[d.axis][i];
                    units[u].leftCount = left;
                    d.leftCount += left;
                }
            } else if (d.mode == Mode::Halve) {
                // All centroids equal: halve the range so that leaves stay within maxLeafSize
                // and the depth stays logarithmic.
                d.leftCount = n / 2;
                const uint32_t mid = w.begin + d.leftCount;
                for (uint32_t i = w.begin; i < mid; ++i) d.lb.grow(src[i]);
                for (uint32_t i = mid; i < w.end; ++i) d.rb.grow(src[i]);
                for (size_t u = firstUnit[k]; u < firstUnit[k + 1]; ++u)
                    units[u].leftCount = std::clamp(mid, units[u].begin, units[u].end) - units[u].begin;
            } else {
                // A leaf this high up (maxLeafSize above kTaskPrims): its primitives must end
                // up in refs_, which leaves index.
                if (parity) std::memcpy(&refs_[w.begin], &src[w.begin], sizeof(PrimRef) * n);
                nodes[w.slot].leftOrFirst = w.begin;
                nodes[w.slot].count = n;
                maxDepth = std::max(maxDepth, w.depth);
            }
            // Destinations: a unit's left primitives follow the left ones of the units before
            // it, its right ones the right ones before it (a stable partition).
            uint32_t leftDst = w.begin, rightDst = w.begin + d.leftCount;
            for (size_t u = firstUnit[k]; u < firstUnit[k + 1]; ++u) {
                units[u].leftDst = leftDst;
                units[u].rightDst = rightDst;
                leftDst += units[u].leftCount;
                rightDst += units[u].end - units[u].begin - units[u].leftCount;
            }
        }

        // Scatter, collecting each side's centroid bounds.
        parallelFor(threads_, units.size(), [&](size_t u) {
            Unit& un = units[u];
            const Decision& d = decisions[un.item];
            if (d.mode == Mode::Leaf) return;
            const int shift = 8 * d.axis;
            const uint32_t mid = frontier[un.item].begin + d.leftCount;
            uint32_t l = un.leftDst, r = un.rightDst;
            Box4 cl, cr;
            for (uint32_t i = un.begin; i < un.end; ++i) {
                const PrimRef& p = src[i];
                const bool left = d.mode == Mode::Binned ? int((p.binKeys >> shift) & 0xffu) < d.bin : i < mid;
                dst[left ? l : r] = p;
                // Branch-free: the side is unpredictable.
                addCentroidToSide(centroidOf(loadLo(p), loadHi(p)), left, cl, cr);
                l += uint32_t(left);
                r += uint32_t(!left);
            }
            un.centroids[0] = cl;
            un.centroids[1] = cr;
        });

        // Children: nodes, and the next level's items or tasks.
        std::vector<WorkItem> next;
        for (size_t k = 0; k < items; ++k) {
            const Decision& d = decisions[k];
            if (d.mode == Mode::Leaf) continue;
            const WorkItem& w = frontier[k];
            Box4 cl, cr;
            for (size_t u = firstUnit[k]; u < firstUnit[k + 1]; ++u) {
                cl.grow(units[u].centroids[0]);
                cr.grow(units[u].centroids[1]);
            }
            const uint32_t left = uint32_t(nodes.size());
            nodes.push_back(BvhNode{d.lb.lo3(), 0, d.lb.hi3(), 0});
            nodes.push_back(BvhNode{d.rb.lo3(), 0, d.rb.hi3(), 0});
            nodes[w.slot].leftOrFirst = left;
            nodes[w.slot].count = 0;
            const uint32_t mid = w.begin + d.leftCount;
            for (const WorkItem& c :
                {WorkItem{left, w.begin, mid, w.depth + 1, cl}, WorkItem{left + 1, mid, w.end, w.depth + 1, cr}}) {
                if (c.end - c.begin <= kTaskPrims)
                    tasks.push_back({c, parity == 0});
                else
                    next.push_back(c);
            }
        }
        frontier = std::move(next);
    }
}

} // namespace pt::bvh_detail
