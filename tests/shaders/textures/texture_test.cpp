// Textures (shaders/textures/): image lookups against an independent CPU implementation of
// the same filter, wrap and decode rules; the course's procedural patterns against their
// definitions; and end-to-end renders where the answer is known exactly (an unshaded textured
// quad and a background texture reproduce their image; flat normal and bump maps change nothing).
#include "lights/texture_emission.h"
#include "support/gpu_test_support.h"

#include <cmath>
#include <random>

namespace pt::test {
namespace {

// A small image with distinct, non-symmetric texels (so flips and offsets show).
TextureImage makeImage(int w, int h) {
    TextureImage img;
    img.width = w;
    img.height = h;
    img.source = "test";
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint32_t r = (37u * x + 11u * y + 5u) & 255u, g = (91u * y + 7u * x + 60u) & 255u;
            const uint32_t b = (13u * x * y + 200u) & 255u, a = (x + y) % 3 == 0 ? 255u : 128u;
            img.rgba8.push_back(r | g << 8 | b << 16 | a << 24);
        }
    return img;
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

int wrap(int i, int n, TextureWrap mode) {
    switch (mode) {
    case TextureWrap::Clamp: return std::clamp(i, 0, n - 1);
    case TextureWrap::Mirror: {
        int m = ((i % (2 * n)) + 2 * n) % (2 * n);
        return m < n ? m : 2 * n - 1 - m;
    }
    default: return ((i % n) + n) % n;
    }
}

glm::dvec4 texel(const TextureImage& img, const Texture& t, int x, int y) {
    const uint32_t p =
        img.rgba8[static_cast<size_t>(wrap(y, img.height, t.wrapV)) * img.width + wrap(x, img.width, t.wrapU)];
    glm::dvec4 c((p & 255u) / 255.0, (p >> 8 & 255u) / 255.0, (p >> 16 & 255u) / 255.0, (p >> 24) / 255.0);
    if (t.encoding == Texture::Encoding::Srgb)
        c = glm::dvec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a);
    if (t.encoding == Texture::Encoding::Gamma22)
        c = glm::dvec4(std::pow(c.r, 2.2), std::pow(c.g, 2.2), std::pow(c.b, 2.2), c.a);
    return c;
}

// The reference lookup: texel centres at half-integers, v = 0 at the top row.
glm::dvec4 lookup(const TextureImage& img, const Texture& t, glm::dvec2 uv) {
    const glm::dvec2 st(uv.x * img.width, uv.y * img.height);
    glm::dvec4 c;
    if (!t.bilinear) {
        c = texel(img, t, static_cast<int>(std::floor(st.x)), static_cast<int>(std::floor(st.y)));
    } else {
        const glm::dvec2 f = st - 0.5;
        const int x0 = static_cast<int>(std::floor(f.x)), y0 = static_cast<int>(std::floor(f.y));
        const double wx = f.x - x0, wy = f.y - y0;
        c = (1 - wy) * ((1 - wx) * texel(img, t, x0, y0) + wx * texel(img, t, x0 + 1, y0)) +
            wy * ((1 - wx) * texel(img, t, x0, y0 + 1) + wx * texel(img, t, x0 + 1, y0 + 1));
    }
    return glm::dvec4(glm::dvec3(c) * double(t.valueScale), c.a);
}

struct Uploaded {
    FlatScene flat;
    std::unique_ptr<GpuScene> gpu;
};

// A scene that only carries textures (the kernel needs some geometry to bind).
Uploaded upload(Scene scene) {
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeQuad(glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0));
    Uploaded u;
    u.flat = flattenScene(scene);
    u.gpu = std::make_unique<GpuScene>(sharedContext(), u.flat, gpu::GpuSceneParams{}, 0);
    return u;
}

std::vector<glm::vec4> evaluate(const Uploaded& u, uint32_t texture, const std::vector<glm::vec4>& at) {
    return runTestKernel(TEST_MODE_TEXTURE, static_cast<uint32_t>(at.size()), u.gpu.get(), std::as_bytes(std::span(at)),
        glm::vec3(0.0f), glm::vec3(0, 0, 1), 1, texture);
}

