// Collapse of the binary tree into four-wide nodes (see wide_bvh.h), chosen by dynamic
// programming over the binary tree rather than by the greedy rule of opening the child of
// largest area (Embree's and pbrt's): the optimum also merges small binary subtrees into one
// leaf and fills the slots the greedy rule left empty beside leaves (3.5 children a node
// against 3.0 on a 1 M-triangle surface, a fifth fewer nodes; bench/RESULTS.md, "Optimal
// collapse").
#include "accel/wide_bvh.h"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>

namespace pt {
namespace {

constexpr int kWidth = 4;

Aabb boxOf(const BvhNode& n) {
    Aabb b;
    b.lo = n.lo;
    b.hi = n.hi;
    return b;
}

// The collapse as an optimisation (Ylitie, Karras and Laine, "Efficient incoherent ray
// traversal on GPUs through compressed wide BVHs", 2017): for every binary node n and slot
// budget i (1..4), cost[n][i] is the least SAH cost of covering n's subtree with at most i
// wide-tree children (each a wide node or a leaf). Bottom-up over the binary tree (a child's
// index is above its parent's), then read back from the root.
class Collapser {
public:
    Collapser(const Bvh& bvh, const WideCollapseOptions& options) : bvh_(bvh), options_(options) {}

    WideBvh run() {
        WideBvh out;
        if (bvh_.nodes.empty()) return out;
        solve();
        out.nodes.reserve(bvh_.nodes.size() / 4 + 1);
        nodes_ = &out.nodes;
        const Result r = emit(0);
        out.depth = r.depth;
        out.stackNeed = r.stackNeed;
        return out;
    }

private:
    static constexpr float kInfinity = std::numeric_limits<float>::infinity();
    static constexpr uint8_t kFewerSlots = 0xff; // cost[n][i] is cost[n][i - 1]: no use for slot i

    struct Result {
        int depth;
        int stackNeed;
    };

    struct Plan {
        std::array<float, kWidth + 1> cost;     // [1..kWidth]; [0] unused
        std::array<uint8_t, kWidth + 1> choice; // [1]: 1 leaf, 0 wide node; [i >= 2]: slots given to
                                                // the left child, or kFewerSlots
        std::array<uint8_t, kWidth + 1> split;  // [j >= 2]: the best slots for the left child when
                                                // the two children share j slots
        uint32_t first;                         // first primitive of the subtree
        uint32_t count;                         // primitives in the subtree
    };

    bool isBinaryLeaf(uint32_t n) const { return bvh_.nodes[n].count != 0; }

    float leafCost(uint32_t n) const {
        const Plan& p = plans_[n];
        if (p.count > uint32_t(options_.maxLeafSize) && !isBinaryLeaf(n)) return kInfinity;
        return area(n) * (options_.leafCost + options_.primitiveCost * float(p.count));
    }

    float area(uint32_t n) const { return boxOf(bvh_.nodes[n]).surfaceArea(); }

    void solve() {
        plans_.resize(bvh_.nodes.size());
        for (size_t k = bvh_.nodes.size(); k-- > 0;) {
            const uint32_t n = uint32_t(k);
            const BvhNode& node = bvh_.nodes[n];
            Plan& p = plans_[n];
            if (isBinaryLeaf(n)) {
                p.first = node.leftOrFirst;
                p.count = node.count;
                p.cost.fill(leafCost(n));
                p.choice.fill(kFewerSlots);
                p.choice[1] = 1;
                continue;
            }
            const Plan& l = plans_[node.leftOrFirst];
            const Plan& r = plans_[node.leftOrFirst + 1];
            p.first = l.first;
            p.count = l.count + r.count;
            // Both children's slot budgets summing to j, for j = 2..kWidth.
            std::array<float, kWidth + 1> shared;
            shared.fill(kInfinity);
            for (int j = 2; j <= kWidth; ++j)
                for (int left = 1; left < j; ++left) {
                    const float c = l.cost[size_t(left)] + r.cost[size_t(j - left)];
                    if (c < shared[size_t(j)]) shared[size_t(j)] = c, p.split[size_t(j)] = uint8_t(left);
                }
            const float asNode = area(n) * options_.nodeCost + shared[kWidth];
            const float asLeaf = leafCost(n);
            p.cost[1] = std::min(asNode, asLeaf);
            p.choice[1] = asLeaf <= asNode ? 1 : 0;
            for (int i = 2; i <= kWidth; ++i) {
                if (shared[size_t(i)] < p.cost[size_t(i - 1)]) {
                    p.cost[size_t(i)] = shared[size_t(i)];
                    p.choice[size_t(i)] = p.split[size_t(i)];
                } else {
                    p.cost[size_t(i)] = p.cost[size_t(i - 1)];
                    p.choice[size_t(i)] = kFewerSlots;
                }
            }
        }
    }

