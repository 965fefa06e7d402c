#include "flatten/flat_instances.h"

#include "accel/quantized_bvh.h"
#include "scene/memory_estimate.h"
#include "scene/mesh_placement.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

namespace pt {
namespace {

// Whether a placement must be copied into world space: light sampling picks points on
// world-space triangles (each placed emitter is a light of its own power), and motion blur moves
// world-space triangles.
bool mustExpand(const Scene& scene, const MeshInstance& instance) {
    if (instance.motion != glm::vec3(0.0f)) return true;
    for (const Mesh& part : scene.sharedMeshes.at(instance.mesh).parts) {
        const uint32_t material = instance.material.value_or(part.material);
        if (material < scene.materials.size() && scene.materials[material].emissive()) return true;
        if (part.motion != glm::vec3(0.0f)) return true;
    }
    return false;
}

void setRows(glm::vec4 rows[3], const glm::mat4& m) {
    for (int r = 0; r < 3; ++r) rows[r] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
}

// The world box of a kept mesh under `m`: the boxes of its tree's first two levels, each mapped
// corner by corner (a rotated mesh's box is then much tighter than its root box mapped).
Aabb placedBounds(const std::vector<gpu::GpuBvh4Node>& nodes, uint32_t root, const glm::mat4& m) {
    std::vector<Aabb> boxes;
    const gpu::GpuBvh4Node& top = nodes[root];
    for (int i = 0; i < 4; ++i) {
        const uint32_t child = top.child[i];
        if (child == BVH4_EMPTY) continue;
        if ((child & BVH4_LEAF_BIT) != 0 || child >= nodes.size()) {
            Aabb b;
            b.grow(glm::vec3(top.loX[i], top.loY[i], top.loZ[i]));
            b.grow(glm::vec3(top.hiX[i], top.hiY[i], top.hiZ[i]));
            boxes.push_back(b);
            continue;
        }
        const gpu::GpuBvh4Node& inner = nodes[child];
        for (int j = 0; j < 4; ++j) {
            if (inner.child[j] == BVH4_EMPTY) continue;
            Aabb b;
            b.grow(glm::vec3(inner.loX[j], inner.loY[j], inner.loZ[j]));
            b.grow(glm::vec3(inner.hiX[j], inner.hiY[j], inner.hiZ[j]));
            boxes.push_back(b);
        }
    }
    Aabb world;
    for (const Aabb& b : boxes)
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p(
                (corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y, (corner & 4) ? b.hi.z : b.lo.z);
            world.grow(glm::vec3(m * glm::vec4(p, 1.0f)));
        }
    // Mapping a corner rounds: grow the box by a few ulps of the terms summed (as the kernel's
    // ray into object space rounds too), so that a triangle on the box's face is never culled.
    const glm::mat3 linear(m);
    glm::vec3 terms(0.0f);
    for (const Aabb& b : boxes) terms = glm::max(terms, glm::max(glm::abs(b.lo), glm::abs(b.hi)));
    const glm::vec3 reach = glm::abs(linear[0]) * terms.x + glm::abs(linear[1]) * terms.y +
                            glm::abs(linear[2]) * terms.z + glm::abs(glm::vec3(m[3]));
    const glm::vec3 pad = reach * (8.0f * std::numeric_limits<float>::epsilon());
    world.lo -= pad;
    world.hi += pad;
    return world;
}

// The tree key of an instance that keeps its parts' materials.
constexpr uint32_t kPartsOwnMaterials = 0xffffffffu;

bool finiteBox(const Aabb& b) { return !b.empty() && isFinite(b.lo) && isFinite(b.hi); }

std::string countText(uint64_t n, const char* what) { return std::to_string(n) + " " + what; }

} // namespace

std::vector<bool> chooseKeptInstances(const Scene& scene, const BvhBuildOptions& options, FlatScene& flat) {
    std::vector<bool> kept(scene.instances.size(), false);
    if (scene.instances.empty()) return kept;
    uint64_t expandable = 0, forced = 0;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const MeshInstance& instance = scene.instances[i];
        if (instance.mesh >= scene.sharedMeshes.size())
            throw std::runtime_error(
                scene.source + ": instance '" + instance.name + "' places a mesh that does not exist");
        const uint64_t triangles = scene.sharedMeshes[instance.mesh].triangleCount();
        if (mustExpand(scene, instance))
            forced += 1;
        else {
            kept[i] = true;
            expandable += triangles;
        }
    }
    const uint64_t placements = scene.instances.size();
    std::string why;
    bool expandAll = false;
    switch (options.instancing) {
    case Instancing::Expand:
        expandAll = true;
        why = "asked for";
        break;
    case Instancing::Keep: why = "asked for"; break;
    case Instancing::Auto:
        expandAll = expandable <= options.expandInstancesUpTo;
        why = expandAll ? "their copies add only " + countText(expandable, "triangles")
                        : "their copies would add " + countText(expandable, "triangles");
        break;
    }
    if (expandAll) std::fill(kept.begin(), kept.end(), false);
    // Copies are memory: refuse before making them what the machine cannot hold (the world's
    // triangles, the copies, and each mesh still kept once).
    uint64_t copied = 0, world = 0;
    std::vector<bool> meshKept(scene.sharedMeshes.size(), false);
    for (size_t i = 0; i < kept.size(); ++i) {
        const uint32_t mesh = scene.instances[i].mesh;
        if (kept[i])
            meshKept[mesh] = true;
        else
            copied += scene.sharedMeshes[mesh].triangleCount();
    }
    for (const Mesh& m : scene.meshes) world += m.triangles.size();
    for (size_t m = 0; m < meshKept.size(); ++m)
        if (meshKept[m]) world += scene.sharedMeshes[m].triangleCount();
    if (copied > 0) requireMemoryForTriangles(scene.source, world + copied, "instances copied into world space");
    const uint64_t keptCount = std::count(kept.begin(), kept.end(), true);
    if (keptCount > 0)
        flat.instancing = countText(keptCount, "instances") + " of " + countText(scene.sharedMeshes.size(), "meshes") +
                          " kept as instances (" + why + ")";
    else
        flat.instancing = countText(placements, "instances") + " copied into world space (" + why + ")";
    if (forced > 0 && keptCount > 0) flat.instancing += "; " + countText(forced, "emitting or moving ones copied");
    return kept;
}

