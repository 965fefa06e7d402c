// Two scenes of our own for the glTF material model, each against a high-spp reference of our
// own (tests/references/own/, made by the DISABLED_ test below) and cross-checked between two
// independent estimators, next event estimation on and off:
//  - "textured": an sRGB checker floor, a normal-mapped wall, a sphere whose metalness and
//    roughness come from a texture, lit by a textured emissive panel and a dim sky;
//  - "rough-glass": a GGX-rough glass sphere (alpha 0.09) with Beer-Lambert absorption on the
//    checker floor under the panel.
// A wrong texture decode, tangent frame, emissive lookup in light sampling, or rough-glass pdf
// makes NEE on and off disagree (or both disagree with the reference).
#include "support/gpu_test_support.h"

#include "image/image_io.h"
#include "film/metrics.h"

#include <algorithm>
#include <cmath>

namespace pt::test {
namespace {

TextureImage checker(int n, uint32_t a, uint32_t b) {
    TextureImage img;
    img.width = img.height = n;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) img.rgba8.push_back(((x + y) % 2 ? a : b) | 0xff000000u);
    return img;
}

// Tangent-space normals of a corrugated surface: ridges along v, tilting +-0.5 in x.
TextureImage ridges(int n) {
    TextureImage img;
    img.width = img.height = n;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float tilt = 0.5f * std::sin(6.2831853f * 4.0f * (x + 0.5f) / n);
            const glm::vec3 nrm = glm::normalize(glm::vec3(tilt, 0.0f, 1.0f));
            const auto byte = [](float c) { return static_cast<uint32_t>(std::lround((c * 0.5f + 0.5f) * 255.0f)); };
            img.rgba8.push_back(byte(nrm.x) | byte(nrm.y) << 8 | byte(nrm.z) << 16 | 0xff000000u);
        }
    return img;
}

Mesh uvQuad(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, uint32_t material, float repeat) {
    Mesh m = makeQuad(corner, edgeU, edgeV, material);
    m.uvs = {{0, repeat}, {repeat, repeat}, {repeat, 0}, {0, 0}};
    return m;
}

Scene commonStage(Scene& scene) {
    scene.textureImages.push_back(checker(8, 0x00d0d0d0u, 0x00303060u)); // image 0
    Texture srgb;
    srgb.encoding = Texture::Encoding::Srgb;
    scene.textures.push_back(srgb); // texture 0: the checker, sRGB
    Material floor;
    floor.baseColor = glm::vec3(1.0f);
    floor.baseColorTexture = 0;
    scene.materials.push_back(floor); // material 0
    scene.meshes.push_back(uvQuad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 0, 2.0f));
    // The panel light: emissive, its emission modulated by the checker (sampled lights must
    // look the texture up too).
    Material panel;
    panel.baseColor = glm::vec3(0.0f);
    panel.emission = glm::vec3(6.0f);
    panel.emissiveTexture = 0;
    scene.materials.push_back(panel); // material 1
    scene.meshes.push_back(
        uvQuad({-0.6f, 2.5f, -0.6f}, {1.2f, 0, 0}, {0, 0, 1.2f}, 1, 1.0f)); // (1,0,0) x (0,0,1): faces down
    // A back wall, so that no pixel sees the (noise-free) sky directly.
    Material wall;
    wall.baseColor = glm::vec3(0.6f, 0.5f, 0.4f);
    scene.materials.push_back(wall); // material 2
    scene.meshes.push_back(uvQuad({-2, 0, -1.5f}, {4, 0, 0}, {0, 2.5f, 0}, 2, 1.0f));
    Environment sky;
    sky.colour = glm::vec3(0.05f);
    scene.environment = sky;
    return scene;
}

