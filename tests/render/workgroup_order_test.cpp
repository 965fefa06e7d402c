// The order of a dispatch's workgroups over its blocks (render/workgroup_order.h): a bijection
// for every block count, and every run of consecutive workgroups (what lavapipe hands one
// thread) spread over the whole tile, where row-major order gives each run a band of rows.
#include "render/workgroup_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace pt {
namespace {

// Block of workgroup l in a grid of `blocks` blocks, as integrator/pixel_groups.glsl computes it.
uint32_t blockOf(uint64_t l, uint32_t stride, uint32_t blocks) { return uint32_t(l * stride % blocks); }

TEST(WorkgroupOrder, EveryBlockIsRenderedOnce) {
    for (uint32_t blocks = 1; blocks <= 4096; ++blocks) {
        const uint32_t stride = workgroupBlockStride(blocks);
        std::vector<int> seen(blocks, 0);
        for (uint32_t l = 0; l < blocks; ++l) ++seen[blockOf(l, stride, blocks)];
        ASSERT_EQ(std::count(seen.begin(), seen.end(), 1), blocks) << blocks << " blocks, stride " << stride;
    }
    // A tile of 16384 x 16384 pixels: l * stride needs 64 bits, as the shader computes it.
    const uint32_t huge = 2048u * 2048u;
    EXPECT_EQ(std::gcd(workgroupBlockStride(huge), huge), 1u);
}

// The largest distance, over the runs of `threads` equal runs of consecutive workgroups, of a
// run's mean block row and column (as fractions of the grid) from the grid's centre.
double worstRunImbalance(uint32_t blocksX, uint32_t blocksY, uint32_t stride, uint32_t threads) {
    const uint32_t blocks = blocksX * blocksY;
    double worst = 0.0;
    for (uint32_t t = 0; t < threads; ++t) {
        double row = 0.0, column = 0.0;
        const uint32_t first = t * blocks / threads, end = (t + 1) * blocks / threads;
        for (uint32_t l = first; l < end; ++l) {
            const uint32_t b = blockOf(l, stride, blocks);
            row += double(b / blocksX) / std::max(blocksY - 1, 1u);
            column += double(b % blocksX) / std::max(blocksX - 1, 1u);
        }
        worst = std::max({worst, std::abs(row / (end - first) - 0.5), std::abs(column / (end - first) - 0.5)});
    }
    return worst;
}

TEST(WorkgroupOrder, EachThreadsRunSpansTheTile) {
    // 128x128 (the mesh benchmark), 256x256, 720p and 1080p images, an odd tile.
    const uint32_t grids[][2] = {{16, 16}, {32, 32}, {160, 90}, {240, 135}, {40, 23}};
    for (const auto& g : grids)
        for (uint32_t threads = 2; threads <= 8; ++threads) {
            EXPECT_LT(worstRunImbalance(g[0], g[1], workgroupBlockStride(g[0] * g[1]), threads), 0.06)
                << g[0] << "x" << g[1] << " blocks, " << threads << " threads";
            // Row-major order (stride 1) gives the first thread the top rows.
            EXPECT_GT(worstRunImbalance(g[0], g[1], 1, threads), 0.2);
        }
}

} // namespace
} // namespace pt
