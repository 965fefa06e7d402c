// Binned SAH BVH builder (after Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies"), with an exact SAH sweep for small nodes.
//
// Structure of a build:
//  1. Top phase, level by level: every node of a level is cut into fixed-size units that all
//     threads bin; a node's unit bins are merged (exactly) to choose its split; the units then
//     scatter their primitives into a second buffer (a stable partition whose per-unit counts come
//     from the bins) and collect the children's centroid bounds on the way. Nodes of at most
//     kTaskPrims primitives become tasks.
//  2. Task phase: every task builds its subtree depth-first into its own node vector, in parallel.
//  3. Assembly: nodes are placed exactly where a sequential depth-first build would have put
//     them (children pairs in preorder of their parents), indices remapped.
// Split decisions depend only on the primitives and their order, which a stable partition fixes,
// and every decomposition into units and tasks only on fixed constants, so nodes and primOrder
// are bit-identical for every thread count.
#include "bvh.h"

#include "bvh_parallel.h"
#include "bvh_simd.h"

#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <thread>

namespace pt {

namespace {
constexpr size_t kHugePage = size_t(2) << 20;

// Memory for `bytes` bytes, on transparent huge pages where the system gives them on request
// (Debian's default "madvise" mode); released with std::free.
void* allocateHugePages(size_t bytes)
{
    const size_t rounded = std::max<size_t>(1, (bytes + kHugePage - 1) / kHugePage) * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return p;
}
} // namespace

template <class T>
T* DefaultInitAllocator<T>::allocate(size_t count)
{
    if (count * sizeof(T) < kHugePage) return std::allocator<T>::allocate(count);
    return static_cast<T*>(allocateHugePages(count * sizeof(T)));
}

template <class T>
void DefaultInitAllocator<T>::deallocate(T* p, size_t count) noexcept
{
    if (count * sizeof(T) < kHugePage) std::allocator<T>::deallocate(p, count);
    else std::free(p);
}

template struct DefaultInitAllocator<BvhNode>;

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

// Same formula as the builder's centroids ((lo + hi) * 0.5, not contractible into an FMA).
glm::vec3 Aabb::centroid() const { return (lo + hi) * 0.5f; }

float Aabb::surfaceArea() const
{
    if (empty()) return 0.0f;
    const glm::vec3 d = hi - lo;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

bool Aabb::empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }

namespace {

// The builder's two primitive buffers (32 bytes per primitive each) are first touched by the
// build itself: on huge pages, one fault per 2 MiB instead of per 4 KiB. Trivial types only (the
// memory is not constructed).
struct HugeFree {
    void operator()(void* p) const { std::free(p); }
};
template <class T>
std::unique_ptr<T[], HugeFree> allocateHuge(size_t count) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
    return std::unique_ptr<T[], HugeFree>(static_cast<T*>(allocateHugePages(count * sizeof(T))));
}

using namespace bvh_detail;

// Bin indices are cached per primitive in 8 bits per axis (PrimRef::binKeys).
constexpr int kMaxBins = 128;
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
// Node indices are uint32_t and a tree over N prims has up to 2N-1 nodes.
constexpr size_t kMaxPrims = (size_t(1) << 31) - 1;

inline float boxArea(const glm::vec3& lo, const glm::vec3& hi)
{
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

struct Bins {
    // Plain V4 arrays, not Box4: a Bins object is created per node, and default-initialising all
    // 3 * kMaxBins boxes (instead of resetting the `bins` used ones) would dominate small nodes.
    std::array<std::array<V4, kMaxBins>, 3> lo;
    std::array<std::array<V4, kMaxBins>, 3> hi;
    std::array<std::array<uint32_t, kMaxBins>, 3> count;

    void reset(int bins)
    {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                lo[a][i] = splat(kInf);
                hi[a][i] = splat(-kInf);
                count[a][i] = 0;
            }
    }
    void add(int axis, int bin, V4 plo, V4 phi)
    {
        lo[axis][bin] = vmin(lo[axis][bin], plo);
        hi[axis][bin] = vmax(hi[axis][bin], phi);
        ++count[axis][bin];
    }
    void merge(const Bins& o, int bins)
    {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                lo[a][i] = vmin(lo[a][i], o.lo[a][i]);
                hi[a][i] = vmax(hi[a][i], o.hi[a][i]);
                count[a][i] += o.count[a][i];
            }
    }
};

