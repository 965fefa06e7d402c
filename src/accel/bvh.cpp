// Binned SAH BVH builder (after Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies"), with an exact SAH sweep for small nodes.
//
// Structure of a build:
//  1. Top phase (one thread, but binning of big nodes is split over threads): nodes are split
//     depth-first until a node has at most kTaskPrims primitives; such a node becomes a task.
//  2. Task phase: every task builds its subtree into its own node vector, in parallel.
//  3. Assembly: nodes are placed exactly where a sequential depth-first build would have put
//     them (children pairs in preorder of their parents), indices remapped.
// Split decisions depend only on the primitives, and the decomposition into tasks only on fixed
// constants, so nodes and primOrder are bit-identical for every thread count.
#include "bvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

// PT_BVH_SSE=0 forces the portable scalar path (it gives bit-identical trees).
#ifndef PT_BVH_SSE
#if defined(__SSE2__) || defined(_M_X64)
#define PT_BVH_SSE 1
#else
#define PT_BVH_SSE 0
#endif
#endif
#if PT_BVH_SSE
#include <emmintrin.h>
#endif

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

// Bin indices are cached per primitive in 8 bits per axis (PrimRef::binKeys).
constexpr int kMaxBins = 128;
// Nodes with at most this many primitives are built as independent tasks. A fixed constant (not
// derived from the thread count) so that the node layout never depends on the thread count.
constexpr uint32_t kTaskPrims = 4096;
// Nodes at least this big bin their primitives on several threads. Merging bins uses min/max and
// integer sums, which are exact, so the result does not depend on how the range was chunked.
constexpr uint32_t kParallelBinPrims = 32768;
// Nodes with at most this many primitives use an exact SAH sweep instead of binning (see
// sweepSplit). At most 255 (sort indices are bytes).
constexpr int kSweepPrims = 16;
// Node indices are uint32_t and a tree over N prims has up to 2N-1 nodes.
constexpr size_t kMaxPrims = (size_t(1) << 31) - 1;
constexpr float kInf = std::numeric_limits<float>::infinity();

// Working copy of a primitive, permuted in place (contiguous memory is much faster to bin and
// partition than gathering through an index array). Laid out as two 16-byte rows so a box loads
// as two SIMD registers (lane 3, prim / binKeys, is zeroed on load). binKeys caches each axis' bin from the last binning pass, so the partition uses
// exactly the classification the SAH was evaluated on, with no recomputation that could round
// differently.
struct alignas(16) PrimRef {
    float lo[3];
    uint32_t prim;
    float hi[3];
    uint32_t binKeys;
};
static_assert(sizeof(PrimRef) == 32);

// Minimal 4-lane float vector: SSE2 where available, else a scalar twin with the same semantics
// (min/max return the second operand when unordered, like minps/maxps), so results match.
struct V4 {
#if PT_BVH_SSE
    __m128 v;
#else
    float v[4];
#endif
};

#if PT_BVH_SSE
inline V4 splat(float f) { return { _mm_set1_ps(f) }; }
inline V4 set3(float x, float y, float z) { return { _mm_set_ps(0.0f, z, y, x) }; }
inline V4 loadRow(const void* p) { return { _mm_load_ps(static_cast<const float*>(p)) }; }
inline void store(float* p, V4 a) { _mm_storeu_ps(p, a.v); }
inline V4 vmin(V4 a, V4 b) { return { _mm_min_ps(a.v, b.v) }; }
inline V4 vmax(V4 a, V4 b) { return { _mm_max_ps(a.v, b.v) }; }
inline V4 vadd(V4 a, V4 b) { return { _mm_add_ps(a.v, b.v) }; }
inline V4 vsub(V4 a, V4 b) { return { _mm_sub_ps(a.v, b.v) }; }
inline V4 vmul(V4 a, V4 b) { return { _mm_mul_ps(a.v, b.v) }; }
inline V4 xyz(V4 a) { return { _mm_and_ps(a.v, _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1))) }; } // lane 3 = 0
inline void truncToInt(V4 a, int32_t out[4]) { _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(a.v)); }
#else
template <class F>
inline V4 lanes(V4 a, V4 b, F f)
{
    V4 r;
    for (int i = 0; i < 4; ++i) r.v[i] = f(a.v[i], b.v[i]);
    return r;
}
inline V4 splat(float f) { return { { f, f, f, f } }; }
inline V4 set3(float x, float y, float z) { return { { x, y, z, 0.0f } }; }
inline V4 loadRow(const void* p)
{
    V4 r;
    std::memcpy(r.v, p, sizeof r.v);
    return r;
}
inline void store(float* p, V4 a) { std::memcpy(p, a.v, sizeof a.v); }
inline V4 vmin(V4 a, V4 b) { return lanes(a, b, [](float x, float y) { return x < y ? x : y; }); }
inline V4 vmax(V4 a, V4 b) { return lanes(a, b, [](float x, float y) { return x > y ? x : y; }); }
inline V4 vadd(V4 a, V4 b) { return lanes(a, b, [](float x, float y) { return x + y; }); }
inline V4 vsub(V4 a, V4 b) { return lanes(a, b, [](float x, float y) { return x - y; }); }
inline V4 vmul(V4 a, V4 b) { return lanes(a, b, [](float x, float y) { return x * y; }); }
inline V4 xyz(V4 a)
{
    a.v[3] = 0.0f;
    return a;
}
inline void truncToInt(V4 a, int32_t out[4])
{
    for (int i = 0; i < 4; ++i) out[i] = int32_t(a.v[i]);
}
#endif

