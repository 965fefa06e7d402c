#pragma once
// A storage buffer the shaders reach through its device address. Memory is host-visible
// device memory where the device has it (lavapipe, resizable BAR); otherwise device-local
// memory filled and read through a staging buffer of at most kStagingChunkBytes, reused chunk
// after chunk, so a big upload never holds a second full copy in host memory.
#include "gpu/vulkan_context.h"

#include <cstddef>
#include <span>

namespace pt {

constexpr VkDeviceSize kStagingChunkBytes = VkDeviceSize(64) << 20;

// Tests only: make new buffers take the staging path even on host-visible memory (lavapipe has
// nothing else), with chunks of `chunkBytes`, so that path runs where the tests run.
struct StagingPolicy {
    bool forceStaging = false;
    VkDeviceSize chunkBytes = kStagingChunkBytes;
};
void setStagingPolicyForTests(const StagingPolicy& policy);

class GpuBuffer {
public:
    GpuBuffer() = default;
    GpuBuffer(VulkanContext& context, VkDeviceSize size, const char* name);
    ~GpuBuffer();
    GpuBuffer(GpuBuffer&& other) noexcept;
    GpuBuffer& operator=(GpuBuffer&& other) noexcept;
    GpuBuffer(const GpuBuffer&) = delete;
    GpuBuffer& operator=(const GpuBuffer&) = delete;

    void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
    void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;
    void fillZero();

    template <class T>
    void upload(std::span<const T> values) {
        upload(values.data(), values.size_bytes());
    }

    VkBuffer handle() const { return buffer_; }
    VkDeviceAddress address() const { return address_; }
    VkDeviceSize size() const { return size_; }

private:
    void release();
    void copyThroughStaging(const void* src, void* dst, VkDeviceSize bytes, VkDeviceSize offset, bool toDevice) const;

    VulkanContext* context_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    void* mapped_ = nullptr; // non-null when the memory is host-visible
    VkDeviceAddress address_ = 0;
    VkDeviceSize size_ = 0;
    const char* name_ = "";
};

// Index of a memory type with all of `required` among `allowedTypes`, or -1.
int findMemoryType(
    const VkPhysicalDeviceMemoryProperties& props, uint32_t allowedTypes, VkMemoryPropertyFlags required);

} // namespace pt
