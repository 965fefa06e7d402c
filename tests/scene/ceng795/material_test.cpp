// The CENG795 loader's materials: diffuse, the course BRDFs as glossy materials, mirror,
// dielectric with Beer absorption, conductor with roughness, degamma, and material errors.
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Materials

std::string materialScene(const std::string& material, const std::string& extra = "") {
    return sceneXml("<Materials>" + material + "</Materials>" + extra + kSquare +
                    "<Objects><Mesh id=\"1\"><Material>5</Material><Faces>1 2 3</Faces></Mesh></Objects>");
}

TEST_F(Ceng795, DefaultMaterialIsDiffuse) {
    const pt::Scene s = load(materialScene(
        "<Material id=\"5\"><AmbientReflectance>1 1 1</AmbientReflectance>"
        "<DiffuseReflectance>0.2 0.4 0.6</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance>"
        "<PhongExponent>10</PhongExponent></Material>"));
    ASSERT_EQ(s.materials.size(), 1u);
    const pt::Material& m = s.materials[0];
    EXPECT_EQ(m.type, pt::MaterialType::Diffuse);
    EXPECT_EQ(m.name, "material 5");
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(0.2f, 0.4f, 0.6f)));
    EXPECT_FALSE(m.doubleSided);
    EXPECT_FALSE(contains(s.unsupported, "course BRDF specular lobes (rendered diffuse)"));
}

TEST_F(Ceng795, BrdfsBecomeGlossyMaterials) {
    const std::string brdfs =
        "<BRDFs><ModifiedPhong id=\"1\" normalized=\"true\"><Exponent>90</Exponent></ModifiedPhong>"
        "<TorranceSparrow id=\"2\" kdfresnel=\"true\"><Exponent>50</Exponent></TorranceSparrow></BRDFs>";
    const pt::Scene used =
        load(materialScene("<Material id=\"5\" BRDF=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
                           "<SpecularReflectance>0.3 0.3 0.3</SpecularReflectance></Material>",
            brdfs));
    EXPECT_TRUE(used.unsupported.empty()) << used.unsupported.front();
    EXPECT_EQ(used.materials[0].type, pt::MaterialType::Glossy);
    EXPECT_EQ(used.materials[0].glossyModel, pt::GlossyModel::ModifiedPhong);
    EXPECT_EQ(used.materials[0].exponent, 90.0f);
    EXPECT_TRUE(used.materials[0].normalized);
    const pt::Scene ts = load(
        materialScene("<Material id=\"5\" BRDF=\"2\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
                      "<SpecularReflectance>1 0.86 0.57</SpecularReflectance><RefractionIndex>0.37</RefractionIndex>"
                      "<AbsorptionIndex>2.82</AbsorptionIndex></Material>",
            brdfs));
    EXPECT_EQ(ts.materials[0].glossyModel, pt::GlossyModel::TorranceSparrow);
    EXPECT_TRUE(ts.materials[0].kdFresnel);
    EXPECT_FLOAT_EQ(ts.materials[0].conductorK.x, 2.82f);
    // Without a BRDF, a specular colour means the course's default Blinn-Phong with PhongExponent.
    const pt::Scene classic = load(materialScene(
        "<Material id=\"5\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
        "<SpecularReflectance>0.3 0.3 0.3</SpecularReflectance><PhongExponent>40</PhongExponent></Material>"));
    EXPECT_EQ(classic.materials[0].glossyModel, pt::GlossyModel::OriginalBlinnPhong);
    EXPECT_EQ(classic.materials[0].exponent, 40.0f);
    // The HW6 Cornell files carry unused leftovers (e.g. a <Transparency> material): no warning.
    const pt::Scene unused =
        load(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>"
                           "<Material id=\"6\"><SpecularReflectance>0.3 0.3 "
                           "0.3</SpecularReflectance><Transparency>0.99 0.99 0.99</Transparency></Material>"));
    EXPECT_TRUE(
        unused.unsupported.empty() || !contains(unused.unsupported, "course BRDF specular lobes (rendered diffuse)"));
    expectError(materialScene("<Material id=\"5\" BRDF=\"4\"/>", brdfs), "Material id=5", "unknown BRDF '4'");
}

TEST_F(Ceng795, MirrorMaterial) {
    const pt::Scene s =
        load(materialScene("<Material id=\"5\" type=\"mirror\"><DiffuseReflectance>0.1 0.1 0.1</DiffuseReflectance>"
                           "<MirrorReflectance>0.9 0.8 0.7</MirrorReflectance></Material>"));
    // With a diffuse (or specular) layer: the course adds the BRDF's terms to the mirror, a glossy
    // material with a mirror lobe.
    EXPECT_EQ(s.materials[0].type, pt::MaterialType::Glossy);
    EXPECT_TRUE(near3(s.materials[0].baseColor, glm::vec3(0.1f)));
    EXPECT_TRUE(near3(s.materials[0].mirrorReflectance, glm::vec3(0.9f, 0.8f, 0.7f)));
    EXPECT_TRUE(s.unsupported.empty() || !contains(s.unsupported, "mirror with diffuse layer"));
    const pt::Scene plain =
        load(materialScene("<Material id=\"5\" type=\"mirror\"><MirrorReflectance>0.9 0.8 0.7</MirrorReflectance>"
                           "<DiffuseReflectance>0 0 0</DiffuseReflectance></Material>"));
    EXPECT_EQ(plain.materials[0].type, pt::MaterialType::Mirror);
    EXPECT_TRUE(near3(plain.materials[0].baseColor, glm::vec3(0.9f, 0.8f, 0.7f)));
    expectError(materialScene("<Material id=\"5\" type=\"mirror\"/>"), "Material id=5", "missing <MirrorReflectance>");
}

