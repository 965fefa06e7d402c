// The CENG795 loader's textures (HW4): TextureMaps, decal modes, images, per-object material
// variants, and texture errors.
#include "ceng795_fixture.h"
#include "image/image_io.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Textures (HW4): TextureMaps, decal modes, images, per-object material variants

// A 2x1 binary PPM (stb_image reads PNM like PNG and JPEG): red then green.
std::string tinyPpm() { return std::string("P6\n2 1\n255\n") + std::string("\xff\x00\x00\x00\xff\x00", 6); }

const std::string kTextureMaps =
    "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image></Images>"
    "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode>"
    "<Interpolation>nearest</Interpolation><Normalizer>127.5</Normalizer></TextureMap>"
    "<TextureMap id=\"2\" "
    "type=\"image\"><ImageId>1</ImageId><DecalMode>bump_normal</DecalMode><BumpFactor>0.25</BumpFactor></TextureMap>"
    "<TextureMap id=\"3\" type=\"checkerboard\"><DecalMode>blend_kd</DecalMode><BlackColor>0 0 0.5</BlackColor>"
    "<WhiteColor>1 1 1</WhiteColor><Scale>4</Scale><Offset>0.5</Offset></TextureMap>"
    "<TextureMap id=\"4\" "
    "type=\"perlin\"><DecalMode>replace_normal</DecalMode><NoiseConversion>absval</NoiseConversion>"
    "<NoiseScale>3</NoiseScale></TextureMap>"
    "<TextureMap id=\"5\" type=\"image\" "
    "degamma=\"true\"><ImageId>1</ImageId><DecalMode>replace_all</DecalMode></TextureMap>"
    "</Textures>";

TEST_F(Ceng795, TextureMapsBecomeTexturesAndDecalModesMaterialSlots) {
    write("tex/tiny.ppm", tinyPpm());
    const pt::Scene s = load(triangleScene("", "<Textures>1 2</Textures>", kTextureMaps));
    ASSERT_EQ(s.meshes.size(), 1u);
    const pt::Material& m = s.materials.at(s.meshes[0].material);
    ASSERT_TRUE(m.baseColorTexture && m.normalTexture);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1.0f))); // replace_kd: the texel is kd
    EXPECT_FALSE(m.blendBaseColor);
    EXPECT_TRUE(m.bumpMap);
    EXPECT_FLOAT_EQ(m.normalScale, 0.25f);
    const pt::Texture& kd = s.textures.at(*m.baseColorTexture);
    EXPECT_EQ(kd.type, pt::Texture::Type::Image);
    EXPECT_FALSE(kd.bilinear);
    EXPECT_FLOAT_EQ(kd.valueScale, 2.0f); // 255 / Normalizer
    const pt::Texture& bump = s.textures.at(*m.normalTexture);
    EXPECT_TRUE(bump.bilinear);      // Interpolation omitted: bilinear
    EXPECT_EQ(kd.image, bump.image); // one image, read once
    ASSERT_EQ(s.textureImages.size(), 1u);
    EXPECT_EQ(s.textureImages[0].width, 2);
    EXPECT_EQ(s.textureImages[0].rgba8.at(0), 0xff0000ffu); // red, opaque
    EXPECT_EQ(s.textureImages[0].rgba8.at(1), 0xff00ff00u); // green
    // The untextured material is left as it was.
    EXPECT_TRUE(near3(s.materials.at(0).baseColor, glm::vec3(0.5f)));
    EXPECT_FALSE(s.materials.at(0).baseColorTexture);
}

TEST_F(Ceng795, ProceduralTexturesAndTheOtherDecalModes) {
    write("tex/tiny.ppm", tinyPpm());
    const pt::Scene s = load(triangleScene("", "<Textures>3 4</Textures>", kTextureMaps));
    const pt::Material& m = s.materials.at(s.meshes[0].material);
    const pt::Texture& checker = s.textures.at(*m.baseColorTexture);
    EXPECT_EQ(checker.type, pt::Texture::Type::Checkerboard);
    EXPECT_TRUE(m.blendBaseColor);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(0.5f))); // blend_kd keeps kd to average with
    EXPECT_TRUE(near3(checker.black, glm::vec3(0, 0, 0.5f)));
    EXPECT_FLOAT_EQ(checker.scale, 4.0f);
    EXPECT_FLOAT_EQ(checker.offset, 0.5f);
    const pt::Texture& perlin = s.textures.at(*m.normalTexture);
    EXPECT_EQ(perlin.type, pt::Texture::Type::Perlin);
    EXPECT_TRUE(perlin.perlinAbs);
    EXPECT_FLOAT_EQ(perlin.scale, 3.0f);
    EXPECT_FALSE(m.bumpMap);
    EXPECT_TRUE(s.textureImages.empty()); // no image map used, none loaded

    const pt::Scene all = load(triangleScene("", "<Textures>5</Textures>", kTextureMaps));
    const pt::Material& unlit = all.materials.at(all.meshes[0].material);
    EXPECT_TRUE(unlit.unlit);
    EXPECT_EQ(all.textures.at(*unlit.baseColorTexture).encoding, pt::Texture::Encoding::Gamma22);
}