Scene texturedScene() {
    Scene scene;
    commonStage(scene);
    scene.textureImages.push_back(ridges(16)); // image 1
    Texture normals;
    normals.image = 1;
    scene.textures.push_back(normals); // texture 1
    // Metal-roughness: the checker's channels as G = roughness, B = metallic (linear).
    Texture mr;
    scene.textures.push_back(mr);         // texture 2: image 0, linear
    scene.materials[2].normalTexture = 1; // the back wall, corrugated
    Material sphere;
    sphere.type = MaterialType::Pbr;
    sphere.baseColor = glm::vec3(0.9f, 0.6f, 0.3f);
    sphere.metallic = 1.0f;
    sphere.roughness = 0.8f;
    sphere.metallicRoughnessTexture = 2;
    scene.materials.push_back(sphere); // material 3
    Mesh ball = makeIcosphere(3, glm::vec3(0.3f, 0.6f, 0.0f), 0.6f, 3);
    for (const glm::vec3& p : ball.positions) {
        const glm::vec3 d = glm::normalize(p - glm::vec3(0.3f, 0.6f, 0.0f));
        ball.uvs.emplace_back(
            0.5f + std::atan2(d.z, d.x) / 6.2831853f, std::acos(std::clamp(d.y, -1.0f, 1.0f)) / 3.1415927f);
    }
    scene.meshes.push_back(ball);
    return scene;
}

Scene roughGlassScene() {
    Scene scene;
    commonStage(scene);
    Material glass;
    glass.type = MaterialType::Dielectric;
    glass.ior = 1.5f;
    glass.roughness = 0.3f; // alpha 0.09
    glass.attenuationColor = glm::vec3(0.8f, 0.9f, 1.0f);
    glass.attenuationDistance = 1.0f;
    scene.materials.push_back(glass); // material 3
    scene.meshes.push_back(makeIcosphere(4, glm::vec3(0.0f, 0.7f, 0.0f), 0.7f, 3));
    return scene;
}

Camera stageCamera() {
    Camera c;
    c.position = glm::vec3(0.0f, 1.6f, 3.6f);
    c.forward = glm::normalize(glm::vec3(0.0f, 0.6f, 0.0f) - c.position);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, glm::vec3(0, 1, 0)), c.forward));
    c.yfov = 0.75f;
    return c;
}

constexpr int kSize = 48;

Renderer::Readback render(const Scene& scene, bool nee, uint32_t spp) {
    IntegratorSettings s = independentSettings();
    s.nee = nee;
    s.maxDepth = 12;
    return renderScene(scene, s, stageCamera(), kSize, kSize, spp);
}

// Light sampling with MIS (seed 1, sppOn samples) against BSDF sampling alone (seed 2, sppOff),
// compared in blocks of 8x8 pixels.
struct EstimatorAgreement {
    Renderer::Readback on, off;
    AgreementResult blocks;
};

EstimatorAgreement lightSamplingAgainstBsdfSampling(const Scene& scene, IntegratorSettings s, const Camera& camera,
    int width, int height, uint32_t sppOn, uint32_t sppOff) {
    EstimatorAgreement r;
    s.seed = 1;
    r.on = renderScene(scene, s, camera, width, height, sppOn);
    s.nee = s.mis = false;
    s.seed = 2;
    r.off = renderScene(scene, s, camera, width, height, sppOff);
    r.blocks =
        compareBlocks(blockStats(r.on.mean, &r.on.varianceOfMean, 8), blockStats(r.off.mean, &r.off.varianceOfMean, 8));
    return r;
}

std::filesystem::path referencePath(const std::string& name) {
    return testDataDir() / "references" / "own" / (name + ".exr");
}

void checkAgainstReference(const std::string& name, const Scene& scene, uint32_t sppNee, uint32_t sppNoNee) {
    const Renderer::Readback on = render(scene, true, sppNee);
    const Renderer::Readback off = render(scene, false, sppNoNee);
    EXPECT_EQ(on.droppedSamples + off.droppedSamples, 0u);
    const Image reference = readExr(referencePath(name));
    const auto statsOn = blockStats(on.mean, &on.varianceOfMean, 8);
    const auto statsOff = blockStats(off.mean, &off.varianceOfMean, 8);
    const auto statsRef = blockStats(reference, nullptr, 8);
    const AgreementResult onOff = compareBlocks(statsOn, statsOff);
    const AgreementResult onRef = compareBlocks(statsOn, statsRef);
    const AgreementResult offRef = compareBlocks(statsOff, statsRef);
    std::printf("%s: NEE on vs off chi2/dof %.2f (mean z %.2f), on vs reference %.2f, off vs reference %.2f\n",
        name.c_str(), onOff.chi2PerDof, onOff.meanZ, onRef.chi2PerDof, offRef.chi2PerDof);
    for (const AgreementResult& r : {onOff, onRef, offRef}) {
        EXPECT_LT(r.chi2PerDof, 2.0);
        EXPECT_LT(std::abs(r.meanZ), 0.35);
    }
}

class OwnScenes : public GpuTest {};

