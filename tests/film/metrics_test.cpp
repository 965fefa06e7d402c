#include "film/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace {

pt::Image constantImage(int w, int h, float r, float g, float b) {
    pt::Image im{w, h, std::vector<float>(static_cast<std::size_t>(w) * h * 4)};
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) {
        im.rgba[i] = r, im.rgba[i + 1] = g, im.rgba[i + 2] = b, im.rgba[i + 3] = 1;
    }
    return im;
}

TEST(Metrics, RelMseAndMseByHand) {
    // Values exactly representable in float so the expectation is exact.
    pt::Image x{2, 1, {1, 2, 3, 0.25f, /**/ 0, 0, 0.5f, 7}};
    pt::Image ref{2, 1, {1, 1, 1, 99, /**/ 0.5f, 0, 0, -3}}; // alpha ignored
    const double expectedRel = (0.0 + 1.0 / 1.01 + 4.0 / 1.01 + 0.25 / 0.26 + 0.0 + 0.25 / 0.01) / 6.0;
    EXPECT_NEAR(pt::relMse(x, ref), expectedRel, 1e-12);
    const double expectedMse = (0 + 1 + 4 + 0.25 + 0 + 0.25) / 6.0;
    EXPECT_NEAR(pt::mse(x, ref), expectedMse, 1e-12);
    EXPECT_EQ(pt::relMse(ref, ref), 0.0);
}

TEST(Metrics, SizeMismatchThrows) {
    const pt::Image a = constantImage(4, 4, 1, 1, 1), b = constantImage(4, 3, 1, 1, 1);
    EXPECT_THROW(pt::relMse(a, b), std::invalid_argument);
    EXPECT_THROW(pt::mse(a, b), std::invalid_argument);
    EXPECT_THROW(pt::blockStats(a, &b, 2), std::invalid_argument);
    pt::Image broken{4, 4, std::vector<float>(3)};
    EXPECT_THROW(pt::relMse(broken, broken), std::invalid_argument);
    EXPECT_THROW(pt::blockStats(a, nullptr, 0), std::invalid_argument);
    EXPECT_THROW(pt::blockStats(a, nullptr, 5), std::invalid_argument);
}

// A reference at a whole multiple of the render's size is box-filtered down to it; other sizes
// are refused with both sizes named.
TEST(Metrics, ReferenceAtSizeBoxFiltersWholeMultiples) {
    pt::Image ref = constantImage(4, 6, 0, 0, 0);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 4; ++x) ref.at(x, y)[0] = float(10 * y + x);
    const pt::Image same = pt::referenceAtSize(ref, 4, 6, "r.exr");
    EXPECT_EQ(same.rgba, ref.rgba);
    const pt::Image half = pt::referenceAtSize(ref, 2, 2, "r.exr"); // 2x3 boxes
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 2);
    EXPECT_FLOAT_EQ(half.at(0, 0)[0], (0 + 1 + 10 + 11 + 20 + 21) / 6.0f);
    EXPECT_FLOAT_EQ(half.at(1, 1)[0], (32 + 33 + 42 + 43 + 52 + 53) / 6.0f);
    EXPECT_FLOAT_EQ(half.at(1, 0)[3], 1.0f);
    try {
        pt::referenceAtSize(ref, 3, 6, "r.exr");
        FAIL() << "4 is not a multiple of 3";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("r.exr: reference is 4x6 but the render is 3x6"), std::string::npos)
            << e.what();
    }
}

TEST(Metrics, BlockStatsDropsPartialBlocks) {
    // 5x3 with 2x2 blocks: 2x1 full blocks; column 4 and row 2 are dropped.
    pt::Image im{5, 3, std::vector<float>(5 * 3 * 4)};
    pt::Image var = im;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            float* p = im.at(x, y);
            p[0] = float(x + 10 * y), p[1] = 1.0f, p[2] = float(x), p[3] = 123;
            float* v = var.at(x, y);
            v[0] = 4, v[1] = float(x), v[2] = 0, v[3] = 0;
        }
    const pt::BlockStats s = pt::blockStats(im, &var, 2);
    ASSERT_EQ(s.blocksX, 2);
    ASSERT_EQ(s.blocksY, 1);
    EXPECT_EQ(s.blockSize, 2);
    ASSERT_EQ(s.mean.size(), 6u);
    ASSERT_EQ(s.varOfMean.size(), 6u);
    // Block 0 covers x 0..1, y 0..1.
    EXPECT_DOUBLE_EQ(s.mean[0], (0 + 1 + 10 + 11) / 4.0);
    EXPECT_DOUBLE_EQ(s.mean[1], 1.0);
    EXPECT_DOUBLE_EQ(s.mean[2], 0.5);
    EXPECT_DOUBLE_EQ(s.varOfMean[0], 16.0 / 16.0); // sum 4*4 / n^2
    EXPECT_DOUBLE_EQ(s.varOfMean[1], (0 + 1 + 0 + 1) / 16.0);
    // Block 1 covers x 2..3.
    EXPECT_DOUBLE_EQ(s.mean[3], (2 + 3 + 12 + 13) / 4.0);
    EXPECT_DOUBLE_EQ(s.mean[5], 2.5);
    EXPECT_DOUBLE_EQ(s.varOfMean[4], (2 + 3 + 2 + 3) / 16.0);

    EXPECT_TRUE(pt::blockStats(im, nullptr, 2).varOfMean.empty());
}

