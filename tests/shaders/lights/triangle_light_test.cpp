// Triangle emitters sampled by solid angle (shaders/lights/triangle_light.glsl, Arvo 1995) in the
// integrator: a Lambertian floor 0.4 under an emissive square 1.5 across, lit by light sampling
// alone. The mean is the analytic irradiance's radiance, and the per-sample variance is the one
// uniform sampling of the square's solid angle has (only the floor's cosine varies), which
// sampling points by area (its pdf varying with d^2 / cos) would exceed several times.
#include "support/gpu_test_support.h"

#include <cmath>
#include <cstdio>

namespace pt::test {
namespace {

class TriangleLights : public GpuTest {};

TEST_F(TriangleLights, ANearSquareIsSampledUniformlyInItsSolidAngle) {
    const double rho = 0.5, L = 3.0, edge = 1.5, c = 0.4;
    Scene scene;
    Material floor;
    floor.baseColor = glm::vec3(float(rho));
    Material lamp;
    lamp.baseColor = glm::vec3(0.0f);
    lamp.emission = glm::vec3(float(L));
    scene.materials = {floor, lamp};
    scene.meshes.push_back(makeQuad({-2.0f, 0.0f, 2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.0f}, 0));
    const float h = float(edge / 2);
    scene.meshes.push_back(makeQuad({-h, float(c), -h}, {2 * h, 0.0f, 0.0f}, {0.0f, 0.0f, 2 * h}, 1)); // faces -y
    Camera camera;
    camera.position = glm::vec3(0.0f, 0.2f, 0.0f);
    camera.forward = glm::vec3(0.0f, -1.0f, 0.0f);
    camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.yfov = 0.001f;
    IntegratorSettings s = independentSettings();
    s.maxDepth = 2;
    s.mis = false; // light sampling alone: BSDF rays that reach the light count nothing
    const uint32_t spp = 1024;
    const auto r = renderScene(scene, s, camera, 8, 8, spp);
    double mean = 0, sampleVariance = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            mean += r.mean.at(x, y)[0] / 64;
            sampleVariance += r.varianceOfMean.at(x, y)[0] * spp / 64;
        }
    // Over the square, by a midpoint rule: solid angle, irradiance and the integral of cos^2.
    double omega = 0, irradiance = 0, cos2 = 0;
    const int n = 2000;
    const double dA = (edge / n) * (edge / n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -edge / 2 + (i + 0.5) * edge / n, z = -edge / 2 + (j + 0.5) * edge / n;
            const double d = std::sqrt(x * x + z * z + c * c);
            omega += c / (d * d * d) * dA;
            irradiance += L * c * c / (d * d * d * d) * dA;
            cos2 += c * c * c / (d * d * d * d * d) * dA;
        }
    const double X = edge / (2 * c), q = X / std::sqrt(1 + X * X);
    EXPECT_NEAR(irradiance, 4 * L * q * std::atan(q), 1e-4 * irradiance); // the rule against the closed form
    const double expected = rho / M_PI * irradiance;
    // Each sample is rho / pi * L * cos * omega (the two triangles subtend equal halves here).
    const double expectedVariance = std::pow(rho / M_PI * L * omega, 2) * (cos2 / omega) - expected * expected;
    std::printf("[          ] mean %.5f (expected %.5f), per-sample variance %.5f (solid-angle sampling %.5f)\n", mean,
        expected, sampleVariance, expectedVariance);
    EXPECT_NEAR(mean, expected, 4 * std::sqrt(sampleVariance / (64.0 * spp)) + 1e-4 * expected);
    EXPECT_NEAR(sampleVariance, expectedVariance, 0.1 * expectedVariance);
}

} // namespace
} // namespace pt::test
