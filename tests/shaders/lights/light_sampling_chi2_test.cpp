// The light samplers (shaders/lights/: the light table's triangles, cone- and area-sampled sphere
// lights, the environment map) against the pdf the integrator gives BSDF rays that reach a light,
// by chi-square over directions (support/sampling_chi2.h) and per sample.
#include <glm/gtc/matrix_transform.hpp>
#include "support/sampling_chi2.h"

#include <algorithm>
#include <memory>

namespace pt::test {
namespace {

// ---- Light sampling ----

// Four single-sided emitters around the shading point, all different in power (radiance x area),
// size and orientation. They sit in different directions so none hides another from the point.
// The quad below faces away: its samples carry no radiance but still have a pdf. With
// `equalRadiance` all emit the same, which changes only the light-selection CDF.
pt::Scene lightScene(bool equalRadiance) {
    pt::Scene scene;
    scene.source = "light sampling test";
    const glm::vec3 radiance[4] = {{4, 4, 4}, {1.0f, 0.5f, 0.2f}, {2, 2, 2}, {20, 2, 1}};
    for (int k = 0; k < 4; ++k) {
        pt::Material m;
        m.name = "light " + std::to_string(k);
        m.baseColor = glm::vec3(0.0f);
        m.emission = equalRadiance ? glm::vec3(1.0f) : radiance[k];
        scene.materials.push_back(m);
    }
    using pt::test::makeQuad;
    // Overhead, facing down at the point.
    scene.meshes.push_back(makeQuad({-0.5f, -0.6f, 2.0f}, {0.0f, 1.2f, 0.0f}, {1.0f, 0.0f, 0.0f}, 0));
    // A large tilted quad on the +x side, facing the point.
    scene.meshes.push_back(makeQuad({2.5f, -1.5f, -1.0f}, {-0.8f, 0.0f, 2.0f}, {0.0f, 3.0f, 0.0f}, 1));
    // A quad on the -y side, facing away (its normal points along -y).
    scene.meshes.push_back(makeQuad({-0.8f, -1.5f, -0.6f}, {0.0f, 0.0f, 1.0f}, {1.4f, 0.0f, 0.3f}, 2));
    // A small bright triangle low on the -x side, facing the point.
    pt::Mesh tri;
    tri.name = "small light";
    tri.positions = {{-1.5f, 0.3f, -1.2f}, {-1.2f, 0.9f, -1.0f}, {-1.6f, 0.8f, -0.5f}};
    tri.triangles = {{0, 1, 2}};
    tri.material = 3;
    scene.meshes.push_back(tri);
    return scene;
}
const glm::vec3 kShadingPoint(0.1f, -0.2f, 0.05f);

struct LightTestScene {
    pt::FlatScene flat;
    std::unique_ptr<pt::GpuScene> gpu;
};

LightTestScene uploadScene(const pt::Scene& scene) {
    LightTestScene s;
    s.flat = pt::flattenScene(scene);
    s.gpu = std::make_unique<pt::GpuScene>(pt::test::sharedContext(), s.flat, pt::gpu::GpuSceneParams{}, 0);
    return s;
}

// `lightTree` false: selection by the power CDF alone (the light tree's own tests:
// light_tree_test.cpp).
LightTestScene uploadLightScene(bool equalRadiance, bool lightTree = true) {
    LightTestScene s;
    s.flat = pt::flattenScene(lightScene(equalRadiance));
    if (!lightTree) s.flat.lights.tree = {};
    s.gpu = std::make_unique<pt::GpuScene>(pt::test::sharedContext(), s.flat, pt::gpu::GpuSceneParams{}, 0);
    return s;
}

// TEST_MODE_LIGHT_PDF: the solid-angle pdf the integrator assigns to a BSDF ray from the shading
// point in each direction (0 where it reaches no light).
std::vector<float> lightPdfs(const pt::GpuScene& scene, const std::vector<glm::vec4>& directions) {
    const std::vector<glm::vec4> out =
        pt::test::runTestKernel(TEST_MODE_LIGHT_PDF, static_cast<uint32_t>(directions.size()), &scene,
            std::as_bytes(std::span<const glm::vec4>(directions)), kShadingPoint);
    std::vector<float> pdfs(out.size());
    for (size_t i = 0; i < out.size(); ++i) pdfs[i] = out[i].x;
    return pdfs;
}

// Midpoint rule over sub x sub directions inside each listed bin: returns each bin's integral of
// the pdf, and whether the pdf was zero at some midpoints and not at others.
struct BinIntegrals {
    std::vector<double> integral;
    std::vector<bool> mixed, lit;
};
BinIntegrals integrateBins(
    const pt::GpuScene& scene, const DirectionGrid& grid, const std::vector<int>& bins, int sub) {
    std::vector<glm::vec4> dirs;
    dirs.reserve(bins.size() * sub * sub);
    const double dz = grid.dz() / sub, dphi = grid.dphi() / sub;
    for (int bin : bins) {
        const int zi = bin / grid.phiBins, pi = bin % grid.phiBins;
        for (int a = 0; a < sub; ++a)
            for (int b = 0; b < sub; ++b)
                dirs.emplace_back(
                    directionAt(grid.zLo + zi * grid.dz() + (a + 0.5) * dz, pi * grid.dphi() + (b + 0.5) * dphi), 0.0f);
    }
    const std::vector<float> pdf = lightPdfs(scene, dirs);
    BinIntegrals r{
        std::vector<double>(bins.size(), 0.0), std::vector<bool>(bins.size()), std::vector<bool>(bins.size())};
    for (size_t k = 0; k < bins.size(); ++k) {
        int nonZero = 0;
        for (int j = 0; j < sub * sub; ++j) {
            const float p = pdf[k * sub * sub + j];
            r.integral[k] += p * dz * dphi;
            nonZero += p > 0.0f;
        }
        r.mixed[k] = nonZero > 0 && nonZero < sub * sub;
        r.lit[k] = nonZero > 0;
    }
    return r;
}

// Expected counts of `n` light samples per bin: the light pdf integrated over each bin, by an
// 8 x 8 midpoint rule, redone at 64 x 64 in bins near a light's outline (where the pdf jumps
// and a coarse rule could miss a sliver of light entirely, predicting zero where samples land).
std::vector<double> expectedFromLightPdf(const pt::GpuScene& scene, const DirectionGrid& grid, double n) {
    std::vector<int> all(grid.count());
    for (int b = 0; b < grid.count(); ++b) all[b] = b;
    const BinIntegrals coarse = integrateBins(scene, grid, all, 8);
    std::vector<int> refine;
    for (int zi = 0; zi < grid.zBins; ++zi)
        for (int pi = 0; pi < grid.phiBins; ++pi) {
            const int bin = grid.index(zi, pi);
            bool nearOutline = coarse.mixed[bin];
            for (int dz = -1; dz <= 1; ++dz)
                for (int dp = -1; dp <= 1; ++dp) {
                    const int z = zi + dz;
                    if (z < 0 || z >= grid.zBins) continue;
                    const int other = grid.index(z, (pi + dp + grid.phiBins) % grid.phiBins);
                    nearOutline = nearOutline || coarse.mixed[other] || coarse.lit[other] != coarse.lit[bin];
                }
            if (nearOutline) refine.push_back(bin);
        }
    const BinIntegrals fine = integrateBins(scene, grid, refine, 64);
    std::vector<double> expected(grid.count());
    for (int b = 0; b < grid.count(); ++b) expected[b] = n * coarse.integral[b];
    for (size_t k = 0; k < refine.size(); ++k) expected[refine[k]] = n * fine.integral[k];
    return expected;
}

double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
}

// Whether the ray from `origin` along `dir` meets an emitting triangle of `flat` on one of its
// edges (all barycentrics at least -1e-5, the least within 1e-5 of 0), in double precision.
bool meetsALightEdge(const pt::FlatScene& flat, glm::dvec3 origin, glm::dvec3 dir) {
    for (const pt::gpu::GpuTriangle& t : flat.triangles) {
        if (t.lightIndex == NO_LIGHT) continue;
        const glm::dvec3 p0(t.p0), e1 = glm::dvec3(t.p1) - p0, e2 = glm::dvec3(t.p2) - p0;
        const glm::dvec3 pv = glm::cross(dir, e2);
        const double det = glm::dot(e1, pv);
        if (det == 0.0) continue;
        const glm::dvec3 tv = origin - p0;
        const double u = glm::dot(tv, pv) / det;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double v = glm::dot(dir, qv) / det;
        const double w = 1.0 - u - v, least = std::min({u, v, w});
        if (glm::dot(e2, qv) / det > 0.0 && least >= -1e-5 && least <= 1e-5) return true;
    }
    return false;
}

// sampleLight's directions against the pdf the integrator uses for BSDF rays that hit lights:
// same distribution (chi-square), same pdf per sample (MIS weights need both techniques to
// agree on it), and a pdf that integrates to one over the sphere.
void checkLightSampling(const LightTestScene& scene) {
    const std::vector<double> expected = expectedFromLightPdf(*scene.gpu, kSphere, kSamples);
    EXPECT_NEAR(sum(expected) / kSamples, 1.0, 0.01) << "the light pdf should integrate to 1 over the sphere";
    std::printf("[          ] integral of the light pdf over the sphere: %.5f\n", sum(expected) / kSamples);

    for (uint32_t seed : {1u, 7u}) {
        const std::vector<glm::vec4> samples = pt::test::runTestKernel(
            TEST_MODE_LIGHT_SAMPLE, kSamples, scene.gpu.get(), {}, kShadingPoint, glm::vec3(0, 0, 1), seed);
        std::vector<glm::vec4> dirs(samples.size());
        for (size_t i = 0; i < samples.size(); ++i) dirs[i] = glm::vec4(glm::vec3(samples[i]), 0.0f);
        const std::vector<float> pdfAtSample = lightPdfs(*scene.gpu, dirs);
        // A direction on the edge between two triangles of a quad (or on a light's outline) may be
        // traced into the neighbour (or past the outline) and get its pdf: a tie, rare.
        size_t mismatched = 0, edgeTies = 0;
        for (size_t i = 0; i < samples.size(); ++i) {
            const float sampled = samples[i].w;
            const bool ok = sampled > 0.0f && std::abs(pdfAtSample[i] - sampled) <= 1e-3f * sampled;
            if (ok) continue;
            if (meetsALightEdge(scene.flat, glm::dvec3(kShadingPoint), glm::dvec3(glm::vec3(dirs[i])))) {
                ++edgeTies;
                continue;
            }
            if (++mismatched <= 5)
                ADD_FAILURE() << "seed " << seed << " sample " << i << " direction (" << dirs[i].x << ", " << dirs[i].y
                              << ", " << dirs[i].z << "): sampleLight pdf " << sampled
                              << ", light pdf of that direction " << pdfAtSample[i];
        }
        EXPECT_EQ(mismatched, 0u);
        EXPECT_LE(edgeTies, samples.size() / 2000) << "seed " << seed;
        std::printf("[          ] seed %u: %zu of %zu samples on an edge traced into a neighbour\n", seed, edgeTies,
            samples.size());
        const std::string what = "light sampling seed " + std::to_string(seed);
        EXPECT_GT(pValue(histogram(kSphere, samples), expected, what.c_str()), kMinPValue);
    }
}

// Chosen by the light tree (seven lights: it has one), and by power alone.
TEST_F(SamplingTest, LightSamplingMatchesTheLightPdf) {
    for (bool lightTree : {true, false}) {
        const LightTestScene scene = uploadLightScene(false, lightTree);
        ASSERT_EQ(scene.flat.lights.lights.size(), 7u);
        ASSERT_EQ(scene.flat.lights.tree.nodes.empty(), !lightTree);
        checkLightSampling(scene);
    }
}

pt::Sphere transformedSphere(glm::vec3 centre, float angle, glm::vec3 radii, uint32_t material) {
    pt::Sphere s;
    s.objectToWorld = glm::translate(glm::mat4(1.0f), centre) *
                      glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 0, 1)) * glm::scale(glm::mat4(1.0f), radii);
    s.material = material;
    return s;
}

