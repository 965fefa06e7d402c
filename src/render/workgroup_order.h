#pragma once
// The order in which a dispatch's workgroups visit its 8x8 blocks (GpuRenderPush::blockStride,
// integrator/pixel_groups.glsl). Lavapipe splits a dispatch's workgroups into one contiguous run
// per thread, fixed in advance; rendered row by row, the run with the image's costliest rows
// (where adaptive sampling puts its samples) ended last and the other threads idled. Workgroup
// l renders block (l * stride) mod blocks: with the stride coprime with the count near its
// golden section, consecutive workgroups jump by about 0.618 of the tile (a Kronecker
// sequence), so every run, whatever the thread count, samples the whole tile evenly.

#include <cstdint>
#include <numeric>

namespace pt {

inline uint32_t workgroupBlockStride(uint32_t blocks) {
    if (blocks <= 2) return 1;
    uint32_t stride = static_cast<uint32_t>(0.6180339887498949 * blocks + 0.5);
    while (std::gcd(stride, blocks) != 1) ++stride; // a prime gap: a few steps at most
    return stride;
}

} // namespace pt
