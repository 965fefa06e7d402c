// KHR_materials_variants: the scene's variant names, a variant's materials replacing the
// primitives' defaults where they map one, the defaults elsewhere and without a choice, and a clear
// error for a variant the scene lacks or a mapping that is malformed.
#include "gltf_test_documents.h"

#include "scene/scene_error.h"
#include "scene/scene_loader.h"

#include <fstream>

namespace pt::test::gltf {
namespace {

// Two triangles (meshes 0 and 1) with materials "white" (0) by default; three variants: "red"
// maps mesh 0 to material 1 and mesh 1 to material 2, "blue" maps mesh 0 only (to 2), "none"
// maps nothing. `mapping` replaces mesh 0's mappings when given.
std::string variantsDocument(const std::string& mapping = "") {
    std::vector<unsigned char> bytes(36);
    for (int i = 0; i < 3; ++i) std::memcpy(bytes.data() + 12 * i, &kP[i], 12);
    const std::string mesh0 =
        mapping.empty() ? R"([{"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}])" : mapping;
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"mesh": 1, "translation": [0, 0, -2]}],
  "meshes": [
    {"primitives": [{"attributes": {"POSITION": 0}, "material": 0,
      "extensions": {"KHR_materials_variants": {"mappings": )" +
           mesh0 + R"(}}}]},
    {"primitives": [{"attributes": {"POSITION": 0}, "material": 0,
      "extensions": {"KHR_materials_variants": {"mappings": [{"material": 2, "variants": [0]}]}}}]}],
  "materials": [{"name": "white"}, {"name": "red"}, {"name": "blue"}],
  "extensionsUsed": ["KHR_materials_variants"],
  "extensions": {"KHR_materials_variants": {"variants": [{"name": "red"}, {"name": "blue"}, {"name": "none"}]}},
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" +
           base64(bytes) + R"("}]})";
}

Scene load(const std::string& text, const std::string& variant) {
    return loadGltfText(text, "shoe.gltf", fs::temp_directory_path(), variant);
}

std::string materialName(const Scene& s, size_t mesh) { return s.materials.at(s.meshes.at(mesh).material).name; }

TEST(GltfVariants, NamesAreListedAndTheDefaultsRenderWithoutAChoice) {
    const Scene s = load(variantsDocument(), "");
    EXPECT_EQ(s.materialVariants, (std::vector<std::string>{"red", "blue", "none"}));
    EXPECT_TRUE(s.variant.empty());
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(materialName(s, 0), "white");
    EXPECT_EQ(materialName(s, 1), "white");
    EXPECT_TRUE(s.unsupported.empty()) << "no warning for the extension: " << ::testing::PrintToString(s.unsupported);
}

TEST(GltfVariants, AVariantReplacesTheMaterialsItMapsAndKeepsTheRest) {
    const Scene red = load(variantsDocument(), "red");
    EXPECT_EQ(red.variant, "red");
    EXPECT_EQ(materialName(red, 0), "red");
    EXPECT_EQ(materialName(red, 1), "blue");
    const Scene blue = load(variantsDocument(), "blue");
    EXPECT_EQ(materialName(blue, 0), "blue");
    EXPECT_EQ(materialName(blue, 1), "white") << "mesh 1 maps nothing for blue: its default";
    const Scene none = load(variantsDocument(), "none");
    EXPECT_EQ(materialName(none, 0), "white");
    EXPECT_EQ(materialName(none, 1), "white");
}

TEST(GltfVariants, AVariantTheSceneLacksIsAnErrorListingTheNames) {
    try {
        load(variantsDocument(), "green");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("shoe.gltf"), std::string::npos) << m;
        EXPECT_NE(m.find("'green'"), std::string::npos) << m;
        EXPECT_NE(m.find("red, blue, none"), std::string::npos) << m;
    }
    // A scene without the extension has none to choose.
    EXPECT_THROW(
        loadGltfText(materialDocument(R"([{"name": "a"}])", 1), "plain.gltf", fs::temp_directory_path(), "red"),
        SceneError);
}

TEST(GltfVariants, MalformedMappingsAreErrorsNamingThePrimitive) {
    for (const char* mapping : {R"([{"variants": [0]}])", R"([{"material": 1}])",
             R"([{"material": 9, "variants": [0]}])", R"([{"material": -1, "variants": [0]}])", R"("not an array")"}) {
        SCOPED_TRACE(mapping);
        try {
            load(variantsDocument(mapping), "red");
            FAIL() << "expected a SceneError";
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find("mesh 0"), std::string::npos) << e.what();
        }
        EXPECT_NO_THROW(load(variantsDocument(mapping), "")) << "the defaults never read the mappings";
    }
}

TEST(GltfVariants, OnlyGltfScenesHaveVariants) {
    try {
        loadScene("", "red");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("no material variants"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace pt::test::gltf