// Round spheres seen from outside are sampled in the cone they subtend; they share the table
// with a triangle light.
TEST_F(SamplingTest, ConeSampledSphereLightsMatchTheLightPdf) {
    pt::Scene scene = lightScene(false);
    scene.meshes.resize(1); // keep the overhead quad
    scene.spheres.push_back(transformedSphere({2.0f, 0.5f, 0.3f}, 0.0f, glm::vec3(0.7f), 1));
    scene.spheres.push_back(transformedSphere({-1.5f, -1.0f, -0.5f}, 0.3f, glm::vec3(0.4f), 3));
    const LightTestScene uploaded = uploadScene(scene);
    ASSERT_EQ(uploaded.flat.lights.lights.size(), 4u);
    for (const auto& l : uploaded.flat.lights.lights)
        if (l.type == LIGHT_SPHERE) EXPECT_GT(l.radius, 0.0f) << "round one-sided spheres are sampled by cone";
    checkLightSampling(uploaded);
}

// Ellipsoids (and spheres emitting inwards) are sampled by area through the unit-sphere map.
// From inside, every direction meets the surface exactly once, so the directional pdf is the
// per-point pdf converted to solid angle. (From outside, a direction meets two points; the
// per-point pdf is still what MIS needs, but a directional histogram would see their sum.)
TEST_F(SamplingTest, AreaSampledEllipsoidLightMatchesTheLightPdfFromInside) {
    pt::Scene scene = lightScene(false);
    scene.meshes.clear();
    scene.materials[2].doubleSided = true;
    scene.spheres.push_back(
        transformedSphere(kShadingPoint + glm::vec3(0.3f, -0.2f, 0.1f), 0.7f, {1.5f, 0.6f, 0.9f}, 2));
    const LightTestScene uploaded = uploadScene(scene);
    ASSERT_EQ(uploaded.flat.lights.lights.size(), 1u);
    EXPECT_EQ(uploaded.flat.lights.lights[0].radius, 0.0f);
    checkLightSampling(uploaded);
}

