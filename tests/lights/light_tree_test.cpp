// The light tree's build (src/lights/light_tree.h) on the host: every bounded light in exactly
// one leaf, reached by its trail; each node bounds its children (box, power, cone of normals);
// lights at infinity left to the CDF; and degenerate sets (all lights at one point) still within
// the 64-bit trails.
#include "lights/light_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <random>
#include <vector>

namespace {

using pt::LightBounds;
using pt::LightTree;

double angleOf(glm::vec3 a, glm::vec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(glm::dvec3(a)), glm::normalize(glm::dvec3(b))), -1.0, 1.0));
}

std::vector<LightBounds> randomLights(int n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<LightBounds> lights(n);
    for (int i = 0; i < n; ++i) {
        LightBounds& b = lights[i];
        const glm::vec3 c(10 * u(rng), 10 * u(rng), 10 * u(rng));
        b.lo = c - glm::vec3(0.1f + 0.1f * u(rng));
        b.hi = c + glm::vec3(0.1f);
        b.phi = 1.5 + u(rng);
        b.axis = glm::normalize(glm::vec3(u(rng), u(rng), u(rng) + 0.01f));
        b.cosThetaO = i % 5 == 0 ? -1.0f : (i % 5 == 1 ? 0.5f : 1.0f);
        b.cosThetaE = 0.0f;
        b.twoSided = i % 3 == 0;
        if (i % 11 == 0) b.phi = 0; // at infinity: not in the tree
    }
    return lights;
}

// Walks each light's trail from the root: it must end at that light's leaf, and every node on
// the way must bound the light (its box, its cone of normals, its emission spread, its sides),
// which is what keeps the importance of a node that holds it conservative. The nodes' powers
// add up.
void checkTree(const LightTree& tree, const std::vector<LightBounds>& lights) {
    ASSERT_FALSE(tree.nodes.empty());
    std::vector<int> leaves(lights.size(), 0);
    for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
        const pt::gpu::GpuLightTreeNode& n = tree.nodes[i];
        if ((n.flags & LIGHT_NODE_LEAF) != 0u) {
            ASSERT_LT(n.child, lights.size());
            ++leaves[n.child];
            continue;
        }
        ASSERT_LT(n.child, tree.nodes.size());
        ASSERT_GT(n.child, i + 1);
        EXPECT_NEAR(n.phi, tree.nodes[i + 1].phi + tree.nodes[n.child].phi, 1e-5 * n.phi);
    }
    EXPECT_NEAR(tree.nodes[0].phi, 1.0, 1e-5) << "powers are normalised";
    for (size_t l = 0; l < lights.size(); ++l) {
        const LightBounds& light = lights[l];
        EXPECT_EQ(leaves[l], light.phi > 0 ? 1 : 0) << "light " << l;
        if (!(light.phi > 0)) {
            EXPECT_EQ(tree.trails[l], 0u);
            continue;
        }
        uint64_t trail = tree.trails[l];
        uint32_t node = 0;
        for (int step = 0; step <= 64; ++step) {
            const pt::gpu::GpuLightTreeNode& n = tree.nodes[node];
            EXPECT_TRUE(glm::all(glm::lessThanEqual(n.boundsMin, light.lo)) &&
                        glm::all(glm::greaterThanEqual(n.boundsMax, light.hi)))
                << "node " << node << " does not hold light " << l << "'s box";
            if (n.cosThetaO > -1.0f)
                EXPECT_LE(angleOf(n.axis, light.axis) + std::acos(double(light.cosThetaO)),
                    std::acos(double(n.cosThetaO)) + 1e-4)
                    << "node " << node << " does not hold light " << l << "'s normals";
            EXPECT_LE(n.cosThetaE, light.cosThetaE);
            if (light.twoSided) EXPECT_NE(n.flags & LIGHT_NODE_TWO_SIDED, 0u);
            if ((n.flags & LIGHT_NODE_LEAF) != 0u) break;
            node = (trail & 1u) ? n.child : node + 1;
            trail >>= 1;
        }
        EXPECT_EQ(tree.nodes[node].flags & LIGHT_NODE_LEAF, LIGHT_NODE_LEAF);
        EXPECT_EQ(tree.nodes[node].child, l) << "light " << l << "'s trail leads elsewhere";
    }
}

TEST(LightTreeBuild, EveryLightInOneLeafWhichItsTrailReaches) {
    const std::vector<LightBounds> lights = randomLights(3000, 1);
    const LightTree tree = pt::buildLightTree(lights, 0.75f);
    checkTree(tree, lights);
    EXPECT_EQ(tree.share, 0.75f);
    size_t inTree = 0;
    for (const LightBounds& b : lights) inTree += b.phi > 0;
    EXPECT_EQ(tree.nodes.size(), 2 * inTree - 1);
    EXPECT_LT(tree.depth, 40) << "a cost-driven split of random lights stays shallow";
}

// All lights at one point: no plane separates them, so the builder splits by count, and the
// trails still fit in 64 bits.
TEST(LightTreeBuild, LightsAtOnePointAreSplitByCount) {
    std::vector<LightBounds> lights(5000);
    for (LightBounds& b : lights) {
        b.lo = b.hi = glm::vec3(1e4f, -3.0f, 0.5f);
        b.phi = 1.0;
        b.cosThetaO = -1.0f;
    }
    const LightTree tree = pt::buildLightTree(lights, 1.0f);
    checkTree(tree, lights);
    EXPECT_LE(tree.depth, 13);
}

TEST(LightTreeBuild, FewerThanTwoBoundedLightsMakeNoTree) {
    std::vector<LightBounds> lights(3);
    lights[1].phi = 2.0;
    EXPECT_TRUE(pt::buildLightTree(lights, 0.5f).nodes.empty());
}

TEST(LightTreeBuild, ConeUnionHoldsBothCones) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < 2000; ++k) {
        const glm::vec3 a = glm::normalize(glm::vec3(u(rng), u(rng), u(rng) + 0.01f));
        const glm::vec3 b = glm::normalize(glm::vec3(u(rng), u(rng), u(rng) + 0.01f));
        const float cosA = k % 4 == 0 ? 1.0f : u(rng), cosB = k % 3 == 0 ? 1.0f : u(rng);
        glm::vec3 axis;
        float cosU;
        pt::coneUnion(a, cosA, b, cosB, axis, cosU);
        if (cosU <= -1.0f) continue; // the whole sphere holds anything
        EXPECT_NEAR(glm::length(axis), 1.0f, 1e-5f);
        for (auto [w, c] : {std::pair{a, cosA}, std::pair{b, cosB}})
            EXPECT_LE(angleOf(axis, w) + std::acos(double(c)), std::acos(double(cosU)) + 1e-5) << "case " << k;
    }
    // Opposite normals (a two-faced wall): the whole sphere.
    glm::vec3 axis;
    float cosU;
    pt::coneUnion({0, 0, 1}, 1.0f, {0, 0, -1}, 1.0f, axis, cosU);
    EXPECT_LE(std::acos(double(cosU)), std::acos(-1.0) + 1e-6);
    EXPECT_GE(std::acos(double(cosU)), std::acos(-1.0) - 1e-3);
}

} // namespace
