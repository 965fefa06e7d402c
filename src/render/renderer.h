#pragma once
// Progressive rendering on the GPU: uploads a flattened scene once, then each addSamples()
// dispatches the megakernel to add samples to every pixel's double-float sums (accumulation_state.h).
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "render/gpu_scene.h"
#include "gpu/vulkan_context.h"
#include "film/accumulation_state.h"
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "image/image.h"
#include "flatten/integrator_settings.h"
#include "scene/scene.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

namespace pt {

struct FilmSettings {
    int width = 512;
    int height = 512;
    glm::vec3 background{0.0f};
};

// Largest image pt renders: 64 bytes of sums per pixel must fit comfortably in device memory.
constexpr int kMaxImageSide = 16384;
constexpr int64_t kMaxImagePixels = int64_t(1) << 26;

// A hash of the render kernels' SPIR-V: answers measured with one build's kernels
// (render/texel_load_choice.h) are not reused with another's.
uint64_t renderKernelFingerprint();

class Renderer {
public:
    Renderer(VulkanContext& context, const FlatScene& scene, const FeatureSet& features,
        const IntegratorSettings& settings, const Camera& camera, const FilmSettings& film);
    // The same, freeing the scene's big host arrays as they are uploaded (GpuScene's FlatScene&&
    // constructor): for a render that needs the flattened scene only once.
    Renderer(VulkanContext& context, FlatScene&& scene, const FeatureSet& features, const IntegratorSettings& settings,
        const Camera& camera, const FilmSettings& film);

    // Adds `count` samples to every pixel. `tileSize` > 0 splits each pass into square tiles of
    // that many pixels (one dispatch each); the image is identical either way.
    void addSamples(uint32_t count, uint32_t tileSize = 0);

    // ---- Adaptive sampling (render/adaptive_sampling.h): pixels take different sample counts.
    // Starts an epoch of `rounds` rounds in which pixel p adds allocation[p] samples (one per
    // pixel and row-major); the first call switches the renderer to per-pixel counts, from zero.
    // addSamples(count) then adds `count` rounds of the epoch (at most what is left of it), and
    // samplesPerPixel() counts rounds: the mean samples per pixel.
    void startAdaptiveEpoch(const std::vector<uint32_t>& allocation, uint32_t rounds);
    bool adaptive() const { return adaptiveSamples_ != nullptr; }
    uint32_t epochRoundsLeft() const { return epochRounds_ - epochRoundsDone_; }

    // ---- Interactive rendering (pt view): change what is rendered without reloading the scene.
    // Every change discards the samples so far (as reset() does) and applies from the next pass.
    void setCamera(const Camera& camera);
    // Renders width x height from now on (the viewer renders a fraction of the window while the
    // camera moves); the accumulation buffer grows when needed.
    void setFilmSize(int width, int height);
    // Depth, roulette start and seed go to the scene block; a different feature set (NEE, MIS,
    // RR, sampling, debug view) recreates the pipeline.
    void setIntegrator(const IntegratorSettings& settings, const FeatureSet& features);
    // > 0: scale each sample down so its largest component is at most this. Biased (it removes
    // energy); 0, the default, is off.
    void setSampleClamp(float clamp);
    // Drops the samples; the sums are cleared by the next recorded pass.
    void reset();

