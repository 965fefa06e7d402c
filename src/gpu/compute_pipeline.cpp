#include "gpu/compute_pipeline.h"

#include "base/hash.h"
#include "gpu/vulkan_error.h"
#include "shared/layout.h"

#include <chrono>
#include <string>

namespace pt {

namespace {

// The set layout every pipeline here has: the uniform block at binding 0 and the texel buffers after it.
VkDescriptorSetLayout createSetLayout(VkDevice device, const std::string& what) {
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
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    vkCheck(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout), what.c_str());
    return setLayout;
}

// The driver's compile of `spirv` (with its layouts).
std::shared_ptr<const CompiledKernel> compileKernel(
    VulkanContext& context, std::span<const uint32_t> spirv, uint32_t pushConstantBytes, const std::string& what) {
    const VkDevice device = context.device();
    auto kernel = std::make_shared<CompiledKernel>(device); // destroys what was made if a step throws
    kernel->setLayout = createSetLayout(device, what);
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &kernel->setLayout;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    vkCheck(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &kernel->layout), what.c_str());

    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.size_bytes();
    moduleInfo.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    vkCheck(vkCreateShaderModule(device, &moduleInfo, nullptr, &module), what.c_str());
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = kernel->layout;
    const VkResult result =
        vkCreateComputePipelines(device, context.pipelineCache().handle(), 1, &info, nullptr, &kernel->pipeline);
    vkDestroyShaderModule(device, module, nullptr);
    if (result != VK_SUCCESS) {
        kernel->pipeline = VK_NULL_HANDLE;
        throw VulkanError(result, what);
    }
    return kernel;
}

} // namespace

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
    const SpecializedKernel specialized = cache.specialize(spirv, constants, name);
    specializedFromCache_ = specialized.fromCache;
    const uint64_t key = fnv1a64(&pushConstantBytes, sizeof pushConstantBytes, specialized.key);
    kernel_ = cache.recentKernels().find(key);
    compiledBefore_ = kernel_ != nullptr;
    if (!kernel_) {
        kernel_ = compileKernel(context, specialized.spirv, pushConstantBytes, what);
        cache.recentKernels().keep(key, kernel_);
        cache.save();
    }
    createDescriptors(uniforms, what);
    creationSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VkDeviceSize ComputePipeline::uniformBlockBytes() {
    return VkDeviceSize(UNIFORM_TRIANGLES_MAX) * UNIFORM_TRIANGLE_VEC4S * 16;
}

// A pool of one set and the set itself (of the kernel's set layout), pointing at `uniforms` or
// at a zero-filled buffer of the pipeline's own, and at placeholder texels until setTexelBuffers.
void ComputePipeline::createDescriptors(const GpuBuffer* uniforms, const std::string& what) {
    if (!uniforms) {
        ownUniforms_ = std::make_unique<GpuBuffer>(context_, uniformBlockBytes(), "uniforms");
        ownUniforms_->fillZero();
        uniforms = ownUniforms_.get();
    }
    if (uniforms->size() < uniformBlockBytes())
        throw std::runtime_error(what + ": the uniform buffer is smaller than the kernel's block");
    placeholderTexels_ = TexelView(context_, *uniforms, uniformBlockBytes(), what.c_str());
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
        allocInfo.pSetLayouts = &kernel_->setLayout;
        result = vkAllocateDescriptorSets(context_.device(), &allocInfo, &set_);
    }
    if (result != VK_SUCCESS) {
        if (pool_) vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
        pool_ = VK_NULL_HANDLE;
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
    if (pool_) vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

void ComputePipeline::bindAndPush(VkCommandBuffer cmd, const void* pushData, uint32_t bytes) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel_->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel_->layout, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, kernel_->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, pushData);
}

} // namespace pt
