// glTF materials and textures: metallic-roughness factors and KHR_materials_*, the default
// material, texture slots, encodings, samplers, KHR_texture_transform, alpha modes and tangents.
#include "gltf_test_documents.h"
#include "scene/scene_error.h"

#include <algorithm>

namespace pt::test::gltf {
namespace {

// ---------------------------------------------------------------------------------------------
// Material factors and KHR_materials_*: one triangle per material (materialDocument).

TEST(GltfLoaderMaterials, MetallicRoughnessFactorsAndExtensions) {
    const pt::Scene s = loadText(materialDocument(R"([
      {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.5}},
      {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.3, 1], "metallicFactor": 1, "roughnessFactor": 0.3}},
      {"name": "half", "pbrMetallicRoughness": {"metallicFactor": 0.25, "roughnessFactor": 0.7}},
      {"name": "tinted-spec", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.4},
       "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 0.25]},
                      "KHR_materials_ior": {"ior": 1.33}}},
      {"name": "frosted-glass", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 1, 0.9, 1], "metallicFactor": 0, "roughnessFactor": 0.2},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                      "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationColor": [0.5, 0.8, 1], "attenuationDistance": 2}}},
      {"name": "thin-film", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.6}}},
      {"name": "partly-clear", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}, "KHR_materials_volume": {"thicknessFactor": 1}}},
      {"name": "lambert", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 0.8},
       "extensions": {"KHR_materials_specular": {"specularFactor": 0}}},
      {"name": "chrome", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0}},
      {"name": "lamp", "emissiveFactor": [1, 0.5, 0.25], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}
    ])",
        10));
    auto get = [&](const char* name) {
        const pt::Material* m = findMaterial(s, name);
        EXPECT_NE(m, nullptr) << name;
        return m ? *m : pt::Material{};
    };
    const pt::Material plastic = get("plastic");
    EXPECT_EQ(plastic.type, pt::MaterialType::Pbr);
    EXPECT_TRUE(near3(plastic.baseColor, glm::vec3(0.2f, 0.4f, 0.6f), 1e-6f));
    EXPECT_FLOAT_EQ(plastic.metallic, 0.0f);
    EXPECT_FLOAT_EQ(plastic.roughness, 0.5f);
    EXPECT_FLOAT_EQ(plastic.specularWeight, 1.0f);
    EXPECT_TRUE(near3(plastic.specular, glm::vec3(1.0f), 0.0f));
    EXPECT_FLOAT_EQ(plastic.ior, 1.5f);
    EXPECT_FLOAT_EQ(plastic.transmission, 0.0f);

    const pt::Material gold = get("gold");
    EXPECT_EQ(gold.type, pt::MaterialType::Mirror) << "metallic 1 is the Schlick metal, GGX-rough when rough";
    EXPECT_FLOAT_EQ(gold.metallic, 1.0f);
    EXPECT_FLOAT_EQ(gold.roughness, 0.3f);

    const pt::Material half = get("half");
    EXPECT_EQ(half.type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(half.metallic, 0.25f);
    EXPECT_FLOAT_EQ(half.roughness, 0.7f);
    EXPECT_TRUE(near3(half.baseColor, glm::vec3(1.0f), 0.0f)) << "baseColorFactor defaults to white";

    const pt::Material tinted = get("tinted-spec");
    EXPECT_EQ(tinted.type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(tinted.specularWeight, 0.5f);
    EXPECT_TRUE(near3(tinted.specular, glm::vec3(1.0f, 0.5f, 0.25f), 1e-6f));
    EXPECT_FLOAT_EQ(tinted.ior, 1.33f);

    // Full transmission with a volume and default specular is exactly a (rough) dielectric,
    // which keeps its Beer-Lambert absorption.
    const pt::Material glass = get("frosted-glass");
    EXPECT_EQ(glass.type, pt::MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(glass.roughness, 0.2f);
    EXPECT_FALSE(glass.thinWalled);
    EXPECT_TRUE(near3(glass.baseColor, glm::vec3(0.9f, 1.0f, 0.9f), 1e-6f));
    EXPECT_TRUE(near3(glass.attenuationColor, glm::vec3(0.5f, 0.8f, 1.0f), 1e-6f));
    EXPECT_FLOAT_EQ(glass.attenuationDistance, 2.0f);

    // No volume: thin-walled transmission, partly.
    const pt::Material thin = get("thin-film");
    EXPECT_EQ(thin.type, pt::MaterialType::Pbr);
    EXPECT_TRUE(thin.thinWalled);
    EXPECT_FLOAT_EQ(thin.transmission, 0.6f);
    const pt::Material partly = get("partly-clear");
    EXPECT_EQ(partly.type, pt::MaterialType::Pbr);
    EXPECT_FALSE(partly.thinWalled);
    EXPECT_FLOAT_EQ(partly.transmission, 0.5f);

    // The exact special cases the Mitsuba references rely on.
    EXPECT_EQ(get("lambert").type, pt::MaterialType::Diffuse);
    EXPECT_TRUE(near3(get("lambert").baseColor, glm::vec3(0.5f), 1e-6f));
    EXPECT_EQ(get("chrome").type, pt::MaterialType::Mirror);
    EXPECT_TRUE(near3(get("lamp").emission, glm::vec3(8.0f, 4.0f, 2.0f), 1e-5f));

    // All of it is modelled: nothing in the "not supported" warning.
    EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

// An extension value of the wrong type is not the spec's default silently: the default is used
// and a note names the material, the value and the default.
TEST(GltfLoaderMaterials, MalformedExtensionValuesAreNotedWithTheDefaultTaken) {
    const pt::Scene s = loadText(materialDocument(R"([
      {"name": "odd", "extensions": {"KHR_materials_ior": {"ior": "glass"},
                                     "KHR_materials_specular": {"specularColorFactor": [1, 0.5]},
                                     "KHR_materials_transmission": {"transmissionFactor": true}}}])",
        1));
    const pt::Material* m = findMaterial(s, "odd");
    ASSERT_NE(m, nullptr);
    EXPECT_FLOAT_EQ(m->ior, 1.5f);
    EXPECT_TRUE(near3(m->specular, glm::vec3(1.0f), 0.0f));
    EXPECT_FLOAT_EQ(m->transmission, 0.0f);
    // One note each (the importer lists its notes in sorted order).
    const std::vector<std::string> expected = {"material 0 'odd': ior is not a number (1.5 assumed)",
        "material 0 'odd': specularColorFactor is not 3 numbers (1 1 1 assumed)",
        "material 0 'odd': transmissionFactor is not a number (0 assumed)"};
    EXPECT_EQ(s.unsupported, expected);
}

TEST(GltfLoaderMaterials, PrimitivesWithoutMaterialGetTheGltfDefault) {
    std::string doc = materialDocument(R"([{"name": "unused"}])", 1);
    const std::string withMaterial = R"(, "material": 0)";
    doc.erase(doc.find(withMaterial), withMaterial.size());
    const pt::Scene s = loadText(doc);
    ASSERT_EQ(s.meshes.size(), 1u);
    const pt::Material& m = s.materials[s.meshes[0].material];
    EXPECT_EQ(m.type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(m.metallic, 1.0f);
    EXPECT_FLOAT_EQ(m.roughness, 1.0f);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1.0f), 0.0f));
}