TEST_F(OwnScenes, TexturedSceneAgreesAcrossEstimatorsAndWithItsReference) {
    checkAgainstReference("textured", texturedScene(), 256, 1024);
}

TEST_F(OwnScenes, RoughGlassAgreesAcrossEstimatorsAndWithItsReference) {
    checkAgainstReference("rough-glass", roughGlassScene(), 256, 1024);
}

// The panel light as a grid of 6 x 6 quads under an emission texture that is black but for two
// texels (bilinear, so light bleeds a little past them): the light table weighs each triangle by
// the texture over it, and the triangles whose lookups are all black leave it
// (lights/texture_emission.h). Light there is found by BSDF samples only and counts fully, so
// NEE on and off must still agree, block by block.
TEST_F(OwnScenes, PatchyEmitterWhoseBlackTrianglesLeaveTheTableAgreesAcrossEstimators) {
    Scene scene;
    commonStage(scene);
    TextureImage patches;
    patches.width = patches.height = 8;
    patches.rgba8.assign(64, 0xff000000u);
    patches.rgba8[9] = patches.rgba8[46] = 0xffffffffu; // texels (1, 1) and (6, 5)
    scene.textureImages.push_back(patches);
    Texture emission;
    emission.image = static_cast<uint32_t>(scene.textureImages.size() - 1);
    emission.encoding = Texture::Encoding::Srgb;
    scene.textures.push_back(emission);
    const uint32_t panel = 1;
    scene.materials[panel].emissiveTexture = static_cast<uint32_t>(scene.textures.size() - 1);
    scene.materials[panel].emission = glm::vec3(30.0f);
    auto it =
        std::find_if(scene.meshes.begin(), scene.meshes.end(), [&](const Mesh& m) { return m.material == panel; });
    ASSERT_NE(it, scene.meshes.end());
    scene.meshes.erase(it);
    const int n = 6;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Mesh m =
                makeQuad({-0.6f + 1.2f * i / n, 2.5f, -0.6f + 1.2f * j / n}, {1.2f / n, 0, 0}, {0, 0, 1.2f / n}, panel);
            const float u0 = float(i) / n, u1 = float(i + 1) / n, v0 = float(j) / n, v1 = float(j + 1) / n;
            m.uvs = {{u0, v1}, {u1, v1}, {u1, v0}, {u0, v0}};
            scene.meshes.push_back(m);
        }
    const FlatScene flat = flattenScene(scene);
    size_t emitting = 0;
    for (const auto& t : flat.triangles) emitting += t.materialIndex == panel;
    ASSERT_EQ(emitting, size_t(2 * n * n));
    size_t inTable = 0;
    for (const auto& t : flat.triangles) inTable += t.materialIndex == panel && t.lightIndex != NO_LIGHT;
    std::printf("[          ] patchy panel: %zu of %zu triangles in the light table\n", inTable, emitting);
    EXPECT_GT(inTable, 0u);
    EXPECT_LT(inTable, emitting / 2) << "most of the panel is black";

    IntegratorSettings s = independentSettings();
    s.maxDepth = 12;
    const auto [on, off, a] = lightSamplingAgainstBsdfSampling(scene, s, stageCamera(), kSize, kSize, 256, 1024);
    std::printf("[          ] patchy panel: NEE on vs off chi2/dof %.2f (mean z %.2f)\n", a.chi2PerDof, a.meanZ);
    EXPECT_LT(a.chi2PerDof, 2.0);
    EXPECT_LT(std::abs(a.meanZ), 0.35);
}

