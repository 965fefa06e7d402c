#pragma once
// What makes one `pt render` a piece of a longer or larger render: --samples A:B (a range of
// the global sample sequence, for pt merge), --resume, --checkpoint, SIGINT/SIGTERM (save and
// exit 130/143), and saving the progress already rendered when the device fails.
#include "app/interrupt_signals.h"
#include "app/options.h"
#include "app/render_identity.h"
#include "app/scene_setup.h"
#include "render/checkpoint.h"
#include "render/progressive_render.h"
#include "render/renderer.h"

#include <functional>
#include <optional>

namespace pt {

class RenderSession {
public:
    // Loads the --resume state into `renderer` (after checking it belongs to this render) and
    // sets the first sample index of --samples.
    RenderSession(const RenderOptions& o, const Scene& scene, const Job& job, Renderer& renderer, ImageMetadata base);

    // Runs `render` with the job's target (the range's spp for --samples) plus the checkpoint
    // and signal hook. A Vulkan failure (device lost, out of memory) saves the latest snapshot
    // to the checkpoint and the output first, then is rethrown with where the progress went.
    ProgressiveResult run(const std::function<ProgressiveResult(const ProgressiveTarget&)>& render);

    // Output metadata: the identity (scene hash, settings), sample range, total seconds.
    void addMetadata(ImageMetadata& meta, double seconds) const;
    // Whether the output carries the state channels: parts, and interrupted renders.
    bool outputIsState() const { return !o_.samples.empty() || interrupted() != 0; }
    int interrupted() const { return InterruptSignals::received(); }
    // 0, or 128 + the signal after an interruption (written after the checkpoint and output).
    int exitStatus() const { return interrupted() ? 128 + interrupted() : 0; }
    // Saves the final checkpoint of an interrupted render.
    void finish(double seconds);
    double priorSeconds() const { return priorSeconds_; }
    uint32_t resumedSpp() const { return resumedSpp_; } // samples per pixel loaded by --resume

private:
    const RenderOptions& o_;
    const Job& job_;
    Renderer& renderer_;
    RenderIdentity identity_;
    std::optional<SampleRange> range_;
    double priorSeconds_ = 0;
    uint32_t resumedSpp_ = 0;
    InterruptSignals signals_;
    std::optional<Checkpointer> checkpointer_;
};

} // namespace pt
