// Binned SAH BVH builder (after Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies").
//
// Structure of a build:
//  1. Top phase (one thread, but binning of big nodes is split over threads): nodes are split
//     depth-first until a node has at most kTaskPrims primitives; such a node becomes a task.
//  2. Task phase: every task builds its subtree into its own node vector, in parallel.
//  3. Assembly: top nodes first, then every task's nodes in task order, indices remapped.
// The split decisions only depend on the primitives, and the decomposition into tasks only on
// fixed constants, so nodes and primOrder are bit-identical for every thread count.
#include "bvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <cstdio>

namespace pt {

void Aabb::grow(const glm::vec3& p)
{
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Aabb::grow(const Aabb& b)
{
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
}

// Halves first so that huge finite coordinates cannot overflow to infinity.
glm::vec3 Aabb::centroid() const { return lo * 0.5f + hi * 0.5f; }

float Aabb::surfaceArea() const
{
    if (empty()) return 0.0f;
    const glm::vec3 d = hi - lo;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

bool Aabb::empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }

namespace {

// Bin indices are cached per primitive in 8 bits per axis (PrimRef::binKeys).
constexpr int kMaxBins = 128;
// Nodes with at most this many primitives are built as independent tasks. A fixed constant (not
// derived from the thread count) so that the node layout never depends on the thread count.
constexpr uint32_t kTaskPrims = 4096;
// Nodes at least this big bin their primitives on several threads. Merging bins uses min/max and
// integer sums, which are exact, so the result does not depend on how the range was chunked.
constexpr uint32_t kParallelBinPrims = 32768;
// Nodes with at most this many primitives use an exact SAH sweep instead of binning (see
// sweepSplit). At most 255 (order indices are bytes).
constexpr int kSweepPrims = 16;
// Node indices are uint32_t and a tree over N prims has up to 2N-1 nodes.
constexpr size_t kMaxPrims = (size_t(1) << 31) - 1;

// Working copy of a primitive, permuted in place (contiguous memory is much faster to bin and
// partition than gathering through an index array). binKeys caches the bin of every axis from the
// last binning pass, so the partition uses exactly the classification the SAH was evaluated on
// (no recomputation that could round differently).
struct PrimRef {
    glm::vec3 lo;
    uint32_t prim;
    glm::vec3 hi;
    uint32_t binKeys;
};

inline glm::vec3 centroidOf(const PrimRef& r) { return r.lo * 0.5f + r.hi * 0.5f; }

// Local inline helpers for the hot loops (the exported Aabb::grow is not reliably inlined).
inline void growBox(Aabb& b, const PrimRef& r)
{
    b.lo = glm::min(b.lo, r.lo);
    b.hi = glm::max(b.hi, r.hi);
}

inline void growPoint(Aabb& b, const glm::vec3& p)
{
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
}

struct WorkItem {
    uint32_t slot;  // index of this node in the node vector being filled (bounds already set)
    uint32_t begin; // primitive range [begin, end) in the PrimRef array
    uint32_t end;
    int depth;
    Aabb centroidBounds;
};

// Plain box without default member initialisers: a Bins object is created per node, and
// initialising all kMaxBins * 3 boxes there (instead of only the used ones) would dominate the
// cost of small nodes.
struct BinBox {
    glm::vec3 lo;
    glm::vec3 hi;
};

struct Bins {
    std::array<std::array<BinBox, kMaxBins>, 3> bounds;
    std::array<std::array<uint32_t, kMaxBins>, 3> count;

    void reset(int bins)
    {
        const float inf = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                bounds[a][i] = BinBox{ glm::vec3(inf), glm::vec3(-inf) };
                count[a][i] = 0;
            }
    }
    void merge(const Bins& o, int bins)
    {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                bounds[a][i].lo = glm::min(bounds[a][i].lo, o.bounds[a][i].lo);
                bounds[a][i].hi = glm::max(bounds[a][i].hi, o.bounds[a][i].hi);
                count[a][i] += o.count[a][i];
            }
    }
};

// Maps a centroid coordinate to a bin. An axis with zero centroid extent gets scale 0, which puts
// every primitive in bin 0, so that axis never yields a split with two non-empty sides.
struct BinMapping {
    glm::vec3 origin;
    glm::vec3 scale;
    float lastBin; // bins - 1

