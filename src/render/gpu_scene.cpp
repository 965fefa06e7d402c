#include "render/gpu_scene.h"

#include "gpu/compute_pipeline.h"

#include "base/memory_usage.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pt {
namespace {

template <class T>
GpuBuffer makeBuffer(VulkanContext& ctx, const std::vector<T>& data, const char* name) {
    GpuBuffer buffer(ctx, sizeof(T) * data.size(), name);
    buffer.upload(data.data(), sizeof(T) * data.size());
    return buffer;
}

template <class T>
uint64_t bytesOf(const std::vector<T>& data) {
    return sizeof(T) * data.size();
}

// Refuses a scene whose buffers cannot fit in the device's largest device-local heap (on a CPU
// device, lavapipe, in the host memory left too), naming the scene, the need and the limit,
// before any buffer is made: a failed allocation halfway through says less.
void requireDeviceMemory(VulkanContext& context, const FlatScene& scene, VkDeviceSize accumulationBytes) {
    const uint64_t geometry = bytesOf(scene.triangles) + bytesOf(scene.shading) + bytesOf(scene.tangents) +
                              bytesOf(scene.spheres) + bytesOf(scene.motions);
    const uint64_t bvh = bytesOf(scene.nodes) + bytesOf(scene.quantizedNodes) + bytesOf(scene.sphereNodes) +
                         bytesOf(scene.instances) + bytesOf(scene.instanceNodes);
    const uint64_t textures = bytesOf(scene.texels) + bytesOf(scene.textures) + bytesOf(scene.environment.texels) +
                              bytesOf(scene.environment.marginal) + bytesOf(scene.environment.conditional);
    const uint64_t other = bytesOf(scene.materials) + bytesOf(scene.lights.lights) + bytesOf(scene.lights.cdf) +
                           bytesOf(scene.lights.tree.nodes) + bytesOf(scene.lights.tree.trails);
    const uint64_t need = geometry + bvh + textures + other + accumulationBytes;
    uint64_t heap = 0;
    const VkPhysicalDeviceMemoryProperties& memory = context.memoryProperties();
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            heap = std::max(heap, memory.memoryHeaps[i].size);
    std::string limit = "the largest device-local heap of " + context.info().name + " (" + formatBytes(heap) + ")";
    uint64_t available = heap;
    if (context.info().type == "CPU") {
        const MemoryHeadroom host = hostMemoryHeadroom();
        if (host.bytes < available) {
            available = host.bytes;
            limit = host.limit;
        }
        limit += " allows (the device, " + context.info().name + ", is the CPU: its memory is host memory)";
    } else {
        limit += " allows";
    }
    if (heap == 0 || need <= available) return;
    throw std::runtime_error((scene.source.empty() ? std::string("the scene") : scene.source) + ": needs " +
                             formatBytes(need) + " of device memory (geometry " + formatBytes(geometry) + ", BVH " +
                             formatBytes(bvh) + ", textures " + formatBytes(textures) + ", image buffers " +
                             formatBytes(accumulationBytes) + "), more than " + limit);
}

} // namespace

GpuScene::GpuScene(
    VulkanContext& context, const FlatScene& scene, gpu::GpuSceneParams params, VkDeviceSize accumulationBytes) {
    build(context, scene, nullptr, params, accumulationBytes);
}

GpuScene::GpuScene(
    VulkanContext& context, FlatScene&& scene, gpu::GpuSceneParams params, VkDeviceSize accumulationBytes) {
    build(context, scene, &scene, params, accumulationBytes);
}

