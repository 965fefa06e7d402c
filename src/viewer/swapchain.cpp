#include "viewer/swapchain.h"

#include "gpu/vulkan_error.h"
#include "viewer/window.h"

#include <algorithm>

namespace pt::viewer {
namespace {

// 8-bit formats whose bytes the display pass can write directly (the copy does no conversion,
// so an _SRGB format shows the same encoded bytes as a _UNORM one).
int formatRank(VkFormat f) {
    switch (f) {
    case VK_FORMAT_B8G8R8A8_UNORM: return 4;
    case VK_FORMAT_R8G8B8A8_UNORM: return 3;
    case VK_FORMAT_B8G8R8A8_SRGB: return 2;
    case VK_FORMAT_R8G8B8A8_SRGB: return 1;
    default: return 0;
    }
}

// MAILBOX and IMMEDIATE never block presentation on the display's refresh; the viewer paces
// itself by its work per frame. FIFO is always there.
int presentModeRank(VkPresentModeKHR m) {
    switch (m) {
    case VK_PRESENT_MODE_MAILBOX_KHR: return 3;
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return 2;
    case VK_PRESENT_MODE_FIFO_KHR: return 1;
    default: return 0;
    }
}

} // namespace

Swapchain::Swapchain(VulkanContext& context, int width, int height) : context_(context) { recreate(width, height); }

Swapchain::~Swapchain() { destroy(); }

bool Swapchain::bgra() const { return format_ == VK_FORMAT_B8G8R8A8_UNORM || format_ == VK_FORMAT_B8G8R8A8_SRGB; }

const char* Swapchain::presentModeName() const {
    switch (presentMode_) {
    case VK_PRESENT_MODE_MAILBOX_KHR: return "mailbox";
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return "immediate";
    default: return "fifo";
    }
}

void Swapchain::destroy() {
    VkDevice device = context_.device();
    for (VkSemaphore s : rendered_) vkDestroySemaphore(device, s, nullptr);
    rendered_.clear();
    images_.clear();
    if (swapchain_) vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
}

void Swapchain::recreate(int width, int height) {
    VkPhysicalDevice gpu = context_.physicalDevice();
    VkSurfaceKHR surface = context_.surface();
    vkDeviceWaitIdle(context_.device());

    VkSurfaceCapabilitiesKHR caps;
    vkCheck(
        vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface, &caps), "reading the window surface's capabilities");
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw NoDisplayError("the window surface does not accept copies (no TRANSFER_DST usage)");
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, formats.data());
    VkSurfaceFormatKHR chosen{VK_FORMAT_UNDEFINED, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
    for (const auto& f : formats)
        if (f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR && formatRank(f.format) > formatRank(chosen.format))
            chosen = f;
    if (formatRank(chosen.format) == 0) throw NoDisplayError("the window surface offers no 8-bit RGBA or BGRA format");
    vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &count, nullptr);
    std::vector<VkPresentModeKHR> modes(count);
    vkGetPhysicalDeviceSurfacePresentModesKHR(gpu, surface, &count, modes.data());
    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;
    for (VkPresentModeKHR m : modes)
        if (presentModeRank(m) > presentModeRank(mode)) mode = m;

    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {
        extent.width =
            std::clamp(static_cast<uint32_t>(std::max(width, 1)), caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(
            static_cast<uint32_t>(std::max(height, 1)), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface;
    info.minImageCount = imageCount;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha =
        (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
            : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = mode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR fresh = VK_NULL_HANDLE;
    vkCheck(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &fresh), "creating the swapchain");
    destroy();
    swapchain_ = fresh;
    extent_ = extent;
    format_ = chosen.format;
    presentMode_ = mode;

    vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, images_.data());
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    rendered_.resize(count);
    for (auto& s : rendered_)
        vkCheck(vkCreateSemaphore(context_.device(), &semaphoreInfo, nullptr, &s), "creating a semaphore");
}

bool Swapchain::acquire(VkSemaphore signal, uint32_t* imageIndex) {
    VkResult r = vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, signal, VK_NULL_HANDLE, imageIndex);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (r != VK_SUBOPTIMAL_KHR) vkCheck(r, "acquiring a swapchain image");
    return true;
}

bool Swapchain::present(uint32_t imageIndex, VkSemaphore wait) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &wait;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &imageIndex;
    VkResult r = vkQueuePresentKHR(context_.queue(), &info);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
    vkCheck(r, "presenting to the window");
    return true;
}

} // namespace pt::viewer
