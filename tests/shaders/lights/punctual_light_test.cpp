// Point and directional lights against their analytic direct lighting on a Lambertian plane:
// L = rho / pi * I cos(theta) / d^2 under a point light, rho / pi * E cos(theta) under a
// directional one. Delta lights are sampled exactly, so the only noise is the pixel jitter.
#include "support/gpu_test_support.h"

#include <cmath>

namespace pt::test {
namespace {

class PunctualLights : public GpuTest {
protected:
    Scene plane() {
        Scene scene;
        Material m;
        m.baseColor = glm::vec3(0.6f, 0.5f, 0.4f);
        scene.materials.push_back(m);
        // A plane at y = 0, facing up. Small, because a directional light's selection weight
        // grows with the scene's size: a huge plane would leave the point light almost never chosen.
        scene.meshes.push_back(makeQuad({-2.0f, 0.0f, 2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.0f}, 0));
        return scene;
    }
    // Looks straight down at the origin from height 3 with a narrow field of view.
    Renderer::Readback render(const Scene& scene) {
        Camera camera;
        camera.position = glm::vec3(0.0f, 3.0f, 0.0f);
        camera.forward = glm::vec3(0.0f, -1.0f, 0.0f);
        camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
        camera.yfov = 0.01f;
        IntegratorSettings s = independentSettings();
        s.maxDepth = 2;
        return renderScene(scene, s, camera, 9, 9, 16);
    }
};

TEST_F(PunctualLights, PointLightFollowsTheInverseSquareLaw) {
    Scene scene = plane();
    PunctualLight light;
    light.type = PunctualLight::Type::Point;
    light.position = glm::vec3(1.0f, 2.0f, 0.0f);
    light.intensity = glm::vec3(10.0f, 20.0f, 30.0f);
    scene.punctualLights.push_back(light);
    auto r = render(scene);
    const double d2 = 1.0 + 4.0, cosTheta = 2.0 / std::sqrt(d2);
    for (int c = 0; c < 3; ++c) {
        const double expected = scene.materials[0].baseColor[c] / M_PI * light.intensity[c] * cosTheta / d2;
        EXPECT_NEAR(r.mean.at(4, 4)[c], expected, 2e-3 * expected) << "channel " << c;
    }
}

TEST_F(PunctualLights, DirectionalLightGivesLambertsCosineLaw) {
    Scene scene = plane();
    PunctualLight light;
    light.type = PunctualLight::Type::Directional;
    light.direction = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
    light.intensity = glm::vec3(3.0f);
    scene.punctualLights.push_back(light);
    // A second light of each kind shares the table: the estimate stays unbiased.
    PunctualLight point;
    point.position = glm::vec3(0.0f, 1.0f, 0.0f);
    point.intensity = glm::vec3(1.0f);
    scene.punctualLights.push_back(point);
    auto r = render(scene);
    const double cosTheta = -light.direction.y;
    const double expected = scene.materials[0].baseColor[0] / M_PI * (3.0 * cosTheta + 1.0);
    // Light selection makes each sample see one light or the other: average over the image.
    double sum = 0, var = 0;
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 9; ++x) sum += r.mean.at(x, y)[0], var += r.varianceOfMean.at(x, y)[0];
    EXPECT_NEAR(sum / 81, expected, 4 * std::sqrt(var) / 81 + 2e-3 * expected);
}

TEST_F(PunctualLights, ShadowsBlockPointLights) {
    Scene scene = plane();
    scene.meshes.push_back(
        makeQuad({-1.0f, 1.0f, 1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f}, 0)); // occluder at y = 1
    PunctualLight light;
    light.position = glm::vec3(0.0f, 2.0f, 0.0f);
    light.intensity = glm::vec3(10.0f);
    scene.punctualLights.push_back(light);
    Camera camera;
    camera.position = glm::vec3(0.0f, 0.5f, 0.0f); // between the plane and the occluder
    camera.forward = glm::vec3(0.0f, -1.0f, 0.0f);
    camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.yfov = 0.01f;
    IntegratorSettings s = independentSettings();
    s.maxDepth = 2;
    auto r = renderScene(scene, s, camera, 5, 5, 4);
    EXPECT_EQ(r.mean.at(2, 2)[0], 0.0f);
}

} // namespace
} // namespace pt::test

