#include "gpu/compute_pipeline.h"

#include "gpu/vulkan_error.h"
#include "shared/layout.h"

#include <chrono>
#include <string>

namespace pt {

ComputePipeline::ComputePipeline(VulkanContext& context, std::span<const uint32_t> spirv, uint32_t pushConstantBytes,
    const std::vector<SpecializationConstant>& constants, const char* name, const GpuBuffer* uniforms)
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

    try {
        createDescriptors(uniforms, what);
    } catch (...) {
        vkDestroyShaderModule(context.device(), module, nullptr);
        throw;
    }
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout_;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    VkResult result = vkCreatePipelineLayout(context.device(), &layoutInfo, nullptr, &layout_);
    if (result != VK_SUCCESS) {
        vkDestroyShaderModule(context.device(), module, nullptr);
        vkDestroyDescriptorPool(context.device(), pool_, nullptr);
        vkDestroyDescriptorSetLayout(context.device(), setLayout_, nullptr);
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
        vkDestroyDescriptorPool(context.device(), pool_, nullptr);
        vkDestroyDescriptorSetLayout(context.device(), setLayout_, nullptr);
        throw VulkanError(result, what);
    }
    cache.save();
    creationSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VkDeviceSize ComputePipeline::uniformBlockBytes() {
    return VkDeviceSize(UNIFORM_TRIANGLES_MAX) * UNIFORM_TRIANGLE_VEC4S * 16;
}

// The set layout (the uniform block and the texel buffers), a pool of one set and the set
// itself, pointing at `uniforms` or at a zero-filled buffer of the pipeline's own, and at
// placeholder texels until setTexelBuffers.
void ComputePipeline::createDescriptors(const GpuBuffer* uniforms, const std::string& what) {
    if (!uniforms) {
        ownUniforms_ = std::make_unique<GpuBuffer>(context_, uniformBlockBytes(), "uniforms");
        ownUniforms_->fillZero();
        uniforms = ownUniforms_.get();
    }
    if (uniforms->size() < uniformBlockBytes())
        throw std::runtime_error(what + ": the uniform buffer is smaller than the kernel's block");
    placeholderTexels_ = TexelView(context_, *uniforms, uniformBlockBytes(), what.c_str());
    VkDescriptorSetLayoutBinding bindings[1 + TEXEL_BINDING_COUNT]{};
    for (uint32_t b = 0; b < 1 + TEXEL_BINDING_COUNT; ++b) {
        bindings[b].binding = b;
        bindings[b].descriptorType =
            b == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        bindings[b].descriptorCount = 1;
        bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    static_assert(TEXEL_BINDING_NODES == 1 && TEXEL_BINDING_TRIANGLES == 2 && TEXEL_BINDING_SPHERE_NODES == 3 &&
                      TEXEL_BINDING_SPHERES == 4 && TEXEL_BINDING_COUNT == 4,
        "the set's bindings are 0 (uniforms) and the texel buffers after it, in TexelBuffers' order");
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = 1 + TEXEL_BINDING_COUNT;
    setInfo.pBindings = bindings;
    vkCheck(vkCreateDescriptorSetLayout(context_.device(), &setInfo, nullptr, &setLayout_), what.c_str());
    VkDescriptorPoolSize poolSizes[2] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, TEXEL_BINDING_COUNT}};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 2;
    poolInfo.pPoolSizes = poolSizes;
    VkResult result = vkCreateDescriptorPool(context_.device(), &poolInfo, nullptr, &pool_);
    if (result == VK_SUCCESS) {
        VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        allocInfo.descriptorPool = pool_;
        allocInfo.descriptorSetCount = 1;
        allocInfo.pSetLayouts = &setLayout_;
        result = vkAllocateDescriptorSets(context_.device(), &allocInfo, &set_);
    }
    if (result != VK_SUCCESS) {
        vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
        vkDestroyDescriptorSetLayout(context_.device(), setLayout_, nullptr);
        throw VulkanError(result, what);
    }
    VkDescriptorBufferInfo bufferInfo{uniforms->handle(), 0, uniformBlockBytes()};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.dstBinding = 0;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &bufferInfo;
    vkUpdateDescriptorSets(context_.device(), 1, &write, 0, nullptr);
    setTexelBuffers(TexelBuffers{});
}

void ComputePipeline::setTexelBuffers(const TexelBuffers& views) {
    const VkBufferView placeholder = placeholderTexels_.handle();
    const VkBufferView bound[TEXEL_BINDING_COUNT] = {views.nodes ? views.nodes : placeholder,
        views.triangles ? views.triangles : placeholder, views.sphereNodes ? views.sphereNodes : placeholder,
        views.spheres ? views.spheres : placeholder};
    VkWriteDescriptorSet writes[TEXEL_BINDING_COUNT]{};
    for (uint32_t i = 0; i < TEXEL_BINDING_COUNT; ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = set_;
        writes[i].dstBinding = TEXEL_BINDING_NODES + i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        writes[i].pTexelBufferView = &bound[i];
    }
    vkUpdateDescriptorSets(context_.device(), TEXEL_BINDING_COUNT, writes, 0, nullptr);
}

ComputePipeline::~ComputePipeline() {
    if (pipeline_) vkDestroyPipeline(context_.device(), pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(context_.device(), layout_, nullptr);
    if (pool_) vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(context_.device(), setLayout_, nullptr);
}

void ComputePipeline::bindAndPush(VkCommandBuffer cmd, const void* pushData, uint32_t bytes) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, pushData);
}

} // namespace pt
