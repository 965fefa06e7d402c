// buildLightTable on hand-made triangle arrays: selection pmf proportional to emitted power
// (luminance x area, x2 double-sided), a well-formed CDF whose differences are the pmf to the
// last bit, light indices written back into the triangles, and the degenerate cases.
#include "lights/light_table.h"
#include "flatten/flat_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

namespace {

using pt::LightTable;
using pt::Material;
using pt::gpu::GpuTriangle;

constexpr uint32_t kGarbage = 0xdeadbeefu; // lightIndex before the call: must be overwritten

double luminance(const glm::vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// A right triangle in the z = `z` plane with legs a (along x) and b (along y): area a*b/2.
GpuTriangle rightTriangle(float a, float b, uint32_t material, float z = 0.0f, glm::vec3 offset = glm::vec3(0.0f)) {
    GpuTriangle t{};
    t.p0 = offset + glm::vec3(0, 0, z);
    t.p1 = offset + glm::vec3(a, 0, z);
    t.p2 = offset + glm::vec3(0, b, z);
    t.materialIndex = material;
    t.lightIndex = kGarbage;
    t.flags = 0;
    return t;
}

double triangleArea(const GpuTriangle& t) {
    return 0.5 * glm::length(glm::dvec3(glm::cross(t.p1 - t.p0, t.p2 - t.p0)));
}

Material diffuse(glm::vec3 albedo = glm::vec3(0.5f)) {
    Material m;
    m.name = "diffuse";
    m.baseColor = albedo;
    return m;
}

Material emitter(glm::vec3 emission, bool doubleSided) {
    Material m;
    m.name = doubleSided ? "emitter (two-sided)" : "emitter";
    m.baseColor = glm::vec3(0.0f);
    m.emission = emission;
    m.doubleSided = doubleSided;
    return m;
}

// Expected power of every triangle (0 for non-emitters and zero-area emitters).
std::vector<double> expectedPower(const std::vector<GpuTriangle>& tris, const std::vector<Material>& mats) {
    std::vector<double> p;
    for (const auto& t : tris) {
        const Material& m = mats[t.materialIndex];
        const double a = triangleArea(t);
        p.push_back(m.emissive() && a > 0 ? M_PI * luminance(m.emission) * a * (m.doubleSided ? 2.0 : 1.0) : 0.0);
    }
    return p;
}

// Every structural invariant of a table built over `tris`. With a wide range of powers a light
// whose share is below float resolution near cdf = 1 (~6e-8) legitimately gets pmf 0 (the CDF
// search never picks it, and MIS then gives its BSDF hits full weight), so `positivePmf` is only
// asked of tables with comparable powers.
void checkInvariants(const LightTable& table, const std::vector<GpuTriangle>& tris, bool positivePmf = true) {
    ASSERT_EQ(table.cdf.size(), table.lights.size() + 1);
    EXPECT_EQ(table.cdf.front(), 0.0f);
    if (!table.lights.empty()) EXPECT_EQ(table.cdf.back(), 1.0f);
    for (size_t k = 0; k < table.lights.size(); ++k) {
        EXPECT_LE(table.cdf[k], table.cdf[k + 1]) << "cdf not monotone at " << k;
        // Exactly what the kernel's CDF search selects with.
        EXPECT_EQ(table.lights[k].pmf, table.cdf[k + 1] - table.cdf[k]) << "light " << k;
        if (positivePmf) EXPECT_GT(table.lights[k].pmf, 0.0f) << "light " << k;
        EXPECT_GE(table.lights[k].pmf, 0.0f) << "light " << k;
        ASSERT_LT(table.lights[k].primitive, tris.size());
        EXPECT_EQ(tris[table.lights[k].primitive].lightIndex, k) << "light " << k << " is not linked back";
        EXPECT_FLOAT_EQ(table.lights[k].area, static_cast<float>(triangleArea(tris[table.lights[k].primitive])));
    }
    // Every triangle is either a light that points back to itself, or NO_LIGHT.
    size_t linked = 0;
    for (size_t i = 0; i < tris.size(); ++i) {
        if (tris[i].lightIndex == NO_LIGHT) continue;
        ASSERT_LT(tris[i].lightIndex, table.lights.size()) << "triangle " << i;
        EXPECT_EQ(table.lights[tris[i].lightIndex].primitive, i) << "triangle " << i;
        ++linked;
    }
    EXPECT_EQ(linked, table.lights.size());
}

TEST(LightTable, PmfIsProportionalToLuminanceTimesAreaAndDoubledForTwoSided) {
    const std::vector<Material> mats = {
        diffuse(),                                              // 0
        emitter(glm::vec3(1.0f), false),                        // 1: luminance 1
        emitter(glm::vec3(2.0f, 0.5f, 0.25f), true),            // 2: two-sided
        emitter(glm::vec3(0.0f, 0.0f, 3.0f), false),            // 3: blue only
        emitter(glm::vec3(18.387f, 13.9873f, 6.75357f), false), // 4: the Cornell box light
    };
    std::vector<GpuTriangle> tris = {
        rightTriangle(1, 1, 0),                // 0: wall
        rightTriangle(1, 2, 1),                // 1: area 1
        rightTriangle(2, 3, 0, 1.0f),          // 2: wall
        rightTriangle(0.5f, 0.5f, 2),          // 3: area 0.125, two-sided
        rightTriangle(4, 1, 3, -2.0f),         // 4: area 2, blue
        rightTriangle(0.47f, 0.38f, 4, 0.99f), // 5: ceiling light
        rightTriangle(1, 1, 1, 5.0f),          // 6: same material as 1, area 0.5
    };
    const std::vector<double> power = expectedPower(tris, mats);
    double total = 0;
    for (double p : power) total += p;

    LightTable table = pt::buildLightTable(tris, mats);
    checkInvariants(table, tris);
    ASSERT_EQ(table.lights.size(), 5u);
    EXPECT_NEAR(table.totalPower, total, 1e-6 * total);

    std::map<uint32_t, float> pmfOfTriangle;
    for (const auto& l : table.lights) pmfOfTriangle[l.primitive] = l.pmf;
    for (uint32_t i = 0; i < tris.size(); ++i) {
        if (power[i] == 0) {
            EXPECT_EQ(tris[i].lightIndex, NO_LIGHT) << "triangle " << i << " is not emissive";
            EXPECT_EQ(pmfOfTriangle.count(i), 0u) << "triangle " << i;
        } else {
            ASSERT_EQ(pmfOfTriangle.count(i), 1u) << "emissive triangle " << i << " missing from the table";
            EXPECT_NEAR(pmfOfTriangle[i], power[i] / total, 1e-6) << "triangle " << i;
        }
    }
    // Spot checks of the proportionality by hand: triangle 6 has half the area of triangle 1.
    EXPECT_NEAR(pmfOfTriangle[6] / pmfOfTriangle[1], 0.5, 1e-5);
    // Triangle 3: luminance 2*0.2126 + 0.5*0.7152 + 0.25*0.0722, area 0.125, two-sided.
    const double lum3 = 2 * 0.2126 + 0.5 * 0.7152 + 0.25 * 0.0722;
    EXPECT_NEAR(pmfOfTriangle[3] / pmfOfTriangle[1], lum3 * 0.125 * 2.0 / 1.0, 1e-5);
}

TEST(LightTable, DoubleSidedDoublesThePowerOfAnOtherwiseEqualEmitter) {
    const std::vector<Material> mats = {emitter(glm::vec3(1.0f), false), emitter(glm::vec3(1.0f), true)};
    std::vector<GpuTriangle> tris = {rightTriangle(1, 1, 0), rightTriangle(1, 1, 1, 1.0f)};
    LightTable table = pt::buildLightTable(tris, mats);
    checkInvariants(table, tris);
    ASSERT_EQ(table.lights.size(), 2u);
    const float oneSided = table.lights[tris[0].lightIndex].pmf;
    const float twoSided = table.lights[tris[1].lightIndex].pmf;
    EXPECT_NEAR(oneSided, 1.0 / 3.0, 1e-6);
    EXPECT_NEAR(twoSided, 2.0 / 3.0, 1e-6);
    EXPECT_NEAR(table.totalPower, M_PI * (0.5 + 1.0), 1e-9); // power = pi x radiance x area
}

TEST(LightTable, ZeroAreaEmittersAreLeftOut) {
    const std::vector<Material> mats = {diffuse(), emitter(glm::vec3(5.0f), true)};
    GpuTriangle collinear = rightTriangle(1, 1, 1);
    collinear.p2 = glm::vec3(2, 0, 0); // on the line through p0 and p1
    GpuTriangle point = rightTriangle(1, 1, 1);
    point.p1 = point.p0;
    point.p2 = point.p0;
    std::vector<GpuTriangle> tris = {collinear, rightTriangle(1, 1, 0), point, rightTriangle(2, 2, 1, 3.0f)};
    LightTable table = pt::buildLightTable(tris, mats);
    checkInvariants(table, tris);
    ASSERT_EQ(table.lights.size(), 1u);
    EXPECT_EQ(table.lights[0].primitive, 3u);
    EXPECT_EQ(table.lights[0].pmf, 1.0f);
    EXPECT_EQ(tris[0].lightIndex, NO_LIGHT);
    EXPECT_EQ(tris[1].lightIndex, NO_LIGHT);
    EXPECT_EQ(tris[2].lightIndex, NO_LIGHT);
    EXPECT_EQ(tris[3].lightIndex, 0u);
    EXPECT_EQ(table.cdf, (std::vector<float>{0.0f, 1.0f}));
}

TEST(LightTable, OnlyZeroAreaEmittersGiveAnEmptyTable) {
    const std::vector<Material> mats = {emitter(glm::vec3(1.0f), false)};
    GpuTriangle t = rightTriangle(1, 1, 0);
    t.p2 = t.p1;
    std::vector<GpuTriangle> tris = {t};
    LightTable table = pt::buildLightTable(tris, mats);
    EXPECT_TRUE(table.lights.empty());
    EXPECT_EQ(table.cdf, std::vector<float>{0.0f});
    EXPECT_EQ(tris[0].lightIndex, NO_LIGHT);
}

TEST(LightTable, NoEmittersGiveAnEmptyTableWithCdfZero) {
    const std::vector<Material> mats = {diffuse(), diffuse(glm::vec3(0.9f, 0.1f, 0.1f))};
    std::vector<GpuTriangle> tris = {
        rightTriangle(1, 1, 0), rightTriangle(2, 1, 1, 1.0f), rightTriangle(1, 3, 0, 2.0f)};
    LightTable table = pt::buildLightTable(tris, mats);
    EXPECT_TRUE(table.lights.empty());
    EXPECT_EQ(table.cdf, std::vector<float>{0.0f});
    EXPECT_EQ(table.totalPower, 0.0);
    for (const auto& t : tris) EXPECT_EQ(t.lightIndex, NO_LIGHT);
}

TEST(LightTable, NoTrianglesAtAll) {
    const std::vector<Material> mats = {emitter(glm::vec3(1.0f), false)};
    std::vector<GpuTriangle> tris;
    LightTable table = pt::buildLightTable(tris, mats);
    EXPECT_TRUE(table.lights.empty());
    EXPECT_EQ(table.cdf, std::vector<float>{0.0f});
}

TEST(LightTable, ManyEmittersKeepTheCdfExactAndNormalised) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Material> mats = {diffuse()};
    for (int i = 0; i < 16; ++i)
        mats.push_back(emitter(glm::vec3(10 * u(rng), 10 * u(rng), 10 * u(rng)) + glm::vec3(1e-3f), (i % 3) == 0));
    std::vector<GpuTriangle> tris;
    for (int i = 0; i < 5000; ++i) {
        // Areas over six orders of magnitude; every fourth triangle is a plain wall.
        const float scale = std::pow(10.0f, -3.0f + 3.0f * u(rng));
        const uint32_t material = (i % 4 == 0) ? 0u : 1u + static_cast<uint32_t>(u(rng) * 15.99f);
        tris.push_back(rightTriangle(
            scale * (0.1f + u(rng)), scale * (0.1f + u(rng)), material, u(rng), glm::vec3(u(rng), u(rng), 0.0f)));
    }
    const std::vector<double> power = expectedPower(tris, mats);
    double total = 0;
    size_t emitters = 0;
    for (double p : power) total += p, emitters += p > 0;

    LightTable table = pt::buildLightTable(tris, mats);
    checkInvariants(table, tris, /*positivePmf=*/false);
    ASSERT_EQ(table.lights.size(), emitters);
    EXPECT_NEAR(table.totalPower, total, 1e-6 * total);
    double pmfSum = 0;
    for (const auto& l : table.lights) {
        pmfSum += l.pmf;
        // A float CDF entry near 1 is rounded by up to 6e-8, so each difference by about 1.2e-7.
        EXPECT_NEAR(l.pmf, power[l.primitive] / total, 1.5e-7 + 1e-5 * power[l.primitive] / total)
            << "triangle " << l.primitive;
    }
    EXPECT_NEAR(pmfSum, 1.0, 1e-5);
    for (size_t i = 0; i < tris.size(); ++i)
        if (power[i] == 0) EXPECT_EQ(tris[i].lightIndex, NO_LIGHT) << "triangle " << i;
}

TEST(LightTable, RebuildingOverwritesStaleLightIndices) {
    const std::vector<Material> emissive = {emitter(glm::vec3(1.0f), false)};
    const std::vector<Material> dark = {diffuse()};
    std::vector<GpuTriangle> tris = {rightTriangle(1, 1, 0), rightTriangle(1, 1, 0, 1.0f)};
    LightTable first = pt::buildLightTable(tris, emissive);
    ASSERT_EQ(first.lights.size(), 2u);
    LightTable second = pt::buildLightTable(tris, dark);
    EXPECT_TRUE(second.lights.empty());
    for (const auto& t : tris) EXPECT_EQ(t.lightIndex, NO_LIGHT);
}

} // namespace