// A leaf lit only from behind (KHR_materials_diffuse_transmission, thin): the camera sees the
// light that crosses it, which light sampling must reach from the leaf's dark side through the
// transmissive frame. NEE on and off agree block by block, and the leaf glows.
TEST_F(OwnScenes, LeafLitFromBehindAgreesAcrossEstimators) {
    Scene scene;
    Material leaf;
    leaf.type = MaterialType::Pbr;
    leaf.baseColor = glm::vec3(0.3f, 0.6f, 0.2f);
    leaf.roughness = 0.6f;
    leaf.diffuseTransmission = 0.7f;
    leaf.diffuseTransmissionColor = glm::vec3(0.6f, 0.9f, 0.3f);
    leaf.thinWalled = true;
    scene.materials.push_back(leaf);
    Material lamp;
    lamp.baseColor = glm::vec3(0.0f);
    lamp.emission = glm::vec3(8.0f);
    scene.materials.push_back(lamp);
    scene.meshes.push_back(makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));              // faces +z, the camera
    scene.meshes.push_back(makeQuad({-0.4f, -0.4f, -1}, {0.8f, 0, 0}, {0, 0.8f, 0}, 1)); // behind, facing the leaf
    Camera camera;
    camera.position = glm::vec3(0, 0, 3);
    camera.forward = glm::vec3(0, 0, -1);
    camera.up = glm::vec3(0, 1, 0);
    camera.yfov = 0.5f;
    const FlatScene flat = flattenScene(scene);
    IntegratorSettings s = independentSettings();
    s.maxDepth = 8;
    EXPECT_NE(computeFeatures(flat, s).describe().find("diffuse-transmission"), std::string::npos);
    const auto [on, off, a] = lightSamplingAgainstBsdfSampling(scene, s, camera, 32, 32, 256, 2048);
    double mean = 0;
    for (size_t i = 1; i < on.mean.rgba.size(); i += 4) mean += on.mean.rgba[i] / (on.mean.rgba.size() / 4);
    std::printf("[          ] leaf lit from behind: NEE on vs off chi2/dof %.2f (mean z %.2f), mean green %.4f\n",
        a.chi2PerDof, a.meanZ, mean);
    EXPECT_LT(a.chi2PerDof, 2.0);
    EXPECT_LT(std::abs(a.meanZ), 0.35);
    EXPECT_GT(mean, 0.05) << "the leaf passes the light through";
    EXPECT_EQ(on.droppedSamples + off.droppedSamples, 0u);
}

// Makes the references (run by hand: --gtest_also_run_disabled_tests --gtest_filter='*MakeReferences').
TEST_F(OwnScenes, DISABLED_MakeReferences) {
    std::filesystem::create_directories(referencePath("x").parent_path());
    for (auto [name, scene] : {std::pair{std::string("textured"), texturedScene()},
             std::pair{std::string("rough-glass"), roughGlassScene()}}) {
        const Renderer::Readback r = render(scene, true, 32768);
        writeExr(referencePath(name), r.mean,
            {{"spp", "32768"}, {"made-by", "tests/shaders/integrator/own_scenes_test.cpp DISABLED_MakeReferences"}});
    }
}

// Two spheres under a lamp: a velvet (sheen over a red base) under a rough clearcoat, and a blue
// brushed (anisotropic) half metal under a sheen and a smooth (delta) coat. Light sampling (MIS with the layered pdf)
// and BSDF sampling alone agree block by block, so every layer's eval, pdf and samples agree in
// the integrator; the kernel is specialised to both layers.
TEST(OwnScenesLayers, ClearcoatAndSheenAgreeAcrossEstimators) {
    Scene scene;
    Material velvet;
    velvet.type = MaterialType::Pbr;
    velvet.baseColor = glm::vec3(0.6f, 0.1f, 0.1f);
    velvet.roughness = 0.7f;
    velvet.sheenColor = glm::vec3(0.9f, 0.8f, 0.7f);
    velvet.sheenRoughness = 0.4f;
    velvet.clearcoat = 0.7f;
    velvet.clearcoatRoughness = 0.3f;
    scene.materials.push_back(velvet);
    Material paint = velvet;
    paint.baseColor = glm::vec3(0.1f, 0.2f, 0.7f);
    paint.metallic = 0.5f;
    paint.roughness = 0.4f;
    paint.sheenColor = glm::vec3(0.3f);
    paint.sheenRoughness = 0.8f;
    paint.clearcoat = 1.0f;
    paint.clearcoatRoughness = 0.0f;
    paint.anisotropy = 0.8f; // brushed, along the sphere's tangents turned by 0.5 rad
    paint.anisotropyRotation = 0.5f;
    scene.materials.push_back(paint);
    Material lamp;
    lamp.baseColor = glm::vec3(0.0f);
    lamp.emission = glm::vec3(6.0f);
    scene.materials.push_back(lamp);
    Material floor;
    floor.baseColor = glm::vec3(0.5f);
    scene.materials.push_back(floor);
    scene.meshes.push_back(makeIcosphere(4, {-0.55f, 0, 0}, 0.5f, 0));
    scene.meshes.push_back(makeIcosphere(4, {0.55f, 0, 0}, 0.5f, 1));
    scene.meshes.push_back(makeQuad({-0.6f, 1.5f, -0.6f}, {1.2f, 0, 0}, {0, 0, 1.2f}, 2)); // faces down
    scene.meshes.push_back(makeQuad({-3, -0.5f, 3}, {6, 0, 0}, {0, 0, -6}, 3));            // faces up
    Camera camera;
    camera.position = glm::vec3(0, 0.4f, 3);
    camera.forward = glm::normalize(glm::vec3(0, -0.2f, -1));
    camera.up = glm::vec3(0, 1, 0);
    camera.yfov = 0.6f;
    const FlatScene flat = flattenScene(scene);
    IntegratorSettings s = independentSettings();
    s.maxDepth = 6;
    const std::string features = computeFeatures(flat, s).describe();
    EXPECT_NE(features.find("clearcoat"), std::string::npos) << features;
    EXPECT_NE(features.find("sheen"), std::string::npos) << features;
    const auto [on, off, a] = lightSamplingAgainstBsdfSampling(scene, s, camera, 32, 32, 512, 4096);
    double left = 0, right = 0; // mean red of the velvet's half, blue of the paint's
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 16; ++x) {
            left += on.mean.rgba[4 * (y * 32 + x)] / 512.0;
            right += on.mean.rgba[4 * (y * 32 + x + 16) + 2] / 512.0;
        }
    std::printf(
        "[          ] coated velvet and paint: NEE on vs off chi2/dof %.2f (mean z %.2f), red %.3f, blue %.3f\n",
        a.chi2PerDof, a.meanZ, left, right);
    EXPECT_GT(left, 0.02) << "the velvet is lit";
    EXPECT_GT(right, 0.02) << "the paint is lit";
    EXPECT_LT(a.chi2PerDof, 2.0);
    EXPECT_LT(std::abs(a.meanZ), 0.35);
    EXPECT_EQ(on.droppedSamples + off.droppedSamples, 0u);
}

