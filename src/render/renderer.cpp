#include "render/renderer.h"

#include "base/hash.h"
#include "render/workgroup_order.h"

#include "pt_copy_words_spv.h"           // generated: shaders/viewer/copy_words.comp
#include "pt_render_bdpt_spv.h"          // generated: the same with -DPT_BDPT
#include "pt_render_light_tracing_spv.h" // generated: the same with -DPT_LIGHT_TRACING
#include "pt_render_spv.h"               // generated: the SPIR-V of shaders/integrator/render.comp

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace pt {

constexpr VkDeviceSize kAccumulationBytesPerPixel = ACCUMULATION_VEC4S_PER_PIXEL * sizeof(glm::vec4);
constexpr VkDeviceSize kSplatBytesPerPixel = SPLAT_WORDS_PER_PIXEL * sizeof(uint64_t);
// Vertex merging keeps a light vertex in its grid with probability min(1, this / n), n the
// vertices a pilot round left in its cell (integrator/vcm.glsl, mergeKeep): 4 had half the error
// of 16 at equal time on the two-rooms scene, 4x fewer merges, level with 2 (bench/RESULTS.md).
constexpr float kMergeKeepTarget = 4.0f;

namespace {
// Light tracing and BDPT splat with 64-bit atomics; a device without them renders by path
// tracing alone (the same image, noisier). `texelViews`: whether the scene's arrays fit texel
// views on this device (GpuScene::hasTexelViews; taken as yes before the scene is uploaded, which
// texel loads do not size).
FeatureSet supportedFeatures(const VulkanContext& context, FeatureSet features, bool texelViews = true) {
    if (!context.info().int64Atomics) features.lightTracing = features.bdpt = features.merging = false;
    // Texel buffers are measured faster on lavapipe only (bench/RESULTS.md, "Geometry read through
    // texel buffers"); not measured on a GPU, so there the kernel keeps its address loads.
    if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU || !texelViews) features.texelLoads = false;
    return features;
}

// The kernel's SPIR-V: the module with light tracing or BDPT only when it is used.
std::span<const uint32_t> renderKernel(const FeatureSet& features) {
    if (features.bdpt) return std::span<const uint32_t>(pt_render_bdpt_spv);
    if (features.lightTracing) return std::span<const uint32_t>(pt_render_light_tracing_spv);
    return std::span<const uint32_t>(pt_render_spv);
}
} // namespace

uint64_t renderKernelFingerprint() {
    uint64_t hash = fnv1a64(pt_render_spv, sizeof pt_render_spv);
    hash = fnv1a64(pt_render_light_tracing_spv, sizeof pt_render_light_tracing_spv, hash);
    return fnv1a64(pt_render_bdpt_spv, sizeof pt_render_bdpt_spv, hash);
}

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
    : context_(context), film_(film), camera_(camera), features_(supportedFeatures(context, features)) {
    validateImageSize(film.width, film.height);
    const std::optional<float> hitDistance = scene.cameraHitDistance;
    maxDepth_ = settings.maxDepth; // sizes merging's buffers, which filmBytes counts
    gpuScene_ = std::make_unique<GpuScene>(context, scene, sceneParams(settings), filmBytes());
    mergeRadius_ = initialMergeRadius(settings, hitDistance);
    mergeAlpha_ = settings.mergeAlpha;
    createPipeline();
}

Renderer::Renderer(VulkanContext& context, FlatScene&& scene, const FeatureSet& features,
    const IntegratorSettings& settings, const Camera& camera, const FilmSettings& film)
    : context_(context), film_(film), camera_(camera), features_(supportedFeatures(context, features)) {
    validateImageSize(film.width, film.height);
    const std::optional<float> hitDistance = scene.cameraHitDistance;
    maxDepth_ = settings.maxDepth; // sizes merging's buffers, which filmBytes counts
    gpuScene_ = std::make_unique<GpuScene>(context, std::move(scene), sceneParams(settings), filmBytes());
    mergeRadius_ = initialMergeRadius(settings, hitDistance);
    mergeAlpha_ = settings.mergeAlpha;
    createPipeline();
}

gpu::GpuSceneParams Renderer::sceneParams(const IntegratorSettings& settings) const {
    gpu::GpuSceneParams params{};
    params.camera = toGpuCamera(camera_, film_.width, film_.height);
    params.background = film_.background;
    params.imageSize = glm::uvec2(film_.width, film_.height);
    params.maxDepth = settings.maxDepth;
    params.rrStartDepth = settings.rrStartDepth;
    params.rrThreshold = settings.rrThreshold;
    params.seed = settings.seed;
    return params;
}

