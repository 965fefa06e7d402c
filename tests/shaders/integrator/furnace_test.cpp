// Analytic check: a camera inside a closed diffuse enclosure of albedo rho that emits Le
// everywhere sees L = Le * sum_{k < D} rho^k with D the maximum number of ray segments
// (Le / (1 - rho) without a limit), whatever the shape. Every integrator setting must agree.
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "support/gpu_test_support.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <numeric>

namespace pt::test {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr float kEmission = 1.0f;

Scene enclosure() {
    Scene scene;
    Material m;
    m.name = "furnace";
    m.baseColor = glm::vec3(kAlbedo);
    m.emission = glm::vec3(kEmission);
    m.doubleSided = true;
    scene.materials.push_back(m);
    scene.meshes.push_back(makeIcosphere(2, glm::vec3(0.1f, -0.2f, 0.05f), 1.0f, 0));
    return scene;
}

double expectedRadiance(uint32_t maxDepth) { return kEmission * (1.0 - std::pow(kAlbedo, maxDepth)) / (1.0 - kAlbedo); }

struct Stats {
    double mean = 0;
    double standardError = 0;
};

Stats imageMean(const Renderer::Readback& r) {
    double sum = 0, var = 0;
    const size_t n = r.mean.rgba.size() / 4 * 3;
    for (size_t i = 0; i < r.mean.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        sum += r.mean.rgba[i];
        var += r.varianceOfMean.rgba[i];
    }
    // Channels of one pixel are perfectly correlated here (grey scene): count pixels, not channels.
    return {sum / n, std::sqrt(var / 3.0) / (n / 3.0)};
}

class Furnace : public GpuTest {};

struct FurnaceCase {
    const char* name;
    bool nee, mis, rr;
    DirectionSampling sampling;
    uint32_t maxDepth;
};

TEST_F(Furnace, EverySettingConvergesToTheAnalyticRadiance) {
    const FurnaceCase cases[] = {
        {"nee+mis+rr", true, true, true, DirectionSampling::Cosine, 64},
        {"nee+mis", true, true, false, DirectionSampling::Cosine, 8},
        {"nee only", true, false, true, DirectionSampling::Cosine, 8},
        {"bsdf only", false, false, true, DirectionSampling::Cosine, 64},
        {"bsdf only, no rr", false, false, false, DirectionSampling::Cosine, 8},
        {"uniform+nee+mis", true, true, true, DirectionSampling::Uniform, 8},
        {"uniform, no nee", false, false, false, DirectionSampling::Uniform, 8},
        {"emitters only", true, true, true, DirectionSampling::Cosine, 1},
        {"direct only", true, true, false, DirectionSampling::Cosine, 2},
    };
    Camera camera;
    camera.position = glm::vec3(0.0f);
    camera.yfov = 1.5f;
    for (const auto& c : cases) {
        IntegratorSettings s = independentSettings();
        s.nee = c.nee;
        s.mis = c.mis;
        s.rr = c.rr;
        s.sampling = c.sampling;
        s.maxDepth = c.maxDepth;
        s.rrStartDepth = 2;
        auto r = renderScene(enclosure(), s, camera, 32, 32, 64);
        EXPECT_EQ(r.droppedSamples, 0u) << c.name;
        Stats st = imageMean(r);
        const double expected = expectedRadiance(c.maxDepth);
        // Statistical tolerance (4 standard errors) plus float rounding for zero-variance cases.
        const double tolerance = 4.0 * st.standardError + 2e-5 * expected;
        EXPECT_NEAR(st.mean, expected, tolerance) << c.name << " (standard error " << st.standardError << ")";
    }
}

// Bidirectional path tracing in the furnace: every strategy can make every path (the walls are
// the lights: hit, sampled, started from, connected to, seen by the camera), so the MIS weights
// must sum to one for each path or the mean moves. With MIS off each strategy gets 1 / (their
// number); without NEE the light-sampling strategy drops out of the sums.
TEST_F(Furnace, BidirectionalPathTracingConvergesToTheAnalyticRadiance) {
    const FurnaceCase cases[] = {
        {"bdpt", true, true, true, DirectionSampling::Cosine, 8},
        {"bdpt, no rr", true, true, false, DirectionSampling::Cosine, 6},
        {"bdpt, no mis", true, false, false, DirectionSampling::Cosine, 5},
        {"bdpt, no nee", false, false, true, DirectionSampling::Cosine, 6},
        {"bdpt, uniform", true, true, true, DirectionSampling::Uniform, 6},
    };
    Camera camera;
    camera.position = glm::vec3(0.0f);
    camera.yfov = 1.5f;
    for (const auto& c : cases) {
        IntegratorSettings s = independentSettings();
        s.estimator = Estimator::Bidirectional;
        s.nee = c.nee;
        s.mis = c.mis;
        s.rr = c.rr;
        s.sampling = c.sampling;
        s.maxDepth = c.maxDepth;
        s.rrStartDepth = 2;
        const Scene scene = enclosure();
        ASSERT_TRUE(computeFeatures(flattenScene(scene), s).bdpt) << c.name;
        auto r = renderScene(scene, s, camera, 24, 24, 64);
        EXPECT_EQ(r.droppedSamples, 0u) << c.name;
        Stats st = imageMean(r);
        const double expected = expectedRadiance(c.maxDepth);
        std::printf("[          ] %s: mean %.5f, expected %.5f, standard error %.5f\n", c.name, st.mean, expected,
            st.standardError);
        EXPECT_NEAR(st.mean, expected, 4.0 * st.standardError + 2e-5 * expected) << c.name;
    }
}

// The furnace as an analytic sphere: on a sphere the surface within a ball of radius r around a
// point of it has area pi r^2 exactly (Archimedes), so merging's density estimate of the uniform
// radiance has no bias from the radius, and every deviation is the weights'.
Scene sphereEnclosure() {
    Scene scene = enclosure();
    scene.meshes.clear();
    Sphere sphere;
    sphere.objectToWorld = glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, -0.2f, 0.05f));
    scene.spheres.push_back(sphere);
    return scene;
}