// A brushed metal floor seen from above, lit by a small lamp: the highlight stretches along the
// anisotropy direction, the tangent (+x here, the uv's u) at rotation 0 and the bitangent (z in
// the image's y) at rotation pi/2. Measured by the highlight's second moments in the image.
TEST(OwnScenesLayers, AnisotropicHighlightStretchesAlongTheRotatedTangent) {
    auto spread = [](float rotation) {
        Scene scene;
        Material brushed;
        brushed.type = MaterialType::Pbr;
        brushed.baseColor = glm::vec3(0.9f);
        brushed.metallic = 1.0f;
        brushed.roughness = 0.15f;
        brushed.anisotropy = 0.9f;
        brushed.anisotropyRotation = rotation;
        scene.materials.push_back(brushed);
        Material lamp;
        lamp.baseColor = glm::vec3(0.0f);
        lamp.emission = glm::vec3(50.0f);
        scene.materials.push_back(lamp);
        Mesh floor = makeQuad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 0); // faces +y; u along +x
        floor.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
        scene.meshes.push_back(floor);
        scene.meshes.push_back(makeQuad({0.2f, 2.0f, 0.2f}, {0.2f, 0, 0}, {0, 0, 0.2f}, 1)); // faces down
        Camera camera;
        camera.position = glm::vec3(0, 2.5f, 0);
        camera.forward = glm::vec3(0, -1, 0);
        camera.up = glm::vec3(0, 0, -1);
        camera.yfov = 0.9f;
        IntegratorSettings s = independentSettings();
        s.maxDepth = 2;
        const Renderer::Readback r = renderScene(scene, s, camera, 64, 64, 64);
        double w = 0, mx = 0, my = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const float* p = &r.mean.rgba[4 * (y * 64 + x)];
                const double v = p[0] + p[1] + p[2];
                w += v;
                mx += v * x;
                my += v * y;
            }
        mx /= w;
        my /= w;
        double vx = 0, vy = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const float* p = &r.mean.rgba[4 * (y * 64 + x)];
                const double v = p[0] + p[1] + p[2];
                vx += v * (x - mx) * (x - mx) / w;
                vy += v * (y - my) * (y - my) / w;
            }
        EXPECT_GT(w, 0.0);
        return vx / vy;
    };
    const double along = spread(0.0f), across = spread(float(M_PI / 2));
    std::printf("[          ] brushed floor: highlight spread x / y %.2f at rotation 0, %.2f at pi/2\n", along, across);
    EXPECT_GT(along, 2.0) << "stretched along the tangent (image x)";
    EXPECT_LT(across, 0.5) << "stretched along the bitangent (image y)";
}