struct Split {
    int axis = -1; // -1: no split separates the primitives
    int bin = 0;   // left side = bins [0, bin)
    float cost = kInf; // sum of area * count of both sides, not normalised
    uint32_t imbalance = 0;
};

// Bins [begin, end) of refs on all three axes and caches every primitive's bins in binKeys.
// An axis with zero centroid extent has scale 0: everything lands in bin 0 and the axis never
// offers a split. The clamp is written so that a NaN (0 * inf for a denormal extent) gives 0.
void binRange(PrimRef* refs, uint32_t begin, uint32_t end, V4 origin, V4 scale, int binCount, Bins& bins)
{
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
bool binTransform(const Box4& cb, int binCount, V4& origin, V4& scale)
{
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
        const uint32_t n = uint32_t(input_.size());
        // Uninitialised on purpose: every element is written before it is read, and zero-filling
        // 32 bytes per primitive on one thread would cost more than the top levels' binning.
        refs_ = allocateHuge<PrimRef>(n);
        alt_ = allocateHuge<PrimRef>(n);

        // Root bounds and centroid bounds over fixed chunks (exact min/max, so the merge order does
        // not matter).
        Box4 rootBounds, rootCentroids;
        {
            const size_t chunks = chunkCount(n);
            std::vector<Box4> bb(chunks), cb(chunks);
            parallelFor(threads_, chunks, [&](size_t c) {
                const auto [b, e] = chunkRange(0, n, chunks, c);
                for (uint32_t i = b; i < e; ++i) {
                    const Aabb& s = input_[i];
                    refs_[i] = PrimRef{ { s.lo.x, s.lo.y, s.lo.z }, i, { s.hi.x, s.hi.y, s.hi.z }, 0 };
                    bb[c].grow(refs_[i]);
                    cb[c].grow(centroidOf(loadLo(refs_[i]), loadHi(refs_[i])));
                }
            });
            for (size_t c = 0; c < chunks; ++c) {
                rootBounds.grow(bb[c]);
                rootCentroids.grow(cb[c]);
            }
        }
        std::vector<BvhNode> nodes{ BvhNode{ rootBounds.lo3(), 0, rootBounds.hi3(), 0 } };

        int maxDepth = 0;
        std::vector<Task> tasks;
        buildTop(nodes, WorkItem{ 0, 0, n, 0, rootCentroids }, tasks, maxDepth);

        // Preorder of the top tree: where a sequential depth-first build would have allocated
        // nodes, a children pair of a top node or a task's whole subtree.
        struct Event {
            bool task;
            uint32_t index; // task index, or the (phase-1) index of the first node of a pair
        };
        std::vector<Event> events;
        {
            std::vector<int32_t> taskOf(nodes.size(), -1);
            for (size_t t = 0; t < tasks.size(); ++t) taskOf[tasks[t].work.slot] = int32_t(t);
            std::vector<uint32_t> stack{ 0 };
            while (!stack.empty()) {
                const uint32_t s = stack.back();
                stack.pop_back();
                if (taskOf[s] >= 0) {
                    events.push_back({ true, uint32_t(taskOf[s]) });
                } else if (nodes[s].count == 0) {
                    const uint32_t left = nodes[s].leftOrFirst;
                    events.push_back({ false, left });
                    stack.push_back(left + 1);
                    stack.push_back(left);
                }
            }
        }

        // Phase 2: every task's subtree goes into its own vector; local node 0 is the task root.
        std::vector<std::vector<BvhNode>> local(tasks.size());
        std::vector<int> localDepth(tasks.size(), 0);
        {
            // Biggest first for load balance; execution order does not affect the output.
            std::vector<uint32_t> order(tasks.size());
            for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
            std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
                return tasks[a].work.end - tasks[a].work.begin > tasks[b].work.end - tasks[b].work.begin;
            });
            parallelFor(threads_, tasks.size(), [&](size_t k) {
                const uint32_t t = order[k];
                WorkItem item = tasks[t].work;
                if (tasks[t].inAlt)
                    std::memcpy(&refs_[item.begin], &alt_[item.begin], sizeof(PrimRef) * (item.end - item.begin));
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
        alt_.reset();

        // Phase 3: final positions from the preorder events, then copy with remapped indices.
        std::vector<uint32_t> topIndex(nodes.size(), 0); // phase-1 index -> final index
        std::vector<size_t> base(tasks.size());          // final index of a task's local node 1
        size_t total = 1;
        for (const Event& e : events) {
            if (e.task) {
                base[e.index] = total;
                total += local[e.index].size() - 1;
                maxDepth = std::max(maxDepth, localDepth[e.index]);
            } else {
                topIndex[e.index] = uint32_t(total);
                topIndex[e.index + 1] = uint32_t(total + 1);
                total += 2;
            }
        }
        BvhNodeArray placed(total); // uninitialised: every node is written below
        for (size_t i = 0; i < nodes.size(); ++i) { // task roots among these are overwritten below
            BvhNode nd = nodes[i];
            if (nd.count == 0) nd.leftOrFirst = topIndex[nd.leftOrFirst];
            placed[topIndex[i]] = nd;
        }
        parallelFor(threads_, tasks.size(), [&](size_t t) {
            // Local index k >= 1 moves to base + k - 1; leaves index refs_, which is shared.
            const auto remap = [&](BvhNode nd) {
                if (nd.count == 0) nd.leftOrFirst = uint32_t(base[t] + nd.leftOrFirst - 1);
                return nd;
            };
            placed[topIndex[tasks[t].work.slot]] = remap(local[t][0]);
            for (size_t k = 1; k < local[t].size(); ++k) placed[base[t] + k - 1] = remap(local[t][k]);
            std::vector<BvhNode>().swap(local[t]);
        });
        std::vector<BvhNode>().swap(nodes);

        out.primOrder.resize(n);
        {
            const size_t chunks = chunkCount(n);
            parallelFor(threads_, chunks, [&](size_t c) {
                const auto [b, e] = chunkRange(0, n, chunks, c);
                for (uint32_t i = b; i < e; ++i) out.primOrder[i] = refs_[i].prim;
            });
        }
        refs_.reset();

        out.sahCost = sahCost(placed, n);
        out.maxDepth = maxDepth;
        out.nodes = std::move(placed);
    }

private:
    struct Task {
        WorkItem work;
        bool inAlt; // its primitives lie in alt_ (moved to refs_ when the task starts)
    };

    // Phase 1 (see the file comment). Splits `root` level by level; nodes of at most kTaskPrims
    // primitives (and the root itself if it is that small) are handed back as tasks.
    void buildTop(std::vector<BvhNode>& nodes, const WorkItem& root, std::vector<Task>& tasks,
                  int& maxDepth)
    {
        struct Unit {
            uint32_t item, begin, end;
            uint32_t leftCount = 0;        // primitives of this unit that go to the left child
            uint32_t leftDst = 0, rightDst = 0;
            Box4 centroids[2];             // of the primitives that went left [0] and right [1]
        };
        enum class Mode { Leaf, Binned, Halve };
        struct Decision {
            Mode mode = Mode::Leaf;
            int axis = 0, bin = 0;
            uint32_t leftCount = 0;
            Box4 lb, rb;
        };

        if (root.end - root.begin <= kTaskPrims) {
            tasks.push_back({ root, false });
            return;
        }
        std::vector<WorkItem> frontier{ root };
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
                    units.push_back(Unit{ uint32_t(k), b, e });
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
                    d.mode = n <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(split.cost, nodeArea) ? Mode::Leaf : Mode::Binned;
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
                nodes.push_back(BvhNode{ d.lb.lo3(), 0, d.lb.hi3(), 0 });
                nodes.push_back(BvhNode{ d.rb.lo3(), 0, d.rb.hi3(), 0 });
                nodes[w.slot].leftOrFirst = left;
                nodes[w.slot].count = 0;
                const uint32_t mid = w.begin + d.leftCount;
                for (const WorkItem& c : { WorkItem{ left, w.begin, mid, w.depth + 1, cl }, WorkItem{ left + 1, mid, w.end, w.depth + 1, cr } }) {
                    if (c.end - c.begin <= kTaskPrims) tasks.push_back({ c, parity == 0 });
                    else next.push_back(c);
                }
            }
            frontier = std::move(next);
        }
    }

