#pragma once
// Whether the kernel reads the trees' nodes and the triangles through texel buffers (TEXEL_LOADS,
// shaders/shared/features.h) or through buffer addresses on this CPU device. Which is faster
// depends on the CPU, not the scene: on one 2-core AMD EPYC (Zen 4) texel loads rendered every
// benchmark scene 1.1-1.4x faster than addresses, on another of the same family and model, with
// today's kernel, addresses were the faster by 1.1-1.5x on all four (bench/RESULTS.md, "Texel
// loads or addresses: measured on the machine"). So it is measured, once per machine, driver and
// kernel: the built-in Cornell box rendered both ways for a few passes, the answer remembered in
// the pipeline cache's folder. The image is the same either way (TexelLoads.* tests).
#include "gpu/vulkan_context.h"

#include <optional>
#include <string>

namespace pt {

struct TexelLoadChoice {
    bool texelLoads = true;
    // Seconds of the fastest pass each way (the measurement's, also when remembered).
    double texelSeconds = 0, addressSeconds = 0;
    bool measuredNow = false; // false: read from the cache folder
};

// The choice for this device, measured now or remembered. Nothing when there is nothing to
// choose: not a CPU device (GPUs keep their address loads), texel views unsupported, or no cache
// folder (--no-pipeline-cache): measuring on every run would cost more than it saves, so texel
// loads stay on as before.
std::optional<TexelLoadChoice> chooseTexelLoads(VulkanContext& context);

// The log line for a choice ("geometry loads: ...").
std::string describeTexelLoadChoice(const TexelLoadChoice& choice);

} // namespace pt
