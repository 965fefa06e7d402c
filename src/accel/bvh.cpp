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
//
// Files: this one (the outline above and the assembly), bvh_top_phase.cpp (phase 1),
// bvh_task_phase.cpp (phase 2), bvh_binning.h (the binned SAH both use), bvh_builder.h (the
// builder class), bvh_simd.h, bvh_parallel.h and huge_page_allocator.h (the build's memory).
#include "accel/bvh.h"

#include "accel/bvh_builder.h"
#include "accel/bvh_parallel.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace pt {

void Aabb::grow(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Aabb::grow(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
}

// Same formula as the builder's centroids ((lo + hi) * 0.5, not contractible into an FMA).
glm::vec3 Aabb::centroid() const { return (lo + hi) * 0.5f; }

float Aabb::surfaceArea() const {
    if (empty()) return 0.0f;
    const glm::vec3 d = hi - lo;
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

bool Aabb::empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }

namespace bvh_detail {

Builder::Builder(std::span<const Aabb> primBounds, const BvhBuildOptions& o) : input_(primBounds) {
    bins_ = std::clamp(o.bins, 2, kMaxBins);
    maxLeaf_ = uint32_t(std::max(o.maxLeafSize, 1));
    traversalCost_ = o.traversalCost;
    intersectCost_ = o.intersectCost;
    threads_ = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

void Builder::run(Bvh& out) {
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
                refs_[i] = PrimRef{{s.lo.x, s.lo.y, s.lo.z}, i, {s.hi.x, s.hi.y, s.hi.z}, 0};
                bb[c].grow(refs_[i]);
                cb[c].grow(centroidOf(loadLo(refs_[i]), loadHi(refs_[i])));
            }
        });
        for (size_t c = 0; c < chunks; ++c) {
            rootBounds.grow(bb[c]);
            rootCentroids.grow(cb[c]);
        }
    }
    std::vector<BvhNode> nodes{BvhNode{rootBounds.lo3(), 0, rootBounds.hi3(), 0}};

    int maxDepth = 0;
    std::vector<Task> tasks;
    buildTop(nodes, WorkItem{0, 0, n, 0, rootCentroids}, tasks, maxDepth);

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
        std::vector<uint32_t> stack{0};
        while (!stack.empty()) {
            const uint32_t s = stack.back();
            stack.pop_back();
            if (taskOf[s] >= 0) {
                events.push_back({true, uint32_t(taskOf[s])});
            } else if (nodes[s].count == 0) {
                const uint32_t left = nodes[s].leftOrFirst;
                events.push_back({false, left});
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
            buildTask(tasks[t], nodes[tasks[t].work.slot], local[t], localDepth[t]);
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
    BvhNodeArray placed(total);                 // uninitialised: every node is written below
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

// Summed per fixed chunk, then the chunks in order: the same value for every thread count.
double Builder::sahCost(const BvhNodeArray& nodes, uint32_t primCount) const {
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

} // namespace bvh_detail

namespace {
// Node indices are uint32_t and a tree over N prims has up to 2N-1 nodes.
constexpr size_t kMaxPrims = (size_t(1) << 31) - 1;
} // namespace

Bvh buildBvh(std::span<const Aabb> primBounds, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    if (primBounds.size() > kMaxPrims) throw std::length_error("buildBvh: more than 2^31-1 primitives");
    Bvh bvh;
    if (!primBounds.empty()) bvh_detail::Builder(primBounds, options).run(bvh);
    bvh.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

} // namespace pt