// Vertex merging in the furnace: merges join every strategy of BDPT, so the weights must still sum
// to one for each path. A round's light subpaths are shared by every pixel's merges, so pixels are
// not independent and the image's own variance understates the mean's: the standard error comes
// from the spread of the rounds' image means instead (each round's subpaths are its own; one
// renderer, so the kernel is built once per case).
TEST_F(Furnace, VertexMergingConvergesToTheAnalyticRadiance) {
    struct VcmCase {
        const char* name;
        bool nee, mis, rr;
        uint32_t maxDepth;
    };
    const VcmCase cases[] = {
        {"vcm", true, true, true, 8},
        {"vcm, no mis", true, false, false, 5},
    };
    Camera camera;
    camera.position = glm::vec3(0.0f);
    camera.yfov = 1.5f;
    constexpr int kRounds = 24;
    for (const auto& c : cases) {
        IntegratorSettings s = independentSettings();
        s.estimator = Estimator::VertexMerging;
        s.nee = c.nee;
        s.mis = c.mis;
        s.rr = c.rr;
        s.maxDepth = c.maxDepth;
        s.rrStartDepth = 2;
        s.mergeRadius = 1.0f; // pixel footprints at the scene radius: 0.04 here
        const Scene scene = sphereEnclosure();
        ASSERT_TRUE(computeFeatures(flattenScene(scene), s).merging) << c.name;
        s.seed = 1000u;
        FlatScene flat = flattenScene(scene);
        Renderer renderer(
            sharedContext(), flat, suiteFeatures(flat, s), s, camera, FilmSettings{40, 40, scene.background});
        std::vector<double> means; // of each round alone
        double before = 0;         // the sum of the rounds' means so far
        for (int k = 1; k <= kRounds; ++k) {
            renderer.addSamples(1, 0);
            const Renderer::Readback r = renderer.read();
            EXPECT_EQ(r.droppedSamples, 0u) << c.name;
            const double sum = imageMean(r).mean * k;
            means.push_back(sum - before);
            before = sum;
        }
        const double mean = std::accumulate(means.begin(), means.end(), 0.0) / kRounds;
        double spread = 0;
        for (double m : means) spread += (m - mean) * (m - mean);
        const double standardError = std::sqrt(spread / (kRounds - 1) / kRounds);
        const double expected = expectedRadiance(c.maxDepth);
        std::printf(
            "[          ] %s: mean %.5f, expected %.5f, standard error %.5f\n", c.name, mean, expected, standardError);
        EXPECT_NEAR(mean, expected, 4.0 * standardError + 2e-5 * expected) << c.name;
    }
}

