// The accumulation state: double-float sums keep a constant-radiance image exactly constant at
// 1e5 samples per pixel (float32 sums drift by ~1e-3 there), and the state can be read,
// reloaded and continued, or rendered as disjoint sample ranges and merged, matching a single
// uninterrupted render.
#include "scene/default_scene.h"
#include "support/gpu_test_support.h"

#include <cmath>
#include <cstdio>

namespace pt::test {
namespace {

constexpr uint32_t kManySamples = 100000;

Renderer::Readback renderInPasses(
    const Scene& scene, const IntegratorSettings& s, const Camera& camera, uint32_t spp, uint32_t pass) {
    return renderScene(scene, s, camera, 4, 4, spp, pass);
}

void expectConstant(const Renderer::Readback& r, float expected, const char* what) {
    EXPECT_EQ(r.droppedSamples, 0u) << what;
    double worst = 0;
    for (size_t i = 0; i < r.mean.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        worst = std::max(worst, std::abs(double(r.mean.rgba[i]) / expected - 1.0));
        // A constant has no variance; float32 sums of squares would report ~1e-3 * L^2 here.
        EXPECT_LT(r.varianceOfMean.rgba[i], 1e-12) << what << " pixel " << i / 4;
    }
    std::printf("%s at %u spp: worst relative error over the pixels %.3g\n", what, kManySamples, worst);
    EXPECT_LT(worst, 1e-6) << what << ": worst relative error over the pixels";
}

class Accumulation : public GpuTest {};

TEST_F(Accumulation, PlainFloatSumsWouldDrift) {
    // Why the kernel keeps double-floats: this is what a float32 running sum does.
    float sum = 0.0f;
    for (uint32_t i = 0; i < kManySamples; ++i) sum += 0.3f;
    const double drift = std::abs(double(sum) / kManySamples / double(0.3f) - 1.0);
    std::printf("float32 running sum of %u x 0.3f: relative error %.3g\n", kManySamples, drift);
    EXPECT_GT(drift, 1e-4);
}

TEST_F(Accumulation, EmitterSeenDirectlyStaysConstantAtOneHundredThousandSamples) {
    Scene scene;
    Material m;
    m.baseColor = glm::vec3(0.0f);
    m.emission = glm::vec3(0.3f); // not a power of two: every add of it rounds
    m.doubleSided = true;
    scene.materials.push_back(m);
    scene.meshes.push_back(makeIcosphere(1, glm::vec3(0.0f), 1.0f, 0));
    IntegratorSettings s;
    s.maxDepth = 1; // emitters seen directly: every sample is exactly 0.3f
    Camera camera;
    camera.yfov = 1.0f;
    expectConstant(renderInPasses(scene, s, camera, kManySamples, 25000), 0.3f, "emitter 0.3");
}

TEST_F(Accumulation, WhiteFurnaceStaysConstantAtOneHundredThousandSamples) {
    Scene scene;
    Material white;
    white.baseColor = glm::vec3(1.0f);
    scene.materials.push_back(white);
    scene.spheres.push_back(Sphere{});
    Environment sky;
    sky.colour = glm::vec3(0.7f);
    scene.environment = sky;
    IntegratorSettings s;
    s.nee = false; // BSDF sampling only: each path carries exactly albedo 1 out to the sky
    s.mis = false;
    s.rr = false;
    s.maxDepth = 16;
    Camera camera;
    camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
    camera.yfov = 0.8f; // the sphere fills the middle, the corners see the sky
    expectConstant(renderInPasses(scene, s, camera, kManySamples, 50000), 0.7f, "furnace 0.7");
}

// The built-in Cornell box at a small size.
class StateRoundTrip : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        scene_ = loadGltfScene();
        flat_ = flattenScene(scene_);
        settings_.seed = 7;
        settings_.maxDepth = 8;
    }
    static Scene loadGltfScene() {
        return loadDefaultScene(); // the diffuse Cornell box: a small kernel, quick to build
    }
    std::unique_ptr<Renderer> makeRenderer() {
        return std::make_unique<Renderer>(sharedContext(), flat_, suiteFeatures(flat_, settings_), settings_,
            scene_.cameras.at(0), FilmSettings{24, 20, scene_.background});
    }
    Scene scene_;
    FlatScene flat_;
    IntegratorSettings settings_;
};

// One renderer throughout (a pipeline costs seconds on lavapipe): reset() between renders.
TEST_F(StateRoundTrip, ReloadedStateContinuesBitIdentically) {
    auto renderer = makeRenderer();
    renderer->addSamples(9);
    const AccumulationState saved = renderer->readState();
    renderer->addSamples(8);
    const AccumulationState whole = renderer->readState();
    renderer->reset();
    renderer->loadState(saved);
    EXPECT_EQ(renderer->samplesPerPixel(), 9u);
    renderer->addSamples(8);
    EXPECT_EQ(renderer->readState().sums, whole.sums);
    EXPECT_EQ(renderer->read().mean.rgba, resolve(whole).mean.rgba);
}

TEST_F(StateRoundTrip, MergedPartitionMatchesTheSingleRender) {
    auto renderer = makeRenderer();
    renderer->addSamples(17);
    const auto single = renderer->read().mean.rgba;
    std::vector<AccumulationState> parts;
    for (SampleRange range : {SampleRange{0, 5}, SampleRange{5, 6}, SampleRange{6, 17}}) {
        renderer->reset();
        renderer->setFirstSample(range.begin);
        renderer->addSamples(range.count());
        parts.push_back(renderer->readState());
        EXPECT_EQ(parts.back().samples.begin, range.begin);
    }
    const AccumulationState merged = mergeStates(parts);
    EXPECT_EQ(merged.spp, 17u);
    const auto a = resolve(merged).mean.rgba;
    ASSERT_EQ(a.size(), single.size());
    // Equal up to the final rounding to float: both sums are within n * 2^-48 (relative) of the
    // exact sum (double-float parts added in double), so a mean differs by at most one ulp.
    size_t identical = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        identical += a[i] == single[i];
        EXPECT_LE(std::abs(a[i] - single[i]), std::abs(single[i]) * 1.2e-7f) << "value " << i;
    }
    EXPECT_GT(identical, a.size() * 9 / 10);
}

} // namespace
} // namespace pt::test
