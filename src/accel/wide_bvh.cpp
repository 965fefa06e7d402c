// Collapse of the binary tree into four-wide nodes (see wide_bvh.h). Opening the child of
// largest area first is the greedy rule of Embree's and pbrt's wide builders: the children a
// ray is most likely to enter are split where they cost most.
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

class Collapser {
public:
    explicit Collapser(const Bvh& bvh) : bvh_(bvh) {}

    WideBvh run() {
        WideBvh out;
        if (bvh_.nodes.empty()) return out;
        out.nodes.reserve(bvh_.nodes.size() / 2 + 1);
        nodes_ = &out.nodes;
        const Result r = emit(0);
        out.depth = r.depth;
        out.stackNeed = r.stackNeed;
        return out;
    }

private:
    struct Result {
        int depth;
        int stackNeed;
    };

    // The children a wide node built from binary node `index` takes: for an inner node its
    // children, opened greedily; a leaf root stands alone.
    std::vector<uint32_t> childrenOf(uint32_t index) const {
        const BvhNode& n = bvh_.nodes[index];
        if (n.count != 0) return {index};
        std::vector<uint32_t> children = {n.leftOrFirst, n.leftOrFirst + 1};
        while (children.size() < size_t(kWidth)) {
            int best = -1;
            float bestArea = -1.0f;
            for (size_t i = 0; i < children.size(); ++i) {
                const BvhNode& c = bvh_.nodes[children[i]];
                const float area = boxOf(c).surfaceArea();
                if (c.count == 0 && area > bestArea) best = int(i), bestArea = area;
            }
            if (best < 0) break;
            const uint32_t opened = children[size_t(best)];
            const uint32_t left = bvh_.nodes[opened].leftOrFirst;
            children[size_t(best)] = left; // keep left-to-right order: the tree's spatial order
            children.insert(children.begin() + best + 1, left + 1);
        }
        return children;
    }

    uint32_t leafWord(const BvhNode& leaf) const {
        if (leaf.count > BVH4_MAX_LEAF_PRIMITIVES)
            throw std::length_error("BVH leaf of " + std::to_string(leaf.count) +
                                    " primitives; a wide node holds at most " +
                                    std::to_string(BVH4_MAX_LEAF_PRIMITIVES));
        if (uint64_t(leaf.leftOrFirst) + leaf.count > uint64_t(BVH4_FIRST_MASK) + 1)
            throw std::length_error("BVH over more than " + std::to_string(uint64_t(BVH4_FIRST_MASK) + 1) +
                                    " primitives; the wide BVH indexes at most that many");
        return BVH4_LEAF_BIT | ((leaf.count - 1) << BVH4_COUNT_SHIFT) | leaf.leftOrFirst;
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
            const BvhNode& c = bvh_.nodes[children[i]];
            if (c.count != 0) {
                words[i] = leafWord(c);
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
    std::vector<gpu::GpuBvh4Node>* nodes_ = nullptr;
};

} // namespace

WideBvh collapseToWide(const Bvh& bvh) { return Collapser(bvh).run(); }

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