// A noisy "render": per-pixel true mean m(x,y) plus Gaussian noise with the
// given per-pixel standard deviation; var receives the known variance.
struct Noisy {
    pt::Image mean, var;
};

Noisy noisyRender(int w, int h, std::mt19937& rng, float shift) {
    std::normal_distribution<float> n01(0.0f, 1.0f);
    Noisy r{constantImage(w, h, 0, 0, 0), constantImage(w, h, 0, 0, 0)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                // Smoothly varying mean and noise level, different per channel.
                const float m = 0.2f + 0.5f * x / w + 0.1f * c + 0.3f * y / h;
                const float sigma = 0.05f + 0.1f * (x + y) / (w + h) + 0.02f * c;
                r.mean.at(x, y)[c] = m + shift * sigma + sigma * n01(rng);
                r.var.at(x, y)[c] = sigma * sigma;
            }
    return r;
}

constexpr int kW = 128, kH = 128, kBlock = 8; // 256 blocks x 3 = 768 dof

TEST(Metrics, IndependentNoisyImagesAgree) {
    std::mt19937 rng(2024);
    const Noisy a = noisyRender(kW, kH, rng, 0.0f);
    const Noisy b = noisyRender(kW, kH, rng, 0.0f);
    const pt::AgreementResult r =
        pt::compareBlocks(pt::blockStats(a.mean, &a.var, kBlock), pt::blockStats(b.mean, &b.var, kBlock));
    EXPECT_EQ(r.dof, 768);
    EXPECT_GE(r.chi2PerDof, 0.7);
    EXPECT_LE(r.chi2PerDof, 1.3);
    EXPECT_LT(std::abs(r.meanZ), 0.2); // 1/sqrt(768) = 0.036 expected spread
    EXPECT_LT(r.maxAbsZ, 5.0);
    EXPECT_LT(r.meanRelDiff, 0.05);
}

TEST(Metrics, NoisyImageAgreesWithExactReference) {
    std::mt19937 rng(7);
    const Noisy a = noisyRender(kW, kH, rng, 0.0f);
    // Noise-free reference (e.g. a converged render) without a variance image.
    pt::Image exact = constantImage(kW, kH, 0, 0, 0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) exact.at(x, y)[c] = 0.2f + 0.5f * x / kW + 0.1f * c + 0.3f * y / kH;
    const pt::AgreementResult r =
        pt::compareBlocks(pt::blockStats(a.mean, &a.var, kBlock), pt::blockStats(exact, nullptr, kBlock));
    EXPECT_GE(r.chi2PerDof, 0.7);
    EXPECT_LE(r.chi2PerDof, 1.3);
}

TEST(Metrics, ShiftedMeanIsDetected) {
    // Shifting every pixel by 5 * (pixel sigma / 8) moves every 8x8 block
    // mean by ~5 sigma of the block mean; z per cell is then ~5/sqrt(2).
    std::mt19937 rng(31337);
    const Noisy a = noisyRender(kW, kH, rng, 0.0f);
    const Noisy b = noisyRender(kW, kH, rng, 5.0f / kBlock);
    const pt::AgreementResult r =
        pt::compareBlocks(pt::blockStats(a.mean, &a.var, kBlock), pt::blockStats(b.mean, &b.var, kBlock));
    EXPECT_GT(r.chi2PerDof, 10.0);
    EXPECT_LT(r.meanZ, -3.0); // a is below b: sign tells the direction
}

