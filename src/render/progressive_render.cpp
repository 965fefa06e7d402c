#include "render/progressive_render.h"

#include "film/metrics.h"
#include "render/adaptive_sampling.h"
#include "render/progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace pt {

// Fewest samples per pixel before a target error is judged: below this the per-pixel variance
// is too noisy and rare paths are mostly unseen.
constexpr uint32_t kMinTargetErrorSpp = 4;

ProgressiveResult renderProgressively(Renderer& renderer, const ProgressiveTarget& target, const Image* reference,
    std::ostream* errorLog, bool showProgress) {
    using Clock = std::chrono::steady_clock;
    Progress progress(target.spp, target.seconds, showProgress);
    ProgressiveResult result;
    double lastRelMse = NAN;
    const double pixels = double(renderer.width()) * renderer.height();
    const uint32_t resumedSpp = renderer.samplesPerPixel(); // > 0 after --resume
    while (true) {
        const uint32_t done = renderer.samplesPerPixel();
        if (target.spp > 0 && done >= target.spp) break;
        const uint32_t doneHere = done - resumedSpp; // a resumed render's speed is this run's
        const double secondsPerSpp = doneHere > 0 ? result.seconds / doneHere : 0.0;
        uint32_t pass;
        if (target.passSpp > 0)
            pass = target.passSpp;
        else if (doneHere == 0)
            pass = 1;
        else
            pass = static_cast<uint32_t>(std::clamp(kPassSeconds / std::max(secondsPerSpp, 1e-9), 1.0, 4096.0));
        if (target.targetError > 0 && result.lastEstimate <= 0) {
            // No estimate yet: reach the fewest samples it needs first. A pass sized by speed
            // alone is hundreds of spp on a GPU, and would overshoot the target many times over.
            pass = std::min(pass, done < kMinTargetErrorSpp ? kMinTargetErrorSpp - done : 1u);
        } else if (target.targetError > 0) {
            // relMSE falls as 1/spp: aim at the predicted total instead of overshooting by a pass.
            const double needed = std::ceil(done * result.lastEstimate / target.targetError);
            pass = static_cast<uint32_t>(std::clamp(needed - done, 1.0, double(pass)));
        }
        if (target.spp > 0) pass = std::min(pass, target.spp - done);
        double allocationSeconds = 0;
        if (target.adaptive) {
            if (renderer.epochRoundsLeft() == 0) {
                // A new epoch, its allocation from the image so far (counted as render time).
                const auto start = Clock::now();
                const AdaptiveEpoch epoch = planEpoch(renderer.readState());
                ++result.epochs;
                if (!epoch.allocation.uniform) ++result.adaptiveEpochs;
                if (result.epochs > 1) result.predictedGain = epoch.allocation.predictedGain;
                renderer.startAdaptiveEpoch(epoch.allocation.samples, epoch.rounds);
                allocationSeconds = std::chrono::duration<double>(Clock::now() - start).count();
            }
            pass = std::min(pass, renderer.epochRoundsLeft());
        }
        if (target.seconds > 0 && doneHere > 0) {
            // Never start a pass that would overrun the budget.
            const double fits = std::floor((target.seconds - result.seconds) / std::max(secondsPerSpp, 1e-9));
            if (fits < 1.0) break;
            pass = static_cast<uint32_t>(std::min<double>(pass, fits));
        }
        const auto passStart = Clock::now();
        renderer.addSamples(pass, target.tileSize);
        result.seconds += std::chrono::duration<double>(Clock::now() - passStart).count() + allocationSeconds;
        const uint32_t spp = renderer.samplesPerPixel();
        if (reference) {
            lastRelMse = relMse(renderer.read().mean, *reference);
            if (errorLog) {
                std::ostringstream line;
                line.precision(9);
                line << spp << "," << result.seconds << "," << lastRelMse << "\n";
                *errorLog << line.str() << std::flush;
            }
        }
        progress.update(
            spp, result.seconds, pixels * (spp - resumedSpp) / std::max(result.seconds, 1e-9) * 1e-6, lastRelMse);
        // The estimate needs a variance: a few samples per pixel at least.
        if (target.targetError > 0 && spp >= kMinTargetErrorSpp) {
            const Renderer::Readback r = renderer.read();
            result.lastEstimate = estimatedRelMse(r.mean, r.varianceOfMean);
            if (result.lastEstimate <= target.targetError) {
                result.targetReached = true;
                if (target.afterPass) target.afterPass(result.seconds);
                break;
            }
        }
        if (target.afterPass && !target.afterPass(result.seconds)) break;
        if (target.seconds > 0 && result.seconds >= target.seconds) break;
    }
    progress.finish();
    result.lastRelMse = std::isnan(lastRelMse) ? -1 : lastRelMse;
    return result;
}

} // namespace pt
