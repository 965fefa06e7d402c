#pragma once
// Meshes placed several times (Scene::instances) in the flattened scene: which placements are
// copied into world space (into the world tree) and which stay instances, each kept mesh's own
// tree, and the tree over the kept placements (two-level BVH, traversed by
// shaders/geometry/traverse.glsl). Internal to flattenScene.
#include "flatten/triangle_trees.h"

namespace pt {

// Per instance of scene.instances: true where it stays an instance. Emitters and moving
// placements are always copied (light sampling and motion blur work on world-space triangles);
// the others follow options.instancing (Auto: copied when all copies add at most
// options.expandInstancesUpTo triangles). flat.instancing says what was decided and why.
std::vector<bool> chooseKeptInstances(const Scene& scene, const BvhBuildOptions& options, FlatScene& flat);

// Gathers the copied placements' triangles into the world set.
void gatherExpandedInstances(
    const Scene& scene, const std::vector<bool>& kept, bool keepTangents, FlatScene& flat, TriangleSet& world);

// Builds a tree per kept mesh (and material) after the world tree in flat.nodes, the instance
// records and the tree over them (flat.instances, flat.instanceNodes).
void flattenKeptInstances(const Scene& scene, const std::vector<bool>& kept, const BvhBuildOptions& options,
    bool keepTangents, FlatScene& flat);

} // namespace pt
