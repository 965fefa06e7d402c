#include "viewer/viewer.h"

#include "gpu/vulkan_error.h"
#include "flatten/feature_set.h"
#include "viewer/viewer_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pt::viewer {
namespace {

// Timestamp queries: frame start, after the render dispatches, after the display pass, then
// one after each tile of a tiled pass (at most this many tiles per frame).
constexpr uint32_t kQueryStart = 0, kQueryRendered = 1, kQueryDisplayed = 2, kQueryFirstTile = 3;
constexpr uint32_t kMaxFrameTiles = 256;
// While a still view refines, frames whose work the eye would not see are not displayed: the
// picture is refreshed at least this often (and at every change and every completed pass),
// which saves the display pass and presentation (a few ms a frame on lavapipe) for rendering.
constexpr double kRefineDisplayIntervalMs = 40.0;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Centre and radius of the scene, from the roots of its BVHs.
void sceneSphere(const FlatScene& flat, glm::vec3& centre, float& radius) {
    const Aabb box = sceneBounds(flat);
    glm::vec3 lo = box.lo, hi = box.hi;
    if (box.empty()) lo = hi = glm::vec3(0.0f);
    centre = 0.5f * (lo + hi);
    radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
}

CameraController makeController(const FlatScene& flat, const Camera& camera) {
    glm::vec3 centre;
    float radius;
    sceneSphere(flat, centre, radius);
    return CameraController(camera, centre, radius);
}

// The viewer spreads a pass's tiles over frames; vertex merging renders whole rounds of two
// dispatches over the image (Renderer::addSamples), so the viewer renders its scenes by BDPT.
FeatureSet viewerFeatures(const FlatScene& flat, const IntegratorSettings& settings) {
    FeatureSet features = computeFeatures(flat, settings);
    features.merging = false;
    return features;
}

} // namespace

Session::Session(Window& window, VulkanContext& context, const FlatScene& flat, const ViewerConfig& config)
    : window_(window), context_(context), flat_(flat), config_(config),
      controller_(makeController(flat, config.job.camera)), settings_(config.job.settings), ev_(config.exposure) {
    if (config.job.tonemap.op == TonemapSettings::Operator::Photographic) op_ = DisplayOperator::Photographic;
    windowSize_ = window.framebufferSize();
    if (windowSize_.x <= 0 || windowSize_.y <= 0) windowSize_ = glm::ivec2(config.job.width, config.job.height);

    FeatureSet features = viewerFeatures(flat, settings_);
    renderer_ = std::make_unique<Renderer>(context, flat, features, settings_, config.job.camera,
        FilmSettings{windowSize_.x, windowSize_.y, config.background});
    std::fprintf(stderr, "pt: view: kernel features: %s; pipeline %.3f s (%s kernel)\n", features.describe().c_str(),
        renderer_->pipelineSeconds(), renderer_->pipelineSource());

    swapchain_ = std::make_unique<Swapchain>(context, windowSize_.x, windowSize_.y);
    windowSize_ = glm::ivec2(swapchain_->extent().width, swapchain_->extent().height);
    display_ = std::make_unique<DisplayPass>(context);
    display_->resize(windowSize_.x, windowSize_.y);
    std::fprintf(stderr, "pt: view: swapchain %dx%d, %s presentation, %s\n", windowSize_.x, windowSize_.y,
        swapchain_->presentModeName(), swapchain_->bgra() ? "BGRA" : "RGBA");

    VkDevice device = context.device();
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    vkCheck(vkCreateCommandPool(device, &poolInfo, nullptr, &pool_), "creating the viewer's command pool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    vkCheck(vkAllocateCommandBuffers(device, &alloc, &cmd_), "allocating the viewer's command buffer");
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vkCheck(vkCreateFence(device, &fenceInfo, nullptr, &fence_), "creating a fence");
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    vkCheck(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &acquired_), "creating a semaphore");

    // GPU timestamps around the render dispatches and the display pass, when the queue has them.
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &familyCount, families.data());
    if (families[context.queueFamily()].timestampValidBits > 0) {
        VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
        queryInfo.queryCount = kQueryFirstTile + kMaxFrameTiles;
        vkCheck(vkCreateQueryPool(device, &queryInfo, nullptr, &queries_), "creating a timestamp query pool");
        timestampMs_ = context.properties().limits.timestampPeriod * 1e-6;
    }
}

