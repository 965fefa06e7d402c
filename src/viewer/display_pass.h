#pragma once
// The viewer's display pass: a compute shader tone maps the accumulation into a buffer of
// window pixels (shaders/viewer/display.comp), which is copied into the swapchain image. The
// buffer persists between frames (pixels the film has not reached yet keep their last
// picture) and is what a screenshot reads back.
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "viewer/display_layout.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace pt::viewer {

class DisplayPass {
public:
    explicit DisplayPass(VulkanContext& context);

    // Sizes the pixel buffer for a window (cleared to black).
    void resize(int width, int height);

    // Records: wait for the render dispatches, tone map (push.display is filled in here), copy
    // the pixels into `image` (UNDEFINED -> PRESENT_SRC layout).
    void record(VkCommandBuffer cmd, gpu::GpuDisplayPush push, VkImage image);

    // The last displayed picture as 8-bit RGB rows, top first (after the frame's fence).
    std::vector<uint8_t> readRgb(bool bgra) const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    VulkanContext& context_;
    std::unique_ptr<ComputePipeline> pipeline_;
    std::unique_ptr<GpuBuffer> pixels_;
    int width_ = 0, height_ = 0;
};

} // namespace pt::viewer