VkDeviceSize Renderer::filmBytes() const {
    const VkDeviceSize merging = features_.merging ? mergingBufferSizes(film_.width, film_.height, maxDepth_).bytes : 0;
    return VkDeviceSize(film_.width) * film_.height * bytesPerPixel() + merging;
}

MergingBufferSizes mergingBufferSizes(int width, int height, uint32_t maxDepth) {
    MergingBufferSizes m;
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    m.verticesPerPixel = std::clamp<uint32_t>(maxDepth - 1, 1, BDPT_MAX_LIGHT_VERTICES);
    const VkDeviceSize slots = pixels * m.verticesPerPixel;
    m.cells = 1024;
    while (m.cells < 8 * slots && m.cells < (1u << 25)) m.cells <<= 1;
    m.pilotCells = 1024;
    while (m.pilotCells < 2 * slots && m.pilotCells < (1u << 24)) m.pilotCells <<= 1;
    m.bytes = slots * VCM_VERTEX_VEC4S * 16 + pixels * sizeof(uint32_t) +
              (VkDeviceSize(m.cells) + m.pilotCells) * sizeof(uint32_t);
    return m;
}

void Renderer::createPipeline() {
    features_ = supportedFeatures(context_, features_, gpuScene_->hasTexelViews());
    const size_t pixels = size_t(film_.width) * film_.height;
    paramsAddress_ = gpuScene_->paramsAddress();

    pipeline_ = std::make_unique<ComputePipeline>(context_, renderKernel(features_),
        static_cast<uint32_t>(sizeof(gpu::GpuRenderPush)), features_.constants(localSize_, localSize_), "render",
        gpuScene_->uniformTriangles());
    pipeline_->setTexelBuffers(gpuScene_->texelBuffers());
    primePipeline();
    if (features_.merging) createMergingBuffers();
    if (features_.countRays) {
        rayCounts_ = std::make_unique<GpuBuffer>(context_, pixels * sizeof(glm::uvec4), "ray counts");
        rayCounts_->fillZero();
    }
}

void Renderer::createMergingBuffers() {
    const MergingBufferSizes m = mergingBufferSizes(film_.width, film_.height, maxDepth_);
    const VkDeviceSize pixels = VkDeviceSize(film_.width) * film_.height;
    vcmVerticesPerPixel_ = m.verticesPerPixel;
    vcmVertices_ = std::make_unique<GpuBuffer>(
        context_, pixels * m.verticesPerPixel * VCM_VERTEX_VEC4S * 16 + pixels * sizeof(uint32_t), "light vertices");
    vcmCellMask_ = m.cells - 1;
    vcmCells_ = std::make_unique<GpuBuffer>(context_, VkDeviceSize(m.cells) * sizeof(uint32_t), "merge grid");
    // The pilot: one round of light subpaths of their own, counted in cells of the first round's
    // grid, before any round (integrator/vcm.glsl, mergeKeep).
    vcmPilotMask_ = m.pilotCells - 1;
    vcmPilot_ = std::make_unique<GpuBuffer>(context_, VkDeviceSize(m.pilotCells) * sizeof(uint32_t), "merge pilot");
    vcmPilot_->fillZero();
    pilotPending_ = true;
}

void Renderer::recordMergingPhase(VkCommandBuffer cmd, uint32_t phase, uint32_t sampleIndex, uint32_t tileSize) {
    dispatchTiles(cmd, tileSize, 0, tileCount(tileSize), [&](gpu::GpuRenderPush& push) {
        push.sampleStart = sampleIndex;
        push.sampleCount = 1;
        push.sampleClamp = sampleClamp_;
        push.rayCounts = phase == VCM_PHASE_PILOT || !rayCounts_ ? 0 : rayCounts_->address();
        push.phase = phase;
        push.mergeRadius = mergeRadiusOfRound(sampleIndex);
        push.vcmCellMask = vcmCellMask_;
        push.vcmVertices = vcmVertices_->address();
        push.vcmCells = vcmCells_->address();
        push.vcmPilot = vcmPilot_->address();
        push.vcmVerticesPerPixel = vcmVerticesPerPixel_;
        push.vcmPilotMask = vcmPilotMask_;
        push.vcmPilotCell = 2.0f * mergeRadius_;
        push.vcmKeepTarget = kMergeKeepTarget;
    });
}

