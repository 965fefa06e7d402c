#pragma once
// Adaptive sampling: more samples where the image's relative error is, fewer where a pixel has
// converged (the light itself, a flat wall in full light). The error measure pt reports and
// compares by, relMSE, is the mean over pixels of (value - truth)^2 / (truth^2 + 0.01); a pixel
// whose samples have variance s^2 contributes s^2 / (n (truth^2 + 0.01)) with n samples, and
// if a sample costs c (the rays it traces), for a fixed time the sum is least when n is
// proportional to s / sqrt((truth^2 + 0.01) c). That is the allocation, estimated from the
// samples so far.
//
// The render runs in epochs of doubling length (8 rounds, then as many as so far), each with a
// per-pixel allocation fixed at its start from the image at that point; an epoch is added in
// passes of any size (Renderer::startAdaptiveEpoch), so the image depends on neither how the
// work was split nor where it was stopped and continued, only on the sample count.
//
// Allocating by the samples' own variance correlates a pixel's sample count with its values,
// which biases the mean by O(1/n) (a pixel whose first samples missed a rare bright path looks
// converged). Two things bound that: every pixel keeps at least kMinShare of the mean rate, and
// the estimate is smoothed over 3x3 pixels, so a rare path seen in one pixel raises its
// neighbours' share too.
#include "film/accumulation_state.h"

#include <cstdint>
#include <vector>

namespace pt {

// Rounds of the first epoch, whose allocation is uniform: the variance needs a few samples.
constexpr uint32_t kFirstEpochRounds = 8;
// Pixels of a row that share one allocation: lavapipe runs 8 invocations (8 pixels of a row of
// the kernel's 8x8 workgroup) as one SIMD vector, which runs until its busiest lane is done.
// With a count per pixel, the lanes idled 15% of the time on the diffuse Cornell box.
constexpr uint32_t kBlockWidth = 8;
// The least share of the mean sampling rate a pixel gets in an epoch.
constexpr double kMinShare = 0.25;
// The most: a cap on what one pixel's estimate can claim.
constexpr double kMaxShare = 16.0;

// Length in rounds of the epoch that starts after `roundsDone` rounds. Not cut to a render's
// sample count: a render of N spp stops part-way through its last epoch, so that it is the
// first N rounds of any longer render (and continuing it, to any count, is exact).
uint32_t nextEpochRounds(uint32_t roundsDone);

// Below this predicted gain (AdaptiveAllocation::predictedGain) the epoch is uniform: the
// estimates are noisy, and Sobol' points lower a pixel's error by more than its samples' variance
// says where the integrand is smooth, so a small predicted gain is none. Measured at equal time
// (bench/RESULTS.md, "Adaptive sampling" and "The adaptive threshold"): the diffuse Cornell box
// and the 1 M-triangle mesh predict 1.2 and render 0.93-0.95x the relMSE adaptively, the glass
// box 0.95x with its earlier epochs adaptive too, the rough box level; 1.0 rendered the mesh
// as 1.1 does.
constexpr double kMinPredictedGain = 1.1;

struct AdaptiveAllocation {
    std::vector<uint32_t> samples; // per pixel, row-major
    // relMSE x time of uniform sampling over that of this allocation's ideal, from the
    // estimates (1 for the first epoch, which has none).
    double predictedGain = 1.0;
    bool uniform = true;
};

// Each pixel's samples for an epoch of `rounds` rounds, from the accumulated `state` (adaptive,
// or empty): about rounds x pixels in all.
AdaptiveAllocation allocateSamples(const AccumulationState& state, uint32_t rounds);

// The length of the last epoch, which a render enters the first time an allocation is not
// worth it after kLastEpochAfter rounds: uniform from there on, with no more allocations and no
// more epoch ends to cut passes at (they cost 1-2% on the diffuse Cornell box). Far beyond any
// render. Earlier estimates may not have seen the rare paths yet: the glass box's predicted gain
// is 1.18 after 8 rounds, 1.30 after 16 and 1.49 after 32.
constexpr uint32_t kLastEpochRounds = uint32_t(1) << 31;
constexpr uint32_t kLastEpochAfter = 64;

struct AdaptiveEpoch {
    AdaptiveAllocation allocation;
    uint32_t rounds = 0;
};

// The epoch that follows `state` (its spp rounds done; empty: the first).
AdaptiveEpoch planEpoch(const AccumulationState& state);

} // namespace pt
