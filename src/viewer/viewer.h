#pragma once
// `pt view`'s interactive loop: progressive rendering into a window, camera controls, live
// switches, saving, and the scripted mode used by the tests and bench/bench_viewer.sh.
#include "render/job.h"
#include "gpu/vulkan_context.h"
#include "flatten/flat_scene.h"
#include "viewer/script.h"
#include "viewer/window.h"

#include <filesystem>
#include <string>
#include <vector>

namespace pt::viewer {

struct ViewerConfig {
    std::string sceneSource; // for titles and metadata
    std::string sceneStem;   // names of saved files
    Job job;                 // camera, window size, integrator settings, the camera's tone mapping
    glm::vec3 background{0.0f};
    uint32_t sppCap = 1024;      // stop (and wait for events) at this many samples per pixel
    uint32_t tileSize = 64;      // tiles of a full-resolution pass, spread over frames
    double frameBudgetMs = 20.0; // rendering work per frame (GPU time), which bounds input latency
    float exposure = 0.0f;       // EV
    std::filesystem::path outputDir = "out";
    std::vector<ScriptCommand> script;
    bool scripted = false;
};

// Runs until the window closes, Escape, or the script's quit. Returns the exit status.
int runViewer(Window& window, VulkanContext& context, const FlatScene& flat, const ViewerConfig& config);

} // namespace pt::viewer