// Position of keys[i] in the ascending order of keys[0, nPadded), ties broken by index. nPadded
// is a multiple of 4 and the padding keys are +inf (real keys are finite, so it never counts).
// Branch-free: used by the small-node sort, where comparison sorts mispredict a lot.
#if PT_BVH_SSE
inline int rankOf(const float* keys, int nPadded, int i)
{
    const __m128 ki = _mm_set1_ps(keys[i]);
    const __m128i ii = _mm_set1_epi32(i);
    __m128i idx = _mm_set_epi32(3, 2, 1, 0);
    __m128i count = _mm_setzero_si128();
    for (int b = 0; b < nPadded; b += 4) {
        const __m128 kj = _mm_loadu_ps(keys + b);
        const __m128 tieBefore = _mm_and_ps(_mm_cmpeq_ps(kj, ki), _mm_castsi128_ps(_mm_cmplt_epi32(idx, ii)));
        const __m128 before = _mm_or_ps(_mm_cmplt_ps(kj, ki), tieBefore);
        count = _mm_sub_epi32(count, _mm_castps_si128(before)); // true lanes are -1
        idx = _mm_add_epi32(idx, _mm_set1_epi32(4));
    }
    count = _mm_add_epi32(count, _mm_shuffle_epi32(count, _MM_SHUFFLE(1, 0, 3, 2)));
    count = _mm_add_epi32(count, _mm_shuffle_epi32(count, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtsi128_si32(count);
}
#else
inline int rankOf(const float* keys, int nPadded, int i)
{
    int rank = 0;
    for (int j = 0; j < nPadded; ++j) rank += int(keys[j] < keys[i]) | (int(keys[j] == keys[i]) & int(j < i));
    return rank;
}
#endif

// Lane 3 (integer payload) is zeroed so that it never feeds arithmetic as a denormal or NaN.
inline V4 loadLo(const PrimRef& r) { return xyz(loadRow(&r.lo[0])); }
inline V4 loadHi(const PrimRef& r) { return xyz(loadRow(&r.hi[0])); }
// (lo + hi) * 0.5 rather than lo * 0.5 + hi * 0.5: no FMA contraction can make two call sites
// round differently. Overflows only beyond 1.7e38.
inline V4 centroidOf(V4 lo, V4 hi) { return vmul(vadd(lo, hi), splat(0.5f)); }

struct Box4 {
    V4 lo = splat(kInf);
    V4 hi = splat(-kInf);

    void grow(V4 plo, V4 phi)
    {
        lo = vmin(lo, plo);
        hi = vmax(hi, phi);
    }
    void grow(V4 p) { grow(p, p); }
    void grow(const Box4& b) { grow(b.lo, b.hi); }
    void grow(const PrimRef& r) { grow(loadLo(r), loadHi(r)); }
    // Only meaningful for non-empty boxes.
    float area() const
    {
        float d[4];
        store(d, vsub(hi, lo));
        return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
    }
    glm::vec3 lo3() const
    {
        float f[4];
        store(f, lo);
        return { f[0], f[1], f[2] };
    }
    glm::vec3 hi3() const
    {
        float f[4];
        store(f, hi);
        return { f[0], f[1], f[2] };
    }
};

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

// Fixed chunking for flat parallel loops (independent of the thread count on purpose).
size_t chunkCount(size_t n) { return std::max<size_t>(1, std::min<size_t>(64, n / 16384)); }

std::pair<uint32_t, uint32_t> chunkRange(uint32_t begin, uint32_t end, size_t chunks, size_t c)
{
    const uint64_t n = end - begin;
    return { uint32_t(begin + n * c / chunks), uint32_t(begin + n * (c + 1) / chunks) };
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
        refs_.resize(n);

        // Root bounds over fixed chunks (exact min/max, so the merge order does not matter).
        const WorkItem root{ 0, 0, n, 0 };
        Box4 rootBounds;
        {
            const size_t chunks = chunkCount(n);
            std::vector<Box4> bb(chunks);
            parallelFor(threads_, chunks, [&](size_t c) {
                const auto [b, e] = chunkRange(0, n, chunks, c);
                for (uint32_t i = b; i < e; ++i) {
                    const Aabb& s = input_[i];
                    refs_[i] = PrimRef{ { s.lo.x, s.lo.y, s.lo.z }, i, { s.hi.x, s.hi.y, s.hi.z }, 0 };
                    bb[c].grow(refs_[i]);
                }
            });
            for (size_t c = 0; c < chunks; ++c) rootBounds.grow(bb[c]);
        }
        std::vector<BvhNode> nodes{ BvhNode{ rootBounds.lo3(), 0, rootBounds.hi3(), 0 } };

        // Phase 1: top of the tree, depth-first, deferring small nodes as tasks. `events` records,
        // in preorder, where a sequential build would have allocated nodes: a children pair of a
        // top node, or a task's whole subtree.
        struct Event {
            bool task;
            uint32_t index; // task index, or the (phase-1) index of the first node of a pair
        };
        std::vector<WorkItem> tasks;
        std::vector<Event> events;
        int maxDepth = 0;
        {
            std::vector<WorkItem> stack{ root };
            while (!stack.empty()) {
                const WorkItem item = stack.back();
                stack.pop_back();
                if (item.end - item.begin <= kTaskPrims) {
                    events.push_back({ true, uint32_t(tasks.size()) });
                    tasks.push_back(item);
                } else {
                    const size_t before = nodes.size();
                    processNode(nodes, item, stack, maxDepth);
                    if (nodes.size() != before) events.push_back({ false, uint32_t(before) });
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
        std::vector<BvhNode> placed(total);
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
            placed[topIndex[tasks[t].slot]] = remap(local[t][0]);
            for (size_t k = 1; k < local[t].size(); ++k) placed[base[t] + k - 1] = remap(local[t][k]);
            std::vector<BvhNode>().swap(local[t]);
        });
        nodes = std::move(placed);

        out.primOrder.resize(n);
        {
            const size_t chunks = chunkCount(n);
            parallelFor(threads_, chunks, [&](size_t c) {
                const auto [b, e] = chunkRange(0, n, chunks, c);
                for (uint32_t i = b; i < e; ++i) out.primOrder[i] = refs_[i].prim;
            });
        }
        std::vector<PrimRef>().swap(refs_);

        out.sahCost = sahCost(nodes, n);
        out.maxDepth = maxDepth;
        out.nodes = std::move(nodes);
    }

private:
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

    // Relative SAH cost of a split whose children's sum of area * count is `cost`. A zero-area node
    // (points or a line) makes every split free, and then only the leaf size limit splits it.
    float splitCost(float cost, float nodeArea) const
    {
        return traversalCost_ + intersectCost_ * (nodeArea > 0.0f ? cost / nodeArea : 0.0f);
    }

    // Bins [begin, end) on all three axes and caches every primitive's bins in binKeys.
    // An axis with zero centroid extent has scale 0: everything lands in bin 0 and the axis never
    // offers a split. The clamp is written so that a NaN (0 * inf for a denormal extent) gives 0.
    void binRange(uint32_t begin, uint32_t end, V4 origin, V4 scale, Bins& bins)
    {
        bins.reset(bins_);
        const V4 zero = splat(0.0f), last = splat(float(bins_ - 1));
        for (uint32_t i = begin; i < end; ++i) {
            PrimRef& r = refs_[i];
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

    Split findSplit(const Bins& bins) const
    {
        Split best;
        std::array<float, kMaxBins> rightArea;
        std::array<uint32_t, kMaxBins> rightCount;
        for (int a = 0; a < 3; ++a) {
            const auto& bc = bins.count[a];
            Box4 acc;
            uint32_t cnt = 0;
            float area = 0.0f;
            for (int i = bins_ - 1; i >= 1; --i) {
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
            for (int i = 1; i < bins_; ++i) {
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
    uint32_t partition(uint32_t begin, uint32_t end, int axis, int splitBin)
    {
        const int shift = 8 * axis;
        uint32_t l = begin;
        for (uint32_t i = begin; i < end; ++i) {
            const PrimRef t = refs_[i];
            refs_[i] = refs_[l];
            refs_[l] = t;
            l += uint32_t(int((t.binKeys >> shift) & 0xffu) < splitBin);
        }
        return l;
    }

    // Centroid bounds of a range: exact min/max, so chunking for big ranges does not matter.
    Box4 centroidBounds(uint32_t begin, uint32_t end)
    {
        const auto pass = [&](uint32_t b, uint32_t e) {
            Box4 cb;
            for (uint32_t i = b; i < e; ++i) cb.grow(centroidOf(loadLo(refs_[i]), loadHi(refs_[i])));
            return cb;
        };
        const size_t chunks = std::min<size_t>(size_t(threads_), 8);
        if (end - begin < kParallelBinPrims || chunks < 2) return pass(begin, end);
        std::vector<Box4> partial(chunks);
        parallelFor(threads_, chunks, [&](size_t c) {
            const auto [b, e] = chunkRange(begin, end, chunks, c);
            partial[c] = pass(b, e);
        });
        for (size_t c = 1; c < chunks; ++c) partial[0].grow(partial[c]);
        return partial[0];
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

    // Binned SAH for bigger nodes (binning in parallel for the biggest). Returns false for a leaf.
    bool binnedSplit(const WorkItem& item, float nodeArea, Box4& lb, Box4& rb, uint32_t& mid)
    {
        const uint32_t n = item.end - item.begin;
        const Box4 cb = centroidBounds(item.begin, item.end);
        float lo[4], hi[4];
        store(lo, cb.lo);
        store(hi, cb.hi);
        float sc[3];
        for (int a = 0; a < 3; ++a) {
            const float extent = hi[a] - lo[a];
            sc[a] = extent > 0.0f ? float(bins_) / extent : 0.0f;
        }
        if (sc[0] > 0.0f || sc[1] > 0.0f || sc[2] > 0.0f) {
            const V4 origin = set3(lo[0], lo[1], lo[2]), scale = set3(sc[0], sc[1], sc[2]);
            Bins bins;
            const size_t chunks = std::min<size_t>(size_t(threads_), 8);
            if (n >= kParallelBinPrims && chunks > 1) {
                std::vector<Bins> partial(chunks);
                parallelFor(threads_, chunks, [&](size_t c) {
                    const auto [b, e] = chunkRange(item.begin, item.end, chunks, c);
                    binRange(b, e, origin, scale, partial[c]);
                });
                bins = partial[0];
                for (size_t c = 1; c < chunks; ++c) bins.merge(partial[c], bins_);
            } else {
                binRange(item.begin, item.end, origin, scale, bins);
            }
            const Split split = findSplit(bins);
            if (split.axis >= 0) {
                if (n <= maxLeaf_ && intersectCost_ * float(n) <= splitCost(split.cost, nodeArea)) return false;
                mid = partition(item.begin, item.end, split.axis, split.bin);
                // The children's boxes are the unions of their bins: every primitive's whole box
                // went into the bin its cached key names, so these are exact and tight.
                for (int i = 0; i < bins_; ++i)
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
        return true;
    }

    // Decides leaf or split for one node; on a split appends the two children (adjacent) and
    // pushes them so that the left child is processed next (depth-first).
    void processNode(std::vector<BvhNode>& nodes, const WorkItem& item, std::vector<WorkItem>& stack, int& maxDepth)
    {
        const uint32_t n = item.end - item.begin;
        Box4 lb, rb;
        uint32_t mid = item.begin;
        bool split = false;
        if (n > 1) {
            const float nodeArea = boxArea(nodes[item.slot].lo, nodes[item.slot].hi);
            split = n <= uint32_t(kSweepPrims) ? sweepSplit(item, nodeArea, lb, rb, mid)
                                               : binnedSplit(item, nodeArea, lb, rb, mid);
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
        stack.push_back(WorkItem{ left + 1, mid, item.end, item.depth + 1 });
        stack.push_back(WorkItem{ left, item.begin, mid, item.depth + 1 });
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
