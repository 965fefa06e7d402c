// Host tests of the quantised node format (src/accel/quantized_bvh.cpp): every decoded child box
// contains its exact box, is at most a step or two of its axis' scale larger on each side, and
// the format survives the coordinates the hard cases use (huge, tiny, flat, negative).
#include "accel/quantized_bvh.h"

#include "accel/bvh.h"
#include "accel/wide_bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

using pt::gpu::GpuBvh4Node;
using pt::gpu::GpuBvh4QNode;

// A node over four random child boxes around `centre`, each up to `size` across.
GpuBvh4Node randomNode(std::mt19937& rng, float centre, float size, int children) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), e(0.0f, 1.0f);
    GpuBvh4Node n{};
    for (int i = 0; i < 4; ++i) {
        const bool used = i < children;
        n.child[i] = used ? uint32_t(i + 1) : BVH4_EMPTY;
        for (int a = 0; a < 3; ++a) {
            const float c = centre + u(rng) * size, half = e(rng) * size * 0.5f;
            glm::vec4& lo = a == 0 ? n.loX : a == 1 ? n.loY : n.loZ;
            glm::vec4& hi = a == 0 ? n.hiX : a == 1 ? n.hiY : n.hiZ;
            lo[i] = used ? c - half : std::numeric_limits<float>::max();
            hi[i] = used ? c + half : -std::numeric_limits<float>::max();
        }
    }
    return n;
}

float scaleOfAxis(const GpuBvh4QNode& q, int axis) {
    const uint32_t bits = ((q.exponents >> (8 * axis)) & 0xffu) << 23;
    float s;
    std::memcpy(&s, &bits, sizeof s);
    return s;
}

// Checks containment and tightness of every used slot; returns the largest overshoot in steps.
float checkNode(const GpuBvh4Node& exact) {
    const GpuBvh4QNode q = pt::quantizeWideNode(exact);
    const GpuBvh4Node decoded = pt::decodeWideNode(q);
    EXPECT_EQ(decoded.child, exact.child);
    float worst = 0.0f;
    const glm::vec4* lo[3][2] = {{&exact.loX, &decoded.loX}, {&exact.loY, &decoded.loY}, {&exact.loZ, &decoded.loZ}};
    const glm::vec4* hi[3][2] = {{&exact.hiX, &decoded.hiX}, {&exact.hiY, &decoded.hiY}, {&exact.hiZ, &decoded.hiZ}};
    for (int a = 0; a < 3; ++a) {
        const float scale = scaleOfAxis(q, a);
        for (int i = 0; i < 4; ++i) {
            if (exact.child[i] == BVH4_EMPTY) continue;
            const float exactLo = (*lo[a][0])[i], gotLo = (*lo[a][1])[i];
            const float exactHi = (*hi[a][0])[i], gotHi = (*hi[a][1])[i];
            EXPECT_LE(gotLo, exactLo) << "axis " << a << " slot " << i;
            EXPECT_GE(gotHi, exactHi) << "axis " << a << " slot " << i;
            if (std::isfinite(gotHi)) {
                // One step of the scale, plus the rounding of the origin's addition.
                const float slack = scale + std::abs(exactHi) * 4e-7f + std::abs(exactLo) * 4e-7f;
                EXPECT_LE(exactLo - gotLo, slack) << "axis " << a << " slot " << i;
                EXPECT_LE(gotHi - exactHi, slack) << "axis " << a << " slot " << i;
                worst = std::max(worst, std::max(exactLo - gotLo, gotHi - exactHi) / scale);
            }
        }
    }
    return worst;
}

TEST(QuantizedBvh, DecodedBoxesContainTheExactOnesWithinAStep) {
    std::mt19937 rng(7);
    const float centres[] = {0.0f, 1.0f, -3.5f, 1e4f, -1e4f, 1e7f, 3e-5f};
    const float sizes[] = {1.0f, 1e-3f, 20.0f, 1e5f, 1e-6f};
    for (float c : centres)
        for (float s : sizes)
            for (int children = 1; children <= 4; ++children)
                for (int k = 0; k < 40; ++k) checkNode(randomNode(rng, c, s, children));
}

TEST(QuantizedBvh, FlatAxesAndPointsDecodeExactly) {
    GpuBvh4Node n{};
    for (int i = 0; i < 4; ++i) {
        n.child[i] = uint32_t(i);
        n.loX[i] = n.hiX[i] = -2.0f; // flat in x
        n.loY[i] = float(i), n.hiY[i] = float(i) + 1.0f;
        n.loZ[i] = n.hiZ[i] = 1e30f; // far out and flat
    }
    const GpuBvh4Node d = pt::decodeWideNode(pt::quantizeWideNode(n));
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(d.loX[i], -2.0f);
        EXPECT_EQ(d.hiX[i], -2.0f);
        EXPECT_EQ(d.loZ[i], 1e30f);
        EXPECT_EQ(d.hiZ[i], 1e30f);
        EXPECT_LE(d.loY[i], n.loY[i]);
        EXPECT_GE(d.hiY[i], n.hiY[i]);
    }
}

