// Analytic spheres and ellipsoids: traversal against brute force, and analytic radiance cases
// (enclosure furnace, glass and conductor spheres under a uniform white sky).
#include "support/gpu_test_support.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <random>

namespace pt::test {
namespace {

class Spheres : public GpuTest {};

Sphere makeSphere(glm::vec3 centre, glm::vec3 radii, float angleDegrees, uint32_t material) {
    Sphere s;
    s.objectToWorld = glm::translate(glm::mat4(1.0f), centre) *
                      glm::rotate(glm::mat4(1.0f), glm::radians(angleDegrees), glm::normalize(glm::vec3(1, 2, 3))) *
                      glm::scale(glm::mat4(1.0f), radii);
    s.material = material;
    return s;
}

// The tree's hits against brute force's, ray by ray (t and primitive), with enough sphere hits
// to mean something.
void expectHitsMatch(const std::vector<glm::vec4>& bvh, const std::vector<glm::vec4>& brute, const char* what) {
    int sphereHits = 0, mismatches = 0;
    for (size_t i = 0; i < bvh.size(); ++i) {
        ASSERT_NE(bvh[i].x, -2.0f) << what << ": closest-hit and any-hit disagree on ray " << i;
        uint32_t pb, pf;
        std::memcpy(&pb, &bvh[i].y, 4);
        std::memcpy(&pf, &brute[i].y, 4);
        if (bvh[i].x != brute[i].x || (bvh[i].x >= 0 && pb != pf)) ++mismatches;
        if (bvh[i].x >= 0 && (pb & SPHERE_BIT)) ++sphereHits;
    }
    EXPECT_EQ(mismatches, 0) << what;
    EXPECT_GT(sphereHits, 1000) << what;
}

TEST_F(Spheres, TraversalMatchesBruteForceWithTrianglesAndEllipsoids) {
    Scene scene;
    scene.materials.push_back(Material{});
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-4.0f, 4.0f), r(0.05f, 0.6f), a(0.0f, 180.0f);
    for (int i = 0; i < 300; ++i)
        scene.spheres.push_back(makeSphere({u(rng), u(rng), u(rng)}, {r(rng), r(rng), r(rng)}, a(rng), 0));
    scene.meshes.push_back(makeIcosphere(2, glm::vec3(0.5f), 1.5f, 0));
    FlatScene flat = flattenScene(scene);
    ASSERT_EQ(flat.spheres.size(), 300u);
    GpuScene gpuScene(sharedContext(), flat, gpu::GpuSceneParams{}, 0);

