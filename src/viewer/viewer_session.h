#pragma once
// The state of one `pt view` session, shared by viewer.cpp (frames, rendering, display) and
// viewer_controls.cpp (keys, mouse, script, saving). Internal to src/viewer.
#include "render/renderer.h"
#include "viewer/camera_controller.h"
#include "viewer/display_pass.h"
#include "viewer/display_tonemap.h"
#include "viewer/swapchain.h"
#include "viewer/viewer.h"

#include <chrono>
#include <memory>

namespace pt::viewer {

using Clock = std::chrono::steady_clock;

class Session {
public:
    Session(Window& window, VulkanContext& context, const FlatScene& flat, const ViewerConfig& config);
    ~Session();
    int run();

private:
    // ---- viewer.cpp: frames ----
    bool workLeft() const;
    bool needFrame() const;
    void applyChanges();
    int choosePreviewScale() const;
    void resetPass();
    void planWork(uint32_t& count, uint32_t& firstTile, uint32_t& endTile);
    void frame();
    void recordDisplay(uint32_t image, uint32_t endTile);
    void resizeWindow(glm::ivec2 size);
    void finishPass();
    void updatePhotographicTerms(bool force);
    void updateTitle(bool force);
    uint64_t tilePixels(uint32_t tileSize, uint32_t firstTile, uint32_t endTile) const;
    double predictTileMs(uint32_t tile) const; // one sample over a tile of the tiled pass

    // ---- viewer_controls.cpp: input, script, output ----
    void handleInput(const Input& input, float seconds);
    void handleKey(int key, int mods);
    void stepScript();
    void runCommand(const ScriptCommand& c);
    void save(const std::filesystem::path& exr);
    void screenshot(const std::filesystem::path& png);
    void printCamera() const;
    void printStats();
    void printReport() const;
    std::string settingsText() const;

    Window& window_;
    VulkanContext& context_;
    const FlatScene& flat_;
    ViewerConfig config_;

    // What is rendered and how it is shown.
    CameraController controller_;
    IntegratorSettings settings_;
    uint32_t debugView_ = 0;
    float clamp_ = 0.0f;
    DisplayOperator op_ = DisplayOperator::Srgb;
    float ev_ = 0.0f;
    PhotographicTerms terms_;
    uint32_t termsSpp_ = 0;
    Clock::time_point termsTime_{};
    bool fly_ = false;
    bool paused_ = false;
    bool quit_ = false;
    int status_ = 0;

    // Pending changes, applied at the start of the next frame.
    bool cameraDirty_ = false, integratorDirty_ = false, clampDirty_ = false, sizeDirty_ = true, displayDirty_ = true;

    // Rendering: the film is the window divided by scale_ (> 1 while the view changes).
    std::unique_ptr<Renderer> renderer_;
    glm::ivec2 windowSize_{0};
    int scale_ = 1;
    int previewScale_ = 4;
    bool passActive_ = false;
    uint32_t passCount_ = 0, passTileSize_ = 0, passTiles_ = 0, passTilesDone_ = 0;
    double costMs_ = 2e-3; // GPU milliseconds per path (pixel sample), learnt from timestamps
    // GPU milliseconds of one sample over each tile of a tiled pass, from per-tile timestamps
    // (tiles differ several-fold: sky, walls, glass), for the film size and tile they were
    // measured at; 0 = not measured yet.
    std::vector<double> tileMs_;
    glm::uvec3 tileMsKey_{0};
    Clock::time_point changeTime_ = Clock::now(); // of the last change that restarted accumulation
    double renderSeconds_ = 0;                    // wall time of frames since then

    // Presentation.
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<DisplayPass> display_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkSemaphore acquired_ = VK_NULL_HANDLE;
    VkQueryPool queries_ = VK_NULL_HANDLE;
    double timestampMs_ = 0; // 0: no timestamps on this queue

    // Statistics.
    uint64_t frames_ = 0;
    double lastFrameMs_ = 0, lastGpuMs_ = 0, lastRenderMs_ = 0;
    Clock::time_point titleTime_{};
    Clock::time_point lastShown_{};
    struct Window_ {
        Clock::time_point start = Clock::now();
        uint64_t frames = 0;
        double sumMs = 0, maxMs = 0;
        double pathSamples = 0, renderMs = 0;
    } stats_;

    // Script.
    size_t scriptNext_ = 0;
    int waitFrames_ = 0;
    int64_t waitSpp_ = -1;
    int waitResize_ = 0; // frames left for a requested resize to arrive
    glm::ivec2 resizeTarget_{0};
    int repeatLeft_ = 0;
    ScriptCommand repeated_;
    int saveCounter_ = 0;
};

} // namespace pt::viewer