TEST(GltfLoaderMaterials, OutOfRangeFactorsAreErrors) {
    for (const char* bad : {R"({"pbrMetallicRoughness": {"metallicFactor": 1.5}})",
             R"({"pbrMetallicRoughness": {"roughnessFactor": -0.1}})",
             R"({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 2}}})",
             R"({"extensions": {"KHR_materials_specular": {"specularFactor": -1}}})"}) {
        EXPECT_THROW(loadText(materialDocument(std::string("[") + bad + "]", 1)), pt::SceneError) << bad;
    }
}
// ---------------------------------------------------------------------------------------------
// Textures: slots, encodings, samplers, KHR_texture_transform, alpha modes

const char* const kOnePixelPng =
    "data:image/"
    "png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==";

// materialDocument plus textures / images / samplers arrays.
std::string texturedDocument(const std::string& materials, int materialCount, const std::string& textures,
    const std::string& images, const std::string& samplers = "[]") {
    std::string d = materialDocument(materials, materialCount);
    const std::string head = R"({"asset": {"version": "2.0"},)";
    const size_t at = d.find(head);
    EXPECT_NE(at, std::string::npos);
    d.insert(at + head.size(),
        R"( "textures": )" + textures + R"(, "images": )" + images + R"(, "samplers": )" + samplers + ",");
    return d;
}