// A closed triangular prism, its edges along x, cross-section (y, z) corners a, b, c
// (counter-clockwise seen from +x, so the faces point outwards).
Mesh makePrism(glm::vec2 a, glm::vec2 b, glm::vec2 c, float halfLength, uint32_t material) {
    Mesh m;
    m.name = "prism";
    for (float x : {-halfLength, halfLength})
        for (glm::vec2 p : {a, b, c}) m.positions.emplace_back(x, p.x, p.y);
    // 0-2 at -x, 3-5 at +x
    m.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
    m.material = material;
    return m;
}

// Dispersive glass (KHR_materials_dispersion) under a uniform white sky: glass neither absorbs
// nor emits, so every path ends in the sky and the image is white on average (the wavelength
// weights' mean is 1 in each channel), as without dispersion; a smooth dielectric and a glTF
// transmission with a volume both.
TEST(OwnScenesLayers, DispersiveGlassUnderAWhiteSkyStaysWhiteOnAverage) {
    for (MaterialType type : {MaterialType::Dielectric, MaterialType::Pbr}) {
        Scene scene;
        Material glass;
        glass.type = type;
        glass.baseColor = glm::vec3(1.0f);
        glass.ior = 1.6f;
        glass.dispersion = 3.0f; // an Abbe number of 6.7: far more than any glass
        glass.transmission = 1.0f;
        glass.metallic = 0.0f;
        glass.roughness = 0.0f;
        glass.specular = glm::vec3(1.0f);
        glass.thinWalled = false;
        scene.materials.push_back(glass);
        scene.meshes.push_back(makeIcosphere(3, {0, 0, 0}, 1.0f, 0));
        Environment sky;
        sky.colour = glm::vec3(1.0f);
        scene.environment = sky;
        Camera camera;
        camera.position = glm::vec3(0, 0, 3);
        camera.yfov = 0.7f;
        IntegratorSettings s = independentSettings();
        s.maxDepth = 64;
        const FlatScene flat = flattenScene(scene);
        const std::string features = computeFeatures(flat, s).describe();
        EXPECT_NE(features.find("dispersion"), std::string::npos) << features;
        const Renderer::Readback r = renderScene(scene, s, camera, 24, 24, 256);
        glm::dvec3 mean(0.0), spread(0.0);
        const size_t n = r.mean.rgba.size() / 4;
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                mean[c] += r.mean.rgba[4 * i + c] / n;
                spread[c] += std::abs(r.mean.rgba[4 * i + c] - r.mean.rgba[4 * i + 1]) / n;
            }
        std::printf("[          ] dispersive %s sphere under a white sky: mean %.4f %.4f %.4f, mean |channel - "
                    "green| %.3f %.3f\n",
            type == MaterialType::Pbr ? "glTF transmission" : "dielectric", mean.x, mean.y, mean.z, spread.x, spread.z);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 1.0, 0.015) << "channel " << c;
        EXPECT_EQ(r.droppedSamples, 0u);
    }
}

