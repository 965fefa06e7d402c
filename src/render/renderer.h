#pragma once
// Progressive rendering on the GPU: uploads a flattened scene once, then each addSamples()
// dispatches the megakernel to add samples to every pixel's float32 sums.
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "render/gpu_scene.h"
#include "gpu/vulkan_context.h"
#include "render/feature_set.h"
#include "render/flat_scene.h"
#include "render/image.h"
#include "render/integrator_settings.h"
#include "scene/scene.h"

#include <cstdint>
#include <memory>

namespace pt {

struct FilmSettings {
    int width = 512;
    int height = 512;
    glm::vec3 background{0.0f};
};

// Largest image pt renders: 32 bytes of sums per pixel must fit comfortably in device memory.
constexpr int kMaxImageSide = 16384;
constexpr int64_t kMaxImagePixels = int64_t(1) << 26;

class Renderer {
public:
    Renderer(VulkanContext& context, const FlatScene& scene, const FeatureSet& features,
        const IntegratorSettings& settings, const Camera& camera, const FilmSettings& film);

    // Adds `count` samples to every pixel. `tileSize` > 0 splits each pass into square tiles of
    // that many pixels (one dispatch each); the image is identical either way.
    void addSamples(uint32_t count, uint32_t tileSize = 0);

    uint32_t samplesPerPixel() const { return samples_; }
    int width() const { return film_.width; }
    int height() const { return film_.height; }
    double pipelineSeconds() const { return pipeline_->creationSeconds(); }

    // Reads the sums back: the mean image, per-pixel variance of that mean, non-finite samples dropped.
    struct Readback {
        Image mean;
        Image varianceOfMean;
        uint64_t droppedSamples = 0;
    };
    Readback read() const;

private:
    VulkanContext& context_;
    FilmSettings film_;
    uint32_t samples_ = 0;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<ComputePipeline> pipeline_;
    uint32_t localSize_ = 8;
};

// Checks a requested image size; throws std::runtime_error with the reason.
void validateImageSize(int width, int height);

gpu::GpuCamera toGpuCamera(const Camera& camera, int width, int height);

} // namespace pt
