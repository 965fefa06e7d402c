#pragma once
// Triangles gathered from meshes into the kernel's records, and a tree over each gathered set
// appended to the scene's one node array: the world tree first (root 0), then one per mesh kept
// as an instance (src/flatten/flat_instances.h). Internal to flattenScene.
#include "flatten/flat_scene.h"

#include <optional>
#include <string>
#include <vector>

namespace pt {

// One tree's triangles before it is built: records and boxes in the order gathered.
struct TriangleSet {
    std::vector<gpu::GpuTriangle> triangles;
    std::vector<gpu::GpuTriangleShading> shading;
    std::vector<gpu::GpuTriangleTangents> tangents; // one per triangle when the scene keeps tangents, else empty
    std::vector<Aabb> bounds;
};

bool isFinite(const glm::vec3& v);

// The motion-table entry of an object that moves by `motion` over the shutter, or NO_MOTION.
// Emitters move too: light sampling and light subpaths place them at the path's time
// (shaders/lights, placedTriangle and sphereLightOffset).
uint32_t motionIndex(const glm::vec3& motion, FlatScene& flat);

// Whether the scene keeps the file's vertex tangents (normal maps and anisotropy read them): some
// mesh has them under a material that needs them.
bool sceneKeepsTangents(const Scene& scene);

// Appends `mesh`'s valid triangles (zero-area and non-finite ones are counted in
// flat.degenerateTriangles) with material `material` and `motion` (world space, or zero).
void gatherTriangles(const Scene& scene, const Mesh& mesh, uint32_t material, const glm::vec3& motion,
    bool keepTangents, FlatScene& flat, TriangleSet& set);

// Where a tree went: its root in flat.nodes and its triangles' range in flat.triangles.
struct AppendedTree {
    uint32_t root = 0;
    uint32_t firstTriangle = 0;
    uint32_t triangleCount = 0;
    int binaryDepth = 0;
    int wideDepth = 0;
    double sahCost = 0;
    double buildSeconds = 0;
};

// Builds the set's tree and appends its nodes to flat.nodes (child words offset to their place)
// and its triangles, in the tree's order, to flat's arrays; the set is emptied as it goes.
// `what` names the tree in errors. An empty set appends nothing.
AppendedTree appendTriangleTree(
    TriangleSet& set, const BvhBuildOptions& options, const std::string& what, FlatScene& flat);

// The tree as the kernel reads it, four-wide; `what` names it if the traversal stack cannot hold it.
WideBvh gpuNodes(const Bvh& bvh, const std::string& what);

} // namespace pt