TEST_F(Ceng795, ObjectsWithTheSameTexturesShareOneMaterialVariant) {
    write("tex/tiny.ppm", tinyPpm());
    const std::string xml =
        sceneXml(kOneMaterial + kSquare + kTextureMaps +
                 "<Objects><Mesh id=\"1\"><Material>1</Material><Textures>1</Textures><Faces>1 2 3</Faces></Mesh>"
                 "<Mesh id=\"2\"><Material>1</Material><Textures>1</Textures><Faces>1 3 4</Faces></Mesh>"
                 "<MeshInstance id=\"3\" baseMeshId=\"1\"><Textures>3</Textures></MeshInstance>"
                 "<MeshInstance id=\"4\" baseMeshId=\"1\"></MeshInstance></Objects>");
    const pt::Scene s = loadExpanded(xml);
    ASSERT_EQ(s.meshes.size(), 4u);
    const uint32_t base = findMesh(s, "Mesh 1")->material;
    EXPECT_EQ(findMesh(s, "Mesh 2")->material, base);
    EXPECT_NE(findMesh(s, "MeshInstance 3")->material, base); // its own Textures
    EXPECT_EQ(findMesh(s, "MeshInstance 4")->material, base); // inherits the base's
    EXPECT_EQ(s.materials.size(), 3u);
}

TEST_F(Ceng795, ReplaceBackgroundBecomesTheSceneBackgroundTexture) {
    write("tex/tiny.ppm", tinyPpm());
    const std::string bg =
        "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image></Images>"
        "<TextureMap id=\"1\" "
        "type=\"image\"><ImageId>1</ImageId><DecalMode>replace_background</DecalMode></TextureMap></Textures>";
    const pt::Scene s = load(triangleScene("", "", bg));
    ASSERT_TRUE(s.backgroundTexture.has_value());
    EXPECT_EQ(s.textures.at(*s.backgroundTexture).type, pt::Texture::Type::Image);
    EXPECT_TRUE(std::none_of(s.unsupported.begin(), s.unsupported.end(),
        [](const std::string& n) { return n.find("texture") != std::string::npos; }));
}

// Parameters the format leaves unspecified or to the file, when left out: each named with the
// value taken. (NoiseScale and BumpFactor default to 1 and Normalizer to 255 in the format itself.)
TEST_F(Ceng795, TextureParametersLeftOutAreNoted) {
    write("tex/tiny.ppm", tinyPpm());
    pt::Image hdr;
    hdr.width = hdr.height = 1;
    hdr.rgba = {2.0f, 2.0f, 2.0f, 1.0f};
    pt::writeExr(dir_ / "tex" / "bright.exr", hdr, {});
    const std::string maps =
        "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image><Image id=\"2\">tex/bright.exr</Image></Images>"
        "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap>"
        "<TextureMap id=\"2\" type=\"image\"><ImageId>2</ImageId><DecalMode>replace_ks</DecalMode>"
        "<Interpolation>nearest</Interpolation></TextureMap>"
        "<TextureMap id=\"3\" type=\"checkerboard\"><DecalMode>replace_kd</DecalMode><Scale>2</Scale></TextureMap>"
        "<TextureMap id=\"4\" type=\"perlin\"><DecalMode>bump_normal</DecalMode></TextureMap></Textures>";
    const std::string glossy = "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
                               "<SpecularReflectance>0.5 0.5 0.5</SpecularReflectance><PhongExponent>10</PhongExponent>"
                               "</Material></Materials>";
    const pt::Scene s = load(sceneXml(glossy + kSquare + "<TexCoordData>0 0 1 0 1 1 0 1</TexCoordData>" + maps +
                                      "<Objects><Mesh id=\"1\"><Material>1</Material><Textures>1 2</Textures>"
                                      "<Faces>1 2 3</Faces></Mesh><Mesh id=\"2\"><Material>1</Material>"
                                      "<Textures>3 4</Textures><Faces>1 3 4</Faces></Mesh></Objects>"));
    const std::vector<std::string> expected = {"TextureMap id=1: no Interpolation (bilinear assumed)",
        "TextureMap id=2: no Normalizer for an HDR image (1, texels as stored, assumed)",
        "TextureMap id=3: no BlackColor (0 0 0 assumed)", "TextureMap id=3: no WhiteColor (1 1 1 assumed)",
        "TextureMap id=3: no Offset (0 assumed)", "TextureMap id=4: no NoiseConversion (linear assumed)"};
    EXPECT_EQ(s.unsupported, expected);
    EXPECT_TRUE(s.textures.at(0).bilinear);
}

TEST_F(Ceng795, BadTexturesAreNamedErrors) {
    write("tex/tiny.ppm", tinyPpm());
    write("tex/broken.png", "\x89PNG\r\n\x1a\n truncated");
    expectError(
        triangleScene("", "<Textures>9</Textures>", kTextureMaps), "Mesh id=1: Textures", "unknown TextureMap 9");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><TextureMap id=\"1\" "
                    "type=\"image\"><ImageId>1</ImageId><DecalMode>paint_it</DecalMode></TextureMap></Textures>"),
        "TextureMap id=1: DecalMode", "unknown decal mode");
    expectError(
        triangleScene("", "<Textures>1</Textures>",
            "<Textures><TextureMap id=\"1\" type=\"marble\"><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "TextureMap id=1", "unknown TextureMap type");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><TextureMap id=\"1\" "
                    "type=\"image\"><ImageId>4</ImageId><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "TextureMap id=1: ImageId", "unknown image 4");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><Images><Image id=\"1\">tex/missing.png</Image></Images>"
                    "<TextureMap id=\"1\" "
                    "type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "Image id=1", "missing.png");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><Images><Image id=\"1\">tex/broken.png</Image></Images>"
                    "<TextureMap id=\"1\" "
                    "type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "Image id=1", "cannot decode image");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image></Images>"
                    "<TextureMap id=\"1\" "
                    "type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode><Normalizer>0</Normalizer></"
                    "TextureMap></Textures>"),
        "TextureMap id=1: Normalizer", "must be positive");
}

} // namespace
} // namespace pt::test
