// The default sampler (Owen-scrambled Sobol') against the Mitsuba 3 references. A Sobol'
// render's per-pixel sample variance / n is not the variance of its mean (the points are
// stratified, so the mean varies less), so the z-tests of reference_test.cpp, which run with
// independent samples, would lose their power here. Instead each scene is rendered with
// several seeds: each seed is an independent randomisation of the same point set, so the
// spread of the seeds' means gives the variance of their average (randomised quasi-Monte
// Carlo, Owen 1997) and the block z-test is valid again. The same seeds with independent
// samples check the point of the default: lower error for the same samples.
#include "image/image_io.h"
#include "film/metrics.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <cmath>

namespace pt::test {
namespace {

struct Replicated {
    Image mean, varianceOfMean;
};

// The average of `seeds` renders and the variance of that average from their spread.
Replicated renderReplicas(const Scene& scene, IntegratorSettings s, int width, int height, uint32_t spp, int seeds) {
    std::vector<Image> means;
    for (int i = 0; i < seeds; ++i) {
        s.seed = 101 + uint32_t(i);
        Renderer::Readback r = renderScene(scene, s, scene.cameras.at(0), width, height, spp);
        EXPECT_EQ(r.droppedSamples, 0u);
        means.push_back(std::move(r.mean));
    }
    Replicated out{means[0], means[0]};
    for (size_t k = 0; k < out.mean.rgba.size(); ++k) {
        double sum = 0, sumSq = 0;
        for (const Image& m : means) sum += m.rgba[k], sumSq += double(m.rgba[k]) * m.rgba[k];
        const double mean = sum / seeds;
        const double var = std::max(0.0, (sumSq - seeds * mean * mean) / (seeds - 1));
        out.mean.rgba[k] = float(mean);
        out.varianceOfMean.rgba[k] = float(var / seeds);
    }
    return out;
}

class SobolReference : public GpuTest {
protected:
    void check(const char* name, uint32_t spp, int seeds, double maxChi2PerDof, double maxMeanZ, double maxErrorRatio) {
        const auto dir = testDataDir() / "references" / name;
        Scene scene = loadGltfFile(dir / "scene.gltf");
        const Image reference = readExr(dir / "reference.exr");
        const Image referenceVar = readExr(dir / "reference.var.exr");
        IntegratorSettings s;
        ASSERT_EQ(s.sampler, SamplerKind::Sobol) << "the default sampler";
        s.maxDepth = static_cast<uint32_t>(scene.hints.maxDepth.value());
        const Replicated sobol = renderReplicas(scene, s, reference.width, reference.height, spp, seeds);
        const AgreementResult a =
            compareBlocks(blockStats(sobol.mean, &sobol.varianceOfMean, 16), blockStats(reference, &referenceVar, 16));
        // Error for the same samples, both samplers: every seed's render against the reference.
        s.sampler = SamplerKind::Independent;
        const Replicated independent = renderReplicas(scene, s, reference.width, reference.height, spp, seeds);
        double predictedSobol = 0, predictedIndependent = 0; // relMSE of one seed's render, minus the reference's
        for (size_t i = 0; i < reference.rgba.size(); ++i) {
            if (i % 4 == 3) continue;
            const double w = reference.rgba[i] * reference.rgba[i] + 0.01;
            predictedSobol += sobol.varianceOfMean.rgba[i] * seeds / w;
            predictedIndependent += independent.varianceOfMean.rgba[i] * seeds / w;
        }
        const double ratio = predictedSobol / predictedIndependent;
        std::printf("%s: %d seeds x %u spp, Sobol' chi2/dof %.3f, mean z %+.3f, max |z| %.2f; Sobol' / independent "
                    "variance %.3f\n",
            name, seeds, spp, a.chi2PerDof, a.meanZ, a.maxAbsZ, ratio);
        EXPECT_LT(a.chi2PerDof, maxChi2PerDof) << name << ": block means disagree";
        EXPECT_LT(std::abs(a.meanZ), maxMeanZ) << name << ": systematic offset";
        EXPECT_LT(ratio, maxErrorRatio) << name << ": Sobol' no better than independent samples";
    }
};

TEST_F(SobolReference, CornellBoxDiffuse) { check("cbox-diffuse", 8, 8, 1.5, 0.25, 0.85); }
TEST_F(SobolReference, CornellBoxGlassMirror) { check("cbox-glass-mirror", 8, 4, 2.5, 0.5, 1.1); }

} // namespace
} // namespace pt::test