void Renderer::dispatchTiles(VkCommandBuffer cmd, uint32_t tileSize, uint32_t firstTile, uint32_t endTile,
    const std::function<void(gpu::GpuRenderPush&)>& fill) {
    const uint32_t w = static_cast<uint32_t>(film_.width);
    const uint32_t h = static_cast<uint32_t>(film_.height);
    const uint32_t tw = tileSize ? std::min(tileSize, w) : w;
    const uint32_t th = tileSize ? std::min(tileSize, h) : h;
    const uint32_t tilesX = (w + tw - 1) / tw;
    for (uint32_t tile = firstTile; tile < endTile; ++tile) {
        const uint32_t x = (tile % tilesX) * tw;
        const uint32_t y = (tile / tilesX) * th;
        gpu::GpuRenderPush push{};
        push.sceneParams = paramsAddress_;
        push.tileOrigin = glm::uvec2(x, y);
        push.tileSize = glm::uvec2(std::min(tw, w - x), std::min(th, h - y));
        const uint32_t groupsX = (push.tileSize.x + localSize_ - 1) / localSize_;
        const uint32_t groupsY = (push.tileSize.y + localSize_ - 1) / localSize_;
        push.blockStride = workgroupBlockStride(groupsX * groupsY);
        fill(push);
        pipeline_->bindAndPush(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, groupsX, groupsY, 1);
    }
}

float Renderer::initialMergeRadius(const IntegratorSettings& settings, std::optional<float> hitDistance) const {
    const glm::vec4 window = toGpuCamera(camera_, film_.width, film_.height).window;
    const float pixelAngle = (window.w - window.z) / float(film_.height); // image plane at unit distance
    return settings.mergeRadius * pixelAngle * hitDistance.value_or(gpuScene_->sceneRadius());
}

float Renderer::mergeRadiusOfRound(uint32_t sampleIndex) const {
    return mergeRadius_ * std::pow(float(sampleIndex) + 1.0f, 0.5f * (mergeAlpha_ - 1.0f));
}