    // Branch-free clamp; written so that a NaN (0 * inf for a denormal extent) lands in bin 0.
    int index(float c, float o, float sc) const
    {
        float t = (c - o) * sc;
        t = t > 0.0f ? t : 0.0f;
        t = t < lastBin ? t : lastBin;
        return int(t);
    }
};

inline float boxArea(const glm::vec3& lo, const glm::vec3& hi)
{
    const glm::vec3 d = hi - lo;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

struct Split {
    int axis = -1; // -1: no split separates the primitives
    int bin = 0;   // left side = bins [0, bin)
    float cost = std::numeric_limits<float>::infinity(); // sum of area * count, not normalised
    uint32_t imbalance = 0;
};

// Runs fn(i) for every i in [0, count) on up to `threads` threads (the caller included), handing
// indices out dynamically. Callers must make results independent of which thread ran what.
template <class Fn>
void parallelFor(int threads, size_t count, Fn&& fn)
{
    const size_t workers = std::min<size_t>(size_t(std::max(threads, 1)), count);
    if (workers <= 1) {
        for (size_t i = 0; i < count; ++i) fn(i);
        return;
    }
    std::atomic<size_t> next{ 0 };
    std::mutex errorMutex;
    std::exception_ptr error;
    auto loop = [&] {
        try {
            for (size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < count;) fn(i);
        } catch (...) {
            std::lock_guard lock(errorMutex);
            if (!error) error = std::current_exception();
            next.store(count);
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    for (size_t w = 1; w < workers; ++w) {
        try {
            pool.emplace_back(loop);
        } catch (...) {
            break; // could not start a thread: the caller's loop below does the remaining work
        }
    }
    loop();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

class Builder {
public:
    Builder(std::span<const Aabb> primBounds, const BvhBuildOptions& o)
        : input_(primBounds)
    {
        bins_ = std::clamp(o.bins, 2, kMaxBins);
        maxLeaf_ = uint32_t(std::max(o.maxLeafSize, 1));
        traversalCost_ = o.traversalCost;
        intersectCost_ = o.intersectCost;
        threads_ = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    }

    void run(Bvh& out)
    {
#ifdef BVH_PROFILE
        auto tp = std::chrono::steady_clock::now();
#define PROF(x) { auto t2 = std::chrono::steady_clock::now(); fprintf(stderr, "%s %.1f ms  ", x, std::chrono::duration<double>(t2 - tp).count() * 1e3); tp = t2; }
#else
#define PROF(x)
#endif
        const uint32_t n = uint32_t(input_.size());
        refs_.resize(n);

        // Root bounds, computed over fixed chunks (exact min/max, so order-independent).
        WorkItem root{ 0, 0, n, 0, Aabb{} };
        Aabb rootBounds;
        {
            const size_t chunks = chunkCount(n);
            std::vector<Aabb> cb(chunks), bb(chunks);
            parallelFor(threads_, chunks, [&](size_t c) {
                const auto [b, e] = chunkRange(0, n, chunks, c);
                for (uint32_t i = b; i < e; ++i) {
                    const Aabb& src = input_[i];
                    refs_[i] = PrimRef{ src.lo, i, src.hi, 0 };
                    growBox(bb[c], refs_[i]);
                    growPoint(cb[c], centroidOf(refs_[i]));
                }
            });
            for (size_t c = 0; c < chunks; ++c) {
                rootBounds.grow(bb[c]);
                root.centroidBounds.grow(cb[c]);
            }
        }

        PROF("root");
        std::vector<BvhNode> nodes;
        nodes.reserve(2 * size_t(std::min(n, kTaskPrims * 4)));
        nodes.push_back(BvhNode{ rootBounds.lo, 0, rootBounds.hi, 0 });

        // Phase 1: top of the tree, depth-first, deferring small nodes as tasks.
        std::vector<WorkItem> tasks;
        int maxDepth = 0;
        {
            std::vector<WorkItem> stack{ root };
            while (!stack.empty()) {
                const WorkItem item = stack.back();
                stack.pop_back();
                if (item.end - item.begin <= kTaskPrims)
                    tasks.push_back(item);
                else
                    processNode(nodes, item, stack, maxDepth);
            }
        }

        PROF("phase1");
        // Phase 2: build every task's subtree into its own vector; local node 0 is the task root.
        std::vector<std::vector<BvhNode>> local(tasks.size());
        std::vector<int> localDepth(tasks.size(), 0);
        {
            // Biggest first for load balance; the order of execution does not affect the output.
            std::vector<uint32_t> order(tasks.size());
            for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
            std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
                return tasks[a].end - tasks[a].begin > tasks[b].end - tasks[b].begin;
            });
            parallelFor(threads_, tasks.size(), [&](size_t k) {
                const uint32_t t = order[k];
                WorkItem item = tasks[t];
                std::vector<BvhNode>& ln = local[t];
                ln.reserve(2 * size_t(item.end - item.begin));
                ln.push_back(nodes[item.slot]);
                item.slot = 0;
                std::vector<WorkItem> stack{ item };
                while (!stack.empty()) {
                    const WorkItem w = stack.back();
                    stack.pop_back();
                    processNode(ln, w, stack, localDepth[t]);
                }
            });
        }

        PROF("phase2");
        // Phase 3: top nodes, then task subtrees in task order (which is depth-first order).
        std::vector<size_t> base(tasks.size());
        size_t total = nodes.size();
        for (size_t t = 0; t < tasks.size(); ++t) {
            base[t] = total;
            total += local[t].size() - 1;
            maxDepth = std::max(maxDepth, localDepth[t]);
        }
        nodes.resize(total);
        parallelFor(threads_, tasks.size(), [&](size_t t) {
            // Local index k >= 1 moves to base + k - 1; leaves index refs_, which is shared.
            const auto remap = [&](BvhNode nd) {
                if (nd.count == 0) nd.leftOrFirst = uint32_t(base[t] + nd.leftOrFirst - 1);
                return nd;
            };
            nodes[tasks[t].slot] = remap(local[t][0]);
            for (size_t k = 1; k < local[t].size(); ++k) nodes[base[t] + k - 1] = remap(local[t][k]);
            std::vector<BvhNode>().swap(local[t]);
        });

        PROF("phase3");
        out.primOrder.resize(n);
        {
            const size_t chunks = chunkCount(n);
            parallelFor(threads_, chunks, [&](size_t c) {
                const auto [b, e] = chunkRange(0, n, chunks, c);
                for (uint32_t i = b; i < e; ++i) out.primOrder[i] = refs_[i].prim;
            });
        }
        std::vector<PrimRef>().swap(refs_);

        PROF("order");
        out.sahCost = sahCost(nodes, n);
        PROF("sah");
        out.maxDepth = maxDepth;
        out.nodes = std::move(nodes);
    }

private:
    // Fixed chunking for flat parallel loops; independent of the thread count on purpose.
    static size_t chunkCount(size_t n) { return std::max<size_t>(1, std::min<size_t>(64, n / 16384)); }
    static std::pair<uint32_t, uint32_t> chunkRange(uint32_t begin, uint32_t end, size_t chunks, size_t c)
    {
        const uint64_t n = end - begin;
        return { uint32_t(begin + n * c / chunks), uint32_t(begin + n * (c + 1) / chunks) };
    }

    double sahCost(const std::vector<BvhNode>& nodes, uint32_t primCount) const
    {
        const auto area = [](const BvhNode& nd) {
            const glm::dvec3 d = glm::dvec3(nd.hi) - glm::dvec3(nd.lo);
            return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
        };
        double sum = 0.0;
        size_t interior = 0;
        for (const BvhNode& nd : nodes) {
            if (nd.count == 0) {
                sum += double(traversalCost_) * area(nd);
                ++interior;
            } else {
                sum += double(intersectCost_) * nd.count * area(nd);
            }
        }
        const double rootArea = area(nodes[0]);
        if (rootArea > 0.0) return sum / rootArea;
        return double(traversalCost_) * double(interior) + double(intersectCost_) * primCount;
    }

    void binRange(uint32_t begin, uint32_t end, const BinMapping& map, Bins& bins)
    {
        bins.reset(bins_);
        // Axes written out: glm's operator[] is a switch, which is slow in this loop.
        const glm::vec3 o = map.origin, sc = map.scale;
        const auto add = [&](int axis, int k, const PrimRef& r) {
            BinBox& b = bins.bounds[axis][k];
            b.lo = glm::min(b.lo, r.lo);
            b.hi = glm::max(b.hi, r.hi);
            ++bins.count[axis][k];
        };
        for (uint32_t i = begin; i < end; ++i) {
            PrimRef& r = refs_[i];
            const glm::vec3 c = centroidOf(r);
            const int kx = map.index(c.x, o.x, sc.x);
            const int ky = map.index(c.y, o.y, sc.y);
            const int kz = map.index(c.z, o.z, sc.z);
            add(0, kx, r);
            add(1, ky, r);
            add(2, kz, r);
            r.binKeys = uint32_t(kx) | uint32_t(ky) << 8 | uint32_t(kz) << 16;
        }
    }

    Split findSplit(const Bins& bins) const
    {
        const float inf = std::numeric_limits<float>::infinity();
        Split best;
        std::array<float, kMaxBins> rightArea;
        std::array<uint32_t, kMaxBins> rightCount;
        for (int a = 0; a < 3; ++a) {
            const auto& bb = bins.bounds[a];
            const auto& bc = bins.count[a];
            glm::vec3 lo(inf), hi(-inf);
            uint32_t cnt = 0;
            float area = 0.0f;
            for (int i = bins_ - 1; i >= 1; --i) {
                if (bc[i] != 0) {
                    lo = glm::min(lo, bb[i].lo);
                    hi = glm::max(hi, bb[i].hi);
                    cnt += bc[i];
                    area = boxArea(lo, hi);
                }
                rightArea[i] = area;
                rightCount[i] = cnt;
            }
            lo = glm::vec3(inf);
            hi = glm::vec3(-inf);
            cnt = 0;
            for (int i = 1; i < bins_; ++i) {
                // An empty bin i-1 gives the same partition as the split before it: skip it.
                if (bc[i - 1] == 0) continue;
                if (rightCount[i] == 0) break;
                lo = glm::min(lo, bb[i - 1].lo);
                hi = glm::max(hi, bb[i - 1].hi);
                cnt += bc[i - 1];
                const float cost = boxArea(lo, hi) * float(cnt) + rightArea[i] * float(rightCount[i]);
                const uint32_t imbalance = cnt > rightCount[i] ? cnt - rightCount[i] : rightCount[i] - cnt;
                // Ties (e.g. all-zero areas of flat, collinear input) go to the most balanced split
                // so that degenerate input still gives a logarithmic depth.
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

    // Hoare partition on the cached bin key; accumulates the children's bounds on the way so no
    // further pass is needed. Every element is classified and accumulated exactly once.
    uint32_t partition(uint32_t begin, uint32_t end, int axis, int splitBin, Aabb& lb, Aabb& lcb, Aabb& rb, Aabb& rcb)
    {
        const int shift = 8 * axis;
        const auto isLeft = [&](const PrimRef& r) { return int((r.binKeys >> shift) & 0xffu) < splitBin; };
        uint32_t i = begin, j = end;
        for (;;) {
            while (i < j && isLeft(refs_[i])) {
                growBox(lb, refs_[i]);
                growPoint(lcb, centroidOf(refs_[i]));
                ++i;
            }
            while (i < j && !isLeft(refs_[j - 1])) {
                growBox(rb, refs_[j - 1]);
                growPoint(rcb, centroidOf(refs_[j - 1]));
                --j;
            }
            if (i >= j) break;
            std::swap(refs_[i], refs_[j - 1]);
            growBox(lb, refs_[i]);
            growPoint(lcb, centroidOf(refs_[i]));
            growBox(rb, refs_[j - 1]);
            growPoint(rcb, centroidOf(refs_[j - 1]));
            ++i;
            --j;
        }
        return i;
    }

    void rangeBounds(uint32_t begin, uint32_t end, Aabb& b, Aabb& cb) const
    {
        for (uint32_t i = begin; i < end; ++i) {
            growBox(b, refs_[i]);
            growPoint(cb, centroidOf(refs_[i]));
        }
    }

    void makeLeaf(std::vector<BvhNode>& nodes, const WorkItem& item, int& maxDepth)
    {
        nodes[item.slot].leftOrFirst = item.begin;
        nodes[item.slot].count = item.end - item.begin;
        maxDepth = std::max(maxDepth, item.depth);
    }

    // Exact SAH for small nodes: every object partition along each axis, in centroid order (ties
    // in range order, so it is deterministic). Binning has a fixed cost per node (resetting and
    // sweeping 3 * bins bins) that would dominate here, where most of the nodes are; the exact
    // sweep is cheaper and finds better splits. Also handles identical centroids: all costs tie
    // and the most balanced split (the range median) wins. Returns false if a leaf is better.
    bool sweepSplit(const WorkItem& item, float nodeArea, Aabb& lb, Aabb& lcb, Aabb& rb, Aabb& rcb, uint32_t& mid)
    {
        const int n = int(item.end - item.begin);
        const float inf = std::numeric_limits<float>::infinity();
        std::array<PrimRef, kSweepPrims> tmp;
        std::array<std::array<float, kSweepPrims>, 3> cen;
        std::array<std::array<uint8_t, kSweepPrims>, 3> order;
        std::array<float, kSweepPrims> rightArea;
        for (int i = 0; i < n; ++i) {
            tmp[i] = refs_[item.begin + i];
            const glm::vec3 c = centroidOf(tmp[i]);
            cen[0][i] = c.x;
            cen[1][i] = c.y;
            cen[2][i] = c.z;
        }
        int bestAxis = 0, bestK = 0;
        float bestCost = inf;
        int bestImbalance = 0;
        for (int a = 0; a < 3; ++a) {
            auto& o = order[a];
            const auto& key = cen[a];
            for (int i = 0; i < n; ++i) { // stable insertion sort
                const uint8_t v = uint8_t(i);
                int j = i;
                for (; j > 0 && key[o[j - 1]] > key[v]; --j) o[j] = o[j - 1];
                o[j] = v;
            }
            glm::vec3 lo(inf), hi(-inf);
            for (int k = n - 1; k >= 1; --k) {
                lo = glm::min(lo, tmp[o[k]].lo);
                hi = glm::max(hi, tmp[o[k]].hi);
                rightArea[k] = boxArea(lo, hi);
            }
            lo = glm::vec3(inf);
            hi = glm::vec3(-inf);
            for (int k = 1; k < n; ++k) {
                lo = glm::min(lo, tmp[o[k - 1]].lo);
                hi = glm::max(hi, tmp[o[k - 1]].hi);
                const float cost = boxArea(lo, hi) * float(k) + rightArea[k] * float(n - k);
                const int imbalance = std::abs(2 * k - n);
                if (cost < bestCost || (cost == bestCost && imbalance < bestImbalance)) {
                    bestAxis = a;
                    bestK = k;
                    bestCost = cost;
                    bestImbalance = imbalance;
                }
            }
        }
        if (uint32_t(n) <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(bestCost, nodeArea)) return false;
        const auto& o = order[bestAxis];
        for (int j = 0; j < n; ++j) {
            const PrimRef& r = tmp[o[j]];
            refs_[item.begin + j] = r;
            if (j < bestK) {
                growBox(lb, r);
                growPoint(lcb, centroidOf(r));
            } else {
                growBox(rb, r);
                growPoint(rcb, centroidOf(r));
            }
        }
        mid = item.begin + uint32_t(bestK);
        return true;
    }

    // Relative SAH cost of a split whose children's sum of area * count is `cost`. A zero-area node
    // (points or a line) makes every split free, and then only the leaf size limit splits it.
    float splitCost(float cost, float nodeArea) const
    {
        return traversalCost_ + intersectCost_ * (nodeArea > 0.0f ? cost / nodeArea : 0.0f);
    }

    // Decides leaf or split for one node; on a split appends the two children (adjacent) and
    // pushes them so that the left child is processed next (depth-first).
    void processNode(std::vector<BvhNode>& nodes, const WorkItem& item, std::vector<WorkItem>& stack, int& maxDepth)
    {
        const uint32_t n = item.end - item.begin;
        if (n <= 1) return makeLeaf(nodes, item, maxDepth);
        const float nodeArea = boxArea(nodes[item.slot].lo, nodes[item.slot].hi);

        Aabb lb, lcb, rb, rcb;
        uint32_t mid = item.begin;
        if (n <= kSweepPrims) {
            if (!sweepSplit(item, nodeArea, lb, lcb, rb, rcb, mid)) return makeLeaf(nodes, item, maxDepth);
        } else {
            const glm::vec3 extent = item.centroidBounds.hi - item.centroidBounds.lo;
            Split split;
            if (extent.x > 0.0f || extent.y > 0.0f || extent.z > 0.0f) {
                const auto scaleOf = [&](float e) { return e > 0.0f ? float(bins_) / e : 0.0f; };
                const BinMapping map{ item.centroidBounds.lo,
                                      glm::vec3(scaleOf(extent.x), scaleOf(extent.y), scaleOf(extent.z)), float(bins_ - 1) };
                Bins bins;
                const size_t chunks = std::min<size_t>(size_t(threads_), 8);
                if (n >= kParallelBinPrims && chunks > 1) {
                    std::vector<Bins> partial(chunks);
                    parallelFor(threads_, chunks, [&](size_t c) {
                        const auto [b, e] = chunkRange(item.begin, item.end, chunks, c);
                        binRange(b, e, map, partial[c]);
                    });
                    bins = partial[0];
                    for (size_t c = 1; c < chunks; ++c) bins.merge(partial[c], bins_);
                } else {
                    binRange(item.begin, item.end, map, bins);
                }
                split = findSplit(bins);
            }
            if (split.axis >= 0) {
                if (n <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(split.cost, nodeArea))
                    return makeLeaf(nodes, item, maxDepth);
                mid = partition(item.begin, item.end, split.axis, split.bin, lb, lcb, rb, rcb);
            } else if (n <= maxLeaf_) {
                return makeLeaf(nodes, item, maxDepth);
            }
            if (mid == item.begin || mid == item.end) {
                // All centroids equal (or binning could not separate them): halve the range so
                // leaves stay within maxLeafSize and the depth stays logarithmic.
                mid = item.begin + n / 2;
                lb = lcb = rb = rcb = Aabb{};
                rangeBounds(item.begin, mid, lb, lcb);
                rangeBounds(mid, item.end, rb, rcb);
            }
        }

        const uint32_t left = uint32_t(nodes.size());
        nodes.push_back(BvhNode{ lb.lo, 0, lb.hi, 0 });
        nodes.push_back(BvhNode{ rb.lo, 0, rb.hi, 0 });
        nodes[item.slot].leftOrFirst = left;
        nodes[item.slot].count = 0;
        stack.push_back(WorkItem{ left + 1, mid, item.end, item.depth + 1, rcb });
        stack.push_back(WorkItem{ left, item.begin, mid, item.depth + 1, lcb });
    }

    std::span<const Aabb> input_;
    std::vector<PrimRef> refs_;
    int bins_ = 16;
    uint32_t maxLeaf_ = 4;
    float traversalCost_ = 1.0f;
    float intersectCost_ = 1.0f;
    int threads_ = 1;
};

} // namespace

Bvh buildBvh(std::span<const Aabb> primBounds, const BvhBuildOptions& options)
{
    const auto start = std::chrono::steady_clock::now();
    if (primBounds.size() > kMaxPrims) throw std::length_error("buildBvh: more than 2^31-1 primitives");
    Bvh bvh;
    if (!primBounds.empty()) Builder(primBounds, options).run(bvh);
    bvh.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

} // namespace pt
