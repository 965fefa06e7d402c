// Khronos glTF sample models (tests/data/gltf_samples/README.md): every extension and texture
// setting they use is modelled, so each loads without a "not supported" note, and renders under a
// white sky with no dropped (non-finite) samples and a non-black image.
#include "support/gpu_test_support.h"

#include "scene/scene_loader.h"

namespace pt::test {
namespace {

class GltfSamples : public GpuTest, public ::testing::WithParamInterface<const char*> {};

// The camera a scene without one gets from `pt render`: looking down -z at the scene's box.
Camera framingCamera(const FlatScene& flat) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& t : flat.triangles)
        for (const glm::vec3& p : {t.p0, t.p1, t.p2}) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo);
    Camera c;
    c.yfov = 0.8f;
    c.position = centre + glm::vec3(0, 0, radius / std::tan(0.4f) + radius);
    return c;
}

TEST_P(GltfSamples, LoadsWithoutWarningsAndRendersFinite) {
    const std::string model = GetParam();
    const auto dir = testDataDir() / "data" / "gltf_samples" / model / "glTF";
    Scene scene = loadScene(dir / (model + ".gltf"));
    EXPECT_TRUE(scene.unsupported.empty()) << model << ": " << ::testing::PrintToString(scene.unsupported);
    Environment sky;
    sky.colour = glm::vec3(1.0f);
    scene.environment = sky;
    const FlatScene flat = flattenScene(scene);
    const Camera camera = scene.cameras.empty() ? framingCamera(flat) : scene.cameras[0];
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, camera, 32, 32, 4);
    EXPECT_EQ(r.droppedSamples, 0u) << model;
    double sum = 0;
    for (float v : r.mean.rgba) sum += v;
    EXPECT_GT(sum, 0.0) << model << " rendered black";
}

INSTANTIATE_TEST_SUITE_P(Khronos, GltfSamples,
    ::testing::Values("TextureTransformTest", "TextureCoordinateTest", "TextureSettingsTest", "EmissiveStrengthTest",
        "SpecularTest", "TransmissionRoughnessTest"));

} // namespace
} // namespace pt::test