    // Building blocks of addSamples for callers that submit their own command buffers (the
    // viewer spreads a pass over frames): records tiles [firstTile, endTile) of a pass adding
    // `count` samples to each pixel from sample index samplesPerPixel(), preceded by the clear
    // a reset left pending. Tiles are numbered row by row. Call completePass(count) once every
    // tile of the pass has been recorded and submitted.
    uint32_t tileCount(uint32_t tileSize) const;
    void recordTiles(VkCommandBuffer cmd, uint32_t count, uint32_t tileSize, uint32_t firstTile, uint32_t endTile);
    void completePass(uint32_t count);
    // The sums: vec4[ACCUMULATION_VEC4S_PER_PIXEL * width * height], laid out as
    // GpuSceneParams::accumulation says, then (with light tracing) the splat sums,
    // uint64[SPLAT_WORDS_PER_PIXEL * width * height].
    VkDeviceAddress accumulationAddress() const { return accumulation().address(); }
    bool hasSplats() const { return features_.lightTracing || features_.bdpt; }
    // Where the splat sums start (after every pixel's ACCUM_* block), or 0 without them.
    VkDeviceAddress splatsAddress() const { return hasSplats() ? accumulation().address() + splatOffset() : 0; }
    const Camera& camera() const { return camera_; }
    const FeatureSet& features() const { return features_; }

    // Samples added to every pixel so far; the next pass starts at sample index
    // firstSample() + samplesPerPixel() of the global sequence.
    uint32_t samplesPerPixel() const { return samples_; }
    uint32_t firstSample() const { return firstSample_; }
    // Renders sample indices from `index` on (pt render --samples A:B); only before any pass.
    void setFirstSample(uint32_t index);
    int width() const { return film_.width; }
    int height() const { return film_.height; }
    // Creation plus the driver's compile at the first dispatch (primePipeline).
    double pipelineSeconds() const { return pipeline_->creationSeconds() + primeSeconds_; }
    // "reused" when this process compiled the kernel before (gpu/compiled_kernel.h), "cached"
    // when the specialised kernel was made before (this process or an earlier one).
    const char* pipelineSource() const {
        return pipeline_->compiledBefore() ? "reused" : pipeline_->specializedFromCache() ? "cached" : "specialised";
    }

    // Reads the sums back: the mean image, per-pixel variance of that mean, non-finite samples dropped.
    using Readback = AccumulatedImage;
    Readback read() const;
    // The raw state, exactly (checkpoints, partial renders), and its inverse: loadState makes
    // the renderer continue from `state` (same size) as if it had rendered it.
    AccumulationState readState() const;
    void loadState(const AccumulationState& state);

    // Rays traced so far, summed over pixels; only when the pipeline counts them
    // (FeatureSet::countRays, for pt bench). Camera rays are one per sample.
    struct RayCounts {
        uint64_t camera = 0, continuation = 0, shadow = 0;
    };
    RayCounts rayCounts() const;

private:
    const GpuBuffer& accumulation() const { return ownAccumulation_ ? *ownAccumulation_ : gpuScene_->accumulation(); }
    GpuBuffer& accumulation() { return ownAccumulation_ ? *ownAccumulation_ : gpuScene_->accumulation(); }
    // The constructors' shared steps: the scene block's values, the accumulation buffer's size,
    // and the pipeline (with its first empty dispatch) and ray counters once the scene is up.
    gpu::GpuSceneParams sceneParams(const IntegratorSettings& settings) const;
    VkDeviceSize filmBytes() const;
    void createPipeline();
    void makeParamsEditable();
    void uploadParams();
    VkDeviceSize bytesPerPixel() const;
    VkDeviceSize splatOffset() const; // bytes before the splat sums in the accumulation buffer
    // Interactive use: grows the accumulation buffer (our own) to at least `bytes`.
    void ensureAccumulationBytes(VkDeviceSize bytes);
    // Adaptive sampling's buffer read back (adaptiveSamples_ must exist).
    std::vector<glm::uvec4> adaptivePixels() const;
    // Vertex merging (features_.merging): the light vertex store and grid, sized for the film.
    void createMergingBuffers();
    // Records `count` rounds from sample index `first`: each a light dispatch, then a camera
    // dispatch, over every tile (integrator/vcm.glsl).
    void recordMergingRounds(VkCommandBuffer cmd, uint32_t first, uint32_t count, uint32_t tileSize);
    void recordMergingPhase(VkCommandBuffer cmd, uint32_t phase, uint32_t sampleIndex, uint32_t tileSize);
    // One dispatch per tile from firstTile to endTile, each push filled by `fill` past its tile.
    void dispatchTiles(VkCommandBuffer cmd, uint32_t tileSize, uint32_t firstTile, uint32_t endTile,
        const std::function<void(gpu::GpuRenderPush&)>& fill);
    float mergeRadiusOfRound(uint32_t sampleIndex) const;
    float initialMergeRadius(const IntegratorSettings& settings, std::optional<float> hitDistance) const;

public:
    // Vertex merging: the first round's merge radius (scene units), 0 without merging.
    float mergeRadius() const { return features_.merging ? mergeRadius_ : 0.0f; }

private:
    // Lavapipe turns a compute pipeline into machine code at its first dispatch, not when it
    // is created (seconds for the light-tracing kernel with a cold Mesa cache): one empty
    // dispatch right after creation moves that into start-up, where the log counts it, so that
    // no timed pass (--time budgets, pt bench) pays it.
    void primePipeline();