namespace pt::test {
namespace {

// The course's spot light: full intensity inside the falloff cone, ((cos a - cos coverage) /
// (cos falloff - cos coverage))^4 in the band, nothing outside the coverage cone.
TEST_F(PunctualLights, SpotLightConeAndFalloffBand) {
    const double rho = 0.6, intensity = 10.0, height = 2.0;
    auto radianceBelow = [&](float offsetX, float exponent = 4.0f) {
        Scene scene = plane();
        scene.materials[0].baseColor = glm::vec3(float(rho));
        PunctualLight spot;
        spot.type = PunctualLight::Type::Spot;
        spot.position = glm::vec3(-offsetX, float(height), 0.0f); // the camera looks at the origin
        spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        spot.intensity = glm::vec3(float(intensity));
        spot.cosFalloff = std::cos(glm::radians(10.0f));
        spot.cosCoverage = std::cos(glm::radians(20.0f));
        spot.falloffExponent = exponent;
        scene.punctualLights.push_back(spot);
        return render(scene).mean.at(4, 4)[0];
    };
    auto pointValue = [&](double x) {
        const double d2 = x * x + height * height, cosTheta = height / std::sqrt(d2);
        return rho / M_PI * intensity * cosTheta / d2;
    };
    // Inside the falloff cone (5 degrees off the axis): a plain point light.
    const double inside = height * std::tan(glm::radians(5.0));
    EXPECT_NEAR(radianceBelow(float(inside)), pointValue(inside), 3e-3 * pointValue(inside));
    // In the band (15 degrees): scaled by the course's fourth-power blend.
    const double band = height * std::tan(glm::radians(15.0));
    const double t = (std::cos(glm::radians(15.0)) - std::cos(glm::radians(20.0))) /
                     (std::cos(glm::radians(10.0)) - std::cos(glm::radians(20.0)));
    EXPECT_NEAR(radianceBelow(float(band)), pointValue(band) * std::pow(t, 4), 5e-3 * pointValue(band));
    // glTF's spots (KHR_lights_punctual): the same band squared.
    EXPECT_NEAR(radianceBelow(float(band), 2.0f), pointValue(band) * t * t, 5e-3 * pointValue(band));
    // Outside the coverage cone (25 degrees): dark.
    EXPECT_EQ(radianceBelow(float(height * std::tan(glm::radians(25.0)))), 0.0f);
}

// The course's AreaLight, an invisible square of radiance L: irradiance under its centre at
// distance c is E = 4 L X / sqrt(1 + X^2) atan(X / sqrt(1 + X^2)), X = edge / (2 c).
TEST_F(PunctualLights, SquareAreaLightGivesTheAnalyticIrradiance) {
    const double rho = 0.5, L = 3.0, edge = 1.5, c = 2.0;
    Scene scene = plane();
    scene.materials[0].baseColor = glm::vec3(float(rho));
    PunctualLight square;
    square.type = PunctualLight::Type::Square;
    square.position = glm::vec3(0.0f, float(c), 0.0f);
    square.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    square.intensity = glm::vec3(float(L));
    square.size = float(edge);
    scene.punctualLights.push_back(square);
    Camera camera;
    camera.position = glm::vec3(0.0f, 1.0f, 0.0f); // below the light, which rays cannot see
    camera.forward = glm::vec3(0.0f, -1.0f, 0.0f);
    camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.yfov = 0.001f;
    IntegratorSettings s = independentSettings();
    s.maxDepth = 2;
    auto r = renderScene(scene, s, camera, 8, 8, 256);
    double sum = 0, var = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) sum += r.mean.at(x, y)[0], var += r.varianceOfMean.at(x, y)[0];
    const double X = edge / (2 * c), q = X / std::sqrt(1 + X * X);
    const double expected = rho / M_PI * 4 * L * q * std::atan(q);
    EXPECT_NEAR(sum / 64, expected, 4 * std::sqrt(var) / 64 + 1e-4 * expected);

    // Both faces emit (the course's |n_l . w_i|): a ceiling as far above the square, facing it,
    // receives the same irradiance from its back.
    Scene above = scene;
    above.meshes.push_back(
        makeQuad({-2.0f, float(2 * c), 2.0f}, {0.0f, 0.0f, -4.0f}, {4.0f, 0.0f, 0.0f}, 0)); // normal -y
    above.meshes.erase(above.meshes.begin());
    camera.position = glm::vec3(0.0f, float(1.5 * c), 0.0f);
    camera.forward = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
    auto back = renderScene(above, s, camera, 8, 8, 256);
    double backSum = 0, backVar = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) backSum += back.mean.at(x, y)[0], backVar += back.varianceOfMean.at(x, y)[0];
    EXPECT_NEAR(backSum / 64, expected, 4 * std::sqrt(backVar) / 64 + 1e-4 * expected);
}

} // namespace
} // namespace pt::test
