#pragma once
// The progressive loop: passes of samples until a sample count or a time budget is reached,
// with progress, and relMSE against a reference after every pass when one is given.
#include "image/image.h"
#include "render/renderer.h"

#include <cstdint>
#include <functional>
#include <ostream>

namespace pt {

// How long a pass runs when its size is not given. Each invocation adds a pass's samples to its
// pixel one path after another (paths regenerated), and the SIMD group of 8 ends when its slowest
// lane does; the longer the pass, the smaller that tail's share: on the diffuse box 48-spp passes
// ran 3% faster than 16-spp ones and 128-spp 5% faster than 48 (bench/RESULTS.md, "Pass length").
// Two seconds keeps SIGINT, checkpoints and the progress line prompt.
constexpr double kPassSeconds = 2.0;

struct ProgressiveTarget {
    uint32_t spp = 0;      // stop at this many samples per pixel (0: use seconds)
    double seconds = 0;    // or after this much render time
    uint32_t passSpp = 0;  // samples per pass; 0 chooses passes of about kPassSeconds
    uint32_t tileSize = 0; // split passes into tiles (same image)
    // Adaptive sampling (render/adaptive_sampling.h): spp and the pass sizes count rounds, the
    // mean samples per pixel. The renderer must be new or resumed from an adaptive state.
    bool adaptive = false;
    // > 0: stop once the reference-free relMSE estimate (estimatedRelMse) is at most this;
    // spp and seconds, when set, are then caps.
    double targetError = 0;
    // Called after every pass with the render seconds so far; returning false stops early
    // (checkpoints, SIGINT/SIGTERM: render/checkpoint.h).
    std::function<bool(double seconds)> afterPass;
};

struct ProgressiveResult {
    double seconds = 0; // render time of the passes (excludes relMSE evaluation)
    double lastRelMse = -1;
    double lastEstimate = -1;   // estimatedRelMse after the last pass (target-error renders)
    bool targetReached = false; // targetError was met (not a cap)
    // Adaptive sampling: epochs started, how many of them were not uniform, and the last
    // epoch's predicted gain (AdaptiveAllocation; 1 before the first estimate).
    uint32_t epochs = 0, adaptiveEpochs = 0;
    double predictedGain = 1.0;
};

// `errorLog` receives "spp,seconds,relmse" lines (without header) when `reference` is given.
ProgressiveResult renderProgressively(Renderer& renderer, const ProgressiveTarget& target, const Image* reference,
    std::ostream* errorLog, bool showProgress);

} // namespace pt
