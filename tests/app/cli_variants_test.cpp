// pt render and glTF material variants (KHR_materials_variants): --list-variants prints the
// names, --variant NAME renders that variant's materials and records it in the EXR, and a name
// the scene lacks is one error line listing the ones it has. Also KHR_materials_unlit, the other
// material extension that changes what a material is rather than how it scatters.
#include "cli_fixture.h"
#include "image/image_io.h"

#include <fstream>

namespace pt::test {
namespace {

// One emitting triangle (facing +z, where the framing camera looks from): "lamp" (radiance 1)
// by default, "bright" (radiance 4) under the variant "strong", unchanged under "plain".
void writeLampScene(const fs::path& path) {
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0,
    "extensions": {"KHR_materials_variants": {"mappings": [{"material": 1, "variants": [0]}]}}}]}],
  "materials": [{"name": "lamp", "emissiveFactor": [1, 1, 1]},
                {"name": "bright", "emissiveFactor": [1, 1, 1],
                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}],
  "extensionsUsed": ["KHR_materials_variants", "KHR_materials_emissive_strength"],
  "extensions": {"KHR_materials_variants": {"variants": [{"name": "strong"}, {"name": "plain"}]}},
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
}

double meanRed(const Image& image) {
    double sum = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4) sum += image.rgba[i];
    return sum / (image.rgba.size() / 4);
}

TEST_F(CliTest, ListVariantsPrintsTheNames) {
    const fs::path scene = dir_ / "lamp.gltf";
    writeLampScene(scene);
    const PtRun r = run({"render", scene.string(), "--list-variants"});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_EQ(r.out, "strong\nplain\n");
    EXPECT_TRUE(outputs() == std::vector<std::string>{"lamp.gltf"}) << "nothing rendered";
}

TEST_F(CliTest, VariantRendersItsMaterialsAndIsRecorded) {
    const fs::path scene = dir_ / "lamp.gltf";
    writeLampScene(scene);
    auto render = [&](const std::string& variant, const std::string& name) {
        std::vector<std::string> args = {"render", scene.string(), "--spp", "2", "--width", "16", "--height", "16",
            "-q", "-o", (dir_ / name).string()};
        if (!variant.empty()) args.insert(args.end(), {"--variant", variant});
        const PtRun r = run(args);
        EXPECT_EXIT_STATUS(r, 0);
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << "no warning for the extension: " << r.err;
        ImageMetadata meta;
        const Image image = readExr(dir_ / name, &meta);
        EXPECT_EQ(meta.count("variant") ? meta["variant"] : "", variant);
        return meanRed(image);
    };
    const double plainDefault = render("", "default.exr");
    const double strong = render("strong", "strong.exr");
    const double plain = render("plain", "plain.exr");
    ASSERT_GT(plainDefault, 0.01) << "the lamp must be in view";
    EXPECT_NEAR(strong / plainDefault, 4.0, 1e-4) << "emission seen directly: exactly the strength";
    EXPECT_NEAR(plain, plainDefault, 1e-6);
}

TEST_F(CliTest, UnknownVariantIsOneErrorListingTheScenes) {
    const fs::path scene = dir_ / "lamp.gltf";
    writeLampScene(scene);
    const PtRun r = run({"render", scene.string(), "--variant", "dim", "--spp", "1", "-o", "x.exr"});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find("lamp.gltf"), std::string::npos) << line;
    EXPECT_NE(line.find("'dim'"), std::string::npos) << line;
    EXPECT_NE(line.find("strong, plain"), std::string::npos) << line;
    EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

// KHR_materials_unlit: the base colour shown as is, in a scene with no light at all: no
// "not supported" warning, no "nothing emits light" warning, and the quad's pixels are its colour.
TEST_F(CliTest, UnlitMaterialShowsItsColourWithoutLight) {
    const fs::path scene = dir_ / "unlit.gltf";
    std::ofstream(scene) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"name": "sign", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.8, 1]},
                 "extensions": {"KHR_materials_unlit": {}}}],
  "extensionsUsed": ["KHR_materials_unlit"],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAgD8AAAAAAAAAAAAAgD8AAAAAAAABAAIAAAACAAMA"}]})";
    const PtRun r = run({"render", scene.string(), "--spp", "2", "--width", "16", "--height", "16", "-o",
        (dir_ / "unlit.exr").string()});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    const Image image = readExr(dir_ / "unlit.exr");
    const size_t centre = 4 * (size_t(8) * 16 + 8);
    EXPECT_NEAR(image.rgba[centre + 0], 0.2f, 1e-6f);
    EXPECT_NEAR(image.rgba[centre + 1], 0.5f, 1e-6f);
    EXPECT_NEAR(image.rgba[centre + 2], 0.8f, 1e-6f);
}

} // namespace
} // namespace pt::test
