// Shared samples (`--shared-samples on`, integrator/pixel_groups.glsl): the 8 pixels of a group
// take the same random numbers. Each pixel's estimate must stay unbiased, and the groups must
// really share: their noise is correlated, which is also why the usual per-pixel variances
// cannot judge the image. So every check here takes its variances from the spread of
// independent seeds' renders, block by block, which holds however the pixels are correlated.
#include "film/metrics.h"
#include "image/image_io.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <cstdio>

namespace pt::test {
namespace {

IntegratorSettings sharedSettings() {
    IntegratorSettings s;
    s.sharedSamples = true;
    return s;
}

// Each seed's render reduced to blocks of `blockSize` pixels; the blocks' mean over the seeds and
// the variance of that mean from their spread.
BlockStats seedBlockStats(const std::vector<Image>& renders, int blockSize) {
    std::vector<BlockStats> perSeed;
    for (const Image& r : renders) perSeed.push_back(blockStats(r, nullptr, blockSize));
    BlockStats out = perSeed.at(0);
    out.varOfMean.assign(out.mean.size(), 0.0);
    const double n = double(perSeed.size());
    for (size_t k = 0; k < out.mean.size(); ++k) {
        double sum = 0, sumSq = 0;
        for (const BlockStats& b : perSeed) sum += b.mean[k], sumSq += b.mean[k] * b.mean[k];
        const double mean = sum / n;
        out.mean[k] = mean;
        out.varOfMean[k] = std::max(0.0, (sumSq - n * mean * mean) / (n - 1)) / n;
    }
    return out;
}

class SharedSamples : public GpuTest {};

// The diffuse Cornell box against Mitsuba 3's reference, in blocks of 32x32 pixels: 128 groups a
// block, since at 16x16 (32 groups) the dim corners' skewed sums made the seeds' spread too
// narrow for a z-test (|z| to 5, all low); and the groups' correlation,
// seen as 8x8 block means varying several times more than independent pixels would make them.
TEST_F(SharedSamples, CornellBoxAgreesWithMitsubaAndItsGroupsShareTheirNoise) {
    const auto dir = testDataDir() / "references" / "cbox-diffuse";
    Scene scene = loadGltfFile(dir / "scene.gltf");
    const Image reference = readExr(dir / "reference.exr");
    const Image referenceVar = readExr(dir / "reference.var.exr");
    IntegratorSettings s = sharedSettings();
    s.maxDepth = static_cast<uint32_t>(scene.hints.maxDepth.value());
    const int seeds = 16; // the t-distribution of a z from 16 seeds is near enough normal for chi2
    std::vector<Image> renders;
    for (int i = 0; i < seeds; ++i) {
        s.seed = 201 + uint32_t(i);
        Renderer::Readback r = renderScene(scene, s, scene.cameras.at(0), reference.width, reference.height, 4);
        ASSERT_EQ(r.droppedSamples, 0u);
        renders.push_back(std::move(r.mean));
    }
    const AgreementResult a = compareBlocks(seedBlockStats(renders, 32), blockStats(reference, &referenceVar, 32));

    // The 8x8 blocks' variance against what independent pixels would give: the pixels' own
    // variances (blocks of one pixel, from the seeds' spread) over 64.
    auto meanOf = [](const std::vector<double>& v) {
        double sum = 0;
        for (double x : v) sum += x;
        return sum / double(v.size());
    };
    const double correlation =
        meanOf(seedBlockStats(renders, 8).varOfMean) / (meanOf(seedBlockStats(renders, 1).varOfMean) / 64);
    std::printf("shared samples: chi2/dof %.3f, mean z %+.3f, max |z| %.2f; 8x8 block variance %.2fx independent "
                "pixels'\n",
        a.chi2PerDof, a.meanZ, a.maxAbsZ, correlation);
    EXPECT_LT(a.chi2PerDof, 1.5) << "block means disagree with the reference";
    EXPECT_LT(std::abs(a.meanZ), 0.25) << "systematic offset";
    EXPECT_GT(correlation, 2.0) << "the groups' pixels do not share their random numbers";
}

TEST_F(SharedSamples, ImageIsTheSameHoweverTheSamplesAreSplit) {
    Scene scene = loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    expectTheSameImageHoweverSplit(scene, sharedSettings(), 6);
}

} // namespace
} // namespace pt::test
