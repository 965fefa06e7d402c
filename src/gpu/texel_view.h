#pragma once
// A VkBufferView of a GpuBuffer as 16-byte texels (R32G32B32A32_UINT), for the kernel's texel-buffer
// bindings (TEXEL_BINDING_* in shaders/shared/layout.h). Move-only; empty (null handle) by default.
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace pt {

class TexelView {
public:
    TexelView() = default;
    // The first `bytes` of `buffer` (a multiple of 16, at most fitsTexelView's limit).
    TexelView(VulkanContext& context, const GpuBuffer& buffer, VkDeviceSize bytes, const char* what);
    ~TexelView();
    TexelView(TexelView&& other) noexcept;
    TexelView& operator=(TexelView&& other) noexcept;
    TexelView(const TexelView&) = delete;
    TexelView& operator=(const TexelView&) = delete;

    VkBufferView handle() const { return view_; }

    // Whether `bytes` of 16-byte texels fit one view on this device (maxTexelBufferElements).
    static bool fits(const VulkanContext& context, VkDeviceSize bytes);

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkBufferView view_ = VK_NULL_HANDLE;
};

// The views a kernel's texel-buffer bindings take (TEXEL_BINDING_*); null: a placeholder.
struct TexelBuffers {
    VkBufferView nodes = VK_NULL_HANDLE; // the triangle tree's
    VkBufferView triangles = VK_NULL_HANDLE;
    VkBufferView sphereNodes = VK_NULL_HANDLE;
    VkBufferView spheres = VK_NULL_HANDLE;
};

} // namespace pt
