#pragma once
// A compute pipeline from embedded SPIR-V, with push constants, one uniform buffer (set 0,
// binding 0: a tiny scene's triangles, shaders/common/buffers.glsl), two texel buffers (the
// triangle tree's nodes and the triangles, TEXEL_BINDING_* in shared/layout.h; every other
// buffer is reached through its device address) and specialization constants chosen per scene. The constants are
// baked into the SPIR-V before the driver sees it (spirv_specialization.h), through the context's
// pipeline cache, so a kernel's second creation, in any process, skips that step; in the same
// process it also skips the driver's compile while the kernel is among the recent ones
// (gpu/compiled_kernel.h).
#include "gpu/compiled_kernel.h"
#include "gpu/gpu_buffer.h"
#include "gpu/spirv_specialization.h"
#include "gpu/texel_view.h"
#include "gpu/vulkan_context.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace pt {

class ComputePipeline {
public:
    // `uniforms`: the buffer bound at set 0, binding 0 (at least uniformBlockBytes()); null binds
    // a zero-filled one of the pipeline's own, for kernels and scenes that do not read it.
    ComputePipeline(VulkanContext& context, std::span<const uint32_t> spirv, uint32_t pushConstantBytes,
        const std::vector<SpecializationConstant>& constants, const char* name, const GpuBuffer* uniforms = nullptr);
    ~ComputePipeline();
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    // The size of the uniform block at set 0, binding 0 (UniformTriangleBlock).
    static VkDeviceSize uniformBlockBytes();

    VkPipeline handle() const { return kernel_->pipeline; }
    VkPipelineLayout layout() const { return kernel_->layout; }
    double creationSeconds() const { return creationSeconds_; }
    // Whether the specialised SPIR-V came from the disk cache (for the log line).
    bool specializedFromCache() const { return specializedFromCache_; }
    // Whether the driver's compile was skipped: the kernel was compiled earlier in this process.
    bool compiledBefore() const { return compiledBefore_; }

    // Points the texel-buffer bindings at a scene's views (GpuScene::texelBuffers); a null view
    // binds the placeholder. Not while a dispatch of this pipeline may run.
    void setTexelBuffers(const TexelBuffers& views);

    void bindAndPush(VkCommandBuffer cmd, const void* pushData, uint32_t bytes) const;

private:
    void createDescriptors(const GpuBuffer* uniforms, const std::string& what);

    VulkanContext& context_;
    std::shared_ptr<const CompiledKernel> kernel_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    std::unique_ptr<GpuBuffer> ownUniforms_;
    // A view of the uniform block's buffer, bound at the texel bindings a scene does not fill
    // (a kernel that never reads them still needs something there).
    TexelView placeholderTexels_;
    double creationSeconds_ = 0;
    bool specializedFromCache_ = false;
    bool compiledBefore_ = false;
};

} // namespace pt