TEST(QuantizedBvh, ExtentsNearTheFloatRangeStayConservative) {
    GpuBvh4Node n{};
    const float big = 3e38f;
    for (int i = 0; i < 4; ++i) {
        n.child[i] = uint32_t(i);
        n.loX[i] = -big, n.hiX[i] = big;
        n.loY[i] = -1.0f, n.hiY[i] = 1.0f;
        n.loZ[i] = 0.0f, n.hiZ[i] = big;
    }
    const GpuBvh4Node d = pt::decodeWideNode(pt::quantizeWideNode(n));
    for (int i = 0; i < 4; ++i) {
        EXPECT_LE(d.loX[i], -big);
        EXPECT_GE(d.hiX[i], big); // +inf is allowed: conservative
        EXPECT_GE(d.hiZ[i], big);
        EXPECT_FALSE(std::isnan(d.hiX[i]));
    }
}

TEST(QuantizedBvh, UnusedSlotsDecodeAsEmptyBoxes) {
    std::mt19937 rng(3);
    const GpuBvh4Node n = randomNode(rng, 0.0f, 1.0f, 2);
    const GpuBvh4Node d = pt::decodeWideNode(pt::quantizeWideNode(n));
    for (int i = 2; i < 4; ++i) {
        EXPECT_EQ(d.child[i], BVH4_EMPTY);
        EXPECT_GT(d.loX[i], d.hiX[i]);
    }
    // The origin: the exact low corner rounded down to a multiple of the scale.
    const GpuBvh4QNode q = pt::quantizeWideNode(n);
    EXPECT_LE(q.origin.x, pt::wideNodeBounds(n).lo.x);
    EXPECT_GT(q.origin.x, pt::wideNodeBounds(n).lo.x - scaleOfAxis(q, 0));
}

TEST(QuantizedBvh, OnlyTreesWithin2To60AreQuantizable) {
    std::mt19937 rng(9);
    std::vector<GpuBvh4Node> nodes{randomNode(rng, 0.0f, 1.0f, 4), randomNode(rng, 1e17f, 1e3f, 3)};
    EXPECT_TRUE(pt::quantizable(nodes));
    nodes.push_back(randomNode(rng, -1e19f, 1.0f, 2)); // beyond 2^60 = 1.15e18
    EXPECT_FALSE(pt::quantizable(nodes));
}

// The kernel folds the decode into ray distances, q * (scale / d) + (origin - o) / d, which is
// conservative only if origin + q * scale is the plane exactly: the origin is a multiple of the
// scale, so every decoded plane equals its exact value (computed in double), for every q.
TEST(QuantizedBvh, DecodedPlanesAreExact) {
    std::mt19937 rng(5);
    const float centres[] = {0.0f, 1.0f, -3.5f, 1e4f, -1e4f, 1e7f, -1e7f, 3e-5f, 1e12f};
    const float sizes[] = {1.0f, 1e-3f, 20.0f, 1e5f, 1e-6f, 1e-20f};
    int checked = 0;
    for (float c : centres)
        for (float s : sizes)
            for (int k = 0; k < 20; ++k) {
                const GpuBvh4QNode q = pt::quantizeWideNode(randomNode(rng, c, s, 4));
                for (int a = 0; a < 3; ++a) {
                    const float scale = scaleOfAxis(q, a);
                    EXPECT_EQ(std::fmod(double(q.origin[a]), double(scale)), 0.0) << "centre " << c << " size " << s;
                    for (uint32_t step = 0; step <= 255; step += 5) {
                        const float plane = q.origin[a] + float(step) * scale;
                        ASSERT_EQ(double(plane), double(q.origin[a]) + double(step) * double(scale))
                            << "centre " << c << " size " << s << " axis " << a << " q " << step;
                        ++checked;
                    }
                }
            }
    EXPECT_GT(checked, 10000);
}

TEST(QuantizedBvh, EveryNodeOfABuiltTreeIsConservative) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-50.0f, 50.0f), e(0.0f, 2.0f);
    std::vector<pt::Aabb> boxes(5000);
    for (pt::Aabb& b : boxes) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        b.grow(c - glm::vec3(e(rng)));
        b.grow(c + glm::vec3(e(rng)));
    }
    const pt::WideBvh wide = pt::collapseToWide(pt::buildBvh(boxes, {}));
    ASSERT_GT(wide.nodes.size(), 100u);
    float worst = 0.0f;
    for (const GpuBvh4Node& n : wide.nodes) worst = std::max(worst, checkNode(n));
    EXPECT_LE(worst, 1.01f); // outwards by at most one step
}

} // namespace