Session::~Session() {
    VkDevice device = context_.device();
    vkDeviceWaitIdle(device);
    if (queries_) vkDestroyQueryPool(device, queries_, nullptr);
    if (acquired_) vkDestroySemaphore(device, acquired_, nullptr);
    if (fence_) vkDestroyFence(device, fence_, nullptr);
    if (pool_) vkDestroyCommandPool(device, pool_, nullptr);
}

bool Session::workLeft() const {
    if (paused_) return false;
    return passActive_ || scale_ > 1 || renderer_->samplesPerPixel() < config_.sppCap;
}

bool Session::needFrame() const {
    const bool scriptActive = config_.scripted && (scriptNext_ < config_.script.size() || waitFrames_ > 0 ||
                                                      waitSpp_ >= 0 || repeatLeft_ > 0 || waitResize_ > 0);
    return workLeft() || displayDirty_ || cameraDirty_ || integratorDirty_ || clampDirty_ || sizeDirty_ || scriptActive;
}

// The preview divides the window so that one pass fits the frame budget at the learnt cost.
int Session::choosePreviewScale() const {
    const double passMs = double(windowSize_.x) * windowSize_.y * costMs_;
    return std::clamp(static_cast<int>(std::ceil(std::sqrt(passMs / config_.frameBudgetMs))), 1, 16);
}

void Session::resetPass() {
    passActive_ = false;
    passTilesDone_ = 0;
    renderSeconds_ = 0;
    termsSpp_ = 0;
    displayDirty_ = true;
}

// Applies pending changes. Anything that restarts accumulation first renders a preview (the
// window divided by a scale chosen from the measured speed), refined once the view is still.
void Session::applyChanges() {
    const bool changing = cameraDirty_ || integratorDirty_ || clampDirty_ || sizeDirty_;
    if (integratorDirty_) {
        FeatureSet features = viewerFeatures(flat_, settings_);
        features.debugView = debugView_;
        const auto start = Clock::now();
        renderer_->setIntegrator(settings_, features);
        std::fprintf(stderr, "pt: view: %s (%.3f s; kernel features: %s)\n", settingsText().c_str(),
            msSince(start) * 1e-3, features.describe().c_str());
        integratorDirty_ = false;
    }
    if (clampDirty_) {
        renderer_->setSampleClamp(clamp_);
        clampDirty_ = false;
    }
    bool restarted = changing;
    int wantScale = scale_;
    if (changing) {
        if (scale_ == 1) previewScale_ = choosePreviewScale();
        wantScale = previewScale_;
    } else if (scale_ > 1 && !passActive_ && renderer_->samplesPerPixel() >= 1) {
        wantScale = 1; // the view is still: refine at full resolution
    }
    if (wantScale != scale_ || sizeDirty_) {
        scale_ = wantScale;
        renderer_->setFilmSize((windowSize_.x + scale_ - 1) / scale_, (windowSize_.y + scale_ - 1) / scale_);
        sizeDirty_ = false;
        restarted = true;
    }
    if (cameraDirty_) {
        renderer_->setCamera(controller_.camera());
        cameraDirty_ = false;
    }
    if (restarted) resetPass();
    if (changing) changeTime_ = Clock::now();
}

uint64_t Session::tilePixels(uint32_t tileSize, uint32_t firstTile, uint32_t endTile) const {
    const uint32_t w = static_cast<uint32_t>(renderer_->width()), h = static_cast<uint32_t>(renderer_->height());
    const uint32_t tw = tileSize ? std::min(tileSize, w) : w, th = tileSize ? std::min(tileSize, h) : h;
    const uint32_t tilesX = (w + tw - 1) / tw;
    uint64_t pixels = 0;
    for (uint32_t t = firstTile; t < endTile; ++t) {
        const uint32_t x = (t % tilesX) * tw, y = (t / tilesX) * th;
        pixels += uint64_t(std::min(tw, w - x)) * std::min(th, h - y);
    }
    return pixels;
}