    // The wide-tree children covering binary node n's subtree with at most `slots` of them, in
    // the binary tree's left-to-right (spatial) order.
    void collect(uint32_t n, int slots, std::vector<uint32_t>& out) const {
        while (slots > 1 && plans_[n].choice[size_t(slots)] == kFewerSlots) --slots;
        if (slots == 1 || isBinaryLeaf(n)) {
            out.push_back(n);
            return;
        }
        const int left = plans_[n].choice[size_t(slots)];
        collect(bvh_.nodes[n].leftOrFirst, left, out);
        collect(bvh_.nodes[n].leftOrFirst + 1, slots - left, out);
    }

    // The children of the wide node standing for binary node n: the best split of n's subtree
    // over all four slots, or n itself as one leaf where that is cheaper (a tiny tree's root).
    std::vector<uint32_t> childrenOf(uint32_t n) const {
        std::vector<uint32_t> children;
        if (isBinaryLeaf(n) || plans_[n].choice[1] == 1) return {n};
        const BvhNode& node = bvh_.nodes[n];
        const int left = plans_[n].split[kWidth];
        collect(node.leftOrFirst, left, children);
        collect(node.leftOrFirst + 1, kWidth - left, children);
        return children;
    }

    // Whether wide-tree child n (from collect) is a leaf.
    bool becomesLeaf(uint32_t n) const { return isBinaryLeaf(n) || plans_[n].choice[1] == 1; }

    uint32_t leafWord(uint32_t n) const {
        const Plan& p = plans_[n];
        if (p.count > BVH4_MAX_LEAF_PRIMITIVES)
            throw std::length_error("BVH leaf of " + std::to_string(p.count) +
                                    " primitives; a wide node holds at most " +
                                    std::to_string(BVH4_MAX_LEAF_PRIMITIVES));
        if (uint64_t(p.first) + p.count > uint64_t(BVH4_FIRST_MASK) + 1)
            throw std::length_error("BVH over more than " + std::to_string(uint64_t(BVH4_FIRST_MASK) + 1) +
                                    " primitives; the wide BVH indexes at most that many");
        return BVH4_LEAF_BIT | ((p.count - 1) << BVH4_COUNT_SHIFT) | p.first;
    }

    // Emits the wide node for binary node `index` and, depth-first, its subtrees.
    Result emit(uint32_t index) {
        const std::vector<uint32_t> children = childrenOf(index);
        const size_t self = nodes_->size();
        nodes_->emplace_back();
        std::array<uint32_t, kWidth> words;
        words.fill(BVH4_EMPTY);
        Result r{1, int(children.size()) - 1};
        int deepestChildNeed = 0;
        for (size_t i = 0; i < children.size(); ++i) {
            if (becomesLeaf(children[i])) {
                words[i] = leafWord(children[i]);
                continue;
            }
            if (nodes_->size() > size_t(BVH4_FIRST_MASK)) throw std::length_error("wide BVH of more than 2^27 nodes");
            words[i] = uint32_t(nodes_->size());
            const Result sub = emit(children[i]);
            r.depth = std::max(r.depth, sub.depth + 1);
            deepestChildNeed = std::max(deepestChildNeed, sub.stackNeed);
        }
        r.stackNeed += deepestChildNeed;
        gpu::GpuBvh4Node& node = (*nodes_)[self];
        constexpr float kMax = std::numeric_limits<float>::max();
        for (int i = 0; i < kWidth; ++i) {
            const bool used = size_t(i) < children.size();
            const glm::vec3 lo = used ? bvh_.nodes[children[size_t(i)]].lo : glm::vec3(kMax);
            const glm::vec3 hi = used ? bvh_.nodes[children[size_t(i)]].hi : glm::vec3(-kMax);
            node.loX[i] = lo.x, node.loY[i] = lo.y, node.loZ[i] = lo.z;
            node.hiX[i] = hi.x, node.hiY[i] = hi.y, node.hiZ[i] = hi.z;
            node.child[i] = words[size_t(i)];
        }
        return r;
    }

    const Bvh& bvh_;
    WideCollapseOptions options_;
    std::vector<Plan> plans_;
    std::vector<gpu::GpuBvh4Node>* nodes_ = nullptr;
};

} // namespace

WideBvh collapseToWide(const Bvh& bvh, const WideCollapseOptions& options) { return Collapser(bvh, options).run(); }

Aabb wideNodeBounds(const gpu::GpuBvh4Node& node) {
    Aabb box;
    for (int i = 0; i < kWidth; ++i) {
        if (node.child[i] == BVH4_EMPTY) continue;
        box.grow(glm::vec3(node.loX[i], node.loY[i], node.loZ[i]));
        box.grow(glm::vec3(node.hiX[i], node.hiY[i], node.hiZ[i]));
    }
    return box;
}

} // namespace pt
