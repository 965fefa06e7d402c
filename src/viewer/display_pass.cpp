#include "viewer/display_pass.h"

#include "pt_display_spv.h" // generated: shaders/viewer/display.comp

namespace pt::viewer {

DisplayPass::DisplayPass(VulkanContext& context) : context_(context) {
    pipeline_ = std::make_unique<ComputePipeline>(context, std::span<const uint32_t>(pt_display_spv),
        static_cast<uint32_t>(sizeof(gpu::GpuDisplayPush)), std::vector<SpecializationConstant>{}, "display");
}

void DisplayPass::resize(int width, int height) {
    vkDeviceWaitIdle(context_.device());
    pixels_.reset();
    pixels_ = std::make_unique<GpuBuffer>(context_, VkDeviceSize(width) * height * 4, "display pixels");
    pixels_->fillZero();
    width_ = width;
    height_ = height;
}

void DisplayPass::record(VkCommandBuffer cmd, gpu::GpuDisplayPush push, VkImage image) {
    push.display = pixels_->address();
    push.windowSize = glm::uvec2(width_, height_);

    VkMemoryBarrier sums{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    sums.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    sums.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &sums, 0, nullptr, 0, nullptr);
    pipeline_->bindAndPush(cmd, &push, sizeof(push));
    vkCmdDispatch(cmd, (push.windowSize.x + 7) / 8, (push.windowSize.y + 7) / 8, 1);

    // Pixels -> copy (and the host, for screenshots); image -> transfer destination. The image
    // transition waits at the transfer stage, where the frame waits for the acquire semaphore.
    VkMemoryBarrier pixels{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    pixels.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    pixels.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT;
    VkImageMemoryBarrier toCopy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    toCopy.srcAccessMask = 0;
    toCopy.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toCopy.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toCopy.srcQueueFamilyIndex = toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toCopy.image = image;
    toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &pixels, 0, nullptr, 1, &toCopy);

    VkBufferImageCopy region{};
    region.bufferRowLength = push.windowSize.x;
    region.bufferImageHeight = push.windowSize.y;
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {push.windowSize.x, push.windowSize.y, 1};
    vkCmdCopyBufferToImage(cmd, pixels_->handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);

    VkImageMemoryBarrier toPresent = toCopy;
    toPresent.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toPresent.dstAccessMask = 0;
    toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr, 0,
        nullptr, 1, &toPresent);
}

std::vector<uint8_t> DisplayPass::readRgb(bool bgra) const {
    const size_t n = size_t(width_) * height_;
    std::vector<uint32_t> packed(n);
    pixels_->download(packed.data(), n * 4);
    std::vector<uint8_t> rgb(n * 3);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t p = packed[i];
        const uint8_t b0 = p & 0xff, b1 = (p >> 8) & 0xff, b2 = (p >> 16) & 0xff;
        rgb[3 * i + 0] = bgra ? b2 : b0;
        rgb[3 * i + 1] = b1;
        rgb[3 * i + 2] = bgra ? b0 : b2;
    }
    return rgb;
}

} // namespace pt::viewer