// Every filter, wrap pair and encoding (18 textures of image 0; the linear ones scaled by 2);
// with `transformBilinear`, the bilinear ones also carry a KHR_texture_transform-like uv transform.
std::vector<Texture> everyFilterWrapAndEncoding(bool transformBilinear) {
    std::vector<Texture> cases;
    for (bool bilinear : {false, true})
        for (TextureWrap w : {TextureWrap::Repeat, TextureWrap::Clamp, TextureWrap::Mirror})
            for (Texture::Encoding e :
                {Texture::Encoding::Linear, Texture::Encoding::Srgb, Texture::Encoding::Gamma22}) {
                Texture t;
                t.bilinear = bilinear;
                t.wrapU = w;
                t.wrapV = w == TextureWrap::Clamp ? TextureWrap::Mirror : TextureWrap::Clamp;
                t.encoding = e;
                t.valueScale = e == Texture::Encoding::Linear ? 2.0f : 1.0f;
                if (bilinear && transformBilinear) {
                    t.uvRow0 = glm::vec3(0.0f, 2.0f, 0.25f);
                    t.uvRow1 = glm::vec3(-1.5f, 0.0f, 0.5f);
                }
                cases.push_back(t);
            }
    return cases;
}

// 2000 texture coordinates over several periods of the image, negative ones included.
std::vector<glm::vec4> randomUvs(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-2.3f, 3.1f);
    std::vector<glm::vec4> at;
    for (int i = 0; i < 2000; ++i) at.emplace_back(coord(rng), coord(rng), 0.0f, 0.0f);
    return at;
}

class Textures : public GpuTest {};

TEST_F(Textures, ImageLookupsMatchReferenceForEveryFilterWrapAndEncoding) {
    Scene scene;
    scene.textureImages.push_back(makeImage(5, 3));
    const std::vector<Texture> cases = everyFilterWrapAndEncoding(false);
    scene.textures = cases;
    const Uploaded u = upload(scene);
    const std::vector<glm::vec4> at = randomUvs(7);
    for (uint32_t t = 0; t < cases.size(); ++t) {
        const std::vector<glm::vec4> got = evaluate(u, t, at);
        double worst = 0;
        for (size_t i = 0; i < at.size(); ++i) {
            // Nearest lookups exactly on a texel boundary may round either way: skip those.
            const glm::dvec2 st(double(at[i].x) * 5, double(at[i].y) * 3);
            if (!cases[t].bilinear &&
                (std::abs(st.x - std::round(st.x)) < 1e-4 || std::abs(st.y - std::round(st.y)) < 1e-4))
                continue;
            const glm::dvec4 want = lookup(scene.textureImages[0], cases[t], glm::dvec2(at[i]));
            for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(got[i][c]) - want[c]));
        }
        EXPECT_LT(worst, 2e-4) << "texture case " << t;
    }
}

// The light table weighs textured emitters with a CPU copy of the kernel's lookup
// (lights/texture_emission.h): it must read every filter, wrap, encoding and uv transform as the
// kernel does.
TEST_F(Textures, TheLightTablesCpuLookupMatchesTheKernel) {
    Scene scene;
    scene.textureImages.push_back(makeImage(5, 3));
    const std::vector<Texture> cases = everyFilterWrapAndEncoding(true);
    scene.textures = cases;
    const Uploaded u = upload(scene);
    const std::vector<glm::vec4> at = randomUvs(11);
    for (uint32_t t = 0; t < cases.size(); ++t) {
        const std::vector<glm::vec4> got = evaluate(u, t, at);
        double worst = 0;
        for (size_t i = 0; i < at.size(); ++i) {
            const glm::vec4 cpu = sampleImageTexture(u.flat.textures[t], u.flat.texels, glm::vec2(at[i]));
            for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(got[i][c]) - cpu[c]));
        }
        EXPECT_LT(worst, 2e-4) << "texture case " << t;
    }
}