TEST(GltfLoaderTextures, SlotsEncodingsSamplersAndTransforms) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1},
                                                   "metallicFactor": 1, "roughnessFactor": 0},
       "normalTexture": {"index": 1, "scale": 0.5}, "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 1, 1],
       "alphaMode": "MASK", "alphaCutoff": 0.3},
      {"name": "moved", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.4],
        "baseColorTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 1.5707963, "scale": [2, 3]}}}},
       "alphaMode": "BLEND"}
    ])",
        2, R"([{"source": 0}, {"source": 0, "sampler": 0}])", images,
        R"([{"magFilter": 9728, "wrapS": 33071, "wrapT": 33648}])"));
    const pt::Material* painted = findMaterial(s, "painted");
    const pt::Material* moved = findMaterial(s, "moved");
    ASSERT_TRUE(painted && moved);
    ASSERT_TRUE(painted->baseColorTexture && painted->metallicRoughnessTexture && painted->normalTexture &&
                painted->emissiveTexture);
    // A metallic-roughness texture can make the factors' mirror rough: the full model is needed.
    EXPECT_EQ(painted->type, pt::MaterialType::Pbr);
    EXPECT_EQ(s.textures.at(*painted->baseColorTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_EQ(s.textures.at(*painted->emissiveTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_EQ(s.textures.at(*painted->metallicRoughnessTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_EQ(s.textures.at(*painted->normalTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_FLOAT_EQ(painted->normalScale, 0.5f);
    EXPECT_FALSE(painted->normalMapYDown); // glTF: +y up the image
    EXPECT_EQ(painted->alphaMode, pt::Material::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(painted->alphaCutoff, 0.3f);
    // Sampler 0: nearest, clamp in u, mirror in v; no sampler: bilinear repeat.
    const pt::Texture& sampled = s.textures.at(*painted->metallicRoughnessTexture);
    EXPECT_FALSE(sampled.bilinear);
    EXPECT_EQ(sampled.wrapU, pt::TextureWrap::Clamp);
    EXPECT_EQ(sampled.wrapV, pt::TextureWrap::Mirror);
    const pt::Texture& plain = s.textures.at(*painted->baseColorTexture);
    EXPECT_TRUE(plain.bilinear);
    EXPECT_EQ(plain.wrapU, pt::TextureWrap::Repeat);
    // One image, decoded once, shared by every texture that reads it.
    ASSERT_EQ(s.textureImages.size(), 1u);
    EXPECT_EQ(s.textureImages[0].width, 1);
    EXPECT_EQ(plain.image, sampled.image);
    // KHR_texture_transform: uv' = T R S uv; (1, 0) -> S (2, 0) -> R(90 deg) (0, -2) -> T (0.5, -1.75).
    const pt::Texture& t = s.textures.at(*moved->baseColorTexture);
    const glm::vec2 uv(1, 0);
    EXPECT_NEAR(t.uvRow0.x * uv.x + t.uvRow0.y * uv.y + t.uvRow0.z, 0.5f, 1e-5f);
    EXPECT_NEAR(t.uvRow1.x * uv.x + t.uvRow1.y * uv.y + t.uvRow1.z, -1.75f, 1e-5f);
    EXPECT_EQ(moved->alphaMode, pt::Material::AlphaMode::Blend);
    EXPECT_FLOAT_EQ(moved->opacity, 0.4f);
    EXPECT_TRUE(std::none_of(s.unsupported.begin(), s.unsupported.end(),
        [](const std::string& n) { return n.find("texture") != std::string::npos; }));
}

// The material extensions' textures land in their slots with their encodings (specularTexture:
// alpha, linear; specularColorTexture: sRGB; transmissionTexture: red, linear), with their own
// KHR_texture_transform, and make a factors' glass the full PBR model.
TEST(GltfLoaderTextures, ExtensionTexturesOfSpecularAndTransmission) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0}, "extensions": {
         "KHR_materials_transmission": {"transmissionFactor": 1, "transmissionTexture": {"index": 1}},
         "KHR_materials_specular": {"specularTexture": {"index": 0},
           "specularColorTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0]}}}},
         "KHR_materials_volume": {"thicknessFactor": 1}}}
    ])",
        1, R"([{"source": 0}, {"source": 0}])", images, "[]"));
    const pt::Material* glass = findMaterial(s, "glass");
    ASSERT_TRUE(glass);
    ASSERT_TRUE(glass->specularWeightTexture && glass->specularTexture && glass->transmissionTexture);
    EXPECT_EQ(glass->type, pt::MaterialType::Pbr); // not the factors' dielectric
    EXPECT_EQ(s.textures.at(*glass->specularWeightTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_EQ(s.textures.at(*glass->specularTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_EQ(s.textures.at(*glass->transmissionTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_FLOAT_EQ(s.textures.at(*glass->specularTexture).uvRow0.z, 0.5f);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);

    EXPECT_THROW(
        loadText(texturedDocument(R"([{"extensions": {"KHR_materials_specular": {"specularTexture": {"index": 7}}}}])",
            1, R"([{"source": 0}])", images, "[]")),
        pt::SceneError);
}

// A KHR_texture_transform value of the wrong shape: the identity's part for it, and a note.
TEST(GltfLoaderTextures, MalformedTextureTransformIsNotedWithTheDefaultTaken) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "odd", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
        "extensions": {"KHR_texture_transform": {"offset": [0.5], "scale": [2, 2], "rotation": "quarter"}}}}}])",
        1, R"([{"source": 0}])", images, "[]"));
    const pt::Texture& t = s.textures.at(0);
    EXPECT_TRUE(near3(t.uvRow0, glm::vec3(2, 0, 0), 0.0f));
    EXPECT_TRUE(near3(t.uvRow1, glm::vec3(0, 2, 0), 0.0f));
    const std::vector<std::string> expected = {
        "material 0 'odd': baseColorTexture: KHR_texture_transform: offset is not 2 numbers (0 0 assumed)",
        "material 0 'odd': baseColorTexture: KHR_texture_transform: rotation is not a number (0 assumed)"};
    EXPECT_EQ(s.unsupported, expected);
}

