// Motion blur: an unlit quad of width 1 that moves by +1 in x while the shutter is open covers
// the point x for the fraction of time t in [0, 1) with t <= x < t + 1, a tent rising from 0 at
// x = 0 to 1 at x = 1 and falling to 0 at x = 2. The render's mean over many samples must follow
// it; a static quad stays a box, and the kernel for static scenes leaves out the motion code.
// Moving emitters light the scene from where they are at each sample's time, whichever
// estimator finds them.
#include "film/metrics.h"
#include "scene/scene_loader.h"
#include "support/gpu_test_support.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <utility>

namespace pt::test {
namespace {

class MotionBlur : public GpuTest {};

Scene movingQuad(glm::vec3 motion) {
    Scene scene;
    Material m;
    m.unlit = true;
    m.baseColor = glm::vec3(1.0f);
    scene.materials.push_back(m);
    Mesh quad = makeQuad(glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 2, 0), 0);
    quad.motion = motion;
    scene.meshes.push_back(quad);
    return scene;
}

// Looking down -z at x in [-0.5, 2.5], y in [-0.1, 0.1].
Camera stripCamera() {
    Camera c;
    c.position = glm::vec3(1.0f, 0.0f, 10.0f);
    c.forward = glm::vec3(0, 0, -1);
    c.up = glm::vec3(0, 1, 0);
    c.window = glm::vec4(-0.15f, 0.15f, -0.01f, 0.01f);
    return c;
}

double tent(double x) { return std::clamp(std::min(x, 2.0 - x), 0.0, 1.0); }

TEST_F(MotionBlur, MovingQuadSweepsATentProfile) {
    const int width = 48;
    const Scene scene = movingQuad(glm::vec3(1, 0, 0));
    ASSERT_TRUE(computeFeatures(flattenScene(scene), IntegratorSettings{}).motion);
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, stripCamera(), width, 2, 1024);
    double worst = 0;
    for (int x = 0; x < width; ++x) {
        // Pixel x spans world x in [-0.5 + 3 x / W, -0.5 + 3 (x + 1) / W]; average the tent over it.
        const double x0 = -0.5 + 3.0 * x / width, x1 = -0.5 + 3.0 * (x + 1) / width;
        double expected = 0;
        for (int k = 0; k < 64; ++k) expected += tent(x0 + (x1 - x0) * (k + 0.5) / 64) / 64;
        const double got = 0.5 * (r.mean.at(x, 0)[0] + r.mean.at(x, 1)[0]);
        // 2048 Bernoulli samples per column: standard error at most 0.011.
        worst = std::max(worst, std::abs(got - expected));
        EXPECT_NEAR(got, expected, 0.045) << "column " << x;
    }
    std::printf("largest deviation from the tent: %.4f\n", worst);
}

TEST_F(MotionBlur, StaticQuadIsABoxAndNeedsNoMotionCode) {
    const Scene scene = movingQuad(glm::vec3(0.0f));
    EXPECT_FALSE(computeFeatures(flattenScene(scene), IntegratorSettings{}).motion);
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, stripCamera(), 48, 2, 4);
    for (int x = 0; x < 48; ++x) {
        const double x0 = -0.5 + 3.0 * x / 48, x1 = -0.5 + 3.0 * (x + 1) / 48;
        if (x1 <= 0.0 || x0 >= 1.0)
            EXPECT_EQ(r.mean.at(x, 0)[0], 0.0f) << x;
        else if (x0 >= 0.0 && x1 <= 1.0)
            EXPECT_EQ(r.mean.at(x, 0)[0], 1.0f) << x;
    }
}

// The diffuse box with its lamp moving sideways and a moving emissive ellipsoid: light sampling,
// BSDF sampling alone and bidirectional path tracing (whose light subpaths start on the
// emitters) must render one image. Light sampling that took the emitters where they stand at the
// shutter's opening would light the box from the wrong places.
TEST_F(MotionBlur, MovingEmittersLightTheSceneFromWhereTheyAre) {
    Scene scene = loadScene(testDataDir() / "references" / "cbox-diffuse" / "scene.gltf");
    size_t lamps = 0;
    for (Mesh& mesh : scene.meshes)
        if (scene.materials.at(mesh.material).emission != glm::vec3(0.0f)) {
            mesh.motion = glm::vec3(0.5f, 0.0f, 0.3f);
            ++lamps;
        }
    ASSERT_EQ(lamps, 1u);
    Material glow;
    glow.baseColor = glm::vec3(0.0f);
    glow.emission = glm::vec3(3.0f, 2.0f, 1.0f);
    scene.materials.push_back(glow);
    Sphere ball;
    ball.objectToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, -0.3f, 0.0f)) *
                         glm::scale(glm::mat4(1.0f), glm::vec3(0.15f, 0.25f, 0.15f));
    ball.material = static_cast<uint32_t>(scene.materials.size() - 1);
    ball.motion = glm::vec3(0.6f, 0.4f, 0.0f);
    scene.spheres.push_back(ball);
    IntegratorSettings s = independentSettings();
    s.maxDepth = 4;
    ASSERT_TRUE(computeFeatures(flattenScene(scene), s).motion);
    const Camera& camera = scene.cameras.at(0);
    const auto render = [&](bool nee, Estimator estimator, uint32_t seed, uint32_t spp) {
        IntegratorSettings settings = s;
        settings.nee = nee;
        settings.estimator = estimator;
        settings.seed = seed;
        return renderScene(scene, settings, camera, 24, 24, spp);
    };
    const Renderer::Readback bsdfOnly = render(false, Estimator::Path, 1, 4096);
    for (const auto& [name, image] : {std::pair{"light sampling", render(true, Estimator::Path, 2, 1024)},
             std::pair{"bdpt", render(true, Estimator::Bidirectional, 3, 512)}}) {
        const AgreementResult r = compareBlocks(
            blockStats(image.mean, &image.varianceOfMean, 4), blockStats(bsdfOnly.mean, &bsdfOnly.varianceOfMean, 4));
        std::printf("[          ] %s vs BSDF sampling alone: chi2/dof %.3f, mean z %+.3f, max |z| %.2f\n", name,
            r.chi2PerDof, r.meanZ, r.maxAbsZ);
        EXPECT_LT(r.chi2PerDof, 1.6) << name;
        EXPECT_LT(std::abs(r.meanZ), 0.5) << name;
    }
}

} // namespace
} // namespace pt::test