void Renderer::recordMergingRounds(VkCommandBuffer cmd, uint32_t first, uint32_t count, uint32_t tileSize) {
    auto barrier = [&](VkAccessFlags src, VkPipelineStageFlags srcStage) {
        VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        b.srcAccessMask = src;
        b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
        vkCmdPipelineBarrier(cmd, srcStage, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0, nullptr, 0, nullptr);
    };
    if (clearPending_) {
        vkCmdFillBuffer(cmd, accumulation().handle(), 0, VkDeviceSize(film_.width) * film_.height * bytesPerPixel(), 0);
        clearPending_ = false;
    }
    // The pilot runs in the first pass, so that a time budget counts it (equal-time comparisons).
    if (pilotPending_) {
        recordMergingPhase(cmd, VCM_PHASE_PILOT, 0, tileSize);
        pilotPending_ = false;
    }
    for (uint32_t round = 0; round < count; ++round) {
        // Before the grid is emptied: the pilot's counts written, the last round's camera phase done
        // reading the grid, and the sums' clear or earlier passes done before they are added to.
        barrier(VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdFillBuffer(cmd, vcmCells_->handle(), 0, VK_WHOLE_SIZE, VCM_NO_VERTEX);
        barrier(VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        recordMergingPhase(cmd, VCM_PHASE_LIGHT, first + round, tileSize);
        barrier(VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
        recordMergingPhase(cmd, VCM_PHASE_CAMERA, first + round, tileSize);
    }
}

void Renderer::primePipeline() {
    const auto start = std::chrono::steady_clock::now();
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        gpu::GpuRenderPush push{};
        push.sceneParams = paramsAddress_;
        push.tileSize = glm::uvec2(0); // every invocation returns at once (render.comp)
        pipeline_->bindAndPush(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, 1, 1, 1);
    });
    primeSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VkDeviceSize Renderer::bytesPerPixel() const {
    return kAccumulationBytesPerPixel + (hasSplats() ? kSplatBytesPerPixel : 0);
}

VkDeviceSize Renderer::splatOffset() const {
    return VkDeviceSize(film_.width) * film_.height * kAccumulationBytesPerPixel;
}

void Renderer::startAdaptiveEpoch(const std::vector<uint32_t>& allocation, uint32_t rounds) {
    const size_t pixels = size_t(film_.width) * film_.height;
    if (allocation.size() != pixels) throw std::logic_error("adaptive allocation is not one count per pixel");
    if (rounds == 0) throw std::logic_error("adaptive epoch of no rounds");
    if (epochRoundsDone_ != epochRounds_) throw std::logic_error("adaptive epoch started before the last one ended");
    if (firstSample_ != 0) throw std::runtime_error("adaptive sampling renders whole images, not --samples ranges");
    std::vector<glm::uvec4> perPixel(pixels, glm::uvec4(0));
    if (!adaptiveSamples_) {
        if (samples_ != 0) throw std::logic_error("adaptive sampling switched on after uniform passes");
        adaptiveSamples_ = std::make_unique<GpuBuffer>(context_, pixels * sizeof(glm::uvec4), "adaptive samples");
    } else {
        perPixel = adaptivePixels();
    }
    for (size_t i = 0; i < pixels; ++i) {
        perPixel[i].y = allocation[i];
        perPixel[i].z = 0; // the epoch's rays
        if (uint64_t(perPixel[i].x) + allocation[i] > UINT32_MAX)
            throw std::runtime_error("a pixel's sample index would exceed 2^32");
    }
    adaptiveSamples_->upload(perPixel.data(), pixels * sizeof(glm::uvec4));
    epochRounds_ = rounds;
    epochRoundsDone_ = 0;
}

std::vector<glm::uvec4> Renderer::adaptivePixels() const {
    std::vector<glm::uvec4> perPixel(size_t(film_.width) * film_.height);
    adaptiveSamples_->download(perPixel.data(), perPixel.size() * sizeof(glm::uvec4));
    return perPixel;
}

void Renderer::addSamples(uint32_t count, uint32_t tileSize) {
    if (count == 0) return;
    if (adaptive() && count > epochRoundsLeft()) throw std::logic_error("pass runs past its adaptive epoch");
    if (uint64_t(firstSample_) + samples_ + count > UINT32_MAX) throw std::runtime_error("sample index exceeds 2^32");
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        if (features_.merging)
            recordMergingRounds(cmd, firstSample_ + samples_, count, tileSize);
        else
            recordTiles(cmd, count, tileSize, 0, tileCount(tileSize));
        // Make the sums visible to the host (read back after the fence).
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    completePass(count);
}

uint32_t Renderer::tileCount(uint32_t tileSize) const {
    const uint32_t w = static_cast<uint32_t>(film_.width);
    const uint32_t h = static_cast<uint32_t>(film_.height);
    const uint32_t tw = tileSize ? std::min(tileSize, w) : w;
    const uint32_t th = tileSize ? std::min(tileSize, h) : h;
    return ((w + tw - 1) / tw) * ((h + th - 1) / th);
}

void Renderer::recordTiles(
    VkCommandBuffer cmd, uint32_t count, uint32_t tileSize, uint32_t firstTile, uint32_t endTile) {
    const uint32_t w = static_cast<uint32_t>(film_.width);
    const uint32_t h = static_cast<uint32_t>(film_.height);
    endTile = std::min(endTile, tileCount(tileSize));
    if (count == 0 || firstTile >= endTile) return;
    if (features_.merging)
        throw std::logic_error("vertex merging renders whole rounds (addSamples), not tiles of a pass");
    if (clearPending_) {
        const VkDeviceSize bytes = VkDeviceSize(w) * h * bytesPerPixel();
        vkCmdFillBuffer(cmd, accumulation().handle(), 0, bytes, 0);
        clearPending_ = false;
    }
    // Earlier passes (and the clear) wrote these sums: finish them before adding to them.
    VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    before.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
    dispatchTiles(cmd, tileSize, firstTile, endTile, [&](gpu::GpuRenderPush& push) {
        push.sampleStart = adaptive() ? epochRoundsDone_ : firstSample_ + samples_;
        push.sampleCount = count;
        push.adaptiveSamples = adaptive() ? adaptiveSamples_->address() : 0;
        push.epochRounds = epochRounds_;
        push.sampleClamp = sampleClamp_;
        push.rayCounts = rayCounts_ ? rayCounts_->address() : 0;
    });
}

void Renderer::completePass(uint32_t count) {
    if (uint64_t(firstSample_) + samples_ + count > UINT32_MAX) throw std::runtime_error("sample index exceeds 2^32");
    samples_ += count;
    if (adaptive()) epochRoundsDone_ += count;
}

void Renderer::reset() {
    samples_ = 0;
    firstSample_ = 0;
    clearPending_ = true;
    adaptiveSamples_.reset(); // the viewer's passes are uniform
    epochRounds_ = epochRoundsDone_ = 0;
    if (rayCounts_) rayCounts_->fillZero(); // only headless renders count, with nothing in flight
}

// The scene block's buffer addresses exist only in device memory (GpuScene fills them in), so
// the first interactive change copies the block on the device into a buffer of our own and
// reads it back; from then on the host edits params_ and the kernel reads our copy.
void Renderer::makeParamsEditable() {
    if (ownParams_) return;
    ownParams_ = std::make_unique<GpuBuffer>(context_, sizeof(gpu::GpuSceneParams), "editable scene params");
    static_assert(sizeof(gpu::GpuSceneParams) % 4 == 0);
    struct {
        VkDeviceAddress source, destination;
        uint32_t count;
    } push{gpuScene_->paramsAddress(), ownParams_->address(), sizeof(gpu::GpuSceneParams) / 4};
    ComputePipeline copy(context_, std::span<const uint32_t>(pt_copy_words_spv), sizeof(push), {}, "copy words");
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        copy.bindAndPush(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, (push.count + 63) / 64, 1, 1);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    ownParams_->download(&params_, sizeof(params_));
    paramsAddress_ = ownParams_->address();
}

void Renderer::uploadParams() {
    // The viewer only changes the block between frames, with nothing in flight.
    ownParams_->upload(&params_, sizeof(params_));
}

void Renderer::setCamera(const Camera& camera) {
    makeParamsEditable();
    camera_ = camera;
    params_.camera = toGpuCamera(camera_, film_.width, film_.height);
    uploadParams();
    reset();
}

void Renderer::ensureAccumulationBytes(VkDeviceSize bytes) {
    if (bytes <= accumulation().size()) return;
    vkDeviceWaitIdle(context_.device());
    ownAccumulation_.reset();
    ownAccumulation_ = std::make_unique<GpuBuffer>(context_, bytes, "accumulation");
    params_.accumulation = accumulation().address();
}

void Renderer::setFilmSize(int width, int height) {
    validateImageSize(width, height);
    makeParamsEditable();
    ensureAccumulationBytes(VkDeviceSize(width) * height * bytesPerPixel());
    film_.width = width;
    film_.height = height;
    params_.imageSize = glm::uvec2(width, height);
    params_.camera = toGpuCamera(camera_, width, height);
    uploadParams();
    reset();
}

void Renderer::setIntegrator(const IntegratorSettings& settings, const FeatureSet& features) {
    makeParamsEditable();
    params_.maxDepth = settings.maxDepth;
    params_.rrStartDepth = settings.rrStartDepth;
    params_.rrThreshold = settings.rrThreshold;
    params_.seed = settings.seed;
    const FeatureSet wanted = supportedFeatures(context_, features, gpuScene_->hasTexelViews());
    const auto constants = wanted.constants(localSize_, localSize_);
    const auto current = features_.constants(localSize_, localSize_);
    const bool same = std::equal(constants.begin(), constants.end(), current.begin(), current.end(),
        [](const SpecializationConstant& a, const SpecializationConstant& b) {
            return a.id == b.id && a.value == b.value;
        });
    if (!same) {
        auto fresh = std::make_unique<ComputePipeline>(context_, renderKernel(wanted),
            static_cast<uint32_t>(sizeof(gpu::GpuRenderPush)), constants, "render", gpuScene_->uniformTriangles());
        fresh->setTexelBuffers(gpuScene_->texelBuffers());
        vkDeviceWaitIdle(context_.device());
        pipeline_ = std::move(fresh);
        primePipeline();
        features_ = wanted;
        // Turning light tracing on needs room for the splat sums.
        ensureAccumulationBytes(VkDeviceSize(film_.width) * film_.height * bytesPerPixel());
    }
    uploadParams();
    reset();
}

void Renderer::setSampleClamp(float clamp) {
    sampleClamp_ = clamp > 0.0f ? clamp : 0.0f;
    reset();
}

Renderer::Readback Renderer::read() const { return resolve(readState()); }

AccumulationState Renderer::readState() const {
    AccumulationState state;
    state.width = film_.width;
    state.height = film_.height;
    state.samples = {firstSample_, firstSample_ + samples_};
    state.spp = samples_;
    state.sums.resize(state.pixels() * ACCUMULATION_VEC4S_PER_PIXEL);
    if (hasSplats()) state.splats.assign(state.pixels() * SPLAT_WORDS_PER_PIXEL, 0);
    if (samples_ > 0) {
        accumulation().download(state.sums.data(), state.sums.size() * sizeof(glm::vec4));
        if (!state.splats.empty())
            accumulation().download(state.splats.data(), state.splats.size() * sizeof(uint64_t), splatOffset());
    }
    if (adaptive()) {
        const std::vector<glm::uvec4> perPixel = adaptivePixels();
        state.pixelSamples.resize(perPixel.size());
        state.allocation.resize(perPixel.size());
        state.epochRays.resize(perPixel.size());
        for (size_t i = 0; i < perPixel.size(); ++i) {
            state.pixelSamples[i] = perPixel[i].x;
            state.allocation[i] = perPixel[i].y;
            state.epochRays[i] = perPixel[i].z;
        }
        state.epochRounds = epochRounds_;
        state.epochRoundsDone = epochRoundsDone_;
    }
    return state; // zeros before the first pass, even if a reset left the buffer uncleared
}

void Renderer::loadState(const AccumulationState& state) {
    if (state.width != film_.width || state.height != film_.height)
        throw std::runtime_error("saved state is " + std::to_string(state.width) + "x" + std::to_string(state.height) +
                                 " but the render is " + std::to_string(film_.width) + "x" +
                                 std::to_string(film_.height));
    if (state.spp != state.samples.count())
        throw std::runtime_error(
            "saved state has gaps in its sample range " + state.samples.describe() + " and cannot be continued");
    if (state.hasSplats() != hasSplats())
        throw std::runtime_error(std::string("saved state was rendered ") + (state.hasSplats() ? "with" : "without") +
                                 " light paths but this render is " + (hasSplats() ? "with" : "without") +
                                 " (--light-tracing, --integrator)");
    accumulation().upload(state.sums.data(), state.sums.size() * sizeof(glm::vec4));
    if (state.hasSplats())
        accumulation().upload(state.splats.data(), state.splats.size() * sizeof(uint64_t), splatOffset());
    firstSample_ = state.samples.begin;
    samples_ = state.spp;
    clearPending_ = false;
    adaptiveSamples_.reset();
    epochRounds_ = epochRoundsDone_ = 0;
    if (state.adaptive()) {
        const size_t pixels = state.pixels();
        if (state.pixelSamples.size() != pixels || state.allocation.size() != pixels ||
            state.epochRays.size() != pixels || state.epochRoundsDone > state.epochRounds || state.samples.begin != 0)
            throw std::runtime_error("saved adaptive sampling state is inconsistent");
        std::vector<glm::uvec4> perPixel(pixels);
        for (size_t i = 0; i < pixels; ++i)
            perPixel[i] = glm::uvec4(state.pixelSamples[i], state.allocation[i], state.epochRays[i], 0);
        adaptiveSamples_ = std::make_unique<GpuBuffer>(context_, pixels * sizeof(glm::uvec4), "adaptive samples");
        adaptiveSamples_->upload(perPixel.data(), pixels * sizeof(glm::uvec4));
        epochRounds_ = state.epochRounds;
        epochRoundsDone_ = state.epochRoundsDone;
    }
}

void Renderer::setFirstSample(uint32_t index) {
    if (samples_ != 0) throw std::logic_error("setFirstSample after samples were added");
    firstSample_ = index;
}

Renderer::RayCounts Renderer::rayCounts() const {
    RayCounts counts;
    counts.camera = uint64_t(samples_) * film_.width * film_.height;
    if (adaptive()) {
        counts.camera = 0;
        for (const glm::uvec4& p : adaptivePixels()) counts.camera += p.x;
    }
    if (!rayCounts_) return counts;
    std::vector<glm::uvec4> perPixel(size_t(film_.width) * film_.height);
    rayCounts_->download(perPixel.data(), perPixel.size() * sizeof(glm::uvec4));
    uint64_t closest = 0;
    for (const glm::uvec4& c : perPixel) {
        closest += c.x;
        counts.shadow += c.y;
    }
    counts.continuation = closest > counts.camera ? closest - counts.camera : 0;
    return counts;
}

} // namespace pt