TEST(GltfLoaderTextures, BadTexturesAreErrors) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    auto expectError = [&](const std::string& doc, const std::string& problem) {
        try {
            loadText(doc);
            ADD_FAILURE() << "no error for " << problem;
        } catch (const pt::SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
        }
    };
    const std::string base = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}}])";
    expectError(texturedDocument(base, 1, R"([{"source": 0}])", images), "texture 3 does not exist");
    expectError(texturedDocument(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])", 1,
                    R"([{"source": 0, "sampler": 4}])", images),
        "sampler 4 does not exist");
    expectError(texturedDocument(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])", 1,
                    R"([{"source": 0}])", R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAA"}])"),
        "image 0");
    expectError(texturedDocument(R"([{"alphaMode": "SOMETIMES"}])", 1, "[]", "[]"), "unknown alphaMode");
}
// TANGENT: read as VEC4, mapped with the node's matrix, the bitangent sign flipped by a
// mirroring transform, invalid ones zeroed.
TEST(GltfLoaderTextures, TangentsAreTransformedWithTheirHandedness) {
    const glm::vec3 p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::vec3 n(0, 0, 1);
    const glm::vec4 t[3] = {{1, 0, 0, 1}, {1, 0, 0, 1}, {0, 0, 0, 1}}; // the last one is invalid
    std::vector<unsigned char> bytes(3 * 12 + 3 * 12 + 3 * 16);
    for (int i = 0; i < 3; ++i) {
        std::memcpy(bytes.data() + 12 * i, &p[i], 12);
        std::memcpy(bytes.data() + 36 + 12 * i, &n, 12);
        std::memcpy(bytes.data() + 72 + 16 * i, &t[i], 16);
    }
    auto document = [&](const std::string& scale) {
        return std::string(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
          "nodes": [{"mesh": 0, "scale": )") +
               scale + R"(}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2}, "material": 0}]}],
          "materials": [{"normalTexture": {"index": 0}}],
          "textures": [{"source": 0}], "images": [{"uri": ")" +
               kOnePixelPng + R"("}],
          "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}],
          "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                          {"buffer": 0, "byteOffset": 72, "byteLength": 48}],
          "buffers": [{"byteLength": 120, "uri": "data:application/octet-stream;base64,)" +
               base64(bytes) + R"("}]})";
    };
    const pt::Scene plain = loadText(document("[2, 1, 1]"));
    ASSERT_EQ(plain.meshes.at(0).tangents.size(), 3u);
    EXPECT_TRUE(near3(glm::vec3(plain.meshes[0].tangents[0]), glm::vec3(1, 0, 0), 1e-6f)); // renormalised after scaling
    EXPECT_EQ(plain.meshes[0].tangents[0].w, 1.0f);
    EXPECT_EQ(plain.meshes[0].tangents[2], glm::vec4(0.0f)); // invalid
    const pt::Scene mirrored = loadText(document("[-1, 1, 1]"));
    EXPECT_TRUE(near3(glm::vec3(mirrored.meshes.at(0).tangents[0]), glm::vec3(-1, 0, 0), 1e-6f));
    EXPECT_EQ(mirrored.meshes[0].tangents[0].w, -1.0f);
}

} // namespace
} // namespace pt::test::gltf

