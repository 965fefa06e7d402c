#include "render/renderer.h"

#include "pt_render_spv.h" // generated: the SPIR-V of shaders/integrator/render.comp

#include <cmath>
#include <stdexcept>
#include <string>

namespace pt {

void validateImageSize(int width, int height) {
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide ||
        int64_t(width) * height > kMaxImagePixels)
        throw std::runtime_error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is out of range (each side 1.." + std::to_string(kMaxImageSide) + ", at most " +
                                 std::to_string(kMaxImagePixels) + " pixels)");
}

gpu::GpuCamera toGpuCamera(const Camera& camera, int width, int height) {
    gpu::GpuCamera c{};
    c.origin = camera.position;
    c.forward = glm::normalize(camera.forward);
    c.right = glm::normalize(glm::cross(c.forward, camera.up));
    c.up = glm::cross(c.right, c.forward);
    if (camera.window) {
        c.window = *camera.window;
    } else {
        const float t = std::tan(0.5f * camera.yfov);
        const float r = t * static_cast<float>(width) / static_cast<float>(height);
        c.window = glm::vec4(-r, r, -t, t);
    }
    c.lensRadius = 0.5f * camera.apertureSize;
    c.focusDistance = camera.focusDistance;
    return c;
}


Renderer::Renderer(VulkanContext& context, const FlatScene& scene, const FeatureSet& features,
    const IntegratorSettings& settings, const Camera& camera, const FilmSettings& film)
    : context_(context), film_(film) {
    validateImageSize(film.width, film.height);
    gpu::GpuSceneParams params{};
    params.camera = toGpuCamera(camera, film.width, film.height);
    params.background = film.background;
    params.imageSize = glm::uvec2(film.width, film.height);
    params.maxDepth = settings.maxDepth;
    params.rrStartDepth = settings.rrStartDepth;
    params.seed = settings.seed;
    const size_t pixels = size_t(film.width) * film.height;
    gpuScene_ = std::make_unique<GpuScene>(context, scene, params, pixels * 2 * sizeof(glm::vec4));

    pipeline_ = std::make_unique<ComputePipeline>(context, std::span<const uint32_t>(pt_render_spv),
        static_cast<uint32_t>(sizeof(gpu::GpuRenderPush)), features.constants(localSize_, localSize_), "render");
}

void Renderer::addSamples(uint32_t count, uint32_t tileSize) {
    if (count == 0) return;
    if (uint64_t(samples_) + count > UINT32_MAX) throw std::runtime_error("sample count exceeds 2^32");
    const uint32_t w = static_cast<uint32_t>(film_.width);
    const uint32_t h = static_cast<uint32_t>(film_.height);
    const uint32_t tw = tileSize ? std::min(tileSize, w) : w;
    const uint32_t th = tileSize ? std::min(tileSize, h) : h;
    const uint32_t start = samples_;
    const ComputePipeline& pipeline = *pipeline_;
    const VkDeviceAddress paramsAddress = gpuScene_->paramsAddress();
    const uint32_t local = localSize_;
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        for (uint32_t y = 0; y < h; y += th)
            for (uint32_t x = 0; x < w; x += tw) {
                gpu::GpuRenderPush push{};
                push.sceneParams = paramsAddress;
                push.tileOrigin = glm::uvec2(x, y);
                push.tileSize = glm::uvec2(std::min(tw, w - x), std::min(th, h - y));
                push.sampleStart = start;
                push.sampleCount = count;
                pipeline.bindAndPush(cmd, &push, sizeof(push));
                vkCmdDispatch(cmd, (push.tileSize.x + local - 1) / local, (push.tileSize.y + local - 1) / local, 1);
            }
        // Make the sums visible to the host (read back after the fence).
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    samples_ += count;
}

Renderer::Readback Renderer::read() const {
    const size_t pixels = size_t(film_.width) * film_.height;
    std::vector<glm::vec4> sums(pixels * 2);
    gpuScene_->accumulation().download(sums.data(), sums.size() * sizeof(glm::vec4));
    Readback r;
    r.mean.width = r.varianceOfMean.width = film_.width;
    r.mean.height = r.varianceOfMean.height = film_.height;
    r.mean.rgba.assign(pixels * 4, 0.0f);
    r.varianceOfMean.rgba.assign(pixels * 4, 0.0f);
    const double n = samples_;
    for (size_t i = 0; i < pixels; ++i) {
        const glm::vec4 s = sums[2 * i];
        const glm::vec4 s2 = sums[2 * i + 1];
        r.droppedSamples += static_cast<uint64_t>(s.w);
        for (int c = 0; c < 3; ++c) {
            const double mean = n > 0 ? s[c] / n : 0.0;
            r.mean.rgba[4 * i + c] = static_cast<float>(mean);
            // Unbiased sample variance, divided by n for the variance of the mean.
            const double var = n > 1 ? std::max(0.0, (s2[c] / n - mean * mean) * n / (n - 1)) / n : 0.0;
            r.varianceOfMean.rgba[4 * i + c] = static_cast<float>(var);
        }
        r.mean.rgba[4 * i + 3] = 1.0f;
        r.varianceOfMean.rgba[4 * i + 3] = 1.0f;
    }
    return r;
}

} // namespace pt
