// Light tracing of caustics (shaders/integrator/light_tracer.glsl) against BSDF sampling alone:
// the two split the same paths differently, so they must render the same image. The glass
// Cornell box (triangle light, meshes with shading normals) is in switch_agreement_test.cpp;
// this covers analytic spheres: an ellipsoidal sphere light, glass, a mirror, a gold conductor,
// and a receiver whose BRDF is not reciprocal (the course's Original Phong).
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "film/metrics.h"
#include "scene/gltf/gltf_loader.h"
#include "scene/scene_loader.h"
#include "support/gpu_test_support.h"

#include <cstdio>

namespace pt::test {
namespace {

std::filesystem::path causticsScene() {
    return std::filesystem::path(PT_TEST_DATA_DIR).parent_path() / "scenes" / "caustics" /
           "ellipsoid-light-caustics.xml";
}

AgreementResult agreement(const Renderer::Readback& a, const Renderer::Readback& b) {
    return compareBlocks(blockStats(a.mean, &a.varianceOfMean, 8), blockStats(b.mean, &b.varianceOfMean, 8));
}

// The same image two ways, 48x48: with light tracing at 256 spp, and by BSDF sampling alone at
// 8x the samples (at equal spp most caustic blocks have not yet seen their rare bright paths and
// their variance estimate is too small; see switch_agreement_test.cpp), with their agreement.
struct TracedAndSampled {
    Renderer::Readback traced, sampled;
    AgreementResult agreement;
};

TracedAndSampled traceAndSample(const Scene& scene, IntegratorSettings s, const Camera& camera) {
    TracedAndSampled r;
    s.seed = 1000;
    r.traced = renderScene(scene, s, camera, 48, 48, 256);
    s.lightTracing = false;
    s.seed = 1;
    r.sampled = renderScene(scene, s, camera, 48, 48, 2048);
    r.agreement = agreement(r.traced, r.sampled);
    return r;
}

class LightTracing : public GpuTest {};

TEST_F(LightTracing, SphereLightCausticsAgreeWithBsdfSampling) {
    const Scene scene = loadScene(causticsScene());
    IntegratorSettings s = independentSettings();
    s.maxDepth = 8;
    ASSERT_TRUE(computeFeatures(flattenScene(scene), s).lightTracing);
    const Camera& camera = scene.cameras.at(0);
    const TracedAndSampled both = traceAndSample(scene, s, camera);
    const auto& traced = both.traced;
    EXPECT_EQ(traced.droppedSamples, 0u);
    const AgreementResult& r = both.agreement;
    std::printf("[          ] light traced vs BSDF sampled: chi2/dof %.3f, mean z %+.3f, max |z| %.2f\n", r.chi2PerDof,
        r.meanZ, r.maxAbsZ);
    EXPECT_LT(r.chi2PerDof, 1.6);
    EXPECT_LT(std::abs(r.meanZ), 0.5);

    // The control: without the caustics (direct light only, depth 2) the same comparison fails.
    IntegratorSettings direct = s;
    direct.lightTracing = false;
    direct.seed = 1;
    direct.maxDepth = 2;
    const auto noCaustics = renderScene(scene, direct, camera, 48, 48, 256);
    const AgreementResult control = agreement(traced, noCaustics);
    std::printf("[          ] light traced vs direct light only: chi2/dof %.1f\n", control.chi2PerDof);
    EXPECT_GT(control.chi2PerDof, 10.0);
}

// The glTF metal (a GGX-rough Schlick mirror since the loader reduces metallic 1 to it) receives
// caustics like any rough conductor: the glass box with its mirror block made rough gold,
// light tracing on against BSDF sampling alone.
TEST_F(LightTracing, RoughGltfMetalReceivesCausticsAsBsdfSamplingDoes) {
    Scene scene = loadGltfFile(testDataDir() / "references" / "cbox-glass-mirror" / "scene.gltf");
    size_t mirrors = 0;
    for (Material& m : scene.materials)
        if (m.type == MaterialType::Mirror) {
            m.roughness = 0.4f;
            m.baseColor = glm::vec3(1.0f, 0.78f, 0.34f);
            ++mirrors;
        }
    ASSERT_GT(mirrors, 0u);
    IntegratorSettings s = independentSettings();
    s.maxDepth = 12;
    ASSERT_TRUE(computeFeatures(flattenScene(scene), s).lightTracing) << "the glass still makes caustics";
    const AgreementResult r = traceAndSample(scene, s, scene.cameras.at(0)).agreement;
    std::printf("[          ] rough gold receiving: light traced vs BSDF sampled: chi2/dof %.3f, mean z %+.3f\n",
        r.chi2PerDof, r.meanZ);
    EXPECT_LT(r.chi2PerDof, 1.6);
    EXPECT_LT(std::abs(r.meanZ), 0.5);
}

TEST_F(LightTracing, UsedOnlyWhereTheSceneHasCausticsItModels) {
    IntegratorSettings s = independentSettings();
    const auto features = [&](const std::filesystem::path& path) {
        return computeFeatures(flattenScene(loadScene(path)), s);
    };
    const std::filesystem::path refs = testDataDir() / "references";
    EXPECT_TRUE(features(refs / "cbox-glass-mirror" / "scene.gltf").lightTracing);
    EXPECT_FALSE(features(refs / "cbox-diffuse" / "scene.gltf").lightTracing) << "no specular surface";
    // Its glass absorbs (AbsorptionCoefficient), which light paths do not model.
    EXPECT_FALSE(features(testDataDir() / "data" / "ceng795" / "cornellbox_jaroslav_path_glass.xml").lightTracing);
    s.lightTracing = false;
    EXPECT_FALSE(features(refs / "cbox-glass-mirror" / "scene.gltf").lightTracing) << "--light-tracing off";
    s.lightTracing = true;
    s.classic = true;
    EXPECT_FALSE(features(refs / "cbox-glass-mirror" / "scene.gltf").lightTracing) << "classic ray tracer";
}

} // namespace
} // namespace pt::test
