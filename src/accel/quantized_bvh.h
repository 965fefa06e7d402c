#pragma once
// The four-wide tree's nodes as the kernel stores them: child boxes quantised to 8 bits per
// plane relative to the node's own box (GpuBvh4QNode in shared/layout.h). Decoding is exact
// float arithmetic (q * 2^e is exact, then one rounded addition), done the same way here and in
// the kernel (loadBvh4Node, shaders/common/buffers.glsl), and every decoded box contains the
// exact box it stands for, so the traversal stays conservative.
#include "shared/layout.h"

#include <vector>

namespace pt {

// Quantises one node. Unused slots (child word BVH4_EMPTY) get zero planes: the child word,
// not the box, keeps them out of the traversal.
gpu::GpuBvh4QNode quantizeWideNode(const gpu::GpuBvh4Node& node);
std::vector<gpu::GpuBvh4QNode> quantizeWideNodes(const std::vector<gpu::GpuBvh4Node>& nodes);

// The boxes the kernel sees: the decoded node, unused slots with empty boxes as in GpuBvh4Node.
gpu::GpuBvh4Node decodeWideNode(const gpu::GpuBvh4QNode& node);

} // namespace pt
