// Bidirectional path tracing (shaders/integrator/bdpt.glsl) against path tracing, an independent
// estimator of the same image: block z-tests on scenes with every kind of light and material.
// Then each strategy alone, unweighted: for one path length every strategy must render the same
// image, which checks each one's throughput, sampling densities and adjoint BSDF; the MIS
// weights are checked by the agreement with path tracing (weights that do not sum to one over
// the strategies bias the image). And the image is the same however the samples are split.
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "film/metrics.h"
#include "render/light_visibility_probe.h"
#include "scene/scene_loader.h"
#include "support/gpu_test_support.h"

#include <cstdio>
#include <cstring>

namespace pt::test {
namespace {

std::filesystem::path repoDir() { return std::filesystem::path(PT_TEST_DATA_DIR).parent_path(); }
std::filesystem::path diffuseBox() { return testDataDir() / "references" / "cbox-diffuse" / "scene.gltf"; }

AgreementResult agreement(const Renderer::Readback& a, const Renderer::Readback& b, int block = 8) {
    return compareBlocks(blockStats(a.mean, &a.varianceOfMean, block), blockStats(b.mean, &b.varianceOfMean, block));
}

IntegratorSettings bdptSettings(uint32_t maxDepth) {
    IntegratorSettings s = independentSettings();
    s.estimator = Estimator::Bidirectional;
    s.maxDepth = maxDepth;
    return s;
}

// The scene rendered by BDPT and by path tracing (light tracing of caustics where the scene has
// them) with other seeds, and how well the two agree.
AgreementResult bdptAgainstPath(const char* what, const Scene& scene, uint32_t maxDepth, int width, int height,
    uint32_t bdptSpp, uint32_t pathSpp) {
    IntegratorSettings s = bdptSettings(maxDepth);
    s.seed = 1000;
    const FeatureSet f = computeFeatures(flattenScene(scene), s);
    EXPECT_TRUE(f.bdpt) << what << ": " << f.describe();
    const Camera& camera = scene.cameras.at(0);
    const Renderer::Readback bdpt = renderScene(scene, s, camera, width, height, bdptSpp);
    s.estimator = Estimator::Path;
    s.seed = 1;
    const Renderer::Readback path = renderScene(scene, s, camera, width, height, pathSpp);
    EXPECT_EQ(bdpt.droppedSamples, 0u) << what;
    const AgreementResult r = agreement(bdpt, path);
    std::printf("[          ] %s: bdpt vs path: chi2/dof %.3f, mean z %+.3f, max |z| %.2f, mean rel diff %.4f\n", what,
        r.chi2PerDof, r.meanZ, r.maxAbsZ, r.meanRelDiff);
    return r;
}

void expectAgreement(const AgreementResult& r) {
    EXPECT_LT(r.chi2PerDof, 1.6);
    EXPECT_LT(std::abs(r.meanZ), 0.5);
}

class Bdpt : public GpuTest {};

TEST_F(Bdpt, AgreesWithPathTracingInTheDiffuseCornellBox) {
    expectAgreement(bdptAgainstPath("diffuse box", loadScene(diffuseBox()), 6, 32, 32, 256, 1024));
}

// Glass, a mirror and a gold conductor lit by an ellipsoidal sphere light, in front of the
// course's Original Phong BRDF (not reciprocal: light subpaths must use the adjoint).
TEST_F(Bdpt, AgreesWithPathTracingThroughGlassMirrorsAndANonReciprocalBrdf) {
    const Scene scene = loadScene(repoDir() / "scenes" / "caustics" / "ellipsoid-light-caustics.xml");
    expectAgreement(bdptAgainstPath("sphere light caustics", scene, 8, 48, 48, 512, 1024));
}

// Lights a camera path cannot hit (point, spot, the course's square) or no light subpath starts
// from (directional, the sky), with the box's own triangle light; one wall rough gold, one
// the course's glossy BRDF, so non-Lambertian densities enter the weights.
TEST_F(Bdpt, AgreesWithPathTracingUnderEveryKindOfLight) {
    Scene scene = loadScene(diffuseBox());
    size_t changed = 0;
    for (Material& m : scene.materials) {
        if (m.emission != glm::vec3(0.0f)) continue;
        if (changed == 0) {
            m.type = MaterialType::Mirror; // rough: the glTF metal, GGX with Schlick's Fresnel
            m.roughness = 0.5f;
            m.baseColor = glm::vec3(1.0f, 0.78f, 0.34f);
        }
        ++changed;
    }
    ASSERT_GT(changed, 1u);
    PunctualLight point;
    point.position = glm::vec3(0.3f, 1.2f, 0.2f);
    point.intensity = glm::vec3(0.3f, 0.25f, 0.2f);
    PunctualLight spot;
    spot.type = PunctualLight::Type::Spot;
    spot.position = glm::vec3(-0.5f, 1.5f, 0.5f);
    spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
    spot.intensity = glm::vec3(0.6f);
    spot.cosFalloff = std::cos(0.3f);
    spot.cosCoverage = std::cos(0.5f);
    PunctualLight square;
    square.type = PunctualLight::Type::Square;
    square.position = glm::vec3(0.6f, 0.4f, -0.6f);
    square.direction = glm::normalize(glm::vec3(-1.0f, 0.2f, 0.5f));
    square.intensity = glm::vec3(1.5f, 1.0f, 0.5f);
    square.size = 0.3f;
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(0.2f, -0.3f, -1.0f));
    sun.intensity = glm::vec3(0.5f);
    scene.punctualLights = {point, spot, square, sun};
    Environment sky;
    sky.colour = glm::vec3(0.2f, 0.3f, 0.5f);
    scene.environment = sky;
    expectAgreement(bdptAgainstPath("every kind of light", scene, 6, 32, 32, 256, 1024));
}

// An emitter inside a glass sphere under a sky (the hard case of scenes/hard): light subpaths
// start inside the glass and leave through it. The emitter is part of a uniform field there, so
// both images are nearly constant and their variance estimates nearly zero: the z-test says
// little, the difference of the means says it all.
TEST_F(Bdpt, AgreesWithPathTracingForALightInsideGlass) {
    const Scene scene = loadScene(repoDir() / "scenes" / "hard" / "light-inside-glass.xml");
    const AgreementResult r = bdptAgainstPath("light inside glass", scene, 12, 32, 32, 256, 1024);
    EXPECT_LT(r.meanRelDiff, 1e-3);
}

// Each strategy alone, unweighted, for the paths of three segments (camera, two bounces, light)
// in the box with a rough gold wall: s = 0 (hitting the light), 1 (light sampling), 2 (a
// connection), 3 (a light subpath seen by the camera) must render one image. The control: the
// paths of four segments differ from it.
TEST_F(Bdpt, EachStrategyAloneRendersTheSamePaths) {
    Scene scene = loadScene(diffuseBox());
    for (Material& m : scene.materials)
        if (m.emission == glm::vec3(0.0f)) {
            m.type = MaterialType::Mirror; // rough: the glTF metal, GGX with Schlick's Fresnel
            m.roughness = 0.5f;
            m.baseColor = glm::vec3(1.0f, 0.78f, 0.34f);
            break;
        }
    const IntegratorSettings s = bdptSettings(4);
    const FlatScene flat = flattenScene(scene);
    const Camera& camera = scene.cameras.at(0);
    const auto strategy = [&](uint32_t segments, uint32_t lightVertices, uint32_t spp) {
        FeatureSet f = computeFeatures(flat, s);
        EXPECT_TRUE(f.bdpt);
        f.bdptStrategy = BDPT_ONE_STRATEGY(segments, lightVertices);
        IntegratorSettings seeded = s;
        seeded.seed = 100 * segments + lightVertices;
        return renderSceneWith(scene, seeded, f, camera, 24, 24, spp);
    };
    const Renderer::Readback sampled = strategy(3, 1, 1024);
    const uint32_t spp[4] = {4096, 0, 4096, 1024};
    for (uint32_t lightVertices : {0u, 2u, 3u}) {
        const AgreementResult r = agreement(strategy(3, lightVertices, spp[lightVertices]), sampled, 4);
        std::printf("[          ] 3 segments, s = %u alone vs s = 1: chi2/dof %.3f, mean z %+.3f, max |z| %.2f\n",
            lightVertices, r.chi2PerDof, r.meanZ, r.maxAbsZ);
        EXPECT_LT(r.chi2PerDof, 1.6) << "s = " << lightVertices;
        EXPECT_LT(std::abs(r.meanZ), 0.5) << "s = " << lightVertices;
    }
    const AgreementResult control = agreement(strategy(4, 1, 1024), sampled, 4);
    std::printf("[          ] 4 segments vs 3: chi2/dof %.1f\n", control.chi2PerDof);
    EXPECT_GT(control.chi2PerDof, 10.0);
}

// The light subpaths' splats are integer sums and the camera paths' samples are added in sample
// order: the same image, bit for bit, in one pass or in passes of 3 spp over 16-pixel tiles.
TEST_F(Bdpt, ImageIsTheSameHoweverTheSamplesAreSplit) {
    const Scene scene = loadScene(diffuseBox());
    const IntegratorSettings s = bdptSettings(6);
    const Camera& camera = scene.cameras.at(0);
    const Renderer::Readback whole = renderScene(scene, s, camera, 40, 40, 12);
    const Renderer::Readback split = renderScene(scene, s, camera, 40, 40, 12, 3, 16);
    ASSERT_EQ(whole.mean.rgba.size(), split.mean.rgba.size());
    EXPECT_EQ(0, std::memcmp(whole.mean.rgba.data(), split.mean.rgba.data(), whole.mean.rgba.size() * sizeof(float)));
    IntegratorSettings other = s;
    other.seed = 7;
    const Renderer::Readback reseeded = renderScene(scene, other, camera, 40, 40, 12);
    EXPECT_NE(0, std::memcmp(whole.mean.rgba.data(), reseeded.mean.rgba.data(), whole.mean.rgba.size() * sizeof(float)))
        << "the comparison can tell images apart";
}

TEST_F(Bdpt, ChosenOnlyWhereItCanRenderTheScene) {
    FlatScene box = flattenScene(loadScene(diffuseBox()));
    IntegratorSettings s = bdptSettings(BDPT_MAX_LIGHT_VERTICES + 2);
    EXPECT_TRUE(computeFeatures(box, s).bdpt);
    EXPECT_FALSE(computeFeatures(box, s).lightTracing) << "BDPT subsumes the caustic light tracer";
    s.maxDepth = BDPT_MAX_LIGHT_VERTICES + 3;
    EXPECT_FALSE(computeFeatures(box, s).bdpt) << "longer paths than its light vertices reach";
    s.maxDepth = 6;
    s.classic = true;
    EXPECT_FALSE(computeFeatures(box, s).bdpt) << "the classic ray tracer";
    s.classic = false;
    s.estimator = Estimator::Path;
    EXPECT_FALSE(computeFeatures(box, s).bdpt) << "--integrator path";
    // auto: by the measured fraction of light samples that find their light.
    s.estimator = Estimator::Auto;
    EXPECT_FALSE(computeFeatures(box, s).bdpt) << "not measured";
    box.lightVisibility = 0.9f;
    EXPECT_FALSE(computeFeatures(box, s).bdpt) << "light sampling finds the light";
    box.lightVisibility = 0.02f;
    EXPECT_TRUE(computeFeatures(box, s).bdpt) << "light sampling seldom finds the light";
    s.maxDepth = BDPT_MAX_LIGHT_VERTICES + 3;
    EXPECT_FALSE(computeFeatures(box, s).bdpt) << "nor where it cannot render the scene";
}

// The measurement auto decides by: nine in ten light samples find the box's light, hardly any
// find the lamp in the next room of scenes/ajar.
TEST_F(Bdpt, LightSamplesFindTheLightInTheBoxButNotThroughADoorAjar) {
    const auto visibility = [](const std::filesystem::path& path) {
        const Scene scene = loadScene(path);
        const std::optional<float> v = probeLightVisibility(
            sharedContext(), flattenScene(scene), independentSettings(), scene.cameras.at(0), 64, 36);
        EXPECT_TRUE(v.has_value()) << path;
        return v.value_or(-1.0f);
    };
    const float box = visibility(diffuseBox());
    const float ajar = visibility(repoDir() / "scenes" / "ajar" / "scene.gltf");
    std::printf("[          ] light samples that find their light: box %.3f, two rooms %.3f\n", box, ajar);
    EXPECT_GT(box, 0.8f);
    EXPECT_LT(ajar, 0.05f);
    EXPECT_GT(ajar, 0.0f) << "some surfaces by the gap see the lamp";
}

} // namespace
} // namespace pt::test