// This frame's share of the work: a preview pass whole; at full resolution, as many samples
// as fit the budget when a whole pass does, else one sample per pass spread over frames in
// tiles.
void Session::planWork(uint32_t& count, uint32_t& firstTile, uint32_t& endTile) {
    count = firstTile = endTile = 0;
    const uint32_t spp = renderer_->samplesPerPixel();
    if (!passActive_) {
        if (paused_ || (scale_ == 1 && spp >= config_.sppCap)) return;
        const double passMs = double(renderer_->width()) * renderer_->height() * costMs_;
        passTileSize_ = 0;
        passCount_ = 1;
        if (scale_ == 1 && passMs <= config_.frameBudgetMs)
            passCount_ = static_cast<uint32_t>(
                std::clamp(std::floor(config_.frameBudgetMs / passMs), 1.0, double(config_.sppCap - spp)));
        else if (scale_ == 1)
            passTileSize_ = config_.tileSize;
        passTiles_ = renderer_->tileCount(passTileSize_);
        passTilesDone_ = 0;
        passActive_ = true;
    }
    uint32_t tiles = 1;
    if (passTileSize_ > 0) {
        const glm::uvec3 key(renderer_->width(), renderer_->height(), passTileSize_);
        if (key != tileMsKey_) tileMs_.assign(passTiles_, 0.0), tileMsKey_ = key;
        // As many tiles as their predicted cost fits in the budget (at least one).
        double planned = predictTileMs(passTilesDone_) * passCount_;
        while (passTilesDone_ + tiles < passTiles_ && tiles < kMaxFrameTiles) {
            const double next = predictTileMs(passTilesDone_ + tiles) * passCount_;
            if (planned + next > config_.frameBudgetMs) break;
            planned += next;
            ++tiles;
        }
    }
    count = passCount_;
    firstTile = passTilesDone_;
    endTile = std::min(passTiles_, passTilesDone_ + tiles);
}

double Session::predictTileMs(uint32_t tile) const {
    if (tile < tileMs_.size() && tileMs_[tile] > 0.0) return tileMs_[tile];
    return double(tilePixels(passTileSize_, tile, tile + 1)) * costMs_;
}

// Renders the rest of the pass in progress at once (before saving, so every pixel has the same
// number of samples).
void Session::finishPass() {
    if (!passActive_) return;
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        renderer_->recordTiles(cmd, passCount_, passTileSize_, passTilesDone_, passTiles_);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    });
    renderer_->completePass(passCount_);
    passActive_ = false;
    displayDirty_ = true;
}

void Session::resizeWindow(glm::ivec2 size) {
    swapchain_->recreate(size.x, size.y);
    windowSize_ = glm::ivec2(swapchain_->extent().width, swapchain_->extent().height);
    display_->resize(windowSize_.x, windowSize_.y);
    sizeDirty_ = true;
    std::fprintf(stderr, "pt: view: swapchain recreated at %dx%d\n", windowSize_.x, windowSize_.y);
}

void Session::updatePhotographicTerms(bool force) {
    if (op_ != DisplayOperator::Photographic || renderer_->samplesPerPixel() == 0) return;
    if (!force &&
        (passActive_ || (termsSpp_ != 0 && std::chrono::duration<double>(Clock::now() - termsTime_).count() < 0.5)))
        return;
    if (!force && termsSpp_ == renderer_->samplesPerPixel()) return;
    terms_ = photographicTerms(renderer_->read().mean, settingsFor(op_, config_.job.tonemap), ev_);
    termsSpp_ = renderer_->samplesPerPixel();
    termsTime_ = Clock::now();
}

