#include "gpu/texel_view.h"

#include "gpu/vulkan_error.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace pt {

bool TexelView::fits(const VulkanContext& context, VkDeviceSize bytes) {
    return bytes % 16 == 0 && bytes / 16 <= context.properties().limits.maxTexelBufferElements;
}

TexelView::TexelView(VulkanContext& context, const GpuBuffer& buffer, VkDeviceSize bytes, const char* what)
    : device_(context.device()) {
    if (!fits(context, bytes) || bytes > buffer.size())
        throw std::runtime_error(
            std::string(what) + ": " + std::to_string(bytes) + " bytes do not fit a texel-buffer view of the buffer");
    VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    info.buffer = buffer.handle();
    info.format = VK_FORMAT_R32G32B32A32_UINT; // uniform texel buffers must support it (Vulkan's required formats)
    info.offset = 0;
    info.range = bytes;
    vkCheck(vkCreateBufferView(device_, &info, nullptr, &view_), what);
}

TexelView::~TexelView() {
    if (view_) vkDestroyBufferView(device_, view_, nullptr);
}

TexelView::TexelView(TexelView&& other) noexcept
    : device_(other.device_), view_(std::exchange(other.view_, VK_NULL_HANDLE)) {}

TexelView& TexelView::operator=(TexelView&& other) noexcept {
    if (this != &other) {
        if (view_) vkDestroyBufferView(device_, view_, nullptr);
        device_ = other.device_;
        view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    }
    return *this;
}

} // namespace pt
