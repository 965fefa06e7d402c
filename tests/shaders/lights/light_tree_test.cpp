// The light tree (src/lights/light_tree.h, shaders/lights/light_tree.glsl) on a box with many
// lights of every bounded kind and a sky: the lights it chooses follow the pmf it gives them
// (chi-square over lights, and the same pmf per sample), those pmfs sum to one, a light it never
// chooses is one that cannot light the point, and the image is the power CDF's.
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "film/metrics.h"
#include "render/gpu_scene.h"
#include "scene/scene_loader.h"
#include "support/gpu_test_support.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

namespace pt::test {
namespace {

std::filesystem::path diffuseBox() { return testDataDir() / "references" / "cbox-diffuse" / "scene.gltf"; }

// The diffuse box (its ceiling light kept) with 24 small emissive triangles of random sizes,
// orientations and colours inside, a third of them double-sided; an emissive sphere and an
// ellipsoid; a point, a spot and a square light; and a faint sky through nothing (the box is
// closed), which only the tree's share and the CDF's tail see.
Scene manyLightsBox() {
    Scene scene = loadScene(diffuseBox());
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Mesh& m : scene.meshes)
        for (const glm::vec3& p : m.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    const glm::vec3 size = hi - lo;
    auto inside = [&] {
        return lo + size * glm::vec3(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng));
    };
    for (int k = 0; k < 24; ++k) {
        Material m;
        m.name = "small light " + std::to_string(k);
        m.baseColor = glm::vec3(0.0f);
        m.emission = glm::vec3(0.5f + 4.0f * u(rng), 0.5f + 4.0f * u(rng), 0.5f + 4.0f * u(rng));
        m.doubleSided = k % 3 == 0;
        scene.materials.push_back(m);
        Mesh tri;
        tri.name = "small light " + std::to_string(k);
        const glm::vec3 c = inside();
        const float r = 0.02f * glm::length(size) * (0.3f + u(rng));
        for (int v = 0; v < 3; ++v)
            tri.positions.push_back(c + r * glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)));
        tri.triangles = {{0, 1, 2}};
        tri.material = static_cast<uint32_t>(scene.materials.size() - 1);
        scene.meshes.push_back(tri);
    }
    Material glow;
    glow.baseColor = glm::vec3(0.0f);
    glow.emission = glm::vec3(3.0f, 2.0f, 1.0f);
    scene.materials.push_back(glow);
    const uint32_t glowIndex = static_cast<uint32_t>(scene.materials.size() - 1);
    Sphere ball;
    ball.objectToWorld =
        glm::translate(glm::mat4(1.0f), inside()) * glm::scale(glm::mat4(1.0f), glm::vec3(0.03f * size.x));
    ball.material = glowIndex;
    Sphere ellipsoid;
    ellipsoid.objectToWorld = glm::translate(glm::mat4(1.0f), inside()) *
                              glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 0, 1)) *
                              glm::scale(glm::mat4(1.0f), size * glm::vec3(0.05f, 0.02f, 0.03f));
    ellipsoid.material = glowIndex;
    scene.spheres = {ball, ellipsoid};
    PunctualLight point;
    point.position = inside();
    point.intensity = glm::vec3(0.05f);
    PunctualLight spot;
    spot.type = PunctualLight::Type::Spot;
    spot.position = inside();
    spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
    spot.intensity = glm::vec3(0.2f);
    spot.cosFalloff = std::cos(0.3f);
    spot.cosCoverage = std::cos(0.5f);
    PunctualLight square;
    square.type = PunctualLight::Type::Square;
    square.position = inside();
    square.direction = glm::normalize(glm::vec3(-1.0f, 0.2f, 0.5f));
    square.intensity = glm::vec3(1.0f);
    square.size = 0.05f * size.x;
    scene.punctualLights = {point, spot, square};
    Environment sky;
    sky.colour = glm::vec3(0.1f);
    scene.environment = sky;
    return scene;
}

struct Uploaded {
    FlatScene flat;
    std::unique_ptr<GpuScene> gpu;
};

Uploaded upload(const Scene& scene) {
    Uploaded u;
    u.flat = flattenScene(scene);
    u.gpu = std::make_unique<GpuScene>(sharedContext(), u.flat, gpu::GpuSceneParams{}, 0);
    return u;
}

