// The course's glossy BRDFs (shaders/bsdf/glossy.glsl) through the GLSL test kernel: their
// importance sampling against their own pdf (chi-square, with the mass lost below the horizon
// as one more bin), every sample weight equal to f cos / pdf, and energy bounds.
#include "support/gpu_test_support.h"

#include <cmath>
#include <cstdio>

namespace pt::test {
namespace {

constexpr int kZBins = 16, kPhiBins = 32, kSub = 12;
constexpr uint32_t kSamples = 200000;

glm::vec3 direction(double z, double phi) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

constexpr double dz = 1.0 / kZBins / kSub, dphi = 2 * M_PI / kPhiBins / kSub;

// kSub x kSub midpoint directions inside each (cos theta, phi) bin, bin after bin.
std::vector<glm::vec4> midpointGrid() {
    std::vector<glm::vec4> dirs;
    for (int zi = 0; zi < kZBins; ++zi)
        for (int pi = 0; pi < kPhiBins; ++pi)
            for (int a = 0; a < kSub; ++a)
                for (int b = 0; b < kSub; ++b)
                    dirs.emplace_back(direction((zi * kSub + a + 0.5) * dz, (pi * kSub + b + 0.5) * dphi), 0.0f);
    return dirs;
}

int binOf(const glm::vec3& w) {
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * M_PI;
    const int zi = std::min(kZBins - 1, static_cast<int>(w.z * kZBins));
    const int pi = std::min(kPhiBins - 1, static_cast<int>(phi / (2 * M_PI) * kPhiBins));
    return zi * kPhiBins + pi;
}

struct Case {
    const char* name;
    GlossyModel model;
    float exponent;
    bool normalized;
    float cosThetaO;
};

class GlossyBsdf : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        for (const Case& c : cases()) {
            Material m;
            m.type = MaterialType::Glossy;
            m.baseColor = glm::vec3(0.3f);
            m.specular = glm::vec3(0.6f);
            m.glossyModel = c.model;
            m.exponent = c.exponent;
            m.normalized = c.normalized;
            m.conductorEta = glm::vec3(0.37f);
            m.conductorK = glm::vec3(2.82f);
            scene_.materials.push_back(m);
        }
        scene_.meshes.push_back(makeQuad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0)); // any geometry
        flat_ = flattenScene(scene_);
        gpu_ = std::make_unique<GpuScene>(sharedContext(), flat_, gpu::GpuSceneParams{}, 0);
    }
    static std::vector<Case> cases() {
        return {
            {"modified Phong, normalised, p 20", GlossyModel::ModifiedPhong, 20.0f, true, 0.75f},
            {"modified Blinn-Phong, normalised, p 50", GlossyModel::ModifiedBlinnPhong, 50.0f, true, 0.75f},
            {"Torrance-Sparrow, p 30", GlossyModel::TorranceSparrow, 30.0f, false, 0.6f},
            {"original Phong, p 10", GlossyModel::OriginalPhong, 10.0f, false, 0.9f},
            {"original Blinn-Phong, p 8, grazing", GlossyModel::OriginalBlinnPhong, 8.0f, false, 0.1f},
            {"modified Phong, p 5, grazing", GlossyModel::ModifiedPhong, 5.0f, true, 0.05f},
        };
    }
    // (f cos, pdf) at each direction, for material `index` seen from wo.
    std::vector<glm::vec4> evaluate(uint32_t index, glm::vec3 wo, const std::vector<glm::vec4>& dirs) {
        return runTestKernel(TEST_MODE_BSDF_PDF, static_cast<uint32_t>(dirs.size()), gpu_.get(),
            std::as_bytes(std::span<const glm::vec4>(dirs)), glm::vec3(0.0f), wo, 1, index);
    }
    Scene scene_;
    FlatScene flat_;
    std::unique_ptr<GpuScene> gpu_;
};

