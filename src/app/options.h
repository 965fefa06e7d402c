#pragma once
// Parsed command lines of `pt render` and `pt view`.
#include "accel/bvh.h"
#include "flatten/integrator_settings.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pt {

struct RenderOptions {
    std::string scene;         // empty: the built-in Cornell box
    std::string variant;       // --variant NAME: a glTF KHR_materials_variants variant (empty: the defaults)
    bool listVariants = false; // --list-variants: print the scene's variants and stop
    std::string output;        // .exr; a tonemapped .png is written beside it
    std::optional<uint32_t> spp;
    std::optional<double> seconds;
    std::optional<double> targetError; // --target-error: stop at this estimated relMSE (spp, seconds: caps)
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
    uint32_t tileSize = 0;        // 0: whole image per dispatch
    uint32_t passSpp = 0;         // 0: choose passes of about two seconds
    std::optional<bool> adaptive; // --adaptive: per-pixel sample counts (default: on, except for --samples parts)
    bool validation = false;
    bool noPipelineCache = false;  // --no-pipeline-cache: nothing read from or written to the disk cache
    bool measureTexelLoads = true; // --texel-loads auto: texel or address loads, whichever this machine runs faster
    bool allFeatures = false;      // compile every feature into the kernel (benchmarking specialisation)
    Instancing instancing = Instancing::Auto; // --instances: meshes placed several times kept or copied
    bool quiet = false;
    bool varianceAov = false; // --variance: variance-of-the-mean channels in the EXR
    float exposure = 0.0f;
    std::string environment;                    // --env FILE.exr: equirectangular radiance map
    std::optional<glm::vec3> environmentColour; // --env-colour R G B: constant environment
    float environmentScale = 1.0f;
    float environmentRotation = 0.0f; // degrees about +y
    IntegratorSettings integrator;    // seed and rrStartDepth; the rest comes from the fields above
    // Long and distributed renders (app/render_session.h).
    std::string samples;         // --samples A:B: sample indices [A, B) of the global sequence
    std::string checkpoint;      // --checkpoint FILE: save the state there periodically and on SIGINT/SIGTERM
    double checkpointEvery = 60; // seconds of rendering between checkpoints
    std::string resume;          // --resume FILE: continue from a checkpoint or part
};

// `pt view`: the scene, size, switches, camera, device and environment options of `pt render`
// (render.spp is the sample cap, render.tileSize the tile of a full-resolution pass).
struct ViewOptions {
    RenderOptions render;
    std::string script;            // --script FILE: timed inputs (tests, benchmarks)
    double frameBudgetMs = 20.0;   // rendering work per frame
    std::string outputDir = "out"; // where F5 and F6 save
};

// `pt bench`: the scene options of `pt render` (its switches are replaced by the configurations).
struct BenchOptions {
    RenderOptions render;
    std::string reference;                         // REF.exr; empty: render one (referenceSpp)
    uint32_t referenceSpp = 4096;                  // samples of a reference made here
    std::vector<double> budgets{2, 5, 10, 30, 60}; // seconds
    std::string configs;                           // comma-separated; empty: the default list
    std::string outputDir = "out/bench";
    bool plot = true; // run tools/bench_plot.py (python3 + matplotlib) on the CSV
};

} // namespace pt
