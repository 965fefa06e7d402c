#pragma once
// The per-pixel accumulation state exactly as the kernel keeps it (shaders/shared/layout.h,
// ACCUM_*): double-float sums and sums of squares and the dropped-sample count, over a range of
// sample indices. Exact to save (checkpoints, `--samples` parts), reload and merge, so a
// resumed or merged render matches an uninterrupted one.
#include "image/image.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace pt {

// Sample indices [begin, end) of the global sequence every pixel was given.
struct SampleRange {
    uint32_t begin = 0, end = 0;
    uint32_t count() const { return end - begin; }
    std::string describe() const; // "A:B"
};

// Parses "A:B" (0 <= A < B < 2^32); throws std::runtime_error naming the problem.
SampleRange parseSampleRange(const std::string& text);

struct AccumulationState {
    int width = 0, height = 0;
    SampleRange samples;         // from the first index summed to one past the last
    uint32_t spp = 0;            // samples summed per pixel: samples.count() unless merged over gaps
    std::vector<glm::vec4> sums; // ACCUMULATION_VEC4S_PER_PIXEL vec4 per pixel, row-major
    // Light tracing's fixed-point splat sums (SPLAT_WORDS_PER_PIXEL per pixel, shared/layout.h),
    // or empty when the render had none.
    std::vector<uint64_t> splats;
    // Adaptive sampling (render/adaptive_sampling.h), or empty when every pixel has spp samples:
    // each pixel's own sample count, and the epoch in progress (its per-pixel allocation, the
    // rays its samples traced so far, its length in rounds and the rounds done), so that a
    // resumed render continues it exactly. spp then counts rounds: the mean samples per pixel.
    std::vector<uint32_t> pixelSamples;
    std::vector<uint32_t> allocation;
    std::vector<uint32_t> epochRays;
    uint32_t epochRounds = 0, epochRoundsDone = 0;

    size_t pixels() const { return size_t(width) * size_t(height); }
    bool hasSplats() const { return !splats.empty(); }
    bool adaptive() const { return !pixelSamples.empty(); }
    // Samples summed in `pixel`, and over the image (the light paths traced, with light tracing).
    double samplesOf(size_t pixel) const { return adaptive() ? double(pixelSamples[pixel]) : double(spp); }
    double totalSamples() const;
    // Per-pixel sum of radiance (hi + lo) and of its squares, and the dropped count.
    glm::dvec3 sum(size_t pixel) const;
    glm::dvec3 sumSquares(size_t pixel) const;
    uint64_t dropped(size_t pixel) const;
    // Per-pixel splat sums of the light paths' contributions (each already divided by the
    // pixel count) and of their squares; zero without splats.
    glm::dvec3 splatSum(size_t pixel) const;
    glm::dvec3 splatSumSquares(size_t pixel) const;
};

// What an image file shows: the mean, the variance of that mean, the dropped sample count.
struct AccumulatedImage {
    Image mean;
    Image varianceOfMean;
    uint64_t droppedSamples = 0;
};

// Mean = (hi + lo) / n in double, rounded once to float; the unbiased variance of the mean.
// With splats, the light tracer's estimate (its N = n x pixels paths) and its variance are added.
AccumulatedImage resolve(const AccumulationState& state);

// The state of the union of `parts`: same size, pairwise disjoint ranges (else throws), summed
// per pixel in double in order of range begin and split back into a double-float. The merged
// range runs from the first begin to the last end; gaps are the caller's to report (findGaps).
AccumulationState mergeStates(std::vector<AccumulationState> parts);

// The ranges in [first begin, last end) that none of `ranges` covers, sorted.
std::vector<SampleRange> findGaps(std::vector<SampleRange> ranges);
// Total samples in `ranges` (their counts summed; the merged image's spp).
uint64_t totalSamples(const std::vector<SampleRange>& ranges);

} // namespace pt
