#pragma once

#include <string>

#include <vector>

#include "image/image.h"

namespace pt {

// Image-comparison metrics used by convergence and regression tests.
// All of them look at R,G,B only (alpha is ignored) and throw
// std::invalid_argument if the images differ in size or are empty.

// relMSE = mean over pixels and R,G,B of (x - ref)^2 / (ref^2 + 0.01)
// (the project's definition; the 0.01 keeps black reference pixels from
// dominating).
double relMse(const Image& x, const Image& ref);

// The reference `ref` (read from `name`) at a render's size: as it is, or box-filtered down where
// each of its sides is a whole multiple of the render's (a long render at the official size
// scoring a smaller, faster one). Anything else is an error naming both sizes.
Image referenceAtSize(const Image& ref, int width, int height, const std::string& name);
// Plain mean over pixels and R,G,B of (x - ref)^2.
double mse(const Image& x, const Image& ref);

// The relMSE a render is expected to have against its converged image, estimated from the
// render alone: mean over pixels and channels of Var[mean] / (m^2 + 0.01), m the mean of the
// pixel's 8 neighbours, the same normalisation as relMse. It sees variance only (no bias).
// Checked against true relMSE in bench/RESULTS.md: within 1.1x on the Mitsuba scenes from 5 spp
// with the independent sampler; with Sobol' it overestimates (the per-pixel variance ignores
// the stratification), by up to 1.5x. Rare paths not yet seen at a few spp make it
// unreliable there (tests/film/metrics_test.cpp shows both ways).
double estimatedRelMse(const Image& mean, const Image& varianceOfMean);

// Per-block means of an image, used to compare two noisy renders without
// per-pixel noise swamping the test. mean and varOfMean hold 3 entries
// (R,G,B) per block, blocks in row-major order; varOfMean is empty when no
// variance image was given.
struct BlockStats {
    int blocksX = 0, blocksY = 0, blockSize = 0;
    std::vector<double> mean;
    std::vector<double> varOfMean;
};

// blocksX = width / blockSize (partial blocks at the right/bottom edges are
// dropped). varOfMean, if given, is a per-pixel image of the variance of
// each pixel's estimate; the block mean's variance is then
// sum(var_i) / n^2 (pixels are independent). Throws std::invalid_argument
// for blockSize < 1, a block larger than the image, or a size mismatch.
BlockStats blockStats(const Image& mean, const Image* varOfMean, int blockSize);

struct AgreementResult {
    double chi2PerDof = 0;  // mean z^2; ~1 when the two agree within noise
    double maxAbsZ = 0;     // worst single block/channel
    double meanZ = 0;       // signed mean z; far from 0 => systematic bias
    int dof = 0;            // number of block/channel cells compared
    double meanRelDiff = 0; // mean |a-b| / ((|a|+|b|)/2), noise-free effect size
};

// z = (a - b) / sqrt(varA + varB + tiny) per block and channel. Cells where
// both means are ~0 (|.| < 1e-12, e.g. black background) are skipped since
// they carry no information. A missing varOfMean on one side counts as zero
// variance (e.g. a converged reference); both missing throws
// std::invalid_argument, as does a block-layout mismatch. Non-finite means
// give z = inf, so they fail any threshold instead of being ignored.
AgreementResult compareBlocks(const BlockStats& a, const BlockStats& b);

} // namespace pt