// Records the display pass for the tiles of the pass rendered so far (`endTile`).
void Session::recordDisplay(uint32_t image, uint32_t endTile) {
    gpu::GpuDisplayPush push{};
    push.accumulation = renderer_->accumulationAddress();
    push.filmSize = glm::uvec2(renderer_->width(), renderer_->height());
    push.spp = renderer_->samplesPerPixel();
    push.passSamples = passActive_ ? passCount_ : 0;
    push.passTiles = passActive_ ? endTile : 0;
    push.tileSize = passTileSize_ ? passTileSize_ : std::max(push.filmSize.x, push.filmSize.y);
    push.tilesX = (push.filmSize.x + push.tileSize - 1) / push.tileSize;
    const bool debug = debugView_ != 0;
    push.op = debug                                  ? DISPLAY_TONEMAP_CLAMP
              : op_ == DisplayOperator::Photographic ? DISPLAY_TONEMAP_PHOTOGRAPHIC
              : op_ == DisplayOperator::Aces         ? DISPLAY_TONEMAP_ACES
                                                     : DISPLAY_TONEMAP_CLAMP;
    const TonemapSettings tm = settingsFor(op_, config_.job.tonemap);
    push.flags = (debug || tm.srgb ? DISPLAY_FLAG_SRGB : 0u) | (swapchain_->bgra() ? DISPLAY_FLAG_BGRA : 0u);
    push.exposure = debug ? 1.0f : std::exp2(ev_);
    push.toL = terms_.toL;
    push.invWhite2 = terms_.invWhite2;
    push.saturation = tm.saturation;
    push.invGamma = tm.srgb ? 1.0f : 1.0f / tm.gamma;
    if (renderer_->hasSplats()) {
        // Light paths land anywhere: normalise by the paths traced so far, the pass in
        // progress counted by the share of its tiles done.
        const uint32_t tiles = std::max(1u, renderer_->tileCount(passTileSize_));
        const double spp = push.spp + double(push.passSamples) * std::min(push.passTiles, tiles) / tiles;
        push.splats = renderer_->splatsAddress();
        push.splatScale = spp > 0 ? static_cast<float>(1.0 / (SPLAT_SUM_SCALE * spp)) : 0.0f;
    }
    display_->record(cmd_, push, swapchain_->image(image));
}

