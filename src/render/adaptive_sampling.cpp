#include "render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace pt {

uint32_t nextEpochRounds(uint32_t roundsDone) {
    // Doubling keeps the number of allocations logarithmic in the render's length, and each
    // allocation sees at least as many samples as its epoch will add.
    return roundsDone == 0 ? kFirstEpochRounds : std::min<uint32_t>(roundsDone, uint32_t(1) << 20);
}

namespace {

// Per pixel, relMSE's term per sample: the variance of the pixel's own samples over the squared
// value (its mean, light tracing's splats included, standing in for the truth), averaged over
// R, G, B. The splats' variance is left out: more samples in one pixel do not lower it.
std::vector<double> relativeVariance(const AccumulationState& state) {
    const AccumulatedImage image = resolve(state);
    std::vector<double> relative(state.pixels(), 0.0);
    for (size_t i = 0; i < relative.size(); ++i) {
        const double n = state.samplesOf(i);
        if (n < 2) continue;
        const glm::dvec3 s = state.sum(i), s2 = state.sumSquares(i);
        double sum = 0;
        for (int c = 0; c < 3; ++c) {
            const double sampleMean = s[c] / n;
            const double variance = std::max(0.0, (s2[c] / n - sampleMean * sampleMean) * n / (n - 1));
            const double mean = image.mean.rgba[4 * i + c];
            sum += variance / (mean * mean + 0.01);
        }
        relative[i] = std::isfinite(sum) ? sum / 3.0 : 0.0;
    }
    return relative;
}

// The mean of `values` over the 3x3 pixels around each (those that exist at the edges).
std::vector<double> boxFilter3x3(const std::vector<double>& values, int w, int h) {
    std::vector<double> out(values.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            int count = 0;
            for (int yy = std::max(y - 1, 0); yy <= std::min(y + 1, h - 1); ++yy)
                for (int xx = std::max(x - 1, 0); xx <= std::min(x + 1, w - 1); ++xx) {
                    sum += values[size_t(yy) * w + xx];
                    ++count;
                }
            out[size_t(y) * w + x] = sum / count;
        }
    return out;
}

// Each block's mean of `values`, given to each of its pixels.
std::vector<double> blockMeans(const std::vector<double>& values, int w, int h) {
    std::vector<double> out(values.size());
    for (int y = 0; y < h; ++y)
        for (int x0 = 0; x0 < w; x0 += int(kBlockWidth)) {
            const int x1 = std::min(x0 + int(kBlockWidth), w);
            double sum = 0;
            for (int x = x0; x < x1; ++x) sum += values[size_t(y) * w + x];
            for (int x = x0; x < x1; ++x) out[size_t(y) * w + x] = sum / (x1 - x0);
        }
    return out;
}

} // namespace

AdaptiveAllocation allocateSamples(const AccumulationState& state, uint32_t rounds) {
    const size_t pixels = state.pixels();
    AdaptiveAllocation result;
    result.samples.assign(pixels, rounds);
    if (!state.adaptive() || state.spp == 0) return result; // the first epoch: nothing to go by
    const int w = state.width, h = state.height;
    const std::vector<double> relative = blockMeans(boxFilter3x3(relativeVariance(state), w, h), w, h);
    // A sample's cost: the rays it traced in the last epoch (at least one, the camera ray).
    std::vector<double> cost(pixels);
    for (size_t i = 0; i < pixels; ++i)
        cost[i] = std::max(1.0, double(state.epochRays[i]) / std::max(1u, state.allocation[i]));
    cost = blockMeans(cost, w, h);
    // With costs c and relative variances v, relMSE x time is least with n ~ sqrt(v / c), and
    // then lower than with uniform n by G = sum(v) sum(c) / sum(sqrt(v c))^2 (Cauchy-Schwarz:
    // G >= 1, equal when v / c is the same everywhere).
    double sumV = 0, sumC = 0, sumVC = 0;
    for (size_t i = 0; i < pixels; ++i) {
        sumV += relative[i];
        sumC += cost[i];
        sumVC += std::sqrt(relative[i] * cost[i]);
    }
    result.predictedGain = sumVC > 0 ? sumV * sumC / (sumVC * sumVC) : 1.0;
    if (!(result.predictedGain >= kMinPredictedGain)) return result; // uniform
    result.uniform = false;
    // Each pixel's target total after the epoch: its rate times K, with K such that the targets
    // sum to all samples so far and the epoch's; the epoch tops each pixel up to it, within
    // [kMinShare, kMaxShare] of the rounds, scaled to rounds x pixels samples in all (so spp
    // stays the mean per pixel).
    double samplesAfter = 0, rateSum = 0;
    std::vector<double> rate(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        rate[i] = std::sqrt(relative[i] / cost[i]);
        samplesAfter += state.samplesOf(i) + rounds;
        rateSum += rate[i];
    }
    const double k = rateSum > 0 ? samplesAfter / rateSum : 0.0;
    std::vector<double> wanted(pixels);
    double wantedSum = 0;
    for (size_t i = 0; i < pixels; ++i) {
        wanted[i] = std::clamp(rate[i] * k - state.samplesOf(i), kMinShare * rounds, kMaxShare * rounds);
        wantedSum += wanted[i];
    }
    const double scale = double(rounds) * double(pixels) / wantedSum;
    for (size_t i = 0; i < pixels; ++i) {
        const double a = std::clamp(wanted[i] * scale, kMinShare * rounds, kMaxShare * rounds);
        result.samples[i] = static_cast<uint32_t>(std::max(1.0, std::floor(a + 0.5)));
    }
    return result;
}

AdaptiveEpoch planEpoch(const AccumulationState& state) {
    AdaptiveEpoch epoch;
    epoch.rounds = nextEpochRounds(state.spp);
    epoch.allocation = allocateSamples(state, epoch.rounds);
    if (epoch.allocation.uniform && state.spp >= kLastEpochAfter) {
        epoch.rounds = kLastEpochRounds;
        epoch.allocation.samples.assign(state.pixels(), kLastEpochRounds);
    }
    return epoch;
}

} // namespace pt
