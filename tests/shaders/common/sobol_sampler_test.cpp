// The Owen-scrambled Sobol' sampler (shaders/common/sobol.glsl) run through the test kernel:
// one pixel's stream of 2D points, in sample order, as a render draws them, and the 4D points
// of consecutive bounces' directions (common/rng.glsl).
#include "support/gpu_test_support.h"

#include "shared/layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

namespace pt::test {
namespace {

constexpr uint32_t kPoints = 1u << 16;

class SobolSampler : public GpuTest {};

std::vector<glm::vec4> sobolPoints(uint32_t seed) {
    return runTestKernel(TEST_MODE_SOBOL_POINTS, kPoints, nullptr, {}, {}, {0, 0, 1}, seed);
}

// Number of the first `n` points (x, y) that share an elementary interval of size
// 2^-a x 2^-(k-a) with an earlier one, over every a; zero for a (0, k, 2)-net with n = 2^k.
size_t pointsSharingAnInterval(const std::vector<glm::vec4>& points, int k, bool secondPair) {
    const uint32_t n = 1u << k;
    size_t shared = 0;
    for (int a = 0; a <= k; ++a) {
        std::set<uint64_t> cells;
        for (uint32_t i = 0; i < n; ++i) {
            const float x = secondPair ? points[i].z : points[i].x, y = secondPair ? points[i].w : points[i].y;
            const uint64_t cx = static_cast<uint64_t>(std::ldexp(double(x), a));
            const uint64_t cy = static_cast<uint64_t>(std::ldexp(double(y), k - a));
            if (!cells.insert((cx << 32) | cy).second) ++shared;
        }
    }
    return shared;
}

// Every power-of-two prefix of a pixel's samples is a (0, k, 2)-net in each 2D pair: one point
// in every elementary interval. Independent random points fail this at once.
TEST_F(SobolSampler, PowerOfTwoPrefixesAreNetsInEveryPair) {
    for (uint32_t seed : {1u, 77u}) {
        const auto points = sobolPoints(seed);
        for (int k : {2, 5, 8, 12, 14})
            for (bool second : {false, true})
                EXPECT_EQ(pointsSharingAnInterval(points, k, second), 0u)
                    << "seed " << seed << ", 2^" << k << " points";
    }
}

// The test can fail: a prefix of 2^k + 1 points, or shifted by one, is not a net.
TEST_F(SobolSampler, NetCheckDetectsAPrefixThatIsNotANet) {
    auto points = sobolPoints(1);
    points.erase(points.begin());
    EXPECT_GT(pointsSharingAnInterval(points, 8, false), 0u);
}

// Values in [0, 1), each of the two 2D pairs uniform (chi-square on a 32 x 32 grid), and the
// pairs of one sample uncorrelated with each other.
void expectUniformAndUncorrelated(const std::vector<glm::vec4>& points) {
    std::vector<double> counts(32 * 32, 0.0), countsSecond(32 * 32, 0.0);
    double sxz = 0, sx = 0, sz = 0, sxx = 0, szz = 0;
    for (const glm::vec4& p : points) {
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(p[c] >= 0.0f && p[c] < 1.0f) << p[c];
        counts[int(p.y * 32) * 32 + int(p.x * 32)] += 1;
        countsSecond[int(p.w * 32) * 32 + int(p.z * 32)] += 1;
        sxz += double(p.x) * p.z;
        sx += p.x;
        sz += p.z;
        sxx += double(p.x) * p.x;
        szz += double(p.z) * p.z;
    }
    const std::vector<double> expected(counts.size(), double(points.size()) / counts.size());
    const double pFirst = chiSquarePValue(counts, expected), pSecond = chiSquarePValue(countsSecond, expected);
    std::printf("[          ] chi-square p-values %.3g %.3g (stratified points give values near 1)\n", pFirst, pSecond);
    EXPECT_GT(pFirst, 1e-3);
    EXPECT_GT(pSecond, 1e-3);
    const double n = double(points.size());
    const double correlation =
        (sxz / n - sx / n * sz / n) / std::sqrt((sxx / n - sx / n * sx / n) * (szz / n - sz / n * sz / n));
    EXPECT_LT(std::abs(correlation), 4.0 / std::sqrt(n)) << correlation;
}

TEST_F(SobolSampler, PointsAreUniformAndPairsUncorrelated) { expectUniformAndUncorrelated(sobolPoints(5)); }

// Pixels get different scrambles: the same sample index in two pixels gives unrelated points.
TEST_F(SobolSampler, SeedsDecorrelateStreams) {
    const auto a = sobolPoints(1), b = sobolPoints(2);
    size_t equal = 0;
    for (uint32_t i = 0; i < kPoints; ++i) equal += a[i].x == b[i].x;
    EXPECT_LT(equal, 16u);
}

std::vector<glm::vec4> bouncePairPoints(uint32_t seed) {
    return runTestKernel(TEST_MODE_SOBOL_BOUNCE_PAIR, kPoints, nullptr, {}, {}, {0, 0, 1}, seed);
}

// Whether the first 2^k points are a (t, k, s)-net in the coordinates `dims` (indices into the
// vec4): every elementary interval of volume 2^(t - k), 2^-a_j wide along dims[j] with the a_j
// summing to k - t, holds exactly 2^t points.
bool isNet(const std::vector<glm::vec4>& points, int k, int t, const std::vector<int>& dims) {
    const uint32_t n = 1u << k;
    std::vector<int> widths(dims.size(), 0);
    // Every split of k - t bits over the dimensions, as an odometer over 0..k-t per dimension.
    while (true) {
        int sum = 0;
        for (int w : widths) sum += w;
        if (sum == k - t) {
            std::map<uint64_t, uint32_t> cells;
            for (uint32_t i = 0; i < n; ++i) {
                uint64_t key = 0;
                for (size_t j = 0; j < dims.size(); ++j)
                    key = (key << 16) | static_cast<uint64_t>(std::ldexp(double(points[i][dims[j]]), widths[j]));
                ++cells[key];
            }
            if (cells.size() != (size_t(1) << (k - t))) return false;
            for (const auto& [cell, count] : cells)
                if (count != (1u << t)) return false;
        }
        size_t j = 0;
        while (j < widths.size() && ++widths[j] > k - t) widths[j++] = 0;
        if (j == widths.size()) return true;
    }
}

// The directions of bounces 1 and 2 are one 4D Sobol' point (common/rng.glsl): each power-of-two
// prefix is a (0, k, 2)-net in the first direction, a net with t <= 2 in the second (Sobol'
// dimensions 2-3), and a (3, k, 4)-net in all four coordinates, which padded (independent) pairs
// are not: the same check fails on two unpaired streams.
TEST_F(SobolSampler, ConsecutiveBouncesAreOne4DPoint) {
    for (uint32_t seed : {1u, 77u}) {
        const auto points = bouncePairPoints(seed);
        for (int k : {4, 6, 8, 10}) {
            EXPECT_TRUE(isNet(points, k, 0, {0, 1})) << "seed " << seed << ", 2^" << k;
            EXPECT_TRUE(isNet(points, k, 2, {2, 3})) << "seed " << seed << ", 2^" << k;
            EXPECT_TRUE(isNet(points, k, 3, {0, 1, 2, 3})) << "seed " << seed << ", 2^" << k;
        }
    }
    const auto unpaired = sobolPoints(1);
    EXPECT_TRUE(isNet(unpaired, 8, 0, {2, 3}));
    EXPECT_FALSE(isNet(unpaired, 8, 3, {0, 1, 2, 3}));
}

// The pairing keeps what the other tests ask of every stream: uniform, and the two directions
// uncorrelated.
TEST_F(SobolSampler, PairedBouncesAreUniformAndUncorrelated) { expectUniformAndUncorrelated(bouncePairPoints(5)); }

} // namespace
} // namespace pt::test
