#pragma once
// A flattened scene in device memory, plus the GpuSceneParams block that points at it.
// Shared by the renderer and the GLSL test kernels.
#include "gpu/gpu_buffer.h"
#include "gpu/texel_view.h"
#include "flatten/flat_scene.h"
#include "shared/layout.h"

namespace pt {

class GpuScene {
public:
    // `params` holds everything but the buffer addresses, which this fills in; `accumulationBytes`
    // sizes the accumulation buffer (0 for none), zero-filled.
    GpuScene(
        VulkanContext& context, const FlatScene& scene, gpu::GpuSceneParams params, VkDeviceSize accumulationBytes);
    // The same, freeing each of the scene's big host arrays as soon as it is on the device, so
    // a big scene is never held twice (on lavapipe device memory is host memory); `scene` keeps
    // its materials, lights and counts' sources only until this returns.
    GpuScene(VulkanContext& context, FlatScene&& scene, gpu::GpuSceneParams params, VkDeviceSize accumulationBytes);

    VkDeviceAddress paramsAddress() const { return params_.address(); }
    // The radius of a sphere around all geometry (GpuSceneParams::sceneSphere).
    float sceneRadius() const { return sceneRadius_; }
    // What the render pipeline binds at set 0, binding 0: the triangles again where the scene has
    // at most UNIFORM_TRIANGLES_MAX (shaders/common/buffers.glsl), else null.
    const GpuBuffer* uniformTriangles() const { return uniformTriangles_.size() ? &uniformTriangles_ : nullptr; }
    // The trees' nodes, the triangles and the spheres as texel buffers (TEXEL_BINDING_*), where
    // all four fit the device's limit on a view; else null.
    TexelBuffers texelBuffers() const {
        return {nodeTexels_.handle(), triangleTexels_.handle(), sphereNodeTexels_.handle(), sphereTexels_.handle()};
    }
    bool hasTexelViews() const { return nodeTexels_.handle() != VK_NULL_HANDLE; }
    const GpuBuffer& accumulation() const { return accumulation_; }
    GpuBuffer& accumulation() { return accumulation_; }

private:
    // `release`: the scene itself when its big arrays may be freed as they are uploaded, or null.
    void build(VulkanContext& context, const FlatScene& scene, FlatScene* release, gpu::GpuSceneParams params,
        VkDeviceSize accumulationBytes);

    GpuBuffer triangles_, shading_, nodes_, spheres_, sphereNodes_, instances_, instanceNodes_, materials_, lights_,
        lightCdf_, lightTreeNodes_, lightTreeTrails_, envTexels_, envMarginal_, envConditional_, textures_, texels_,
        motions_, tangents_, uniformTriangles_, accumulation_, params_;
    // After the buffers: destroyed before them.
    TexelView nodeTexels_, triangleTexels_, sphereNodeTexels_, sphereTexels_;
    float sceneRadius_ = 1.0f;
};

} // namespace pt