namespace pt::test::gltf {
namespace {

// KHR_materials_diffuse_transmission: factor, colour and both textures land in the model (the
// factor's texture read from alpha, linear; the colour's sRGB), with no warning; a material that
// would be Lambertian but transmits diffusely stays the full model.
TEST(GltfLoaderMaterials, DiffuseTransmissionIsRead) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "leaf", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.6},
       "extensions": {"KHR_materials_specular": {"specularFactor": 0},
         "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.4,
           "diffuseTransmissionColorFactor": [0.5, 1, 0.25], "diffuseTransmissionTexture": {"index": 0},
           "diffuseTransmissionColorTexture": {"index": 1}}}}
    ])",
        1, R"([{"source": 0}, {"source": 0}])", images, "[]"));
    const pt::Material* leaf = findMaterial(s, "leaf");
    ASSERT_TRUE(leaf);
    EXPECT_EQ(leaf->type, pt::MaterialType::Pbr) << "not the Lambertian shortcut";
    EXPECT_FLOAT_EQ(leaf->diffuseTransmission, 0.4f);
    EXPECT_TRUE(near3(leaf->diffuseTransmissionColor, glm::vec3(0.5f, 1.0f, 0.25f), 0.0f));
    ASSERT_TRUE(leaf->diffuseTransmissionTexture && leaf->diffuseTransmissionColorTexture);
    EXPECT_EQ(s.textures.at(*leaf->diffuseTransmissionTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_EQ(s.textures.at(*leaf->diffuseTransmissionColorTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);
    EXPECT_THROW(loadText(materialDocument(R"([{"extensions": {"KHR_materials_diffuse_transmission":
        {"diffuseTransmissionColorFactor": [2, 0, 0]}}}])",
                     1)),
        pt::SceneError);
}

} // namespace
} // namespace pt::test::gltf

namespace pt::test::gltf {
namespace {

// KHR_materials_clearcoat and KHR_materials_sheen: factors, roughnesses, the coat's normal map
// with its scale and every texture land in the model with the spec's encodings (the sheen
// colour's sRGB, the rest linear), with no warning; a layer turns what would be a Lambertian
// surface or a plain metal into the full model, which has the layers. Out-of-range factors fail.
TEST(GltfLoaderMaterials, ClearcoatAndSheenAreRead) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "car paint", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.4},
       "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.1,
         "clearcoatTexture": {"index": 0}, "clearcoatRoughnessTexture": {"index": 1},
         "clearcoatNormalTexture": {"index": 2, "scale": 0.5}}}},
      {"name": "velvet", "pbrMetallicRoughness": {"metallicFactor": 0},
       "extensions": {"KHR_materials_specular": {"specularFactor": 0},
         "KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.2, 0.4], "sheenRoughnessFactor": 0.6,
           "sheenColorTexture": {"index": 3}, "sheenRoughnessTexture": {"index": 4}}}}
    ])",
        2, R"([{"source": 0}, {"source": 0}, {"source": 0}, {"source": 0}, {"source": 0}])", images, "[]"));
    const pt::Material* paint = findMaterial(s, "car paint");
    const pt::Material* velvet = findMaterial(s, "velvet");
    ASSERT_TRUE(paint && velvet);
    EXPECT_EQ(paint->type, pt::MaterialType::Pbr) << "not the plain-metal shortcut";
    EXPECT_EQ(velvet->type, pt::MaterialType::Pbr) << "not the Lambertian shortcut";
    EXPECT_FLOAT_EQ(paint->clearcoat, 0.8f);
    EXPECT_FLOAT_EQ(paint->clearcoatRoughness, 0.1f);
    EXPECT_FLOAT_EQ(paint->clearcoatNormalScale, 0.5f);
    ASSERT_TRUE(paint->clearcoatTexture && paint->clearcoatRoughnessTexture && paint->clearcoatNormalTexture);
    for (auto t : {paint->clearcoatTexture, paint->clearcoatRoughnessTexture, paint->clearcoatNormalTexture})
        EXPECT_EQ(s.textures.at(*t).encoding, pt::Texture::Encoding::Linear);
    EXPECT_TRUE(near3(velvet->sheenColor, glm::vec3(0.9f, 0.2f, 0.4f), 0.0f));
    EXPECT_FLOAT_EQ(velvet->sheenRoughness, 0.6f);
    ASSERT_TRUE(velvet->sheenColorTexture && velvet->sheenRoughnessTexture);
    EXPECT_EQ(s.textures.at(*velvet->sheenColorTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_EQ(s.textures.at(*velvet->sheenRoughnessTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);

    for (const char* bad : {R"({"KHR_materials_clearcoat": {"clearcoatFactor": 1.5}})",
             R"({"KHR_materials_clearcoat": {"clearcoatRoughnessFactor": -0.1}})",
             R"({"KHR_materials_sheen": {"sheenColorFactor": [2, 0, 0]}})",
             R"({"KHR_materials_sheen": {"sheenRoughnessFactor": 3}})"})
        EXPECT_THROW(loadText(materialDocument(std::string(R"([{"extensions": )") + bad + "}]", 1)), pt::SceneError)
            << bad;
}

} // namespace
} // namespace pt::test::gltf