void gatherExpandedInstances(
    const Scene& scene, const std::vector<bool>& kept, bool keepTangents, FlatScene& flat, TriangleSet& world) {
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        if (kept[i]) continue;
        if (!isPlaceable(scene.instances[i].objectToWorld)) {
            flat.degenerateInstances++;
            continue;
        }
        for (const Mesh& placed : placeInstance(scene, scene.instances[i]))
            gatherTriangles(scene, placed, placed.material, placed.motion, keepTangents, flat, world);
    }
}

void flattenKeptInstances(const Scene& scene, const std::vector<bool>& kept, const BvhBuildOptions& options,
    bool keepTangents, FlatScene& flat) {
    // One tree per mesh and material: an instance that replaces the material needs triangle
    // records of its own (the material decides alpha testing and tangents per triangle).
    std::map<std::pair<uint32_t, uint32_t>, AppendedTree> trees;
    std::vector<gpu::GpuInstance> instances;
    std::vector<Aabb> bounds;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        if (!kept[i]) continue;
        const MeshInstance& instance = scene.instances[i];
        if (!isPlaceable(instance.objectToWorld)) {
            flat.degenerateInstances++;
            continue;
        }
        const std::pair<uint32_t, uint32_t> key(instance.mesh, instance.material.value_or(kPartsOwnMaterials));
        auto found = trees.find(key);
        if (found == trees.end()) {
            const SharedMesh& shared = scene.sharedMeshes[instance.mesh];
            TriangleSet set;
            for (const Mesh& part : shared.parts)
                gatherTriangles(
                    scene, part, instance.material.value_or(part.material), glm::vec3(0.0f), keepTangents, flat, set);
            found = trees
                        .emplace(key, appendTriangleTree(
                                          set, options, scene.source + ": BVH of mesh '" + shared.name + "'", flat))
                        .first;
        }
        const AppendedTree& tree = found->second;
        if (tree.triangleCount == 0) continue;
        const Aabb box = placedBounds(flat.nodes, tree.root, instance.objectToWorld);
        if (!finiteBox(box)) {
            flat.degenerateInstances++;
            continue;
        }
        gpu::GpuInstance g{};
        setRows(g.objectToWorld, instance.objectToWorld);
        setRows(g.worldToObject, glm::inverse(instance.objectToWorld));
        g.root = tree.root;
        g.firstTriangle = tree.firstTriangle;
        g.triangleCount = tree.triangleCount;
        instances.push_back(g);
        bounds.push_back(box);
    }
    if (instances.empty()) return;
    // Each leaf one instance: testing one means a whole traversal of its mesh's tree.
    BvhBuildOptions top = options;
    top.maxLeafSize = 1;
    const Bvh bvh = buildBvh(bounds, top);
    flat.instanceNodes = gpuNodes(bvh, scene.source + ": instance BVH").nodes;
    flat.instances.reserve(instances.size());
    for (uint32_t original : bvh.primOrder) flat.instances.push_back(instances[original]);
}

} // namespace pt