// Whether light `index` could light point x at all (a one-sided triangle with x behind its
// plane, or a spot with x outside its cone, cannot).
bool couldLight(const FlatScene& flat, uint32_t index, glm::vec3 x) {
    const gpu::GpuLight& light = flat.lights.lights[index];
    if (light.type == LIGHT_TRIANGLE) {
        const gpu::GpuTriangle& t = flat.triangles[light.primitive];
        if ((flat.materials[t.materialIndex].flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u) return true;
        const glm::dvec3 n = glm::cross(glm::dvec3(t.p1 - t.p0), glm::dvec3(t.p2 - t.p0));
        return glm::dot(n, glm::dvec3(x) - glm::dvec3(t.p0)) > 0.0;
    }
    if (light.type == LIGHT_SPOT)
        return glm::dot(glm::normalize(x - light.position), light.direction) > light.cosCoverage;
    return true;
}

class LightTree : public GpuTest {};

// At points on the floor, the walls, in mid-air (no normal) and among the lights: each light's
// pmf from its trail, the lights chosen by descending the tree (200,000 per point), and the pmf
// each choice carries.
TEST_F(LightTree, ChoicesFollowThePmfOfEachLight) {
    const Uploaded scene = upload(manyLightsBox());
    const FlatScene& flat = scene.flat;
    ASSERT_FALSE(flat.lights.tree.nodes.empty());
    const uint32_t numLights = static_cast<uint32_t>(flat.lights.lights.size());
    ASSERT_EQ(numLights, 2u + 24u + 2u + 3u + 1u); // the ceiling's two triangles ... the sky
    EXPECT_EQ(flat.lights.lights.back().type, LIGHT_ENVIRONMENT);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const gpu::GpuTriangle& t : flat.triangles) {
        lo = glm::min(lo, glm::min(t.p0, glm::min(t.p1, t.p2)));
        hi = glm::max(hi, glm::max(t.p0, glm::max(t.p1, t.p2)));
    }
    const glm::vec3 size = hi - lo;
    struct At {
        const char* what;
        glm::vec3 x, n;
    };
    const At points[] = {
        {"floor", lo + size * glm::vec3(0.3f, 0.001f, 0.6f), {0, 1, 0}},
        {"left wall", lo + size * glm::vec3(0.001f, 0.7f, 0.4f), {1, 0, 0}},
        {"mid-air, no normal", lo + size * glm::vec3(0.5f, 0.5f, 0.5f), {0, 0, 0}},
        {"tilted, among the lights", lo + size * glm::vec3(0.62f, 0.45f, 0.3f), glm::normalize(glm::vec3(1, 2, -1))},
    };
    for (const At& at : points) {
        std::vector<glm::vec4> pmfOut =
            runTestKernel(TEST_MODE_LIGHT_SELECTION_PMF, numLights, scene.gpu.get(), {}, at.x, at.n);
        std::vector<double> pmf(numLights);
        double sum = 0;
        int never = 0;
        for (uint32_t i = 0; i < numLights; ++i) {
            pmf[i] = pmfOut[i].x;
            sum += pmf[i];
            if (pmf[i] == 0.0) {
                ++never;
                EXPECT_FALSE(couldLight(flat, i, at.x))
                    << at.what << ": light " << i << " has pmf 0 but can light the point";
            }
            if (flat.lights.lights[i].type == LIGHT_ENVIRONMENT) EXPECT_EQ(pmfOut[i].x, flat.lights.lights[i].pmf);
        }
        // Where both children of a node hold no light that can reach the point, the descent
        // stops without a light: the pmfs may sum to less than one, by that chance.
        EXPECT_LE(sum, 1.0 + 1e-5) << at.what;

        const uint32_t n = 200000;
        const std::vector<glm::vec4> choices =
            runTestKernel(TEST_MODE_LIGHT_CHOICE, n, scene.gpu.get(), {}, at.x, at.n, 3u);
        // The last bin: no light chosen.
        std::vector<double> observed(numLights + 1, 0.0), expected(numLights + 1);
        size_t wrongPmf = 0;
        for (const glm::vec4& c : choices) {
            uint32_t index;
            std::memcpy(&index, &c.x, sizeof index);
            if (index == NO_LIGHT) {
                observed[numLights] += 1.0;
                EXPECT_EQ(c.y, 0.0f);
                continue;
            }
            ASSERT_LT(index, numLights) << at.what;
            observed[index] += 1.0;
            if (std::abs(c.y - pmf[index]) > 1e-6 * pmf[index]) ++wrongPmf;
        }
        EXPECT_EQ(wrongPmf, 0u) << at.what << ": a choice's pmf differs from its light's";
        for (uint32_t i = 0; i < numLights; ++i) expected[i] = n * pmf[i];
        expected[numLights] = n * std::max(0.0, 1.0 - sum);
        int dof = 0;
        const double p = chiSquarePValue(observed, expected, &dof);
        std::printf("[          ] %s: pmfs sum to %.7f, %d of %u lights never chosen, chi-square p %.3f (%d dof)\n",
            at.what, sum, never, numLights, p, dof);
        EXPECT_GT(p, 1e-3) << at.what;
    }
}

// The box scaled by `s`: every position, sphere and square light; point and spot intensities by s^2,
// so that every light's power scales alike and the lights' pmfs stay what they were.
Scene scaled(Scene scene, float s) {
    for (Mesh& m : scene.meshes)
        for (glm::vec3& p : m.positions) p *= s;
    for (Sphere& sphere : scene.spheres)
        sphere.objectToWorld = glm::scale(glm::mat4(1.0f), glm::vec3(s)) * sphere.objectToWorld;
    for (PunctualLight& l : scene.punctualLights) {
        l.position *= s;
        l.size *= s;
        if (l.type == PunctualLight::Type::Point || l.type == PunctualLight::Type::Spot) l.intensity *= s * s;
    }
    return scene;
}

