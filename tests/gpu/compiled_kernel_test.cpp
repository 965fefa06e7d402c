// One driver compile per kernel in a process (gpu/compiled_kernel.h): a second pipeline of the
// same specialised kernel shares the first's compiled one while keeping descriptors of its own,
// so two scenes rendered by one kernel at once each get their own image; the kernels kept are the
// most recently used.
#include "flatten/feature_set.h"
#include "gpu/compiled_kernel.h"
#include "gpu/compute_pipeline.h"
#include "pt_test_kernels_spv.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <memory>
#include <span>
#include <vector>

namespace pt::test {
namespace {

TEST(RecentKernels, KeepTheMostRecentlyUsedWithinTheirCapacity) {
    RecentKernels recent(2);
    // Null handles: nothing for their destructors to destroy.
    auto a = std::make_shared<const CompiledKernel>(VK_NULL_HANDLE);
    auto b = std::make_shared<const CompiledKernel>(VK_NULL_HANDLE);
    auto c = std::make_shared<const CompiledKernel>(VK_NULL_HANDLE);
    recent.keep(1, a);
    recent.keep(2, b);
    EXPECT_EQ(recent.find(1), a); // now the most recent: 2 is the one to forget next
    recent.keep(3, c);
    EXPECT_EQ(recent.size(), 2u);
    EXPECT_EQ(recent.find(2), nullptr);
    EXPECT_EQ(recent.find(1), a);
    EXPECT_EQ(recent.find(3), c);
    auto c2 = std::make_shared<const CompiledKernel>(VK_NULL_HANDLE);
    recent.keep(3, c2); // the same key again replaces, not duplicates
    EXPECT_EQ(recent.size(), 2u);
    EXPECT_EQ(recent.find(3), c2);
    EXPECT_EQ(recent.find(1), a);
}

using CompiledKernels = GpuTest;

TEST_F(CompiledKernels, TwoScenesOfOneKernelRenderedAtOnceEachGetTheirOwnImage) {
    const Scene a = loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    // Other materials and one box moved: the same kernel, other buffers (the tree and the
    // triangles through texel views of their own, the materials through their addresses).
    Scene b = a;
    for (Material& m : b.materials) m.baseColor *= 0.6f;
    ASSERT_GT(b.meshes.size(), 1u);
    for (glm::vec3& p : b.meshes.back().positions) p += glm::vec3(0.05f, 0.0f, 0.0f);
    IntegratorSettings s;
    s.texelLoads = true;
    const FlatScene flatA = flattenScene(a), flatB = flattenScene(b);
    const FeatureSet features = computeFeatures(flatA, s);
    ASSERT_EQ(features.constants(8, 8), computeFeatures(flatB, s).constants(8, 8)) << "one kernel for both";
    const Camera& camera = a.cameras.at(0);
    const FilmSettings film{32, 32, a.background};
    constexpr uint32_t kSpp = 4;

    auto alone = [&](const FlatScene& flat) {
        Renderer r(sharedContext(), flat, features, s, camera, film);
        r.addSamples(kSpp);
        return r.read();
    };
    const Renderer::Readback soloA = alone(flatA), soloB = alone(flatB);
    EXPECT_NE(soloA.mean.rgba, soloB.mean.rgba) << "the two scenes differ";

    Renderer first(sharedContext(), flatA, features, s, camera, film);
    Renderer second(sharedContext(), flatB, features, s, camera, film);
    EXPECT_STREQ(first.pipelineSource(), "reused") << "compiled for the solo renders";
    EXPECT_STREQ(second.pipelineSource(), "reused");
    for (uint32_t k = 0; k < kSpp; k += 2) { // passes of each in turn
        first.addSamples(2);
        second.addSamples(2);
    }
    EXPECT_EQ(first.read().mean.rgba, soloA.mean.rgba);
    EXPECT_EQ(second.read().mean.rgba, soloB.mean.rgba);
}

// Pipelines of one kernel share its compiled pipeline; other constants make another (all three
// alive at once, so their handles tell them apart).
TEST_F(CompiledKernels, TheSameConstantsShareACompiledPipelineAndOthersMakeTheirOwn) {
    auto create = [](uint32_t mode) {
        std::vector<SpecializationConstant> constants = FeatureSet::all(IntegratorSettings{}).constants(8, 8);
        constants.push_back({TEST_MODE_CONSTANT_ID, mode});
        return std::make_unique<ComputePipeline>(sharedContext(), std::span<const uint32_t>(pt_test_kernels_spv),
            static_cast<uint32_t>(sizeof(gpu::GpuTestPush)), constants, "test kernels");
    };
    const auto first = create(TEST_MODE_COSINE_HEMISPHERE);
    const auto second = create(TEST_MODE_COSINE_HEMISPHERE);
    const auto other = create(TEST_MODE_UNIFORM_HEMISPHERE);
    EXPECT_TRUE(second->compiledBefore());
    EXPECT_EQ(second->handle(), first->handle());
    EXPECT_EQ(second->layout(), first->layout());
    EXPECT_NE(other->handle(), first->handle());
}

} // namespace
} // namespace pt::test
