#pragma once
// Shared helpers for tests that run on the Vulkan device (lavapipe in CI): one context with
// the validation layer on, the GLSL test kernel runner, small procedural scenes, and a
// one-call render.
#include "gpu/vulkan_context.h"
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "render/gpu_scene.h"
#include "flatten/integrator_settings.h"
#include "render/renderer.h"
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <span>
#include <vector>

namespace pt::test {

// The process-wide context, created on first use with validation enabled.
VulkanContext& sharedContext();

// Fixture: fails a test if the validation layer said anything during it.
class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

private:
    uint32_t messagesBefore_ = 0;
};

// Runs shaders/tests/test_kernels.comp in `mode` over `count` items. `scene` may be null for
// modes that need none; `inputs` is uploaded as the kernel's input array. TEST_MODE_BSDF_SAMPLE
// returns 2 x count values: (wi, pdf) per sample, then (weight, valid) per sample.
std::vector<glm::vec4> runTestKernel(uint32_t mode, uint32_t count, const GpuScene* scene,
    std::span<const std::byte> inputs = {}, glm::vec3 point = glm::vec3(0.0f), glm::vec3 normal = glm::vec3(0, 0, 1),
    uint32_t seed = 1, uint32_t materialIndex = 0);

// Whether runTestKernel's kernels read the triangle tree and the triangles through texel buffers
// (TEXEL_LOADS) or through buffer addresses (the default, as FeatureSet::all has it).
void setTestKernelTexelLoads(bool on);

// Procedural geometry.
Mesh makeIcosphere(int subdivisions, glm::vec3 centre, float radius, uint32_t material);
Mesh makeQuad(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, uint32_t material); // normal = edgeU x edgeV

// The integrator defaults with independent samples, for tests whose statistics divide by each
// pixel's sample variance / n: that is the variance of the mean only for independent samples.
// Under the default Sobol' points the mean varies less, so such a z-test would lose power (pass
// too easily), not fail; the default sampler is tested with seeds as replicates instead
// (tests/shaders/integrator/sobol_reference_test.cpp).
IntegratorSettings independentSettings();

// Whether the suite's renders read the geometry through texel buffers: this machine's faster loads,
// measured once for the whole suite (the fixture test GpuSuite.GeometryLoadsChosen) and
// remembered in the tests' pipeline-cache folder, as `--texel-loads auto` does for users. Both
// give the same image (TexelLoads.*, which choose explicitly), so this only decides the suite's time:
// on a Zen 4 where addresses were faster, texel loads took 1.2-1.35x as long in render-heavy tests.
bool suiteTexelLoads();

// computeFeatures with the suite's geometry loads: what the tests' renderers are specialised to.
FeatureSet suiteFeatures(const FlatScene& flat, const IntegratorSettings& settings);

// Renders `scene` from `camera` with the kernel specialised for it and returns the sums read back.
// `bvh` says how it is flattened (instances kept or copied, node format).
Renderer::Readback renderScene(const Scene& scene, const IntegratorSettings& settings, const Camera& camera, int width,
    int height, uint32_t spp, uint32_t passSpp = 0, uint32_t tileSize = 0, const BvhBuildOptions& bvh = {});

// The same with the kernel specialised as `features` says (tests that change what the scene decides;
// the geometry loads still the suite's).
Renderer::Readback renderSceneWith(const Scene& scene, const IntegratorSettings& settings, const FeatureSet& features,
    const Camera& camera, int width, int height, uint32_t spp);

// Renders `spp` samples of `scene` (its first camera, 40x40) in one pass and in passes of 3 spp over
// 16-pixel tiles, and expects the two images equal bit for bit; a render with another seed must
// differ, so that the comparison can tell images apart.
void expectTheSameImageHoweverSplit(const Scene& scene, const IntegratorSettings& settings, uint32_t spp);

// Directory of test data (tests/), set by CMake.
std::filesystem::path testDataDir();

// Regularised upper incomplete gamma Q(a, x): the chi-square p-value is Q(dof / 2, chi2 / 2).
double gammaQ(double a, double x);

// Pearson chi-square test of observed counts against expected ones; bins with expected < 5
// are pooled (as in pbrt's chi2 tests). Returns the p-value; `dof` receives the degrees of freedom.
double chiSquarePValue(std::span<const double> observed, std::span<const double> expected, int* dof = nullptr);

} // namespace pt::test
