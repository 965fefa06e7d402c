// The trees, the triangles and the spheres read through texel buffers (TEXEL_LOADS): taken on
// lavapipe wherever there is a tree, and the image is the one the buffer-address loads give, bit
// for bit, with float nodes and with quantised ones, with spheres too.
#include "flatten/feature_set.h"
#include "scene/gltf/gltf_loader.h"
#include "gpu/texel_view.h"
#include "support/gpu_test_support.h"

#include <limits>

namespace pt::test {
namespace {

class TexelLoads : public GpuTest {};

// The diffuse box with a subdivided sphere in it (1,280 triangles more), through the tree.
Scene boxWithSphere() {
    Scene box = loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    box.meshes.push_back(makeIcosphere(3, glm::vec3(0.2f, -0.5f, 0.1f), 0.3f, 0));
    return box;
}

Renderer::Readback render(const Scene& scene, IntegratorSettings s, bool texels, bool quantized, uint32_t seed) {
    s.texelLoads = texels;
    s.seed = seed;
    BvhBuildOptions bvh;
    bvh.quantizeOverBytes = quantized ? 0 : std::numeric_limits<size_t>::max();
    FlatScene flat = flattenScene(scene, bvh);
    EXPECT_EQ(flat.quantizedNodes.empty(), !quantized);
    Renderer renderer(sharedContext(), flat, computeFeatures(flat, s), s, scene.cameras.at(0),
        FilmSettings{40, 40, scene.background});
    EXPECT_EQ(renderer.features().texelLoads, texels); // lavapipe is a CPU device: taken where asked
    renderer.addSamples(8, 0);
    return renderer.read();
}

TEST_F(TexelLoads, TheSameImageAsBufferAddressesWithEitherNodeFormat) {
    const Scene scene = boxWithSphere();
    IntegratorSettings s;
    for (bool quantized : {false, true}) {
        const Renderer::Readback texels = render(scene, s, true, quantized, 3);
        const Renderer::Readback addresses = render(scene, s, false, quantized, 3);
        EXPECT_EQ(texels.mean.rgba, addresses.mean.rgba) << (quantized ? "quantised nodes" : "float nodes");
        // The comparison can tell images apart: another seed differs.
        EXPECT_NE(texels.mean.rgba, render(scene, s, true, quantized, 4).mean.rgba);
    }
}

TEST_F(TexelLoads, DecidedByTheTreeAndTheSwitch) {
    const FlatScene flat = flattenScene(boxWithSphere());
    IntegratorSettings s;
    EXPECT_TRUE(computeFeatures(flat, s).texelLoads);
    s.texelLoads = false;
    EXPECT_FALSE(computeFeatures(flat, s).texelLoads);
    // A tiny scene traced without its tree (--bvh auto: all-triangles) reads no nodes, and its
    // triangles at hits only: no texels there.
    const FlatScene box = flattenScene(loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf"));
    EXPECT_TRUE(computeFeatures(box, IntegratorSettings{}).texelLoads);
    IntegratorSettings noTree;
    noTree.alwaysTree = false;
    EXPECT_FALSE(computeFeatures(box, noTree).texelLoads);
    // Spheres alone have their own tree, read the same way.
    Scene spheres;
    spheres.materials.push_back(Material{});
    spheres.spheres.push_back(Sphere{});
    EXPECT_TRUE(computeFeatures(flattenScene(spheres), IntegratorSettings{}).texelLoads);
    // With --bvh auto a tiny scene's triangles skip their tree, but its spheres still have one.
    Scene both = loadGltfFile(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    both.spheres.push_back(Sphere{});
    EXPECT_TRUE(computeFeatures(flattenScene(both), noTree).texelLoads);
}

// A box with ellipsoids (the sphere tree and the spheres through texel buffers too): the same
// image as through buffer addresses, bit for bit.
TEST_F(TexelLoads, SpheresGiveTheSameImageAsBufferAddresses) {
    Scene scene = boxWithSphere();
    for (int i = 0; i < 12; ++i) {
        Sphere s;
        s.objectToWorld = glm::mat4(glm::vec4(0.08f + 0.01f * i, 0, 0, 0), glm::vec4(0, 0.1f, 0, 0),
            glm::vec4(0, 0, 0.12f, 0), glm::vec4(-0.6f + 0.1f * i, -0.8f + 0.05f * i, -0.2f, 1));
        s.material = 0;
        scene.spheres.push_back(s);
    }
    IntegratorSettings s;
    const Renderer::Readback texels = render(scene, s, true, false, 3);
    const Renderer::Readback addresses = render(scene, s, false, false, 3);
    EXPECT_EQ(texels.mean.rgba, addresses.mean.rgba);
    EXPECT_NE(texels.mean.rgba, render(scene, s, true, false, 4).mean.rgba);
}

// A view must be whole 16-byte texels within the device's limit; past it the scene keeps its
// address loads (GpuScene makes no views, and the renderer turns the feature off).
TEST_F(TexelLoads, ViewsFitTheDevicesLimitInWholeTexels) {
    VulkanContext& ctx = sharedContext();
    const VkDeviceSize limit = ctx.properties().limits.maxTexelBufferElements;
    EXPECT_TRUE(TexelView::fits(ctx, 16));
    EXPECT_TRUE(TexelView::fits(ctx, limit * 16));
    EXPECT_FALSE(TexelView::fits(ctx, (limit + 1) * 16));
    EXPECT_FALSE(TexelView::fits(ctx, 24)); // not whole texels
    GpuBuffer buffer(ctx, 64, "texel view test");
    EXPECT_THROW(TexelView(ctx, buffer, 128, "a view past its buffer"), std::runtime_error);
    EXPECT_NE(TexelView(ctx, buffer, 64, "a view of the whole buffer").handle(), VK_NULL_HANDLE);
}

} // namespace
} // namespace pt::test
