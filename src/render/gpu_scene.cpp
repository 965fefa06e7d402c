#include "render/gpu_scene.h"

namespace pt {
namespace {

template <class T>
GpuBuffer makeBuffer(VulkanContext& ctx, const std::vector<T>& data, const char* name) {
    GpuBuffer buffer(ctx, sizeof(T) * data.size(), name);
    buffer.upload(data.data(), sizeof(T) * data.size());
    return buffer;
}

} // namespace

GpuScene::GpuScene(
    VulkanContext& context, const FlatScene& scene, gpu::GpuSceneParams params, VkDeviceSize accumulationBytes) {
    triangles_ = makeBuffer(context, scene.triangles, "triangles");
    shading_ = makeBuffer(context, scene.shading, "shading");
    const bool quantized = !scene.quantizedNodes.empty();
    nodes_ = quantized ? makeBuffer(context, scene.quantizedNodes, "bvh nodes")
                       : makeBuffer(context, scene.nodes, "bvh nodes");
    spheres_ = makeBuffer(context, scene.spheres, "spheres");
    sphereNodes_ = makeBuffer(context, scene.sphereNodes, "sphere bvh nodes");
    materials_ = makeBuffer(context, scene.materials, "materials");
    lights_ = makeBuffer(context, scene.lights.lights, "lights");
    lightCdf_ = makeBuffer(context, scene.lights.cdf, "light cdf");
    envTexels_ = makeBuffer(context, scene.environment.texels, "environment texels");
    envMarginal_ = makeBuffer(context, scene.environment.marginal, "environment marginal cdf");
    envConditional_ = makeBuffer(context, scene.environment.conditional, "environment conditional cdf");
    textures_ = makeBuffer(context, scene.textures, "textures");
    texels_ = makeBuffer(context, scene.texels, "texels");
    motions_ = makeBuffer(context, scene.motions, "motions");
    tangents_ = makeBuffer(context, scene.tangents, "tangents");
    accumulation_ = GpuBuffer(context, accumulationBytes, "accumulation");
    if (accumulationBytes > 0) accumulation_.fillZero();

    params.triangles = triangles_.address();
    params.shading = shading_.address();
    params.nodes = nodes_.address();
    params.spheres = spheres_.address();
    params.sphereNodes = sphereNodes_.address();
    params.materials = materials_.address();
    params.lights = lights_.address();
    params.lightCdf = lightCdf_.address();
    params.accumulation = accumulation_.address();
    params.envTexels = envTexels_.address();
    params.envMarginal = envMarginal_.address();
    params.envConditional = envConditional_.address();
    params.textures = textures_.address();
    params.texels = texels_.address();
    params.backgroundTexture = scene.backgroundTexture;
    params.ambientLight = scene.ambientLight;
    params.motions = motions_.address();
    params.tangents = tangents_.address();
    params.envWidth = scene.environment.width;
    params.envHeight = scene.environment.height;
    params.envLightIndex = scene.lights.environmentIndex;
    params.envRotationCos = scene.environment.rotationCos;
    params.envRotationSin = scene.environment.rotationSin;
    params.numLights = static_cast<uint32_t>(scene.lights.lights.size());
    params.numTriangles = static_cast<uint32_t>(scene.triangles.size());
    params.numNodes = static_cast<uint32_t>(quantized ? scene.quantizedNodes.size() : scene.nodes.size());
    params.nodeFormat = quantized ? BVH_NODES_QUANTIZED : BVH_NODES_FLOAT;
    params.numSpheres = static_cast<uint32_t>(scene.spheres.size());
    params.numSphereNodes = static_cast<uint32_t>(scene.sphereNodes.size());
    params_ = GpuBuffer(context, sizeof(params), "scene params");
    params_.upload(&params, sizeof(params));
}

} // namespace pt