    std::vector<gpu::GpuTestRay> rays(50000);
    for (auto& ray : rays) {
        ray.origin = glm::vec3(u(rng), u(rng), u(rng)) * 1.5f;
        ray.direction = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        ray.tMax = 1e30f;
    }
    const auto bytes = std::as_bytes(std::span(rays));
    auto brute = runTestKernel(TEST_MODE_TRACE_BRUTE_FORCE, static_cast<uint32_t>(rays.size()), &gpuScene, bytes);
    // The trees and the spheres read through buffer addresses and through texel buffers.
    for (bool texels : {false, true}) {
        setTestKernelTexelLoads(texels);
        auto bvh = runTestKernel(TEST_MODE_TRACE_BVH, static_cast<uint32_t>(rays.size()), &gpuScene, bytes);
        setTestKernelTexelLoads(false);
        expectHitsMatch(bvh, brute, texels ? "texel loads" : "address loads");
    }
}

TEST_F(Spheres, CameraInsideAnEmissiveDiffuseSphereSeesTheAnalyticRadiance) {
    // Le * sum_{k < D} rho^k, as for the triangle enclosure, here with an analytic ellipsoid
    // that is also a light: light sampling by area from inside, with and without MIS.
    Scene scene;
    Material m;
    m.baseColor = glm::vec3(0.5f);
    m.emission = glm::vec3(1.0f);
    m.doubleSided = true;
    scene.materials.push_back(m);
    scene.spheres.push_back(makeSphere({0.3f, -0.2f, 0.1f}, {2.0f, 1.0f, 1.5f}, 30.0f, 0));
    Camera camera;
    camera.position = glm::vec3(0.3f, -0.2f, 0.1f);
    camera.yfov = 1.5f;
    const double expected = (1.0 - std::pow(0.5, 6)) / 0.5;
    for (int mode = 0; mode < 3; ++mode) {
        IntegratorSettings s = independentSettings();
        s.maxDepth = 6;
        s.rr = false;
        s.nee = mode > 0;
        s.mis = mode == 2;
        auto r = renderScene(scene, s, camera, 32, 32, 64);
        EXPECT_EQ(r.droppedSamples, 0u);
        double sum = 0, var = 0;
        const size_t pixels = r.mean.rgba.size() / 4;
        for (size_t i = 0; i < pixels; ++i) {
            sum += r.mean.rgba[4 * i];
            var += r.varianceOfMean.rgba[4 * i];
        }
        const double mean = sum / pixels, standardError = std::sqrt(var) / pixels;
        // Without NEE every path carries exactly the sum (cosine sampling, albedo weights).
        EXPECT_NEAR(mean, expected, 4.0 * standardError + 1e-4 * expected) << "mode " << mode;
        if (mode > 0) EXPECT_GT(standardError, 0.0) << "light sampling should add noise";
    }
}

// A sphere in a uniform white sky: every camera ray that hits it ends in the sky after delta
// bounces, carrying exactly the product of the Fresnel weights.
class WhiteSky : public GpuTest {
protected:
    Renderer::Readback render(const Material& material) {
        Scene scene;
        scene.materials.push_back(material);
        scene.spheres.push_back(makeSphere({0, 0, 0}, {1, 1, 1}, 0.0f, 0));
        scene.background = glm::vec3(1.0f);
        Camera camera;
        camera.position = glm::vec3(0, 0, 4);
        camera.yfov = 0.6f;
        IntegratorSettings s = independentSettings();
        s.maxDepth = 64;
        s.rr = false;
        return renderScene(scene, s, camera, 33, 33, 64);
    }
};

TEST_F(WhiteSky, GlassSphereConservesRadiance) {
    Material glass;
    glass.type = MaterialType::Dielectric;
    glass.baseColor = glm::vec3(1.0f);
    glass.ior = 1.5f;
    auto r = render(glass);
    EXPECT_EQ(r.droppedSamples, 0u);
    // Reflection and refraction choices are random but every path ends in the sky with weight 1
    // (the 1/eta^2 of entering cancels on leaving), so every pixel is exactly 1.
    double worst = 0;
    for (size_t i = 0; i < r.mean.rgba.size(); i += 4) worst = std::max(worst, std::abs(r.mean.rgba[i] - 1.0));
    EXPECT_LT(worst, 1e-4);
}

TEST_F(WhiteSky, ConductorReflectsItsFresnelReflectance) {
    Material gold;
    gold.type = MaterialType::Conductor;
    gold.baseColor = glm::vec3(1.0f);
    gold.conductorEta = glm::vec3(0.17f, 0.35f, 1.5f);
    gold.conductorK = glm::vec3(3.1f, 2.7f, 1.9f);
    auto r = render(gold);
    // The centre pixel sees the sphere head-on: R = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
    const float* centre = r.mean.at(16, 16);
    for (int c = 0; c < 3; ++c) {
        const double n = gold.conductorEta[c], k = gold.conductorK[c];
        const double expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
        EXPECT_NEAR(centre[c], expected, 2e-3) << "channel " << c;
    }
    // A corner pixel misses the sphere and sees the sky.
    EXPECT_FLOAT_EQ(r.mean.at(0, 0)[0], 1.0f);
}

// The course's mirror with a diffuse layer (a glossy material with a mirror lobe): on a convex
// sphere under a white sky both lobes see only sky, so each pixel on the sphere is kd + km.
TEST_F(WhiteSky, LayeredMirrorReflectsItsDiffuseAndMirrorReflectances) {
    Material layered;
    layered.type = MaterialType::Glossy;
    layered.baseColor = glm::vec3(0.3f, 0.2f, 0.1f);
    layered.mirrorReflectance = glm::vec3(0.4f, 0.5f, 0.6f);
    auto r = render(layered);
    EXPECT_EQ(r.droppedSamples, 0u);
    for (int c = 0; c < 3; ++c) {
        double sum = 0, var = 0;
        int n = 0;
        for (int y = 12; y <= 20; ++y)
            for (int x = 12; x <= 20; ++x, ++n) {
                sum += r.mean.at(x, y)[c];
                var += r.varianceOfMean.at(x, y)[c];
            }
        const double expected = layered.baseColor[c] + layered.mirrorReflectance[c];
        EXPECT_NEAR(sum / n, expected, 4.0 * std::sqrt(var) / n + 1e-4) << "channel " << c;
    }
}

} // namespace
} // namespace pt::test
