#pragma once
// The light tree: a binary tree over the bounded lights (emissive triangles and spheres, point,
// spot and square lights) whose nodes bound where their lights are, how much they emit and in
// which directions (Conty Estevez and Kulla 2018, "Importance Sampling of Many Lights with
// Adaptive Tree Splitting"; pbrt-v4's BVHLightSampler). Light sampling descends it by each
// child's importance at the shading point (shaders/lights/light_tree.glsl), so a light that is
// far away, faces away or is small is rarely chosen, where the power CDF chooses every light
// by its power alone, wherever the shading point is.
#include "shared/layout.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace pt {

// What the tree knows of one light (or of the lights under a node).
struct LightBounds {
    glm::vec3 lo{0.0f}, hi{0.0f};
    double phi = 0;          // power (the light table's weight)
    glm::vec3 axis{0, 0, 1}; // the cone of the lights' normals: its axis...
    float cosThetaO = 1.0f;  // ...and half-angle
    float cosThetaE = 0.0f;  // how far from its normal a light emits (0: a hemisphere)
    bool twoSided = false;   // emits from both sides of its normal
};

struct LightTree {
    std::vector<gpu::GpuLightTreeNode> nodes; // root first; a node's first child follows it
    // Per light of the table: its path from the root (GpuSceneParams::lightTreeTrails); 0 for
    // lights at infinity, which the tree leaves out.
    std::vector<uint64_t> trails;
    // The sum of the bounded lights' pmfs in the power table: the probability that light sampling
    // takes the tree (the lights at infinity share the rest by their power).
    float share = 0.0f;
    int depth = 0; // edges on the longest path
};

// Trails are 64 bits: below this depth the builder splits by count, which keeps any tree of up to
// 2^(64 - kLightTreeCountSplitDepth) lights within them.
inline constexpr int kLightTreeCountSplitDepth = 32;

// Builds the tree over `bounds` (one per light of the table; entries with phi <= 0 are left out,
// as the lights at infinity are). `share`: the bounded lights' total pmf in the power table.
// Fewer than two lights give an empty tree: there is nothing to choose between.
LightTree buildLightTree(std::span<const LightBounds> bounds, float share);

// The bounds of each light of the table, from the geometry it was built over (final triangle and
// sphere arrays, with `motions` for moving ones: a moving light's box covers its whole
// translation) and `power` (the table's weights); phi 0 for lights at infinity.
std::vector<LightBounds> lightBoundsOf(std::span<const gpu::GpuLight> lights, std::span<const double> power,
    std::span<const gpu::GpuTriangle> triangles, std::span<const gpu::GpuSphere> spheres,
    std::span<const gpu::GpuMaterial> materials, std::span<const glm::vec4> motions);

// Union of two direction cones (axis, cos half-angle), as pbrt-v4's DirectionCone::Union: the
// smallest cone around both, or the whole sphere (cos -1).
void coneUnion(glm::vec3 axisA, float cosA, glm::vec3 axisB, float cosB, glm::vec3& axis, float& cosTheta);

} // namespace pt
