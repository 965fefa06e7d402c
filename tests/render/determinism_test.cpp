// Reproducibility: the image is a function of (scene, seed, sample count) only, not of how the
// samples were split into dispatches or tiles.
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

namespace pt::test {
namespace {

class Determinism : public GpuTest {
protected:
    Renderer::Readback render(uint32_t seed, uint32_t passSpp, uint32_t tile) {
        Scene scene = loadGltfFile(testDataDir() / "references" / "cbox-glass-mirror" / "scene.gltf");
        IntegratorSettings s;
        s.seed = seed;
        s.maxDepth = 32;
        return renderScene(scene, s, scene.cameras.at(0), 40, 36, 12, passSpp, tile);
    }
};

TEST_F(Determinism, SameSeedSameImage) {
    auto a = render(3, 12, 0);
    auto b = render(3, 12, 0);
    EXPECT_EQ(a.mean.rgba, b.mean.rgba);
}

TEST_F(Determinism, ChunkingDoesNotChangeTheImage) {
    auto whole = render(3, 12, 0);
    auto passes = render(3, 5, 0); // 5 + 5 + 2 samples
    auto tiles = render(3, 1, 7);  // 12 passes of 1 sample, 7x7-pixel tiles
    EXPECT_EQ(whole.mean.rgba, passes.mean.rgba);
    EXPECT_EQ(whole.mean.rgba, tiles.mean.rgba);
    EXPECT_EQ(whole.varianceOfMean.rgba, tiles.varianceOfMean.rgba);
}

// A renderer given the flattened scene to keep (FlatScene&&) frees its big host arrays as they
// are uploaded, and renders the same image as one that only reads it.
TEST_F(Determinism, ARendererThatConsumesTheSceneRendersTheSameImage) {
    const Scene scene = loadGltfFile(testDataDir() / "references" / "cbox-glass-mirror" / "scene.gltf");
    IntegratorSettings s;
    s.maxDepth = 32;
    FlatScene flat = flattenScene(scene);
    const FeatureSet features = computeFeatures(flat, s);
    const FilmSettings film{40, 36, scene.background};
    Renderer reading(sharedContext(), flat, features, s, scene.cameras.at(0), film);
    reading.addSamples(6);
    ASSERT_FALSE(flat.triangles.empty());
    Renderer consuming(sharedContext(), std::move(flat), features, s, scene.cameras.at(0), film);
    consuming.addSamples(6);
    EXPECT_TRUE(flat.triangles.empty() && flat.shading.empty() && flat.nodes.empty()); // NOLINT: freed, not moved
    EXPECT_EQ(flat.triangles.capacity(), 0u);
    EXPECT_EQ(reading.read().mean.rgba, consuming.read().mean.rgba);
}

TEST_F(Determinism, DifferentSeedDifferentImage) {
    auto a = render(3, 12, 0);
    auto b = render(4, 12, 0);
    EXPECT_NE(a.mean.rgba, b.mean.rgba);
}

} // namespace
} // namespace pt::test