namespace pt::test::gltf {
namespace {

// KHR_materials_iridescence: factor, film index, thickness range and both textures (linear); a
// film on a metal keeps the full model (the plain-metal shortcut has no film); bad values fail.
TEST(GltfLoaderMaterials, IridescenceIsRead) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "soap", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.1},
       "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 0.9, "iridescenceIor": 1.8,
         "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 600,
         "iridescenceTexture": {"index": 0}, "iridescenceThicknessTexture": {"index": 1}}}}
    ])",
        1, R"([{"source": 0}, {"source": 0}])", images, "[]"));
    const pt::Material* soap = findMaterial(s, "soap");
    ASSERT_TRUE(soap);
    EXPECT_EQ(soap->type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(soap->iridescence, 0.9f);
    EXPECT_FLOAT_EQ(soap->iridescenceIor, 1.8f);
    EXPECT_FLOAT_EQ(soap->iridescenceThicknessMinimum, 200.0f);
    EXPECT_FLOAT_EQ(soap->iridescenceThicknessMaximum, 600.0f);
    ASSERT_TRUE(soap->iridescenceTexture && soap->iridescenceThicknessTexture);
    EXPECT_EQ(s.textures.at(*soap->iridescenceTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_EQ(s.textures.at(*soap->iridescenceThicknessTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);
    // The extension's defaults: film index 1.3, 100 to 400 nm.
    const pt::Scene d = loadText(materialDocument(
        R"([{"name": "thin", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1}}}])", 1));
    const pt::Material* thin = findMaterial(d, "thin");
    ASSERT_TRUE(thin);
    EXPECT_FLOAT_EQ(thin->iridescenceIor, 1.3f);
    EXPECT_FLOAT_EQ(thin->iridescenceThicknessMinimum, 100.0f);
    EXPECT_FLOAT_EQ(thin->iridescenceThicknessMaximum, 400.0f);
    for (const char* bad :
        {R"({"iridescenceFactor": 2})", R"({"iridescenceIor": 0.5})", R"({"iridescenceThicknessMaximum": -5})"})
        EXPECT_THROW(loadText(materialDocument(
                         std::string(R"([{"extensions": {"KHR_materials_iridescence": )") + bad + "}}]", 1)),
            pt::SceneError)
            << bad;
}

} // namespace
} // namespace pt::test::gltf

namespace pt::test::gltf {
namespace {

// KHR_materials_anisotropy: strength, rotation and the texture (linear); it keeps the full model
// (the plain-metal shortcut is isotropic); strength outside [0, 1] fails.
TEST(GltfLoaderMaterials, AnisotropyIsRead) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "brushed", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.3},
       "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 1.25,
         "anisotropyTexture": {"index": 0}}}}
    ])",
        1, R"([{"source": 0}])", images, "[]"));
    const pt::Material* brushed = findMaterial(s, "brushed");
    ASSERT_TRUE(brushed);
    EXPECT_EQ(brushed->type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(brushed->anisotropy, 0.6f);
    EXPECT_FLOAT_EQ(brushed->anisotropyRotation, 1.25f);
    ASSERT_TRUE(brushed->anisotropyTexture);
    EXPECT_EQ(s.textures.at(*brushed->anisotropyTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);
    EXPECT_THROW(
        loadText(materialDocument(R"([{"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.5}}}])", 1)),
        pt::SceneError);
}

} // namespace
} // namespace pt::test::gltf

