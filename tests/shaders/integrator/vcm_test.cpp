// Vertex merging (shaders/integrator/vcm.glsl): BDPT whose camera vertices also merge with the
// light subpath vertices of every pixel near them. Merging is a density estimate over the
// radius, so it is consistent rather than unbiased: the tests check that at a small radius the
// image agrees with an independent renderer (Mitsuba 3) within noise, that a large radius shows
// its bias to the same test (the test can fail), that the image is the same however the work is
// split, and where the integrator is chosen. The furnace (furnace_test.cpp) checks that the MIS
// weights with merges sum to one. A round's light subpaths serve every pixel, so neighbouring
// pixels share noise and the image's own variance understates a block's: block variances come
// from the spread of independent rounds.
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "film/metrics.h"
#include "image/image_io.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace pt::test {
namespace {

class Vcm : public GpuTest {};

std::filesystem::path diffuseBoxDir() { return testDataDir() / "references" / "cbox-diffuse"; }

IntegratorSettings vcmSettings(uint32_t maxDepth, float radius) {
    IntegratorSettings s = independentSettings();
    s.estimator = Estimator::VertexMerging;
    s.maxDepth = maxDepth;
    s.mergeRadius = radius;
    return s;
}

// Block means over `rounds` rounds of one renderer, and the variance of their mean from the spread
// of the rounds' own images (each round's light and camera subpaths are its own, so rounds are
// independent; one renderer builds the kernel once).
BlockStats blocksOverRounds(
    const Scene& scene, const IntegratorSettings& s, int width, int height, int rounds, int blockSize) {
    FlatScene flat = flattenScene(scene);
    Renderer renderer(sharedContext(), flat, suiteFeatures(flat, s), s, scene.cameras.at(0),
        FilmSettings{width, height, scene.background});
    std::vector<BlockStats> each;
    std::vector<float> before; // the sums of the rounds so far, per channel
    for (int k = 1; k <= rounds; ++k) {
        renderer.addSamples(1, 0);
        const Renderer::Readback r = renderer.read();
        EXPECT_EQ(r.droppedSamples, 0u);
        Image round = r.mean;
        before.resize(round.rgba.size(), 0.0f);
        for (size_t i = 0; i < round.rgba.size(); ++i) {
            const float sum = r.mean.rgba[i] * float(k);
            round.rgba[i] = sum - before[i];
            before[i] = sum;
        }
        each.push_back(blockStats(round, nullptr, blockSize));
    }
    BlockStats out = each.front();
    out.varOfMean.assign(out.mean.size(), 0.0);
    for (size_t i = 0; i < out.mean.size(); ++i) {
        double sum = 0, squares = 0;
        for (const BlockStats& b : each) sum += b.mean[i];
        const double mean = sum / rounds;
        for (const BlockStats& b : each) squares += (b.mean[i] - mean) * (b.mean[i] - mean);
        out.mean[i] = mean;
        out.varOfMean[i] = squares / (rounds - 1) / rounds;
    }
    return out;
}

// The diffuse Cornell box against its Mitsuba 3 reference, rendered at half its size (128x128) and
// compared in blocks of 8x8 pixels (the reference's 16x16): at a radius of one pixel footprint
// the merges' bias is far below the noise of 32 spp; at 30 footprints (a tenth of the box)
// light leaks from the bright ceiling and the corners darken, and the same test sees it.
TEST_F(Vcm, AgreesWithMitsubaInTheDiffuseCornellBoxAtASmallRadius) {
    const auto dir = diffuseBoxDir();
    const Scene scene = loadGltfFile(dir / "scene.gltf");
    const Image reference = readExr(dir / "reference.exr");
    const Image referenceVar = readExr(dir / "reference.var.exr");
    BlockStats theirs = blockStats(reference, &referenceVar, 16);
    theirs.blockSize = 8; // the same blocks, of the half-size render
    const uint32_t depth = static_cast<uint32_t>(scene.hints.maxDepth.value());
    ASSERT_TRUE(computeFeatures(flattenScene(scene), vcmSettings(depth, 1.0f)).merging);
    const int width = reference.width / 2, height = reference.height / 2;
    const AgreementResult small =
        compareBlocks(blocksOverRounds(scene, vcmSettings(depth, 1.0f), width, height, 32, 8), theirs);
    const AgreementResult large =
        compareBlocks(blocksOverRounds(scene, vcmSettings(depth, 30.0f), width, height, 32, 8), theirs);
    std::printf("[          ] radius 1: chi2/dof %.3f, mean z %.3f; radius 30: chi2/dof %.3f, mean z %.3f\n",
        small.chi2PerDof, small.meanZ, large.chi2PerDof, large.meanZ);
    // The block variance has 31 degrees of freedom (32 rounds): z^2 then has mean 31/29 rather
    // than 1 (Student's t), well inside the threshold.
    EXPECT_LT(small.chi2PerDof, 4.0) << "block means disagree (max |z| " << small.maxAbsZ << ")";
    EXPECT_LT(std::abs(small.meanZ), 0.5) << "systematic offset";
    EXPECT_GT(large.chi2PerDof, 3.0 * small.chi2PerDof) << "a radius of a tenth of the box must show its bias";
}

// Splats are integer sums, each cell's list of light vertices is kept in slot order, and camera
// samples are added in order: the same image, bit for bit, in one pass or in passes of 3 spp over
// 16-pixel tiles; another seed gives another image.
TEST_F(Vcm, ImageIsTheSameHoweverTheSamplesAreSplit) {
    const Scene scene = loadGltfFile(diffuseBoxDir() / "scene.gltf");
    expectTheSameImageHoweverSplit(scene, vcmSettings(6, 5.0f), 9);
}

// Merging comes with BDPT wherever BDPT renders the scene (asked for, or chosen by auto), except
// when BDPT alone is asked for, with moving objects, and deeper than a pixel keeps light vertices.
TEST_F(Vcm, ChosenWithBdptUnlessBdptAloneIsAskedFor) {
    FlatScene box = flattenScene(loadGltfFile(diffuseBoxDir() / "scene.gltf"));
    IntegratorSettings s = vcmSettings(8, 5.0f);
    EXPECT_TRUE(computeFeatures(box, s).bdpt);
    EXPECT_TRUE(computeFeatures(box, s).merging);
    s.estimator = Estimator::Bidirectional;
    EXPECT_TRUE(computeFeatures(box, s).bdpt);
    EXPECT_FALSE(computeFeatures(box, s).merging) << "--integrator bdpt";
    s.estimator = Estimator::Path;
    EXPECT_FALSE(computeFeatures(box, s).merging) << "--integrator path";
    s.estimator = Estimator::Auto;
    box.lightVisibility = 0.9f;
    EXPECT_FALSE(computeFeatures(box, s).merging) << "auto where light sampling finds the light";
    box.lightVisibility = 0.02f;
    EXPECT_TRUE(computeFeatures(box, s).merging) << "auto where light sampling seldom finds the light";
    s.maxDepth = BDPT_MAX_LIGHT_VERTICES + 2;
    EXPECT_TRUE(computeFeatures(box, s).bdpt);
    EXPECT_FALSE(computeFeatures(box, s).merging) << "more light vertices than a pixel keeps";
}

} // namespace
} // namespace pt::test
