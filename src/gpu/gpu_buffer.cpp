#include "gpu/gpu_buffer.h"

#include "gpu/fault_injection.h"
#include "gpu/vulkan_error.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace pt {

int findMemoryType(
    const VkPhysicalDeviceMemoryProperties& props, uint32_t allowedTypes, VkMemoryPropertyFlags required) {
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((allowedTypes & (1u << i)) && (props.memoryTypes[i].propertyFlags & required) == required)
            return static_cast<int>(i);
    return -1;
}

namespace {

StagingPolicy stagingPolicy;

struct RawBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
};

// Creates a buffer and binds memory: host-visible + coherent if `preferHostVisible` finds such a
// type that is also device-local (or if `requireHostVisible`), else device-local.
RawBuffer createRawBuffer(
    VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool requireHostVisible, const char* name) {
    RawBuffer raw;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    std::string what = std::string("creating buffer '") + name + "' (" + std::to_string(size >> 20) + " MiB)";
    vkCheck(vkCreateBuffer(ctx.device(), &info, nullptr, &raw.buffer), what.c_str());
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device(), raw.buffer, &req);
    const VkMemoryPropertyFlags hostFlags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    int type = -1;
    if (requireHostVisible) {
        type = findMemoryType(ctx.memoryProperties(), req.memoryTypeBits, hostFlags);
    } else {
        type =
            findMemoryType(ctx.memoryProperties(), req.memoryTypeBits, hostFlags | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        if (type < 0)
            type = findMemoryType(ctx.memoryProperties(), req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    }
    if (type < 0) {
        vkDestroyBuffer(ctx.device(), raw.buffer, nullptr);
        throw std::runtime_error(what + ": no suitable memory type");
    }
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) ? VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT : 0;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = &flags;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = static_cast<uint32_t>(type);
    VkResult result = injectedAllocationFault(); // PT_FAULT test hook
    if (result == VK_SUCCESS) result = vkAllocateMemory(ctx.device(), &alloc, nullptr, &raw.memory);
    if (result != VK_SUCCESS) {
        vkDestroyBuffer(ctx.device(), raw.buffer, nullptr);
        throw VulkanError(result, what);
    }
    vkCheck(vkBindBufferMemory(ctx.device(), raw.buffer, raw.memory, 0), what.c_str());
    const VkMemoryPropertyFlags typeFlags = ctx.memoryProperties().memoryTypes[type].propertyFlags;
    if ((typeFlags & hostFlags) == hostFlags)
        vkCheck(vkMapMemory(ctx.device(), raw.memory, 0, VK_WHOLE_SIZE, 0, &raw.mapped), what.c_str());
    return raw;
}

void destroyRawBuffer(VulkanContext& ctx, RawBuffer& raw) {
    if (raw.mapped) vkUnmapMemory(ctx.device(), raw.memory);
    if (raw.buffer) vkDestroyBuffer(ctx.device(), raw.buffer, nullptr);
    if (raw.memory) vkFreeMemory(ctx.device(), raw.memory, nullptr);
    raw = {};
}

} // namespace

void setStagingPolicyForTests(const StagingPolicy& policy) { stagingPolicy = policy; }

GpuBuffer::GpuBuffer(VulkanContext& context, VkDeviceSize size, const char* name)
    : context_(&context), size_(std::max<VkDeviceSize>(size, 16)), name_(name) {
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                     VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    RawBuffer raw = createRawBuffer(context, size_, usage, false, name);
    if (stagingPolicy.forceStaging && raw.mapped) {
        vkUnmapMemory(context.device(), raw.memory);
        raw.mapped = nullptr;
    }
    buffer_ = raw.buffer;
    memory_ = raw.memory;
    mapped_ = raw.mapped;
    VkBufferDeviceAddressInfo addressInfo{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addressInfo.buffer = buffer_;
    address_ = vkGetBufferDeviceAddress(context.device(), &addressInfo);
}

GpuBuffer::~GpuBuffer() { release(); }

GpuBuffer::GpuBuffer(GpuBuffer&& other) noexcept { *this = std::move(other); }

GpuBuffer& GpuBuffer::operator=(GpuBuffer&& other) noexcept {
    if (this != &other) {
        release();
        context_ = std::exchange(other.context_, nullptr);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        mapped_ = std::exchange(other.mapped_, nullptr);
        address_ = std::exchange(other.address_, 0);
        size_ = std::exchange(other.size_, 0);
        name_ = other.name_;
    }
    return *this;
}

void GpuBuffer::release() {
    if (!context_) return;
    RawBuffer raw{buffer_, memory_, mapped_};
    destroyRawBuffer(*context_, raw);
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    context_ = nullptr;
}

void GpuBuffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
    if (bytes == 0) return;
    if (offset + bytes > size_) throw std::out_of_range(std::string("upload past the end of buffer ") + name_);
    if (mapped_)
        std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
    else
        copyThroughStaging(data, nullptr, bytes, offset, true);
}

void GpuBuffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
    if (bytes == 0) return;
    if (offset + bytes > size_) throw std::out_of_range(std::string("download past the end of buffer ") + name_);
    if (mapped_)
        std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
    else
        copyThroughStaging(nullptr, data, bytes, offset, false);
}

void GpuBuffer::fillZero() {
    VkBuffer buffer = buffer_;
    VkDeviceSize size = size_;
    context_->submitAndWait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer, 0, size, 0); });
}

void GpuBuffer::copyThroughStaging(
    const void* src, void* dst, VkDeviceSize bytes, VkDeviceSize offset, bool toDevice) const {
    // One staging buffer of at most a chunk, filled (or drained) and copied chunk after chunk.
    const VkDeviceSize chunk = std::min(bytes, std::max<VkDeviceSize>(stagingPolicy.chunkBytes, 16));
    RawBuffer staging = createRawBuffer(
        *context_, chunk, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, "staging");
    try {
        VkBuffer buffer = buffer_;
        for (VkDeviceSize done = 0; done < bytes; done += chunk) {
            const VkDeviceSize n = std::min(chunk, bytes - done);
            if (toDevice) std::memcpy(staging.mapped, static_cast<const char*>(src) + done, n);
            context_->submitAndWait([&](VkCommandBuffer cmd) {
                VkBufferCopy region{toDevice ? 0 : offset + done, toDevice ? offset + done : 0, n};
                if (toDevice)
                    vkCmdCopyBuffer(cmd, staging.buffer, buffer, 1, &region);
                else
                    vkCmdCopyBuffer(cmd, buffer, staging.buffer, 1, &region);
            });
            if (!toDevice) std::memcpy(static_cast<char*>(dst) + done, staging.mapped, n);
        }
    } catch (...) {
        destroyRawBuffer(*context_, staging);
        throw;
    }
    destroyRawBuffer(*context_, staging);
}

} // namespace pt
