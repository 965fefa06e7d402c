// The hemisphere samplers of shaders/common/sampling.glsl against their pdfs by chi-square
// (support/sampling_chi2.h), their returned pdfs against the analytic ones, and random numbers on
// the edges of [0, 1).
#include "support/sampling_chi2.h"

namespace pt::test {
namespace {

// Expected counts of `n` samples from a pdf that depends only on cos theta, integrated over
// each bin exactly from its antiderivative in z (times dphi).
template <class Antiderivative>
std::vector<double> expectedFromZPdf(const DirectionGrid& grid, double n, Antiderivative cdfOfZ) {
    std::vector<double> expected(grid.count());
    for (int zi = 0; zi < grid.zBins; ++zi) {
        const double z0 = grid.zLo + zi * grid.dz(), z1 = z0 + grid.dz();
        for (int pi = 0; pi < grid.phiBins; ++pi)
            expected[grid.index(zi, pi)] = n * (cdfOfZ(z1) - cdfOfZ(z0)) * grid.dphi();
    }
    return expected;
}
// Integral of cos theta / pi dz and of 1 / (2 pi) dz.
double cosineAntiderivative(double z) { return 0.5 * z * z / kPi; }
double uniformAntiderivative(double z) { return z / (2.0 * kPi); }

// Per sample: unit length, in the upper hemisphere, and the returned pdf equal to the analytic
// one; then the distribution by chi-square. Two seeds, so one lucky stream cannot hide a bias.
void checkHemisphereSampler(uint32_t mode, double (*pdf)(double), double (*antiderivative)(double), const char* name) {
    for (uint32_t seed : {1u, 0x9e3779b9u}) {
        const std::vector<glm::vec4> samples =
            pt::test::runTestKernel(mode, kSamples, nullptr, {}, glm::vec3(0.0f), glm::vec3(0, 0, 1), seed);
        size_t bad = 0;
        for (const glm::vec4& s : samples) {
            const double z = s.z;
            const double expectedPdf = pdf(z);
            const bool ok = z >= 0.0 && std::abs(glm::length(glm::dvec3(s)) - 1.0) < 1e-5 &&
                            std::abs(s.w - expectedPdf) <= 1e-5 * expectedPdf;
            if (!ok && ++bad <= 5)
                ADD_FAILURE() << name << " seed " << seed << ": sample (" << s.x << ", " << s.y << ", " << s.z
                              << ") pdf " << s.w << ", analytic pdf " << expectedPdf;
        }
        EXPECT_EQ(bad, 0u) << name;
        const std::vector<double> expected = expectedFromZPdf(kHemisphere, kSamples, antiderivative);
        const std::string what = std::string(name) + " seed " + std::to_string(seed);
        EXPECT_GT(pValue(histogram(kHemisphere, samples), expected, what.c_str()), kMinPValue) << what;
    }
}

TEST_F(SamplingTest, CosineHemisphereMatchesItsPdf) {
    checkHemisphereSampler(
        TEST_MODE_COSINE_HEMISPHERE, [](double z) { return std::max(z, 0.0) / kPi; }, cosineAntiderivative,
        "cosine hemisphere");
}

TEST_F(SamplingTest, UniformHemisphereMatchesItsPdf) {
    // The production pdf is 0 exactly at z = 0 (a boundary of measure zero); mirror that.
    checkHemisphereSampler(
        TEST_MODE_UNIFORM_HEMISPHERE, [](double z) { return z > 0.0 ? 0.5 / kPi : 0.0; }, uniformAntiderivative,
        "uniform hemisphere");
}

// Random numbers on the edges of [0, 1) map to the rim of the disk, a tangent direction of pdf 0
// that ends the path (1 in 2^23 bounces). The samplers must keep clear of it on every device:
// NVIDIA's approximate sin and cos put the old cos^2 + sin^2 at or above 1 for u = 0.
TEST_F(SamplingTest, EdgeRandomNumbersGiveDirectionsAboveTheHorizon) {
    const float top = 1.0f - 1.0f / 16777216.0f;
    std::vector<glm::vec4> at;
    for (float a : {0.0f, 0.5f, top, 0.25f, 0.75f})
        for (float b : {0.0f, 0.5f, top, 1.0f / 16777216.0f}) at.emplace_back(a, b, 0, 0), at.emplace_back(b, a, 0, 0);
    for (uint32_t mode : {TEST_MODE_COSINE_HEMISPHERE, TEST_MODE_UNIFORM_HEMISPHERE}) {
        const std::vector<glm::vec4> w =
            pt::test::runTestKernel(mode, static_cast<uint32_t>(at.size()), nullptr, std::as_bytes(std::span(at)));
        for (size_t i = 0; i < at.size(); ++i) {
            EXPECT_GT(w[i].z, 0.0f) << "mode " << mode << " u = (" << at[i].x << ", " << at[i].y << ")";
            EXPECT_GT(w[i].w, 0.0f) << "pdf, mode " << mode << " u = (" << at[i].x << ", " << at[i].y << ")";
            EXPECT_NEAR(glm::length(glm::vec3(w[i])), 1.0f, 1e-5f) << "mode " << mode;
        }
    }
}

// The chi-square test must be able to fail: cosine samples judged against uniform expectations.
TEST_F(SamplingTest, ChiSquareRejectsAWrongPdf) {
    const std::vector<glm::vec4> samples = pt::test::runTestKernel(TEST_MODE_COSINE_HEMISPHERE, kSamples, nullptr);
    const double p = pValue(histogram(kHemisphere, samples),
        expectedFromZPdf(kHemisphere, kSamples, uniformAntiderivative), "cosine samples vs uniform pdf (must fail)");
    EXPECT_LT(p, 1e-6);
}

} // namespace
} // namespace pt::test