    VulkanContext& context_;
    FilmSettings film_;
    uint32_t samples_ = 0;
    uint32_t firstSample_ = 0;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<ComputePipeline> pipeline_;
    double primeSeconds_ = 0;
    // Workgroups of 8x8: shaders/integrator/pixel_groups.glsl maps their invocations to pixels
    // for exactly that size.
    static constexpr uint32_t localSize_ = 8;
    Camera camera_;
    FeatureSet features_;
    float sampleClamp_ = 0.0f;
    bool clearPending_ = false;
    // Interactive use only: a host-editable copy of the scene block, and an accumulation
    // buffer that outgrew the one GpuScene made. Null on the headless path.
    gpu::GpuSceneParams params_{};
    std::unique_ptr<GpuBuffer> ownParams_;
    std::unique_ptr<GpuBuffer> ownAccumulation_;
    std::unique_ptr<GpuBuffer> rayCounts_; // uvec4 per pixel when features_.countRays
    // Adaptive sampling: uvec4 per pixel (samples so far, this epoch's allocation, its rays, 0).
    std::unique_ptr<GpuBuffer> adaptiveSamples_;
    uint32_t epochRounds_ = 0, epochRoundsDone_ = 0;
    // Vertex merging: stored light vertices (GpuRenderPush::vcmVertices) and the grid's cell heads.
    std::unique_ptr<GpuBuffer> vcmVertices_, vcmCells_, vcmPilot_;
    uint32_t vcmVerticesPerPixel_ = 0, vcmCellMask_ = 0, vcmPilotMask_ = 0;
    bool pilotPending_ = false;                     // the pilot round is recorded with the first pass's rounds
    float mergeRadius_ = 0.0f, mergeAlpha_ = 0.75f; // the first round's radius (scene units)
    uint32_t maxDepth_ = 16;
    VkDeviceAddress paramsAddress_ = 0;
};

// Vertex merging's buffers for a film: a slot per light vertex a pixel's light subpath can leave
// (one per segment but the camera's), the grid's cell heads (8 per slot) and the pilot's counts
// (2 per slot), each a power of two.
struct MergingBufferSizes {
    uint32_t verticesPerPixel = 0, cells = 0, pilotCells = 0;
    VkDeviceSize bytes = 0; // all three buffers
};
MergingBufferSizes mergingBufferSizes(int width, int height, uint32_t maxDepth);
// --integrator auto renders by BDPT alone where merging's buffers would need more than this
// (1280x720 at depth 16 needs 1.6 GiB; 4K at depth 16, 6.3 GiB).
constexpr VkDeviceSize kAutoMergingMaxBytes = VkDeviceSize(2) << 30;

// Checks a requested image size; throws std::runtime_error with the reason.
void validateImageSize(int width, int height);

gpu::GpuCamera toGpuCamera(const Camera& camera, int width, int height);

} // namespace pt
