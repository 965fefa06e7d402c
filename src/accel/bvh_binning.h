// Binned SAH split search for the BVH builder (src/accel/bvh.cpp): the per-axis bins a node's
// primitives are counted into, how a primitive's bin is chosen, and the sweep over bin
// boundaries that finds the cheapest split. Used by the top phase (bvh_top_phase.cpp, bins of
// several units merged) and the task phase (bvh_task_phase.cpp, one node at a time).
#pragma once
#include "accel/bvh_simd.h"

#include <array>
#include <cstdint>

namespace pt::bvh_detail {

// Bin indices are cached per primitive in 8 bits per axis (PrimRef::binKeys).
constexpr int kMaxBins = 128;

struct Bins {
    // Plain V4 arrays, not Box4: a Bins object is created per node, and default-initialising all
    // 3 * kMaxBins boxes (instead of resetting the `bins` used ones) would dominate small nodes.
    std::array<std::array<V4, kMaxBins>, 3> lo;
    std::array<std::array<V4, kMaxBins>, 3> hi;
    std::array<std::array<uint32_t, kMaxBins>, 3> count;

    void reset(int bins) {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                lo[a][i] = splat(kInf);
                hi[a][i] = splat(-kInf);
                count[a][i] = 0;
            }
    }
    void add(int axis, int bin, V4 plo, V4 phi) {
        lo[axis][bin] = vmin(lo[axis][bin], plo);
        hi[axis][bin] = vmax(hi[axis][bin], phi);
        ++count[axis][bin];
    }
    void merge(const Bins& o, int bins) {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                lo[a][i] = vmin(lo[a][i], o.lo[a][i]);
                hi[a][i] = vmax(hi[a][i], o.hi[a][i]);
                count[a][i] += o.count[a][i];
            }
    }
};

struct Split {
    int axis = -1;     // -1: no split separates the primitives
    int bin = 0;       // left side = bins [0, bin)
    float cost = kInf; // sum of area * count of both sides, not normalised
    uint32_t imbalance = 0;
};

// Bins [begin, end) of refs on all three axes and caches every primitive's bins in binKeys.
// An axis with zero centroid extent has scale 0: everything lands in bin 0 and the axis never
// offers a split. The clamp is written so that a NaN (0 * inf for a denormal extent) gives 0.
inline void binRange(PrimRef* refs, uint32_t begin, uint32_t end, V4 origin, V4 scale, int binCount, Bins& bins) {
    bins.reset(binCount);
    const V4 zero = splat(0.0f), last = splat(float(binCount - 1));
    for (uint32_t i = begin; i < end; ++i) {
        PrimRef& r = refs[i];
        const V4 lo = loadLo(r), hi = loadHi(r);
        const V4 t = vmin(vmax(vmul(vsub(centroidOf(lo, hi), origin), scale), zero), last);
        int32_t k[4];
        truncToInt(t, k);
        bins.add(0, k[0], lo, hi);
        bins.add(1, k[1], lo, hi);
        bins.add(2, k[2], lo, hi);
        r.binKeys = uint32_t(k[0]) | uint32_t(k[1]) << 8 | uint32_t(k[2]) << 16;
    }
}

// Bin origin and scale (bins per unit length, 0 on an axis with no centroid extent) for the
// centroid bounds cb. Returns false when no axis has any extent (nothing to bin).
inline bool binTransform(const Box4& cb, int binCount, V4& origin, V4& scale) {
    float lo[4], hi[4];
    store(lo, cb.lo);
    store(hi, cb.hi);
    float sc[3];
    for (int a = 0; a < 3; ++a) {
        const float extent = hi[a] - lo[a];
        sc[a] = extent > 0.0f ? float(binCount) / extent : 0.0f;
    }
    origin = set3(lo[0], lo[1], lo[2]);
    scale = set3(sc[0], sc[1], sc[2]);
    return sc[0] > 0.0f || sc[1] > 0.0f || sc[2] > 0.0f;
}

// The cheapest split over the bin boundaries of all three axes (axis -1 when no boundary
// separates the primitives).
inline Split findSplit(const Bins& bins, int binCount) {
    Split best;
    std::array<float, kMaxBins> rightArea;
    std::array<uint32_t, kMaxBins> rightCount;
    for (int a = 0; a < 3; ++a) {
        const auto& bc = bins.count[a];
        Box4 acc;
        uint32_t cnt = 0;
        float area = 0.0f;
        for (int i = binCount - 1; i >= 1; --i) {
            if (bc[i] != 0) {
                acc.grow(bins.lo[a][i], bins.hi[a][i]);
                cnt += bc[i];
                area = acc.area();
            }
            rightArea[i] = area;
            rightCount[i] = cnt;
        }
        acc = Box4{};
        cnt = 0;
        for (int i = 1; i < binCount; ++i) {
            // An empty bin i-1 gives the same partition as the split before it: skip it.
            if (bc[i - 1] == 0) continue;
            if (rightCount[i] == 0) break;
            acc.grow(bins.lo[a][i - 1], bins.hi[a][i - 1]);
            cnt += bc[i - 1];
            const float cost = acc.area() * float(cnt) + rightArea[i] * float(rightCount[i]);
            const uint32_t imbalance = cnt > rightCount[i] ? cnt - rightCount[i] : rightCount[i] - cnt;
            // Ties (e.g. all-zero areas of flat, collinear input) go to the most balanced split
            // so that degenerate input still gets a logarithmic depth.
            if (cost < best.cost || (cost == best.cost && imbalance < best.imbalance)) {
                best.axis = a;
                best.bin = i;
                best.cost = cost;
                best.imbalance = imbalance;
            }
        }
    }
    return best;
}

} // namespace pt::bvh_detail
