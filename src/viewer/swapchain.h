#pragma once
// The window's swapchain: images the display pass copies into (transfer destination, so no
// graphics queue or storage-image support is needed), recreated when the window resizes.
#include "gpu/vulkan_context.h"

#include <vector>

namespace pt::viewer {

class Swapchain {
public:
    Swapchain(VulkanContext& context, int width, int height);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // Waits for the device, then builds a swapchain for the surface's current size (or this one).
    void recreate(int width, int height);

    // False when the swapchain is out of date (recreate, then try again).
    bool acquire(VkSemaphore signal, uint32_t* imageIndex);
    bool present(uint32_t imageIndex, VkSemaphore wait);

    VkExtent2D extent() const { return extent_; }
    VkFormat format() const { return format_; }
    bool bgra() const; // byte order B, G, R, A
    VkImage image(uint32_t index) const { return images_[index]; }
    // Signalled by the frame that fills image `index`, waited on by its presentation.
    VkSemaphore renderedSemaphore(uint32_t index) const { return rendered_[index]; }
    const char* presentModeName() const;

private:
    void destroy();

    VulkanContext& context_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    std::vector<VkImage> images_;
    std::vector<VkSemaphore> rendered_;
};

} // namespace pt::viewer
