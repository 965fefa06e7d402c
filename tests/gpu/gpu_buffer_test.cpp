// GpuBuffer's staging path (device-local memory without host access, as on discrete GPUs):
// chunked through one bounded staging buffer. Lavapipe's memory is all host-visible, so the tests
// force the path (setStagingPolicyForTests) with small chunks, byte-exact and in a whole render.
#include "gpu/gpu_buffer.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <random>

namespace pt::test {
namespace {

class StagedBuffers : public GpuTest {
protected:
    void TearDown() override {
        setStagingPolicyForTests({});
        GpuTest::TearDown();
    }
};

TEST_F(StagedBuffers, UploadsAndDownloadsGoThroughChunksByteForByte) {
    setStagingPolicyForTests({true, 1000}); // chunks that do not divide the sizes below
    GpuBuffer buffer(sharedContext(), 10007, "staged");
    std::vector<unsigned char> data(10007), back(10007);
    std::mt19937 rng(3);
    for (auto& b : data) b = static_cast<unsigned char>(rng());
    buffer.upload(data.data(), data.size());
    buffer.download(back.data(), back.size());
    EXPECT_EQ(data, back);
    // A part at an offset, across chunk boundaries.
    std::vector<unsigned char> part(2500, 0xab);
    buffer.upload(part.data(), part.size(), 1234);
    std::copy(part.begin(), part.end(), data.begin() + 1234);
    std::vector<unsigned char> window(3001);
    buffer.download(window.data(), window.size(), 999);
    EXPECT_TRUE(std::equal(window.begin(), window.end(), data.begin() + 999));
}

TEST_F(StagedBuffers, ARenderThroughStagingIsBitIdentical) {
    const Scene scene = loadGltfFile(testDataDir() / "references" / "cbox-glass-mirror" / "scene.gltf");
    IntegratorSettings s;
    s.maxDepth = 16;
    const auto direct = renderScene(scene, s, scene.cameras.at(0), 24, 20, 4);
    setStagingPolicyForTests({true, 4096});
    const auto staged = renderScene(scene, s, scene.cameras.at(0), 24, 20, 4);
    EXPECT_EQ(direct.mean.rgba, staged.mean.rgba);
    EXPECT_EQ(direct.varianceOfMean.rgba, staged.varianceOfMean.rgba);
}

} // namespace
} // namespace pt::test