// A glass prism in front of a wall lit in its lower part: the wall's bright edge, seen through
// the prism, is bent by the glass, the blue more than the red with dispersion (a higher index at
// short wavelengths) and both alike without. (Measured: rows 11 and 17 of 48 with dispersion 2,
// 16 and 16 without.)
TEST(OwnScenesLayers, PrismBendsBlueMoreThanRed) {
    auto edgeRows = [](float dispersion) {
        Scene scene;
        Material glass;
        glass.type = MaterialType::Dielectric;
        glass.baseColor = glm::vec3(1.0f);
        glass.ior = 1.5f;
        glass.dispersion = dispersion;
        scene.materials.push_back(glass);
        Material wall;
        wall.baseColor = glm::vec3(0.0f);
        wall.emission = glm::vec3(1.0f);
        scene.materials.push_back(wall);
        scene.meshes.push_back(makePrism({0.8f, -3.0f}, {-0.6f, -2.2f}, {-0.6f, -3.8f}, 3.0f, 0));
        scene.meshes.push_back(makeQuad({-20, -40, -12}, {40, 0, 0}, {0, 40 - 6.0f, 0}, 1)); // faces +z
        Camera camera;
        camera.yfov = 0.5f;
        IntegratorSettings s = independentSettings();
        s.maxDepth = 8;
        const Renderer::Readback r = renderScene(scene, s, camera, 48, 48, 64);
        // Rows (from the top) where red and blue first exceed half brightness, centre column.
        glm::dvec2 rows(-1.0);
        for (int c = 0; c < 2; ++c)
            for (int y = 0; y < 48; ++y) {
                double v = 0;
                for (int x = 20; x < 28; ++x) v += r.mean.rgba[4 * (y * 48 + x) + (c == 0 ? 0 : 2)] / 8.0;
                if (v > 0.5) {
                    rows[c] = y;
                    break;
                }
            }
        return rows;
    };
    const glm::dvec2 with = edgeRows(2.0f), without = edgeRows(0.0f);
    std::printf("[          ] prism: edge row red %.0f blue %.0f with dispersion, %.0f %.0f without\n", with.x, with.y,
        without.x, without.y);
    ASSERT_GE(with.x, 0.0);
    ASSERT_GE(with.y, 0.0);
    ASSERT_GE(without.x, 0.0);
    // The prism's apex is up, so it bends the view down onto the lit part of the wall: the more it
    // bends a colour, the higher in the image that colour's edge appears.
    EXPECT_LT(with.y, with.x - 3) << "blue bent more than red";
    EXPECT_NEAR(without.x, without.y, 1.0) << "no dispersion: one edge";
}

// glTF specular-glossiness: its texture's alpha is glossiness, roughness = 1 - glossiness x alpha.
// A sphere whose texture says glossiness 0.4 renders as one of roughness 0.6 without a texture,
// and unlike one whose texture says 0.9.
TEST(OwnScenesLayers, SpecularGlossinessTextureAlphaIsGlossiness) {
    auto render = [](int alphaByte, float roughness) {
        Scene scene;
        Material m;
        m.type = MaterialType::Pbr;
        m.baseColor = glm::vec3(0.3f, 0.4f, 0.5f);
        m.ior = 1.5f;
        m.specular = glm::vec3(0.08f / 0.04f);
        m.roughness = roughness;
        if (alphaByte >= 0) {
            TextureImage img;
            img.width = img.height = 1;
            img.rgba8 = {0x00ffffffu | (uint32_t(alphaByte) << 24)};
            scene.textureImages.push_back(img);
            Texture t;
            t.image = 0;
            t.encoding = Texture::Encoding::Srgb;
            scene.textures.push_back(t);
            m.specularTexture = m.metallicRoughnessTexture = 0u;
            m.glossinessTexture = true;
            m.glossiness = 1.0f;
        }
        scene.materials.push_back(m);
        Material lamp;
        lamp.baseColor = glm::vec3(0.0f);
        lamp.emission = glm::vec3(10.0f);
        scene.materials.push_back(lamp);
        Mesh ball = makeIcosphere(3, {0, 0, 0}, 1.0f, 0);
        scene.meshes.push_back(ball);
        scene.meshes.push_back(makeQuad({-0.3f, 2.0f, 1.0f}, {0.6f, 0, 0}, {0, 0, 0.6f}, 1)); // faces down
        Camera camera;
        camera.position = glm::vec3(0, 0, 3.5f);
        camera.yfov = 0.7f;
        IntegratorSettings s = independentSettings();
        s.maxDepth = 3;
        return renderScene(scene, s, camera, 32, 32, 64);
    };
    const Renderer::Readback textured = render(102, 0.0f), plain = render(-1, 0.6f), glossier = render(230, 0.0f);
    double same = 0, other = 0, total = 0;
    for (size_t i = 0; i < plain.mean.rgba.size(); ++i) {
        same += std::abs(textured.mean.rgba[i] - plain.mean.rgba[i]);
        other += std::abs(glossier.mean.rgba[i] - plain.mean.rgba[i]);
        total += std::abs(plain.mean.rgba[i]);
    }
    std::printf("[          ] specular-glossiness: |glossiness 0.4 texture - roughness 0.6| / |image| %.2e, "
                "|glossiness 0.9 texture - roughness 0.6| / |image| %.3f\n",
        same / total, other / total);
    ASSERT_GT(total, 0.0);
    EXPECT_LT(same / total, 1e-3);
    EXPECT_GT(other / total, 0.01); // measured 0.020: the highlight is a small part of the image
}

} // namespace
} // namespace pt::test