void GpuScene::build(VulkanContext& context, const FlatScene& scene, FlatScene* release, gpu::GpuSceneParams params,
    VkDeviceSize accumulationBytes) {
    requireDeviceMemory(context, scene, accumulationBytes);
    // Before the trees are released: a sphere around them, a little larger than the box's, so that
    // the discs the paths of lights at infinity start on lie outside the geometry.
    const Aabb bounds = sceneBounds(scene);
    params.sceneSphere = bounds.empty() ? glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)
                                        : glm::vec4(0.5f * (bounds.lo + bounds.hi),
                                              std::max(0.505f * glm::length(bounds.hi - bounds.lo), 1e-6f));
    sceneRadius_ = params.sceneSphere.w;
    const bool quantized = !scene.quantizedNodes.empty();
    params.numTriangles = static_cast<uint32_t>(scene.triangles.size());
    params.numNodes = scene.worldNodes;
    params.nodeFormat = quantized ? BVH_NODES_QUANTIZED : BVH_NODES_FLOAT;
    // The big arrays, each freed (when `release` is the scene) once it is on the device.
    auto upload = [&](auto FlatScene::*array, const char* name) {
        GpuBuffer buffer = makeBuffer(context, scene.*array, name);
        if (release) std::remove_reference_t<decltype(release->*array)>().swap(release->*array);
        return buffer;
    };
    if (!scene.triangles.empty() && scene.triangles.size() <= UNIFORM_TRIANGLES_MAX) {
        uniformTriangles_ = GpuBuffer(context, ComputePipeline::uniformBlockBytes(), "uniform triangles");
        uniformTriangles_.fillZero();
        uniformTriangles_.upload(std::span<const gpu::GpuTriangle>(scene.triangles));
    }
    triangles_ = upload(&FlatScene::triangles, "triangles");
    shading_ = upload(&FlatScene::shading, "shading");
    nodes_ = quantized ? upload(&FlatScene::quantizedNodes, "bvh nodes") : upload(&FlatScene::nodes, "bvh nodes");
    tangents_ = upload(&FlatScene::tangents, "tangents");
    texels_ = upload(&FlatScene::texels, "texels");
    spheres_ = makeBuffer(context, scene.spheres, "spheres");
    sphereNodes_ = makeBuffer(context, scene.sphereNodes, "sphere bvh nodes");
    instances_ = makeBuffer(context, scene.instances, "instances");
    instanceNodes_ = makeBuffer(context, scene.instanceNodes, "instance bvh nodes");
    materials_ = makeBuffer(context, scene.materials, "materials");
    if (TexelView::fits(context, nodes_.size()) && TexelView::fits(context, triangles_.size()) &&
        TexelView::fits(context, sphereNodes_.size()) && TexelView::fits(context, spheres_.size())) {
        nodeTexels_ = TexelView(context, nodes_, nodes_.size(), "bvh node texels");
        triangleTexels_ = TexelView(context, triangles_, triangles_.size(), "triangle texels");
        sphereNodeTexels_ = TexelView(context, sphereNodes_, sphereNodes_.size(), "sphere bvh node texels");
        sphereTexels_ = TexelView(context, spheres_, spheres_.size(), "sphere texels");
    }
    lights_ = makeBuffer(context, scene.lights.lights, "lights");
    lightCdf_ = makeBuffer(context, scene.lights.cdf, "light cdf");
    lightTreeNodes_ = makeBuffer(context, scene.lights.tree.nodes, "light tree");
    lightTreeTrails_ = makeBuffer(context, scene.lights.tree.trails, "light tree trails");
    envTexels_ = makeBuffer(context, scene.environment.texels, "environment texels");
    envMarginal_ = makeBuffer(context, scene.environment.marginal, "environment marginal cdf");
    envConditional_ = makeBuffer(context, scene.environment.conditional, "environment conditional cdf");
    textures_ = makeBuffer(context, scene.textures, "textures");
    motions_ = makeBuffer(context, scene.motions, "motions");
    accumulation_ = GpuBuffer(context, accumulationBytes, "accumulation");
    if (accumulationBytes > 0) accumulation_.fillZero();

    params.triangles = triangles_.address();
    params.shading = shading_.address();
    params.nodes = nodes_.address();
    params.spheres = spheres_.address();
    params.sphereNodes = sphereNodes_.address();
    params.instances = instances_.address();
    params.instanceNodes = instanceNodes_.address();
    params.numInstances = static_cast<uint32_t>(scene.instances.size());
    params.numInstanceNodes = static_cast<uint32_t>(scene.instanceNodes.size());
    params.materials = materials_.address();
    params.lights = lights_.address();
    params.lightCdf = lightCdf_.address();
    // No tree: address 0, and the kernel selects by the CDF.
    params.lightTreeNodes = scene.lights.tree.nodes.empty() ? 0 : lightTreeNodes_.address();
    params.lightTreeTrails = lightTreeTrails_.address();
    params.lightTreeShare = scene.lights.tree.share;
    params.lightTreeInvScale = 1.0f / params.sceneSphere.w;
    params.accumulation = accumulation_.address();
    params.envTexels = envTexels_.address();
    params.envMarginal = envMarginal_.address();
    params.envConditional = envConditional_.address();
    params.textures = textures_.address();
    params.texels = texels_.address();
    params.backgroundTexture = scene.backgroundTexture;
    params.sheenTables = scene.sheenTables;
    params.ambientLight = scene.ambientLight;
    params.motions = motions_.address();
    params.tangents = tangents_.address();
    params.envWidth = scene.environment.width;
    params.envHeight = scene.environment.height;
    params.envLightIndex = scene.lights.environmentIndex;
    params.envRotationCos = scene.environment.rotationCos;
    params.envRotationSin = scene.environment.rotationSin;
    params.numLights = static_cast<uint32_t>(scene.lights.lights.size());
    params.numSpheres = static_cast<uint32_t>(scene.spheres.size());
    params.numSphereNodes = static_cast<uint32_t>(scene.sphereNodes.size());
    params_ = GpuBuffer(context, sizeof(params), "scene params");
    params_.upload(&params, sizeof(params));
}

} // namespace pt