void Session::frame() {
    const auto start = Clock::now();
    const glm::ivec2 fb = window_.framebufferSize();
    if (fb.x <= 0 || fb.y <= 0) return; // minimised
    if (fb != windowSize_) resizeWindow(fb);
    applyChanges();
    uint32_t count, firstTile, endTile;
    planWork(count, firstTile, endTile);

    const bool passEnds = count > 0 && endTile >= passTiles_;
    const bool show =
        displayDirty_ || scale_ > 1 || passEnds || count == 0 || msSince(lastShown_) >= kRefineDisplayIntervalMs;
    uint32_t image = 0;
    if (show && !swapchain_->acquire(acquired_, &image)) {
        resizeWindow(fb);
        return;
    }
    VkDevice device = context_.device();
    vkCheck(vkResetCommandBuffer(cmd_, 0), "resetting the viewer's command buffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(cmd_, &begin), "recording a frame");
    const bool timeTiles = queries_ && passTileSize_ > 0 && count > 0;
    if (queries_) {
        vkCmdResetQueryPool(cmd_, queries_, 0, kQueryFirstTile + (timeTiles ? endTile - firstTile : 0));
        vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, kQueryStart);
    }
    if (timeTiles) {
        for (uint32_t t = firstTile; t < endTile; ++t) {
            renderer_->recordTiles(cmd_, count, passTileSize_, t, t + 1);
            vkCmdWriteTimestamp(
                cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, kQueryFirstTile + (t - firstTile));
        }
    } else if (count > 0) {
        renderer_->recordTiles(cmd_, count, passTileSize_, firstTile, endTile);
    }
    if (queries_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, kQueryRendered);

    if (show) recordDisplay(image, endTile);
    if (queries_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, kQueryDisplayed);
    vkCheck(vkEndCommandBuffer(cmd_), "recording a frame");

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSemaphore rendered = show ? swapchain_->renderedSemaphore(image) : VK_NULL_HANDLE;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = show ? 1 : 0;
    submit.pWaitSemaphores = &acquired_;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    submit.signalSemaphoreCount = show ? 1 : 0;
    submit.pSignalSemaphores = &rendered;
    vkCheck(vkResetFences(device, 1, &fence_), "resetting a fence");
    vkCheck(vkQueueSubmit(context_.queue(), 1, &submit, fence_), "submitting a frame");
    const bool presented = !show || swapchain_->present(image, rendered);
    vkCheck(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX), "waiting for a frame");
    if (!presented) resizeWindow(window_.framebufferSize());
    if (show) lastShown_ = Clock::now();

    // Bookkeeping: timings, the learnt cost per path, pass progress.
    lastFrameMs_ = msSince(start);
    lastRenderMs_ = lastGpuMs_ = 0;
    if (queries_) {
        const uint32_t n = kQueryFirstTile + (timeTiles ? endTile - firstTile : 0);
        std::vector<uint64_t> t(n);
        if (vkGetQueryPoolResults(device, queries_, 0, n, n * sizeof(uint64_t), t.data(), sizeof(uint64_t),
                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) == VK_SUCCESS) {
            lastRenderMs_ = double(t[kQueryRendered] - t[kQueryStart]) * timestampMs_;
            lastGpuMs_ = double(t[kQueryDisplayed] - t[kQueryStart]) * timestampMs_;
            for (uint32_t i = 0; timeTiles && i < endTile - firstTile; ++i) {
                const uint64_t begin = i == 0 ? t[kQueryStart] : t[kQueryFirstTile + i - 1];
                const double ms = double(t[kQueryFirstTile + i] - begin) * timestampMs_ / count;
                double& known = tileMs_[firstTile + i];
                known = known > 0.0 ? 0.5 * known + 0.5 * ms : ms;
            }
        }
    } else {
        lastRenderMs_ = lastGpuMs_ = lastFrameMs_;
    }
    if (count > 0) {
        const double paths = double(tilePixels(passTileSize_, firstTile, endTile)) * count;
        const double measured = lastRenderMs_ / std::max(paths, 1.0);
        costMs_ = stats_.pathSamples == 0 && frames_ < 2 ? measured : 0.7 * costMs_ + 0.3 * measured;
        stats_.pathSamples += paths;
        stats_.renderMs += lastRenderMs_;
        passTilesDone_ = endTile;
        if (passTilesDone_ >= passTiles_) {
            renderer_->completePass(passCount_);
            passActive_ = false;
        }
        renderSeconds_ += lastFrameMs_ * 1e-3;
    }
    displayDirty_ = false;
    ++frames_;
    ++stats_.frames;
    stats_.sumMs += lastFrameMs_;
    stats_.maxMs = std::max(stats_.maxMs, lastFrameMs_);
    updatePhotographicTerms(false);
    updateTitle(false);
}

int Session::run() {
    auto last = Clock::now();
    while (!quit_ && !window_.shouldClose()) {
        const glm::ivec2 fb = window_.framebufferSize();
        if (needFrame() && fb.x > 0 && fb.y > 0)
            window_.pollEvents();
        else
            window_.waitEvents(); // idle: done, paused, minimised or nothing changed
        const auto now = Clock::now();
        const float seconds = std::min(std::chrono::duration<float>(now - last).count(), 0.1f);
        last = now;
        handleInput(window_.takeInput(), seconds);
        if (config_.scripted) stepScript();
        if (quit_) break;
        if (needFrame())
            frame();
        else
            updateTitle(true);
    }
    vkDeviceWaitIdle(context_.device());
    return status_;
}

int runViewer(Window& window, VulkanContext& context, const FlatScene& flat, const ViewerConfig& config) {
    Session session(window, context, flat, config);
    return session.run();
}

} // namespace pt::viewer
