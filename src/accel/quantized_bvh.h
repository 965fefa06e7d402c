#pragma once
// The four-wide tree's nodes as the kernel stores them: child boxes quantised to 8 bits per
// plane relative to the node's own box (GpuBvh4QNode in shared/layout.h). The origin is a
// multiple of the scale 2^e, so decoding origin + q * 2^e is exact float arithmetic, the same
// here and in the kernel (loadBvh4QNode, shaders/common/buffers.glsl; the traversal's
// quantizedChildEntries folds it into distances), and every decoded box contains the exact box
// it stands for, so the traversal stays conservative. (Only axes whose coordinates come near the
// float range's end, far outside what the renderer quantises, keep a rounded decode.)
#include "shared/layout.h"

#include <vector>

namespace pt {

// Quantises one node. Unused slots (child word BVH4_EMPTY) get zero planes: the child word,
// not the box, keeps them out of the traversal.
gpu::GpuBvh4QNode quantizeWideNode(const gpu::GpuBvh4Node& node);

// Whether a tree may be stored quantised: every child box within 2^60 of the origin, so that the
// kernel's folded decode (scale / d, (origin - o) / d) stays far from overflow. Farther trees keep
// float nodes.
bool quantizable(const std::vector<gpu::GpuBvh4Node>& nodes);
std::vector<gpu::GpuBvh4QNode> quantizeWideNodes(const std::vector<gpu::GpuBvh4Node>& nodes);

// The boxes the kernel sees: the decoded node, unused slots with empty boxes as in GpuBvh4Node.
gpu::GpuBvh4Node decodeWideNode(const gpu::GpuBvh4QNode& node);

} // namespace pt
