#pragma once
// One image to render: which camera, at what size, with which settings, to which file. The app
// makes jobs from the command line (app/scene_setup.h); the render loop and the viewer take them.
#include "flatten/integrator_settings.h"
#include "render/progressive_render.h"
#include "scene/scene.h"

#include <filesystem>
#include <string>

namespace pt {

struct Job {
    Camera camera;
    int width = 0, height = 0;
    IntegratorSettings settings;
    std::string maxDepthReason; // why settings.maxDepth, for the log line; empty when --max-depth chose
    ProgressiveTarget target;
    std::filesystem::path output; // .exr; the PNG goes beside it
    TonemapSettings tonemap;
};

} // namespace pt