namespace {

// A quad of two triangles over the uv rectangle [u0, u1] x [0, 1], facing +z.
pt::Mesh uvQuadMesh(float x, float u0, float u1, uint32_t material) {
    pt::Mesh m;
    m.positions = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}};
    m.uvs = {{u0, 1}, {u1, 1}, {u1, 0}, {u0, 0}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.material = material;
    return m;
}

} // namespace

// An emission texture weighs each emitting triangle by the light it gives there: over the black
// half of a 2x1 texture nothing is sampled (the triangles leave the table), over the white half
// the power is the factor's, and over a grey texel it is scaled by the texel's linear value.
TEST(LightTable, TexturedEmittersAreWeighedByTheirTextureAndBlackOnesLeave) {
    pt::Scene scene;
    pt::TextureImage image;
    image.width = 3;
    image.height = 1;
    image.source = "test";
    image.rgba8 = {0xff000000u, 0xffffffffu, 0xff808080u}; // black, white, sRGB grey 128
    scene.textureImages.push_back(image);
    pt::Texture texture;
    texture.image = 0;
    texture.encoding = pt::Texture::Encoding::Srgb;
    texture.bilinear = false;
    scene.textures.push_back(texture);
    pt::Material lamp;
    lamp.emission = glm::vec3(2.0f);
    lamp.emissiveTexture = 0;
    scene.materials.push_back(lamp);
    scene.meshes.push_back(uvQuadMesh(0, 0.02f, 0.31f, 0)); // the black texel
    scene.meshes.push_back(uvQuadMesh(2, 0.36f, 0.64f, 0)); // the white one
    scene.meshes.push_back(uvQuadMesh(4, 0.70f, 0.98f, 0)); // the grey one
    const pt::FlatScene flat = pt::flattenScene(scene);
    ASSERT_EQ(flat.triangles.size(), 6u);
    ASSERT_EQ(flat.lights.lights.size(), 4u) << "the black quad's two triangles leave the table";
    double white = 0, grey = 0;
    for (const auto& t : flat.triangles) {
        const float x = std::min({t.p0.x, t.p1.x, t.p2.x});
        if (x < 1.0f) {
            EXPECT_EQ(t.lightIndex, NO_LIGHT);
            continue;
        }
        ASSERT_NE(t.lightIndex, NO_LIGHT);
        (x < 3.0f ? white : grey) += flat.lights.lights[t.lightIndex].pmf;
    }
    const double greyLinear = std::pow((128.0 / 255 + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(grey / white, greyLinear, 1e-4);
    EXPECT_NEAR(white + grey, 1.0, 1e-6);
}

namespace pt {
namespace {

// Solid-angle sampling of triangle lights is compiled in only where some surface sees one under
// more than SPHERICAL_SAMPLING_MIN: a floor 0.4 under a square 1.5 across does (about 2.6 sr
// from its centroids' side), the same floor 6 below it does not (0.06 sr).
TEST(SphericalTriangleSampling, OnlyWhereASurfaceSeesALightLarge) {
    auto scene = [](float height) {
        std::vector<gpu::GpuTriangle> tris;
        auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t light) {
            gpu::GpuTriangle t{};
            t.p0 = a, t.p1 = b, t.p2 = c, t.lightIndex = light;
            tris.push_back(t);
        };
        add({-0.75f, height, -0.75f}, {0.75f, height, -0.75f}, {0.75f, height, 0.75f}, 0);
        add({-0.75f, height, -0.75f}, {0.75f, height, 0.75f}, {-0.75f, height, 0.75f}, 1);
        add({-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}, NO_LIGHT);
        add({-0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}, {-0.5f, 0, -0.5f}, NO_LIGHT);
        return tris;
    };
    const auto near = scene(0.4f), far = scene(6.0f);
    EXPECT_TRUE(someReceiverSeesALargeTriangleLight(near, near.size()));
    EXPECT_FALSE(someReceiverSeesALargeTriangleLight(far, far.size()));
    // Receivers beyond the world range (instanced meshes, in object space) do not count.
    EXPECT_FALSE(someReceiverSeesALargeTriangleLight(near, 2));
}

} // namespace
} // namespace pt
