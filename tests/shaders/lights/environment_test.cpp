// The environment light: furnace cases (a diffuse and a glass sphere under a uniform sky), and
// light sampling, BSDF sampling and MIS agreeing under a map whose bright texels sit on a pole
// and on the seam.
#include "film/metrics.h"
#include "support/gpu_test_support.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace pt::test {
namespace {

class EnvironmentLight : public GpuTest {
protected:
    static Sphere unitSphere(uint32_t material) {
        Sphere s;
        s.material = material;
        return s;
    }
    static Camera lookingAtOrigin() {
        Camera c;
        c.position = glm::vec3(0.0f, 0.0f, 6.0f); // the sphere fills the middle, the corners see sky
        c.yfov = 0.5f;
        return c;
    }
    // An 16 x 8 map of 0.2, with a bright texel in the top (pole) row and one in column 0 (seam).
    static Environment hotspotMap() {
        Environment env;
        env.image.width = 16;
        env.image.height = 8;
        env.image.rgba.assign(16 * 8 * 4, 0.2f);
        for (int c = 0; c < 3; ++c) {
            env.image.at(5, 0)[c] = 200.0f;
            env.image.at(0, 4)[c] = 100.0f;
        }
        return env;
    }
};

TEST_F(EnvironmentLight, DiffuseSphereUnderUniformSkyReflectsItsAlbedo) {
    Scene scene;
    Material m;
    m.baseColor = glm::vec3(0.8f);
    scene.materials.push_back(m);
    scene.spheres.push_back(unitSphere(0));
    Environment sky;
    sky.colour = glm::vec3(1.0f);
    scene.environment = sky;
    for (int mode = 0; mode < 3; ++mode) {
        IntegratorSettings s = independentSettings();
        s.nee = mode != 2;
        s.mis = mode == 0;
        s.maxDepth = 8;
        auto r = renderScene(scene, s, lookingAtOrigin(), 16, 16, 64);
        EXPECT_EQ(r.droppedSamples, 0u);
        // The centre 4x4 pixels see only the sphere: a convex Lambertian under L = 1 sends rho.
        double sum = 0, var = 0;
        for (int y = 6; y < 10; ++y)
            for (int x = 6; x < 10; ++x) sum += r.mean.at(x, y)[0], var += r.varianceOfMean.at(x, y)[0];
        EXPECT_NEAR(sum / 16, 0.8, 4 * std::sqrt(var) / 16 + 1e-4) << "mode " << mode;
        EXPECT_NEAR(r.mean.at(0, 0)[0], 1.0f, 1e-6) << "a corner sees the sky";
    }
}

TEST_F(EnvironmentLight, GlassSphereUnderUniformSkyConservesRadiance) {
    Scene scene;
    Material glass;
    glass.type = MaterialType::Dielectric;
    glass.baseColor = glm::vec3(1.0f);
    glass.ior = 1.5f;
    scene.materials.push_back(glass);
    scene.spheres.push_back(unitSphere(0));
    Environment sky;
    sky.colour = glm::vec3(1.0f);
    scene.environment = sky;
    IntegratorSettings s = independentSettings();
    s.maxDepth = 64;
    s.rr = false;
    auto r = renderScene(scene, s, lookingAtOrigin(), 16, 16, 32);
    for (size_t i = 0; i < r.mean.rgba.size(); i += 4) EXPECT_NEAR(r.mean.rgba[i], 1.0f, 1e-4) << i / 4;
}

TEST_F(EnvironmentLight, LightSamplingBsdfSamplingAndMisAgree) {
    Scene scene;
    Material m;
    m.baseColor = glm::vec3(0.7f);
    m.doubleSided = true;
    scene.materials.push_back(m);
    scene.meshes.push_back(makeQuad({-2.0f, -0.5f, 2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.0f}, 0)); // floor
    scene.environment = hotspotMap();
    scene.environment->rotationDegrees = 30.0f;
    Camera camera;
    camera.position = glm::vec3(0.0f, 1.5f, 2.5f);
    camera.forward = glm::normalize(glm::vec3(0.0f, -2.0f, -2.5f));
    camera.up = glm::normalize(glm::cross(glm::cross(camera.forward, glm::vec3(0, 1, 0)), camera.forward));
    camera.yfov = 0.9f;
    auto render = [&](bool nee, bool mis, uint32_t seed) {
        IntegratorSettings s = independentSettings();
        s.nee = nee;
        s.mis = mis;
        s.maxDepth = 3;
        s.seed = seed;
        return renderScene(scene, s, camera, 32, 32, 256);
    };
    const auto misRender = render(true, true, 1);
    const BlockStats reference = blockStats(misRender.mean, &misRender.varianceOfMean, 8);
    for (auto [nee, mis] : {std::pair{true, false}, std::pair{false, false}, std::pair{true, true}}) {
        const auto r = render(nee, mis, 2);
        const AgreementResult a = compareBlocks(blockStats(r.mean, &r.varianceOfMean, 8), reference);
        std::printf("[          ] nee %d mis %d: chi2/dof %.3f, mean z %+.3f\n", nee, mis, a.chi2PerDof, a.meanZ);
        EXPECT_LT(a.chi2PerDof, 2.0) << "nee " << nee << " mis " << mis;
        EXPECT_LT(std::abs(a.meanZ), 0.5) << "nee " << nee << " mis " << mis;
    }
}

} // namespace
} // namespace pt::test