TEST_F(Textures, FloatImagesAndUvTransformsAreApplied) {
    Scene scene;
    TextureImage img;
    img.width = 2;
    img.height = 2;
    img.rgbaF = {{0.5f, 10.0f, 100.0f, 1.0f}, {1, 2, 3, 1}, {4, 5, 6, 1}, {7, 8, 9, 1}};
    scene.textureImages.push_back(img);
    Texture t;
    t.bilinear = false;
    // KHR_texture_transform-style: swap u and v, then shift u by half the image.
    t.uvRow0 = glm::vec3(0, 1, 0.5f);
    t.uvRow1 = glm::vec3(1, 0, 0);
    scene.textures.push_back(t);
    const Uploaded u = upload(scene);
    // (u, v) = (0.25, 0.75) -> (0.75 + 0.5, 0.25) = (1.25, 0.25) -> texel (0, 0) after repeat.
    const std::vector<glm::vec4> got = evaluate(u, 0, {glm::vec4(0.25f, 0.75f, 0, 0), glm::vec4(0.75f, 0.25f, 0, 0)});
    EXPECT_EQ(got[0], glm::vec4(0.5f, 10.0f, 100.0f, 1.0f));
    // (0.75, 0.25) -> (0.25 + 0.5, 0.75) -> texel (1, 1).
    EXPECT_EQ(got[1], glm::vec4(7, 8, 9, 1));
}

TEST_F(Textures, CheckerboardFollowsTheCourseDefinition) {
    Scene scene;
    Texture t;
    t.type = Texture::Type::Checkerboard;
    t.black = glm::vec3(0.1f, 0.2f, 0.3f);
    t.white = glm::vec3(0.9f, 0.8f, 0.7f);
    t.scale = 2.5f;
    t.offset = 0.01f;
    scene.textures.push_back(t);
    const Uploaded u = upload(scene);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(-4.0f, 4.0f);
    std::vector<glm::vec4> at;
    for (int i = 0; i < 1000; ++i) at.emplace_back(coord(rng), coord(rng), coord(rng), 0.0f);
    const std::vector<glm::vec4> got = evaluate(u, 0, at);
    for (size_t i = 0; i < at.size(); ++i) {
        // x = int((p.x + offset) * scale) % 2 per axis (truncation, C++ remainder); black if (x xor y) != z.
        auto parity = [&](float p) { return static_cast<int>((p + t.offset) * t.scale) % 2 != 0; };
        const bool black = (parity(at[i].x) != parity(at[i].y)) != parity(at[i].z);
        const glm::vec3 want = black ? t.black : t.white;
        EXPECT_NEAR(got[i].x, want.x, 1e-6) << i;
        EXPECT_NEAR(got[i].z, want.z, 1e-6) << i;
    }
}

TEST_F(Textures, PerlinNoiseIsZeroOnTheLatticeBoundedAndContinuous) {
    Scene scene;
    Texture linear;
    linear.type = Texture::Type::Perlin;
    linear.scale = 1.0f;
    Texture absval = linear;
    absval.perlinAbs = true;
    scene.textures = {linear, absval};
    const Uploaded u = upload(scene);
    std::vector<glm::vec4> lattice, random, nudged;
    for (int x = -3; x <= 3; ++x)
        for (int y = -2; y <= 2; ++y) lattice.emplace_back(float(x), float(y), float(x * y % 4), 0.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-20.0f, 20.0f);
    for (int i = 0; i < 4000; ++i) {
        random.emplace_back(coord(rng), coord(rng), coord(rng), 0.0f);
        nudged.push_back(random.back() + glm::vec4(1e-3f, -1e-3f, 1e-3f, 0.0f));
    }
    // Gradient noise vanishes at lattice points: (n + 1) / 2 = 0.5 and |n| = 0 there.
    for (const glm::vec4& v : evaluate(u, 0, lattice)) EXPECT_NEAR(v.x, 0.5f, 1e-6f);
    for (const glm::vec4& v : evaluate(u, 1, lattice)) EXPECT_NEAR(v.x, 0.0f, 1e-6f);
    const std::vector<glm::vec4> a = evaluate(u, 0, random), b = evaluate(u, 0, nudged), c = evaluate(u, 1, random);
    double mean = 0, lo = 1, hi = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_TRUE(a[i].x >= 0.0f && a[i].x <= 1.0f) << a[i].x;
        EXPECT_NEAR(c[i].x, std::abs(2.0f * a[i].x - 1.0f), 1e-5f); // the two conversions agree
        // Lipschitz: the gradient of improved noise is bounded (well under 10 per unit).
        EXPECT_LT(std::abs(a[i].x - b[i].x), 10 * 1.8e-3f);
        mean += a[i].x;
        lo = std::min(lo, double(a[i].x));
        hi = std::max(hi, double(a[i].x));
    }
    mean /= a.size();
    EXPECT_NEAR(mean, 0.5, 0.02); // symmetric gradients: zero-mean noise
    EXPECT_LT(lo, 0.25);          // and not a constant
    EXPECT_GT(hi, 0.75);
}