// Huge and tiny coordinates (a hard case): the box at 1e-6 and 1e6 of its size gives every light
// the pmf it has at size 1, from the same points scaled: the importance measures distances in
// units of the scene, where squared distances neither underflow nor overflow float.
TEST_F(LightTree, PmfsAreTheSameAtEveryScale) {
    const Scene box = manyLightsBox();
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Mesh& m : box.meshes)
        for (const glm::vec3& p : m.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    const glm::vec3 x = lo + (hi - lo) * glm::vec3(0.3f, 0.01f, 0.6f), n = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
    std::vector<float> atOne;
    for (float s : {1.0f, 1e-6f, 1e6f}) {
        const Uploaded scene = upload(scaled(box, s));
        const uint32_t numLights = static_cast<uint32_t>(scene.flat.lights.lights.size());
        ASSERT_EQ(numLights, 32u) << "scale " << s << ": every light kept";
        ASSERT_FALSE(scene.flat.lights.tree.nodes.empty()) << s;
        const std::vector<glm::vec4> out =
            runTestKernel(TEST_MODE_LIGHT_SELECTION_PMF, numLights, scene.gpu.get(), {}, x * s, n);
        double sum = 0, worst = 0;
        for (uint32_t i = 0; i < numLights; ++i) {
            sum += out[i].x;
            if (s == 1.0f)
                atOne.push_back(out[i].x);
            else
                worst = std::max(worst, double(std::abs(out[i].x - atOne.at(i))));
        }
        std::printf("[          ] scale %g: pmfs sum to %.7f, largest difference from scale 1: %.2e\n", s, sum, worst);
        EXPECT_NEAR(sum, 1.0, 1e-4) << s;
        EXPECT_LT(worst, 1e-5) << "scale " << s;
    }
}

// Two renders of one scene agree block by block (8x8-pixel means, z-tests).
void expectSameImage(const char* what, const Renderer::Readback& a, const Renderer::Readback& b) {
    const AgreementResult r =
        compareBlocks(blockStats(a.mean, &a.varianceOfMean, 8), blockStats(b.mean, &b.varianceOfMean, 8));
    std::printf("[          ] %s: chi2/dof %.3f, mean z %+.3f, max |z| %.2f, mean rel diff %.4f\n", what, r.chi2PerDof,
        r.meanZ, r.maxAbsZ, r.meanRelDiff);
    EXPECT_LT(r.chi2PerDof, 1.6);
    EXPECT_LT(std::abs(r.meanZ), 0.5);
}

// The same box rendered with light selection by the tree and by power alone (other seeds), with
// MIS against BSDF rays that hit the small lights: the images agree block by block.
TEST_F(LightTree, RendersTheImageThePowerCdfRenders) {
    const Scene scene = manyLightsBox();
    IntegratorSettings s = independentSettings();
    s.estimator = Estimator::Path;
    s.maxDepth = 5;
    s.lightSelection = LightSelection::Tree;
    const FlatScene flat = flattenScene(scene);
    ASSERT_TRUE(computeFeatures(flat, s).lightTree);
    const Camera& camera = scene.cameras.at(0);
    const Renderer::Readback tree = renderScene(scene, s, camera, 32, 32, 512);
    s.lightSelection = LightSelection::Power;
    s.seed = 17;
    ASSERT_FALSE(computeFeatures(flat, s).lightTree);
    const Renderer::Readback power = renderScene(scene, s, camera, 32, 32, 512);
    expectSameImage("tree vs power", tree, power);
}

// BDPT's light sampling chooses by the tree while its light subpaths start from lights chosen by
// power: MIS weighs each strategy by the selection that made it (the tree's pmf at the camera
// vertex that samples the light, the table's at the light subpath's start). A weight taken
// with the wrong pmf shifts the image against the path tracer's with the power CDF.
TEST_F(LightTree, BidirectionalWithTheTreeRendersThePathTracersImage) {
    const Scene scene = manyLightsBox();
    IntegratorSettings s = independentSettings();
    s.estimator = Estimator::Bidirectional;
    s.maxDepth = 5;
    s.lightSelection = LightSelection::Tree;
    const FlatScene flat = flattenScene(scene);
    const FeatureSet bdptFeatures = computeFeatures(flat, s);
    ASSERT_TRUE(bdptFeatures.bdpt && bdptFeatures.lightTree) << bdptFeatures.describe();
    const Camera& camera = scene.cameras.at(0);
    const Renderer::Readback bdpt = renderScene(scene, s, camera, 32, 32, 256);
    s.estimator = Estimator::Path;
    s.lightSelection = LightSelection::Power;
    s.seed = 23;
    const Renderer::Readback path = renderScene(scene, s, camera, 32, 32, 1024);
    expectSameImage("bdpt with the tree vs path", bdpt, path);
}

} // namespace
} // namespace pt::test
