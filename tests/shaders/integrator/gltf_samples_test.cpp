// Khronos glTF sample models (tests/data/gltf_samples/README.md): every extension and texture
// setting they use is modelled, so each loads without a "not supported" note, and renders under a
// white sky with no dropped (non-finite) samples and a non-black image.
#include "support/gpu_test_support.h"

#include "app/scene_setup.h"
#include "scene/scene_loader.h"

namespace pt::test {
namespace {

class GltfSamples : public GpuTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(GltfSamples, LoadsWithoutWarningsAndRendersFinite) {
    const std::string model = GetParam();
    const auto dir = testDataDir() / "data" / "gltf_samples" / model / "glTF";
    Scene scene = loadScene(dir / (model + ".gltf"));
    EXPECT_TRUE(scene.unsupported.empty()) << model << ": " << ::testing::PrintToString(scene.unsupported);
    Environment sky;
    sky.colour = glm::vec3(1.0f);
    scene.environment = sky;
    // The camera a scene without one gets from `pt render`.
    const Camera camera = scene.cameras.empty() ? framingCamera(scene, 1.0f) : scene.cameras[0];
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, camera, 32, 32, 4);
    EXPECT_EQ(r.droppedSamples, 0u) << model;
    double sum = 0;
    for (float v : r.mean.rgba) sum += v;
    EXPECT_GT(sum, 0.0) << model << " rendered black";
}

INSTANTIATE_TEST_SUITE_P(Khronos, GltfSamples,
    ::testing::Values("TextureTransformTest", "TextureCoordinateTest", "TextureSettingsTest", "EmissiveStrengthTest",
        "SpecularTest", "TransmissionRoughnessTest", "ClearCoatTest", "IridescenceSuzanne", "AnisotropyStrengthTest"));

} // namespace
} // namespace pt::test