// A camera looking straight at the unit quad in z = 0, its window exactly the quad.
Camera quadCamera() {
    Camera c;
    c.position = glm::vec3(0.5f, 0.5f, 2.0f);
    c.forward = glm::vec3(0, 0, -1);
    c.up = glm::vec3(0, 1, 0);
    c.window = glm::vec4(-0.25f, 0.25f, -0.25f, 0.25f); // half a unit at distance 2
    return c;
}

Mesh texturedQuad(uint32_t material) {
    Mesh m = makeQuad(glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), material);
    // uv (0, 0) at the top-left corner, v down the image, as the course and glTF store images.
    m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    return m;
}

void expectImageIs(const Image& got, const TextureImage& img, double scale) {
    // Each pixel centre falls inside one texel: nearest filtering reproduces the texture.
    const int step = got.width / img.width;
    double worst = 0;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x) {
            const uint32_t p = img.rgba8[static_cast<size_t>(y / step) * img.width + x / step];
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(got.at(x, y)[c] - scale * ((p >> (8 * c)) & 255u) / 255.0));
        }
    EXPECT_LT(worst, 1e-4);
}

TEST_F(Textures, UnlitQuadShowsItsTextureUprightAndUnshaded) {
    Scene scene;
    scene.textureImages.push_back(makeImage(4, 4));
    Texture t;
    t.bilinear = false;
    t.valueScale = 0.5f;
    scene.textures.push_back(t);
    Material m;
    m.baseColor = glm::vec3(1.0f);
    m.baseColorTexture = 0;
    m.unlit = true;
    scene.materials.push_back(m);
    scene.meshes.push_back(texturedQuad(0));
    // Jitter stays inside a pixel and so inside one texel: one sample per pixel is exact.
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, quadCamera(), 32, 32, 4);
    expectImageIs(r.mean, scene.textureImages[0], 0.5);
    EXPECT_EQ(r.droppedSamples, 0u);
}

TEST_F(Textures, BackgroundTextureFillsTheImageForCameraRaysOnly) {
    Scene scene;
    scene.textureImages.push_back(makeImage(8, 8));
    Texture t;
    t.bilinear = false;
    scene.textures.push_back(t);
    scene.backgroundTexture = 0;
    scene.background = glm::vec3(0.0f);
    // A mirror facing the camera would show the background colour (black), not the texture;
    // keep it out of view: nothing but the background is visible.
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeQuad(glm::vec3(100, 100, 100), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0));
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, quadCamera(), 32, 32, 2);
    expectImageIs(r.mean, scene.textureImages[0], 1.0);
}

// Mean radiance of a lit diffuse quad with the given normal/bump texture (or none).
double litQuadMean(std::optional<TextureImage> map, bool bump) {
    Scene scene;
    Material m;
    m.baseColor = glm::vec3(0.7f);
    if (map) {
        scene.textureImages.push_back(*map);
        scene.textures.push_back(Texture{});
        m.normalTexture = 0;
        m.bumpMap = bump;
        m.normalScale = 0.5f;
    }
    scene.materials.push_back(m);
    scene.meshes.push_back(texturedQuad(0));
    PunctualLight light;
    light.position = glm::vec3(0.2f, 0.9f, 1.5f);
    light.intensity = glm::vec3(3.0f);
    scene.punctualLights.push_back(light);
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, quadCamera(), 16, 16, 4);
    double sum = 0;
    for (size_t i = 0; i < r.mean.rgba.size(); i += 4) sum += r.mean.rgba[i];
    return sum / (r.mean.rgba.size() / 4);
}