// Russian roulette is unbiased whatever its threshold: paths below it survive with probability
// throughput / threshold and are reweighted. From throughput 1 (always on) to 4 (most paths
// thinned from the second bounce on), the furnace stays exact.
TEST_F(Furnace, RussianRouletteThresholdsKeepTheFurnaceExact) {
    Camera camera;
    camera.position = glm::vec3(0.0f);
    camera.yfov = 1.5f;
    for (float threshold : {0.25f, 1.0f, 4.0f}) {
        IntegratorSettings s = independentSettings();
        s.nee = false; // BSDF sampling only: every path length is decided by the roulette
        s.maxDepth = 64;
        s.rrStartDepth = 2;
        s.rrThreshold = threshold;
        auto r = renderScene(enclosure(), s, camera, 32, 32, 64);
        EXPECT_EQ(r.droppedSamples, 0u);
        Stats st = imageMean(r);
        const double expected = expectedRadiance(s.maxDepth);
        EXPECT_NEAR(st.mean, expected, 4.0 * st.standardError + 2e-5 * expected)
            << "threshold " << threshold << " (standard error " << st.standardError << ")";
    }
}

TEST_F(Furnace, WrongAlbedoIsDetected) {
    // Negative control: the same comparison against a slightly different albedo must fail.
    IntegratorSettings s = independentSettings();
    s.maxDepth = 64;
    Camera camera;
    camera.position = glm::vec3(0.0f);
    auto r = renderScene(enclosure(), s, camera, 32, 32, 64);
    Stats st = imageMean(r);
    const double wrong = kEmission / (1.0 - 0.51);
    EXPECT_GT(std::abs(st.mean - wrong), 4.0 * st.standardError + 2e-5 * wrong);
}

// A clear glass sphere (no absorption) under a uniform white sky neither absorbs nor emits:
// every path leaves it again, so the whole image is the sky's radiance, 1, up to the paths
// still trapped by total internal reflection at the depth limit. Smooth glass exactly (each
// refraction's 1/eta^2 is undone on the way out); rough glass loses only GGX's single-scattering
// energy: 1.1% on average for alpha 0.04, up to 12% at grazing silhouette pixels.
TEST_F(Furnace, GlassSphereInAWhiteSkyIsInvisible) {
    for (float roughness : {0.0f, 0.2f}) {
        Scene scene;
        Material glass;
        glass.type = MaterialType::Dielectric;
        glass.ior = 1.5f;
        glass.roughness = roughness;
        glass.baseColor = glm::vec3(1.0f); // untinted
        scene.materials.push_back(glass);
        Sphere ball;
        ball.material = 0;
        scene.spheres.push_back(ball);
        Environment sky;
        sky.colour = glm::vec3(1.0f);
        scene.environment = sky;
        Camera camera;
        camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
        camera.yfov = 0.75f; // the sphere fills most of the image
        IntegratorSettings s = independentSettings();
        s.maxDepth = 64;
        const Renderer::Readback r = renderScene(scene, s, camera, 24, 24, 64);
        EXPECT_EQ(r.droppedSamples, 0u);
        const Stats st = imageMean(r);
        double lowest = 1e9;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 24; ++x) lowest = std::min(lowest, double(r.mean.at(x, y)[0]));
        std::printf("glass roughness %.1f: image mean %.5f +- %.5f, lowest pixel %.4f\n", roughness, st.mean,
            st.standardError, lowest);
        if (roughness == 0.0f) {
            EXPECT_NEAR(st.mean, 1.0, 4 * st.standardError + 2e-3);
            EXPECT_GT(lowest, 0.97);
        } else {
            EXPECT_LE(st.mean, 1.0 + 4 * st.standardError);
            EXPECT_GT(st.mean, 0.97);
        }
    }
}

} // namespace
} // namespace pt::test