TEST(Metrics, BlackBlocksAreSkippedAndNanFails) {
    const pt::Image black = constantImage(16, 16, 0, 0, 0);
    const pt::AgreementResult r = pt::compareBlocks(pt::blockStats(black, &black, 4), pt::blockStats(black, &black, 4));
    EXPECT_EQ(r.dof, 0);
    EXPECT_EQ(r.chi2PerDof, 0.0);

    pt::Image withNan = constantImage(16, 16, 1, 1, 1);
    const pt::Image var = constantImage(16, 16, 0.1f, 0.1f, 0.1f);
    withNan.at(3, 3)[1] = std::numeric_limits<float>::quiet_NaN();
    const pt::AgreementResult n = pt::compareBlocks(pt::blockStats(withNan, &var, 4), pt::blockStats(withNan, &var, 4));
    EXPECT_FALSE(n.chi2PerDof <= 1.3); // NaN must not pass a threshold test
    EXPECT_TRUE(std::isinf(n.maxAbsZ));
}

TEST(Metrics, CompareBlocksRejectsBadInput) {
    const pt::Image a = constantImage(16, 16, 1, 1, 1);
    EXPECT_THROW(
        pt::compareBlocks(pt::blockStats(a, nullptr, 4), pt::blockStats(a, nullptr, 4)), std::invalid_argument);
    EXPECT_THROW(pt::compareBlocks(pt::blockStats(a, &a, 4), pt::blockStats(a, &a, 8)), std::invalid_argument);
}

} // namespace

namespace {

// The reference-free estimate against the true relMSE on synthetic renders: a smooth image
// (renders are mostly smooth; the estimate uses each pixel's neighbours), every pixel the mean
// of n samples around its true value, with the variance of the mean estimated from the same
// samples as the renderer does. Two sample distributions: exponential, and a rare-path one
// (0, or value / p with probability p), where a pixel that caught a rare sample must not
// look converged.
struct SyntheticRender {
    pt::Image truth, mean, var;
};

template <class Draw>
SyntheticRender syntheticRender(int n, Draw draw) {
    const int w = 64, h = 64;
    SyntheticRender r;
    r.truth = pt::Image{w, h, std::vector<float>(w * h * 4)};
    r.mean = r.var = r.truth;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) {
                const double mu = 0.05 + 2.95 * (0.5 + 0.5 * std::sin(x / 9.0 + c) * std::cos(y / 7.0));
                double sum = 0, sum2 = 0;
                for (int k = 0; k < n; ++k) {
                    const double v = draw(mu);
                    sum += v;
                    sum2 += v * v;
                }
                const double m = sum / n;
                r.truth.at(x, y)[c] = static_cast<float>(mu);
                r.mean.at(x, y)[c] = static_cast<float>(m);
                // Unbiased sample variance / n: the variance of the mean.
                r.var.at(x, y)[c] = static_cast<float>(std::max(0.0, sum2 / n - m * m) / (n - 1));
            }
    return r;
}

double estimateOverTruth(const SyntheticRender& r) {
    const double actual = pt::relMse(r.mean, r.truth), estimate = pt::estimatedRelMse(r.mean, r.var);
    return estimate / actual;
}

TEST(Metrics, EstimatedRelMseTracksTheTrueOneWithoutAReference) {
    std::mt19937 rng(11);
    for (int n : {4, 16, 64, 256}) {
        const double ratio = estimateOverTruth(
            syntheticRender(n, [&](double mu) { return std::exponential_distribution<double>(1.0 / mu)(rng); }));
        std::printf("exponential, %d spp: estimated / true relMSE %.3f\n", n, ratio);
        EXPECT_LT(ratio, 1.5) << n << " spp";
        EXPECT_GT(ratio, 1.0 / 1.5) << n << " spp";
        if (n == 256) EXPECT_NEAR(ratio, 1.0, 0.1);
    }
}

TEST(Metrics, EstimatedRelMseSeesRarePathsOnceTheyAreSampled) {
    std::mt19937 rng(12);
    const double p = 0.05;
    auto rare = [&](double mu) { return std::uniform_real_distribution<double>(0, 1)(rng) < p ? mu / p : 0.0; };
    for (int n : {64, 256}) {
        const double ratio = estimateOverTruth(syntheticRender(n, rare));
        std::printf("rare paths, %d spp: estimated / true relMSE %.3f\n", n, ratio);
        EXPECT_LT(ratio, 1.5) << n << " spp";
        EXPECT_GT(ratio, 1.0 / 1.5) << n << " spp";
    }
    // At 4 spp most pixels have seen no rare sample: the estimate is far off (here too high,
    // which makes --target-error render longer, not stop early). It must not claim convergence.
    EXPECT_GT(estimateOverTruth(syntheticRender(4, rare)), 1.0);
}

} // namespace
