// Adaptive sampling on the device (render/adaptive_sampling.h with the progressive loop): the
// image agrees with uniform sampling's block by block (light tracing's splats normalised by all
// the light paths traced, per-pixel variances by each pixel's own count); it does not depend on
// how passes and tiles split the epochs; and a render continued from its saved state, to any
// sample count, is bit-identical to one that never stopped.
#include "film/metrics.h"
#include "render/progressive_render.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <algorithm>

namespace pt::test {
namespace {

class AdaptiveRender : public GpuTest {
protected:
    // The glass box: caustics by light tracing, and noise that differs from pixel to pixel.
    void SetUp() override {
        GpuTest::SetUp();
        scene_ = loadGltfFile(testDataDir() / "references" / "cbox-glass-mirror" / "scene.gltf");
        flat_ = flattenScene(scene_);
        settings_ = independentSettings();
        settings_.maxDepth = 8;
    }
    std::unique_ptr<Renderer> makeRenderer(int size) {
        return std::make_unique<Renderer>(sharedContext(), flat_, suiteFeatures(flat_, settings_), settings_,
            scene_.cameras.at(0), FilmSettings{size, size, scene_.background});
    }
    ProgressiveResult renderAdaptively(Renderer& renderer, uint32_t spp, uint32_t passSpp = 0, uint32_t tile = 0) {
        ProgressiveTarget target;
        target.spp = spp;
        target.passSpp = passSpp;
        target.tileSize = tile;
        target.adaptive = true;
        return renderProgressively(renderer, target, nullptr, nullptr, false);
    }

    Scene scene_;
    FlatScene flat_;
    IntegratorSettings settings_;
};

TEST_F(AdaptiveRender, AgreesWithUniformSampling) {
    auto adaptive = makeRenderer(32);
    const ProgressiveResult result = renderAdaptively(*adaptive, 256);
    ASSERT_GT(result.adaptiveEpochs, 0u) << "every epoch was uniform (predicted gain " << result.predictedGain << ")";
    const AccumulationState state = adaptive->readState();
    ASSERT_TRUE(state.adaptive());
    const auto [fewest, most] = std::minmax_element(state.pixelSamples.begin(), state.pixelSamples.end());
    EXPECT_GT(*most, 2 * *fewest) << "the allocation hardly varies";
    EXPECT_NEAR(state.totalSamples() / double(state.pixels()), 256.0, 2.0);
    settings_.seed = 77;
    const Renderer::Readback uniform = renderScene(scene_, settings_, scene_.cameras.at(0), 32, 32, 256);
    const Renderer::Readback image = resolve(state);
    const AgreementResult r = compareBlocks(
        blockStats(image.mean, &image.varianceOfMean, 4), blockStats(uniform.mean, &uniform.varianceOfMean, 4));
    std::printf("[          ] adaptive (%u of %u epochs) vs uniform: chi2/dof %.3f, mean z %+.3f, max |z| %.2f\n",
        result.adaptiveEpochs, result.epochs, r.chi2PerDof, r.meanZ, r.maxAbsZ);
    EXPECT_LT(r.chi2PerDof, 1.6);
    EXPECT_LT(std::abs(r.meanZ), 0.5);
}

TEST_F(AdaptiveRender, ChunkingDoesNotChangeTheImage) {
    auto whole = makeRenderer(24);
    const ProgressiveResult wholeResult = renderAdaptively(*whole, 80, 80);
    ASSERT_GT(wholeResult.adaptiveEpochs, 0u);
    auto pieces = makeRenderer(24);
    renderAdaptively(*pieces, 80, 3, 7); // passes of 3 rounds, 7x7-pixel tiles
    const AccumulationState a = whole->readState(), b = pieces->readState();
    EXPECT_EQ(a.sums, b.sums);
    EXPECT_EQ(a.splats, b.splats);
    EXPECT_EQ(a.pixelSamples, b.pixelSamples);
}

TEST_F(AdaptiveRender, AContinuedRenderIsBitIdentical) {
    auto straight = makeRenderer(24);
    ASSERT_GT(renderAdaptively(*straight, 80, 5).adaptiveEpochs, 0u);
    auto first = makeRenderer(24);
    renderAdaptively(*first, 21, 5); // stops mid-epoch, as an interrupted render
    const AccumulationState saved = first->readState();
    ASSERT_GT(saved.epochRoundsDone, 0u);
    ASSERT_LT(saved.epochRoundsDone, saved.epochRounds);
    auto resumed = makeRenderer(24);
    resumed->loadState(saved);
    renderAdaptively(*resumed, 80, 5);
    const AccumulationState a = straight->readState(), b = resumed->readState();
    EXPECT_EQ(a.sums, b.sums);
    EXPECT_EQ(a.splats, b.splats);
    EXPECT_EQ(a.pixelSamples, b.pixelSamples);
}

} // namespace
} // namespace pt::test