private:
    // Summed per fixed chunk, then the chunks in order: the same value for every thread count.
    double sahCost(const BvhNodeArray& nodes, uint32_t primCount) const
    {
        const auto area = [](const BvhNode& nd) {
            const glm::dvec3 d = glm::dvec3(nd.hi) - glm::dvec3(nd.lo);
            return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
        };
        const size_t chunks = chunkCount(nodes.size());
        std::vector<double> partial(chunks, 0.0);
        std::vector<size_t> interiors(chunks, 0);
        parallelFor(threads_, chunks, [&](size_t c) {
            const auto [b, e] = chunkRange(0, uint32_t(nodes.size()), chunks, c);
            for (uint32_t i = b; i < e; ++i) {
                const BvhNode& nd = nodes[i];
                if (nd.count == 0) {
                    partial[c] += double(traversalCost_) * area(nd);
                    ++interiors[c];
                } else {
                    partial[c] += double(intersectCost_) * nd.count * area(nd);
                }
            }
        });
        double sum = 0.0;
        size_t interior = 0;
        for (size_t c = 0; c < chunks; ++c) {
            sum += partial[c];
            interior += interiors[c];
        }
        const double rootArea = area(nodes[0]);
        if (rootArea > 0.0) return sum / rootArea;
        return double(traversalCost_) * double(interior) + double(intersectCost_) * primCount;
    }

    // Relative SAH cost of a split whose children's sum of area * count is `cost`. A zero-area node
    // (points or a line) makes every split free, and then only the leaf size limit splits it.
    float splitCost(float cost, float nodeArea) const
    {
        return traversalCost_ + intersectCost_ * (nodeArea > 0.0f ? cost / nodeArea : 0.0f);
    }

    Split findSplit(const Bins& bins, int binCount) const
    {
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

    // Branch-free Lomuto partition on the cached bin key (which side an element goes to is
    // unpredictable, so a branchy partition pays a mispredict for about every other element).
    // The children's centroid bounds are collected on the way (saving them a pass of their own).
    uint32_t partition(uint32_t begin, uint32_t end, int axis, int splitBin, Box4& leftCentroids, Box4& rightCentroids)
    {
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
    bool sweepSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, uint32_t& mid)
    {
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
    bool binnedSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, Box4& lc, Box4& rc, uint32_t& mid)
    {
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
    void processNode(std::vector<BvhNode>& nodes, const WorkItem& item, std::vector<WorkItem>& stack, int& maxDepth)
    {
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
        nodes.push_back(BvhNode{ lb.lo3(), 0, lb.hi3(), 0 });
        nodes.push_back(BvhNode{ rb.lo3(), 0, rb.hi3(), 0 });
        nodes[item.slot].leftOrFirst = left;
        nodes[item.slot].count = 0;
        stack.push_back(WorkItem{ left + 1, mid, item.end, item.depth + 1, rc });
        stack.push_back(WorkItem{ left, item.begin, mid, item.depth + 1, lc });
    }

    std::span<const Aabb> input_;
    std::unique_ptr<PrimRef[], HugeFree> refs_; // the primitives, permuted; leaves index ranges of it
    std::unique_ptr<PrimRef[], HugeFree> alt_;  // the top phase's second buffer (it scatters between the two)
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