TEST_F(Textures, FlatNormalMapsAndConstantBumpMapsChangeNothing) {
    TextureImage flatNormals, constantHeight, tilted;
    flatNormals.width = flatNormals.height = constantHeight.width = constantHeight.height = tilted.width =
        tilted.height = 2;
    flatNormals.rgba8.assign(4, 128u | 128u << 8 | 255u << 16 | 255u << 24); // (0, 0, 1) up to 8-bit rounding
    constantHeight.rgba8.assign(4, 90u | 90u << 8 | 90u << 16 | 255u << 24);
    tilted.rgba8.assign(4, 230u | 128u << 8 | 180u << 16 | 255u << 24); // leans towards +u
    const double plain = litQuadMean(std::nullopt, false);
    ASSERT_GT(plain, 0.01);
    EXPECT_NEAR(litQuadMean(flatNormals, false) / plain, 1.0, 0.01); // 128/255 is not exactly 0.5
    EXPECT_NEAR(litQuadMean(constantHeight, true) / plain, 1.0, 1e-5);
    // The light sits towards -u of most of the quad: leaning the normals to +u darkens it.
    EXPECT_LT(litQuadMean(tilted, false) / plain, 0.9);
}

// Mean radiance of a glTF PBR quad lit from the front (reflection) and from behind (thin-walled
// transmission), with `m`'s factors and a 2x2 constant texture `texel` in `slot`.
double pbrQuadMean(Material m, std::optional<uint32_t> Material::*slot, uint32_t texel, Texture::Encoding encoding) {
    Scene scene;
    m.type = MaterialType::Pbr;
    m.baseColor = glm::vec3(0.6f, 0.5f, 0.4f);
    m.roughness = 0.4f;
    if (slot) {
        TextureImage img;
        img.width = img.height = 2;
        img.rgba8.assign(4, texel);
        scene.textureImages.push_back(img);
        Texture t;
        t.encoding = encoding;
        scene.textures.push_back(t);
        m.*slot = 0;
    }
    scene.materials.push_back(m);
    scene.meshes.push_back(texturedQuad(0));
    PunctualLight front, behind;
    front.position = glm::vec3(0.3f, 0.8f, 1.0f);
    front.intensity = glm::vec3(2.0f);
    behind.position = glm::vec3(0.6f, 0.4f, -1.0f);
    behind.intensity = glm::vec3(2.0f);
    scene.punctualLights = {front, behind};
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, quadCamera(), 16, 16, 16);
    double sum = 0;
    for (size_t i = 0; i < r.mean.rgba.size(); ++i)
        if (i % 4 != 3) sum += r.mean.rgba[i];
    return sum / (r.mean.rgba.size() / 4 * 3);
}

// KHR_materials_specular's specularTexture (alpha) and specularColorTexture (sRGB rgb) and
// KHR_materials_transmission's transmissionTexture (red) scale their factors: a constant texture
// renders as the factor times its value, and changes the image.
TEST_F(Textures, ExtensionTexturesScaleTheirFactors) {
    Material base;
    base.specularWeight = 1.0f;
    base.specular = glm::vec3(1.0f);
    base.transmission = 0.5f;
    const double plain = pbrQuadMean(base, nullptr, 0, Texture::Encoding::Linear);
    ASSERT_GT(plain, 0.005);

    // The factor times the texel value, set directly, against the factor 1 with the texture.
    auto expectTextureActsAsFactor = [&](const Material& byFactor, std::optional<uint32_t> Material::*slot,
                                         uint32_t texel, Texture::Encoding encoding, const char* what) {
        const double factor = pbrQuadMean(byFactor, nullptr, 0, Texture::Encoding::Linear);
        const double texture = pbrQuadMean(base, slot, texel, encoding);
        EXPECT_NEAR(texture / factor, 1.0, 1e-4) << what;
        EXPECT_GT(std::abs(factor / plain - 1.0), 0.02) << what;
    };
    Material weight = base;
    weight.specularWeight = 0.2f; // 51 / 255
    expectTextureActsAsFactor(weight, &Material::specularWeightTexture, 0x33ffffffu, Texture::Encoding::Linear,
        "specularTexture"); // a = 51
    Material colour = base;
    colour.specular = glm::vec3(float(srgbToLinear(100.0 / 255.0))); // sRGB-encoded texel 100
    expectTextureActsAsFactor(colour, &Material::specularTexture, 0xff646464u, Texture::Encoding::Srgb,
        "specularColorTexture"); // rgb = 100
    Material transmission = base;
    transmission.transmission = 0.5f * 0.2f; // red 51 / 255
    expectTextureActsAsFactor(transmission, &Material::transmissionTexture, 0xff000033u, Texture::Encoding::Linear,
        "transmissionTexture"); // r = 51
}

