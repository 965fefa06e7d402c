// Tiny scenes without a tree (UNIFORM_TRIANGLE_COUNT, shaders/geometry/traverse.glsl; `--bvh auto`,
// no longer the default): which scenes take it, and that it finds the very hits the tree finds, so the images are the same bit
// for bit, in the Cornell box and in the sealed room at scale 1000, whose 0.1-thick lid is a
// sliver far from most rays, where rounding makes false hits that only a box test stops.
#include "flatten/feature_set.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"
#include "support/hard_case_support.h"

namespace pt::test {
namespace {

class UniformTriangles : public GpuTest {};

FeatureSet featuresOf(const Scene& scene, const IntegratorSettings& s) {
    return computeFeatures(flattenScene(scene), s);
}

TEST_F(UniformTriangles, TakenByScenesOfAtMost48TrianglesWithoutInstances) {
    const Scene box = loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    IntegratorSettings s;
    EXPECT_EQ(featuresOf(box, s).uniformTriangles, 0u); // the tree, unless asked (--bvh auto)
    s.alwaysTree = false;
    EXPECT_EQ(featuresOf(box, s).uniformTriangles, 32u);
    IntegratorSettings tree = s;
    tree.alwaysTree = true;
    EXPECT_EQ(featuresOf(box, tree).uniformTriangles, 0u);

    // The box plus a quad, split until it has UNIFORM_TRIANGLES_MAX triangles, and one more.
    Scene bigger = box;
    Mesh extra = makeQuad(glm::vec3(-0.2f, -0.9f, -0.2f), glm::vec3(0.1f, 0, 0), glm::vec3(0, 0, 0.1f), 0);
    bigger.meshes.push_back(extra);
    while (flattenScene(bigger).triangles.size() < UNIFORM_TRIANGLES_MAX) bigger.meshes.push_back(extra);
    ASSERT_EQ(flattenScene(bigger).triangles.size(), UNIFORM_TRIANGLES_MAX);
    EXPECT_EQ(featuresOf(bigger, s).uniformTriangles, UNIFORM_TRIANGLES_MAX);
    Mesh single = extra;
    single.triangles.resize(1);
    bigger.meshes.push_back(single);
    EXPECT_EQ(featuresOf(bigger, s).uniformTriangles, 0u);
}

// The same image with the tree and without, where every ray is traced by both.
void expectTheSameImageAsTheTree(const Scene& scene, IntegratorSettings s, uint32_t spp, const char* what) {
    s.alwaysTree = false;
    const FeatureSet without = featuresOf(scene, s);
    ASSERT_GT(without.uniformTriangles, 0u) << what;
    s.alwaysTree = true;
    const FeatureSet with = featuresOf(scene, s);
    ASSERT_EQ(with.uniformTriangles, 0u) << what;
    const Renderer::Readback a = renderSceneWith(scene, s, without, scene.cameras.at(0), 40, 40, spp);
    const Renderer::Readback b = renderSceneWith(scene, s, with, scene.cameras.at(0), 40, 40, spp);
    EXPECT_EQ(a.mean.rgba, b.mean.rgba) << what;
    // The comparison can tell images apart: another seed differs.
    s.seed += 1;
    const Renderer::Readback c = renderSceneWith(scene, s, with, scene.cameras.at(0), 40, 40, spp);
    EXPECT_NE(a.mean.rgba, c.mean.rgba) << what;
}

TEST_F(UniformTriangles, FindTheHitsTheTreeFindsInTheCornellBox) {
    const Scene box = loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    expectTheSameImageAsTheTree(box, IntegratorSettings{}, 16, "cbox-diffuse");
}

TEST_F(UniformTriangles, FindTheHitsTheTreeFindsInASealedRoomAtScale1000) {
    IntegratorSettings s = independentSettings();
    s.maxDepth = 8;
    s.estimator = Estimator::Path;
    Scene room = loadHardScene("sealed-room-scale-1e3.gltf", s);
    Environment sky;
    sky.colour = glm::vec3(10.0f);
    room.environment = sky;
    // A lamp inside too (the one above the lid stays): the room is lit, and a ray let through
    // the walls would add the sky's light.
    ASSERT_EQ(room.punctualLights.size(), 1u);
    PunctualLight inside = room.punctualLights[0];
    inside.position = glm::vec3(0.3f, 0.5f, 0.2f) * 1e3f;
    room.punctualLights.push_back(inside);
    expectTheSameImageAsTheTree(room, s, 16, "sealed room at scale 1000");
}

} // namespace
} // namespace pt::test