namespace pt::test::gltf {
namespace {

// KHR_materials_dispersion: 20 / Abbe number, kept on the dielectric shortcut (transmission 1
// with a volume) and on the full model; negative values fail.
TEST(GltfLoaderMaterials, DispersionIsRead) {
    const pt::Scene s = loadText(materialDocument(R"([
      {"name": "flint", "pbrMetallicRoughness": {"metallicFactor": 0},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
        "KHR_materials_volume": {"thicknessFactor": 1}, "KHR_materials_dispersion": {"dispersion": 0.6}}},
      {"name": "tinted", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.2},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5},
        "KHR_materials_volume": {"thicknessFactor": 1}, "KHR_materials_dispersion": {"dispersion": 1.5}}}
    ])",
        2));
    const pt::Material* flint = findMaterial(s, "flint");
    const pt::Material* tinted = findMaterial(s, "tinted");
    ASSERT_TRUE(flint && tinted);
    EXPECT_EQ(flint->type, pt::MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(flint->dispersion, 0.6f);
    EXPECT_EQ(tinted->type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(tinted->dispersion, 1.5f);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);
    EXPECT_THROW(loadText(materialDocument(R"([{"extensions": {"KHR_materials_dispersion": {"dispersion": -1}}}])", 1)),
        pt::SceneError);
}

} // namespace
} // namespace pt::test::gltf

namespace pt::test::gltf {
namespace {

// KHR_materials_pbrSpecularGlossiness (archived, still in files): the metallic-roughness
// dielectric with F0 = specularFactor (ior 1.5's 0.04 times the specular colour
// specularFactor / 0.04), roughness 1 - glossiness, the diffuse as base colour and opacity; its
// specular-glossiness texture both the specular colour (sRGB rgb) and the glossiness (alpha).
TEST(GltfLoaderMaterials, SpecularGlossinessBecomesTheDielectricModel) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "old", "pbrMetallicRoughness": {"metallicFactor": 1},
       "extensions": {"KHR_materials_pbrSpecularGlossiness": {"diffuseFactor": [0.5, 0.25, 1, 0.75],
         "specularFactor": [0.1, 0.05, 0.02], "glossinessFactor": 0.7, "diffuseTexture": {"index": 0},
         "specularGlossinessTexture": {"index": 1}}}}
    ])",
        1, R"([{"source": 0}, {"source": 0}])", images, "[]"));
    const pt::Material* old = findMaterial(s, "old");
    ASSERT_TRUE(old);
    EXPECT_EQ(old->type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(old->metallic, 0.0f) << "the metallic-roughness fallback is not used";
    EXPECT_TRUE(near3(old->baseColor, glm::vec3(0.5f, 0.25f, 1.0f), 0.0f));
    EXPECT_FLOAT_EQ(old->opacity, 0.75f);
    EXPECT_FLOAT_EQ(old->ior, 1.5f);
    EXPECT_TRUE(near3(old->specular * 0.04f, glm::vec3(0.1f, 0.05f, 0.02f), 1e-6f)) << "F0 = specularFactor";
    EXPECT_FLOAT_EQ(old->roughness, 0.3f);
    EXPECT_FLOAT_EQ(old->glossiness, 0.7f);
    ASSERT_TRUE(old->baseColorTexture && old->specularTexture && old->metallicRoughnessTexture);
    EXPECT_EQ(*old->metallicRoughnessTexture, *old->specularTexture);
    EXPECT_TRUE(old->glossinessTexture);
    EXPECT_EQ(s.textures.at(*old->specularTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_TRUE(s.unsupported.empty()) << ::testing::PrintToString(s.unsupported);
    EXPECT_THROW(loadText(materialDocument(
                     R"([{"extensions": {"KHR_materials_pbrSpecularGlossiness": {"glossinessFactor": 2}}}])", 1)),
        pt::SceneError);
}

} // namespace
} // namespace pt::test::gltf
