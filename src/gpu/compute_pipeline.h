#pragma once
// A compute pipeline from embedded SPIR-V, with push constants only (every buffer is reached
// through its device address) and specialization constants chosen per scene. The constants are
// baked into the SPIR-V before the driver sees it (spirv_specialization.h), through the context's
// pipeline cache, so a kernel's second creation, in any process, skips that step.
#include "gpu/spirv_specialization.h"
#include "gpu/vulkan_context.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace pt {

class ComputePipeline {
public:
    ComputePipeline(VulkanContext& context, std::span<const uint32_t> spirv, uint32_t pushConstantBytes,
        const std::vector<SpecializationConstant>& constants, const char* name);
    ~ComputePipeline();
    ComputePipeline(const ComputePipeline&) = delete;
    ComputePipeline& operator=(const ComputePipeline&) = delete;

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }
    double creationSeconds() const { return creationSeconds_; }
    // Whether the specialised SPIR-V came from the disk cache (for the log line).
    bool specializedFromCache() const { return specializedFromCache_; }

    void bindAndPush(VkCommandBuffer cmd, const void* pushData, uint32_t bytes) const;

private:
    VulkanContext& context_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    double creationSeconds_ = 0;
    bool specializedFromCache_ = false;
};

} // namespace pt
