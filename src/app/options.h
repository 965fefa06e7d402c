#pragma once
// Parsed command lines of `pt render` and `pt view`.
#include "render/integrator_settings.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>

namespace pt {

struct RenderOptions {
    std::string scene; // empty: the built-in Cornell box
    std::string output; // .exr; a tonemapped .png is written beside it
    std::optional<uint32_t> spp;
    std::optional<double> seconds;
    std::optional<int> width, height;
    std::optional<uint32_t> maxDepth;
    std::optional<int> camera; // glTF: index; course XML: the Camera's id
    // Switches given on the command line; otherwise the camera's (course XML) or the defaults.
    std::optional<bool> nee, mis, rr;
    std::optional<bool> classic; // --integrator classic|path (default: the scene's choice, else path)
    std::optional<DirectionSampling> sampling;
    std::string device;
    std::string reference;
    std::string errorLog;
    uint32_t tileSize = 0; // 0: whole image per dispatch
    uint32_t passSpp = 0;  // 0: choose passes of about half a second
    bool validation = false;
    bool allFeatures = false; // compile every feature into the kernel (benchmarking specialisation)
    bool quiet = false;
    float exposure = 0.0f;
    std::string environment;                   // --env FILE.exr: equirectangular radiance map
    std::optional<glm::vec3> environmentColour; // --env-colour R G B: constant environment
    float environmentScale = 1.0f;
    float environmentRotation = 0.0f;          // degrees about +y
    IntegratorSettings integrator; // seed and rrStartDepth; the rest comes from the fields above
};

// `pt view`: the scene, size, switches, camera, device and environment options of `pt render`
// (render.spp is the sample cap, render.tileSize the tile of a full-resolution pass).
struct ViewOptions {
    RenderOptions render;
    std::string script;           // --script FILE: timed inputs (tests, benchmarks)
    double frameBudgetMs = 20.0;  // rendering work per frame
    std::string outputDir = "out"; // where F5 and F6 save
};

} // namespace pt
