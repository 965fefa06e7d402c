#include "gpu/compute_pipeline.h"

#include "gpu/vulkan_error.h"

#include <chrono>
#include <string>

namespace pt {

ComputePipeline::ComputePipeline(VulkanContext& context, std::span<const uint32_t> spirv, uint32_t pushConstantBytes,
    const std::vector<SpecializationConstant>& constants, const char* name)
    : context_(context) {
    auto start = std::chrono::steady_clock::now();
    const std::string what = std::string("creating the '") + name + "' compute pipeline";
    if (pushConstantBytes > context.properties().limits.maxPushConstantsSize)
        throw std::runtime_error(what + ": the device allows only " +
                                 std::to_string(context.properties().limits.maxPushConstantsSize) +
                                 " bytes of push constants");

    PipelineCache& cache = context.pipelineCache();
    const SpecializedKernel kernel = cache.specialize(spirv, constants, name);
    specializedFromCache_ = kernel.fromCache;
    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = kernel.spirv.size() * sizeof(uint32_t);
    moduleInfo.pCode = kernel.spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    vkCheck(vkCreateShaderModule(context.device(), &moduleInfo, nullptr, &module), what.c_str());

    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    VkResult result = vkCreatePipelineLayout(context.device(), &layoutInfo, nullptr, &layout_);
    if (result != VK_SUCCESS) {
        vkDestroyShaderModule(context.device(), module, nullptr);
        throw VulkanError(result, what);
    }

    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout_;
    result = vkCreateComputePipelines(context.device(), cache.handle(), 1, &info, nullptr, &pipeline_);
    vkDestroyShaderModule(context.device(), module, nullptr);
    if (result != VK_SUCCESS) {
        vkDestroyPipelineLayout(context.device(), layout_, nullptr);
        throw VulkanError(result, what);
    }
    cache.save();
    creationSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ComputePipeline::~ComputePipeline() {
    if (pipeline_) vkDestroyPipeline(context_.device(), pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(context_.device(), layout_, nullptr);
}

void ComputePipeline::bindAndPush(VkCommandBuffer cmd, const void* pushData, uint32_t bytes) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, pushData);
}

} // namespace pt