// The environment map's 2D piecewise-constant sampling, with bright texels on a pole row and on
// the seam, rotated: samples land in texels with the probabilities of the host's CDF tables
// (chi-square in texel space, where the distribution is exactly piecewise constant), each
// sample's pdf is the pdf escaping BSDF rays get for that direction, and that pdf integrates to 1.
TEST_F(SamplingTest, EnvironmentSamplingMatchesItsPdf) {
    pt::Scene scene;
    scene.source = "environment sampling test";
    pt::Environment env;
    const int W = 16, H = 8;
    env.image.width = W;
    env.image.height = H;
    env.image.rgba.assign(W * H * 4, 0.3f);
    for (int c = 0; c < 3; ++c) {
        env.image.at(5, 0)[c] = 40.0f; // top row: touches the pole
        env.image.at(0, 4)[c] = 20.0f; // first column: on the seam
        env.image.at(11, 6)[c] = 5.0f;
    }
    env.rotationDegrees = 40.0f;
    scene.environment = env;
    const LightTestScene uploaded = uploadScene(scene);
    ASSERT_EQ(uploaded.flat.lights.lights.size(), 1u);
    const pt::FlatEnvironment& fe = uploaded.flat.environment;
    const double angle = glm::radians(40.0);
    auto texelOf = [&](glm::vec3 d) {
        // World to the map's frame (rotation about +y), then the course's lat-long mapping.
        const double x = std::cos(angle) * d.x - std::sin(angle) * d.z,
                     z = std::sin(angle) * d.x + std::cos(angle) * d.z;
        const double u = 0.5 * (1.0 + std::atan2(x, -z) / M_PI), v = std::acos(std::clamp<double>(d.y, -1, 1)) / M_PI;
        return std::min(H - 1, int(v * H)) * W + std::min(W - 1, int(u * W));
    };
    std::vector<double> expected(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            expected[y * W + x] = kSamples * double(fe.marginal[y + 1] - fe.marginal[y]) *
                                  double(fe.conditional[y * (W + 1) + x + 1] - fe.conditional[y * (W + 1) + x]);

    const auto samples =
        pt::test::runTestKernel(TEST_MODE_LIGHT_SAMPLE, kSamples, uploaded.gpu.get(), {}, kShadingPoint);
    std::vector<double> observed(W * H, 0.0);
    std::vector<glm::vec4> dirs;
    for (const auto& s : samples) {
        observed[texelOf(glm::vec3(s))] += 1;
        dirs.emplace_back(glm::vec3(s), 0.0f);
    }
    EXPECT_GT(pValue(observed, expected, "environment texels"), kMinPValue);

    const std::vector<float> pdfAtSample = lightPdfs(*uploaded.gpu, dirs);
    size_t mismatched = 0;
    for (size_t i = 0; i < samples.size(); ++i)
        mismatched += !(samples[i].w > 0.0f && std::abs(pdfAtSample[i] - samples[i].w) <= 1e-3f * samples[i].w);
    EXPECT_EQ(mismatched, 0u) << "samples whose pdf differs from the pdf of their direction";

    // Integral over the sphere: the pdf times sin(theta) is constant inside each texel.
    std::vector<glm::vec4> centres;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double theta = M_PI * (y + 0.5) / H, phi = M_PI * (2.0 * (x + 0.5) / W - 1.0);
            const glm::dvec3 local(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            const glm::dvec3 world(std::cos(angle) * local.x + std::sin(angle) * local.z, local.y,
                -std::sin(angle) * local.x + std::cos(angle) * local.z);
            centres.emplace_back(glm::vec3(world), 0.0f);
        }
    const std::vector<float> pdfAtCentres = lightPdfs(*uploaded.gpu, centres);
    double integral = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            integral += pdfAtCentres[y * W + x] * std::sin(M_PI * (y + 0.5) / H) * (M_PI / H) * (2 * M_PI / W);
    EXPECT_NEAR(integral, 1.0, 1e-4);
}

// Negative control for the light test: the same samples against the pdf of the same emitters with
// equal radiance (so chosen by area instead of power) must be rejected; the test sees the CDF.
TEST_F(SamplingTest, LightChiSquareRejectsTheWrongSelectionCdf) {
    const LightTestScene scene = uploadLightScene(false, false);
    const LightTestScene byArea = uploadLightScene(true, false);
    const std::vector<glm::vec4> samples =
        pt::test::runTestKernel(TEST_MODE_LIGHT_SAMPLE, kSamples, scene.gpu.get(), {}, kShadingPoint);
    const double p = pValue(histogram(kSphere, samples), expectedFromLightPdf(*byArea.gpu, kSphere, kSamples),
        "light samples vs area-proportional pdf (must fail)");
    EXPECT_LT(p, 1e-6);
}

} // namespace
} // namespace pt::test
