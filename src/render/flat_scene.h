#pragma once
// The scene flattened into the arrays the kernel reads: BVH-ordered triangles with their
// shading data, BVH nodes, materials and the light table. Built once per scene on the CPU.
#include "accel/bvh.h"
#include "lights/light_table.h"
#include "scene/scene.h"
#include "shared/layout.h"

#include <vector>

namespace pt {

struct FlatScene {
    std::vector<gpu::GpuTriangle> triangles;
    std::vector<gpu::GpuTriangleShading> shading;
    std::vector<gpu::GpuBvhNode> nodes;
    std::vector<gpu::GpuSphere> spheres;         // BVH-ordered
    std::vector<gpu::GpuBvhNode> sphereNodes;    // a second BVH, over the spheres
    std::vector<gpu::GpuMaterial> materials;
    LightTable lights;
    size_t degenerateTriangles = 0; // zero-area or non-finite triangles dropped
    size_t degenerateSpheres = 0;   // singular or non-finite sphere transforms dropped
    double bvhSeconds = 0;
    double sahCost = 0;
    int bvhDepth = 0;
};

FlatScene flattenScene(const Scene& scene, const BvhBuildOptions& bvhOptions = {});

// Deepest BVH the kernel's traversal stack (shaders/geometry/traverse.glsl) can hold.
constexpr int kMaxTraversalDepth = 64;

} // namespace pt