TEST_F(Ceng795, DielectricMaterialWithBeerAbsorption) {
    const pt::Scene s = load(
        materialScene("<Material id=\"5\" type=\"dielectric\"><AbsorptionCoefficient>0.01 0.5 2</AbsorptionCoefficient>"
                      "<RefractionIndex>1.5</RefractionIndex></Material>"));
    const pt::Material& m = s.materials[0];
    EXPECT_EQ(m.type, pt::MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(m.ior, 1.5f);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1.0f)));
    EXPECT_FLOAT_EQ(m.attenuationDistance, 1.0f);
    EXPECT_TRUE(near3(m.attenuationColor, glm::vec3(std::exp(-0.01f), std::exp(-0.5f), std::exp(-2.0f))));
    // No absorption: no attenuation at all.
    const pt::Scene clear =
        load(materialScene("<Material id=\"5\" type=\"dielectric\"><RefractionIndex>1.3</RefractionIndex></Material>"));
    EXPECT_TRUE(std::isinf(clear.materials[0].attenuationDistance));
    expectError(materialScene("<Material id=\"5\" type=\"dielectric\"><RefractionIndex>0</RefractionIndex></Material>"),
        "Material id=5: RefractionIndex", "must be positive");
    expectError(materialScene("<Material id=\"5\" type=\"dielectric\"><RefractionIndex>1.5</RefractionIndex>"
                              "<AbsorptionCoefficient>-1 0 0</AbsorptionCoefficient></Material>"),
        "Material id=5: AbsorptionCoefficient", "must not be negative");
}

TEST_F(Ceng795, ConductorMaterialAndRoughness) {
    const pt::Scene s =
        load(materialScene("<Material id=\"5\" type=\"conductor\"><MirrorReflectance>1 0.86 0.57</MirrorReflectance>"
                           "<RefractionIndex>0.370</RefractionIndex><AbsorptionIndex>2.820</"
                           "AbsorptionIndex><Roughness>0.2</Roughness></Material>"));
    const pt::Material& m = s.materials[0];
    EXPECT_EQ(m.type, pt::MaterialType::Conductor);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1, 0.86f, 0.57f)));
    EXPECT_TRUE(near3(m.conductorEta, glm::vec3(0.37f)));
    EXPECT_TRUE(near3(m.conductorK, glm::vec3(2.82f)));
    // The course's Roughness r as GGX alpha r / 5 (perceptual roughness sqrt(alpha)).
    EXPECT_NEAR(m.roughness * m.roughness, 0.2f * 0.2f, 1e-6f);
    EXPECT_FALSE(contains(s.unsupported, "rough specular (rendered smooth)"));
}

// Values the course's files give and these leave out: each named with what the loader took
// (noted only for materials in use, as the other material notes).
TEST_F(Ceng795, MissingPhongExponentAndAbsorptionIndexAreNoted) {
    const pt::Scene glossy =
        load(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
                           "<SpecularReflectance>0.2 0.2 0.2</SpecularReflectance></Material>"));
    EXPECT_FLOAT_EQ(glossy.materials[0].exponent, 1.0f);
    EXPECT_FLOAT_EQ(glossy.materials[0].classicExponent, 1.0f);
    EXPECT_EQ(glossy.unsupported,
        std::vector<std::string>{"Material id=5: no PhongExponent for its SpecularReflectance (1 assumed)"});
    // Without a specular term there is nothing for the exponent to shape.
    const pt::Scene matte =
        load(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>"));
    EXPECT_TRUE(matte.unsupported.empty());
    const pt::Scene conductor =
        load(materialScene("<Material id=\"5\" type=\"conductor\"><MirrorReflectance>1 1 1</MirrorReflectance>"
                           "<RefractionIndex>0.37</RefractionIndex></Material>"));
    EXPECT_TRUE(near3(conductor.materials[0].conductorK, glm::vec3(0.0f)));
    EXPECT_EQ(conductor.unsupported, std::vector<std::string>{"Material id=5: no AbsorptionIndex (0 assumed)"});
    const pt::Scene unused =
        load(materialScene("<Material id=\"5\"><DiffuseReflectance>1 1 1</DiffuseReflectance>"
                           "</Material><Material id=\"6\" type=\"conductor\"><MirrorReflectance>1 "
                           "1 1</MirrorReflectance><RefractionIndex>2</RefractionIndex></Material>"));
    EXPECT_TRUE(unused.unsupported.empty());
}

TEST_F(Ceng795, DegammaLinearisesColours) {
    const pt::Scene s = load(materialScene(
        "<Material id=\"5\" degamma=\"true\"><DiffuseReflectance>0.5 1 0</DiffuseReflectance></Material>"));
    EXPECT_TRUE(near3(s.materials[0].baseColor, glm::vec3(std::pow(0.5f, 2.2f), 1.0f, 0.0f)));
}

TEST_F(Ceng795, MaterialErrors) {
    expectError(materialScene("<Material id=\"5\"><DiffuseReflectance>nan 0 0</DiffuseReflectance></Material>"),
        "Material id=5: DiffuseReflectance", "'nan' is not a finite number");
    expectError(materialScene("<Material id=\"5\"><DiffuseReflectance>1e999 0 0</DiffuseReflectance></Material>"),
        "Material id=5: DiffuseReflectance", "'1e999' is out of range");
    expectError(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5</DiffuseReflectance></Material>"),
        "Material id=5: DiffuseReflectance", "expected 3 numbers, found 2");
    expectError(materialScene("<Material id=\"5\"/><Material id=\"5\"/>"), "Material id=5", "duplicate id");
    expectError(materialScene("<Material><DiffuseReflectance>1 1 1</DiffuseReflectance></Material>"),
        "Materials: Material", "missing id attribute");
}

} // namespace
} // namespace pt::test