// An unlit white quad at z = 0 in front of an unlit red one at z = -1, seen by quadCamera().
Scene layeredQuads(Material front) {
    Scene scene;
    front.unlit = true;
    front.baseColor = glm::vec3(1.0f);
    Material back;
    back.unlit = true;
    back.baseColor = glm::vec3(1, 0, 0);
    back.baseColorTexture = std::nullopt;
    scene.materials = {front, back};
    scene.meshes.push_back(texturedQuad(0));
    scene.meshes.push_back(makeQuad(glm::vec3(-1, -1, -1), glm::vec3(3, 0, 0), glm::vec3(0, 3, 0), 1));
    return scene;
}

TEST_F(Textures, AlphaMaskCutsOutWhereTheTextureIsTransparent) {
    TextureImage halves;
    halves.width = 2;
    halves.height = 1;
    halves.rgba8 = {0x00ffffffu, 0xffffffffu}; // left texel alpha 0, right alpha 1
    Material front;
    front.baseColorTexture = 0;
    front.alphaMode = Material::AlphaMode::Mask;
    front.alphaCutoff = 0.5f;
    Scene scene = layeredQuads(front);
    scene.textureImages.push_back(halves);
    Texture nearest;
    nearest.bilinear = false;
    scene.textures.push_back(nearest);
    // Unlit surfaces reach the sensor only when the kernel treats them as such.
    scene.materials[0].unlit = scene.materials[1].unlit = true;
    const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, quadCamera(), 16, 16, 2);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const float* p = r.mean.at(x, y);
            if (x < 8)
                EXPECT_TRUE(p[0] == 1.0f && p[1] == 0.0f) << x << "," << y << ": the back quad shows through";
            else
                EXPECT_TRUE(p[0] == 1.0f && p[1] == 1.0f) << x << "," << y << ": the front quad is opaque";
        }
}

TEST_F(Textures, AlphaBlendLetsThroughOneMinusOpacityOnAverage) {
    Material front;
    front.alphaMode = Material::AlphaMode::Blend;
    front.opacity = 0.25f;
    const Renderer::Readback r = renderScene(layeredQuads(front), IntegratorSettings{}, quadCamera(), 16, 16, 64);
    // Green is 1 where the white quad was kept (probability 0.25) and 0 where red shows.
    double green = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) green += r.mean.at(x, y)[1];
    green /= 256;
    // 16384 Bernoulli(0.25) draws: standard error 0.0034; allow 5 of them.
    EXPECT_NEAR(green, 0.25, 0.017);
}

// The file's tangents (glTF TANGENT) orient the normal map instead of the uv derivatives: a
// map leaning towards tangent-space +x tilts the normal along whichever world direction the
// tangent names, so a light on that side brightens the quad and one on the other side does not.
TEST_F(Textures, FileTangentsOrientTheNormalMap) {
    TextureImage lean;
    lean.width = lean.height = 1;
    lean.rgba8 = {230u | 128u << 8 | 180u << 16 | 255u << 24}; // towards +x
    auto meanWithTangent = [&](glm::vec3 tangent) {
        Scene scene;
        scene.textureImages.push_back(lean);
        scene.textures.push_back(Texture{});
        Material m;
        m.baseColor = glm::vec3(0.7f);
        m.normalTexture = 0;
        scene.materials.push_back(m);
        Mesh quad = texturedQuad(0);
        quad.normals.assign(4, glm::vec3(0, 0, 1));
        quad.tangents.assign(4, glm::vec4(tangent, 1.0f));
        scene.meshes.push_back(quad);
        PunctualLight light; // far up +y, grazing: only a normal tilted towards +y catches much
        light.position = glm::vec3(0.5f, 6.0f, 0.6f);
        light.intensity = glm::vec3(40.0f);
        scene.punctualLights.push_back(light);
        const Renderer::Readback r = renderScene(scene, IntegratorSettings{}, quadCamera(), 8, 8, 4);
        double sum = 0;
        for (size_t i = 0; i < r.mean.rgba.size(); i += 4) sum += r.mean.rgba[i];
        return sum / 64;
    };
    const double towardsLight = meanWithTangent({0, 1, 0}), awayFromLight = meanWithTangent({0, -1, 0});
    const double sideways = meanWithTangent({1, 0, 0});
    EXPECT_GT(towardsLight, 1.5 * sideways);
    EXPECT_GT(sideways, 1.2 * awayFromLight);
}

} // namespace
} // namespace pt::test