TEST_F(GlossyBsdf, SamplingMatchesPdfAndWeightsAreFCosOverPdf) {
    const auto all = cases();
    for (uint32_t index = 0; index < all.size(); ++index) {
        const Case& c = all[index];
        const glm::vec3 wo(std::sqrt(1.0f - c.cosThetaO * c.cosThetaO), 0.0f, c.cosThetaO);
        // Expected counts: the pdf integrated over each bin by a kSub x kSub midpoint rule.
        const std::vector<glm::vec4> dirs = midpointGrid();
        const auto values = evaluate(index, wo, dirs);
        std::vector<double> expected(kZBins * kPhiBins + 1, 0.0), observed(kZBins * kPhiBins + 1, 0.0);
        double albedo = 0, mass = 0;
        for (size_t k = 0; k < dirs.size(); ++k) {
            const int bin = static_cast<int>(k / (kSub * kSub));
            expected[bin] += values[k].w * dz * dphi * kSamples;
            mass += values[k].w * dz * dphi;
            albedo += values[k].x * dz * dphi;
        }
        expected.back() = std::max(0.0, 1.0 - mass) * kSamples; // samples lost below the horizon

        const auto samples =
            runTestKernel(TEST_MODE_BSDF_SAMPLE, kSamples, gpu_.get(), {}, glm::vec3(0.0f), wo, 3, index);
        std::vector<glm::vec4> sampled;
        for (uint32_t i = 0; i < kSamples; ++i) {
            if (samples[kSamples + i].w == 0.0f) {
                observed.back() += 1;
                continue;
            }
            observed[binOf(glm::vec3(samples[i]))] += 1;
            sampled.emplace_back(glm::vec3(samples[i]), 0.0f);
        }
        int dof = 0;
        const double p = chiSquarePValue(observed, expected, &dof);
        std::printf(
            "[          ] %s: chi-square p %.4f (%d dof), pdf mass %.4f, albedo %.4f\n", c.name, p, dof, mass, albedo);
        EXPECT_GT(p, 1e-3) << c.name;
        EXPECT_LE(mass, 1.0 + 2e-3) << c.name;
        if (c.normalized || c.model == GlossyModel::TorranceSparrow)
            EXPECT_LE(albedo, 1.0 + 2e-3) << c.name << ": an energy-normalised BRDF reflects at most what arrives";

        // Each sample's weight is f cos / pdf at its direction.
        const auto atSamples = evaluate(index, wo, sampled);
        size_t j = 0, bad = 0;
        for (uint32_t i = 0; i < kSamples; ++i) {
            if (samples[kSamples + i].w == 0.0f) continue;
            const glm::vec4 v = atSamples[j++];
            const float expectedWeight = v.x / v.w;
            if (!(std::abs(samples[kSamples + i].x - expectedWeight) <= 1e-3f * std::max(1.0f, expectedWeight)) ||
                !(std::abs(samples[i].w - v.w) <= 1e-3f * v.w))
                ++bad;
        }
        EXPECT_EQ(bad, 0u) << c.name;
    }
}

TEST_F(GlossyBsdf, ChiSquareRejectsAWrongExponent) {
    // Negative control: samples of the p = 20 lobe judged by the pdf of a p = 50 lobe.
    const glm::vec3 wo(std::sqrt(1.0f - 0.75f * 0.75f), 0.0f, 0.75f);
    const std::vector<glm::vec4> dirs = midpointGrid();
    const auto wrong = evaluate(1, wo, dirs); // material 1: Blinn-Phong p 50
    std::vector<double> expected(kZBins * kPhiBins, 0.0), observed(kZBins * kPhiBins, 0.0);
    for (size_t k = 0; k < dirs.size(); ++k) expected[k / (kSub * kSub)] += wrong[k].w * dz * dphi * kSamples;
    const auto samples = runTestKernel(TEST_MODE_BSDF_SAMPLE, kSamples, gpu_.get(), {}, glm::vec3(0.0f), wo, 3, 0);
    for (uint32_t i = 0; i < kSamples; ++i)
        if (samples[kSamples + i].w != 0.0f) observed[binOf(glm::vec3(samples[i]))] += 1;
    EXPECT_LT(chiSquarePValue(observed, expected), 1e-6);
}

} // namespace
} // namespace pt::test
