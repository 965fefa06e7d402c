// The CENG795 loader's lights: point, directional, spot and area lights as punctual lights, the
// lights it does not model named once, and SphericalDirectionalLight's environment map.
#include "image/image_io.h"
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Lights

TEST_F(Ceng795, PointAndDirectionalLightsArePunctualLights) {
    const pt::Scene s = load(triangleScene("", "",
        "<Lights>"
        "<PointLight id=\"1\"><Position>0 30 50</Position><Intensity>1000 2000 3000</Intensity></PointLight>"
        "<DirectionalLight id=\"1\"><Direction>0 -2 0</Direction><Radiance>2 2 "
        "2</Radiance></DirectionalLight></Lights>"));
    ASSERT_EQ(s.punctualLights.size(), 2u);
    EXPECT_EQ(s.punctualLights[0].type, pt::PunctualLight::Type::Point);
    EXPECT_TRUE(near3(s.punctualLights[0].position, glm::vec3(0, 30, 50)));
    EXPECT_TRUE(near3(s.punctualLights[0].intensity, glm::vec3(1000, 2000, 3000)));
    EXPECT_EQ(s.punctualLights[1].type, pt::PunctualLight::Type::Directional);
    EXPECT_TRUE(near3(s.punctualLights[1].direction, glm::vec3(0, -1, 0)));
    EXPECT_TRUE(near3(s.punctualLights[1].intensity, glm::vec3(2)));
    EXPECT_TRUE(s.unsupported.empty());
    expectError(triangleScene("", "", "<Lights><PointLight id=\"4\"><Position>0 0 0</Position></PointLight></Lights>"),
        "PointLight id=4", "missing <Intensity>");
    expectError(triangleScene("", "",
                    "<Lights><DirectionalLight id=\"2\"><Direction>0 0 0</Direction><Radiance>1 1 1</Radiance>"
                    "</DirectionalLight></Lights>"),
        "DirectionalLight id=2: Direction", "non-zero");
}

// A falloff cone wider than the coverage cone is cut to it, and the note says so.
TEST_F(Ceng795, SpotFalloffWiderThanCoverageIsCutWithANote) {
    const pt::Scene s = load(triangleScene("", "",
        "<Lights><SpotLight id=\"3\"><Position>0 0 1</Position><Direction>0 0 -1</Direction>"
        "<Intensity>10 10 10</Intensity><CoverageAngle>10</CoverageAngle><FalloffAngle>12.5</FalloffAngle>"
        "</SpotLight></Lights>"));
    ASSERT_EQ(s.punctualLights.size(), 1u);
    EXPECT_FLOAT_EQ(s.punctualLights[0].cosFalloff, s.punctualLights[0].cosCoverage);
    EXPECT_EQ(s.unsupported,
        std::vector<std::string>{"SpotLight id=3: FalloffAngle 12.5 wider than CoverageAngle (10 assumed)"});
}

TEST_F(Ceng795, OtherLightsAreNamedOnce) {
    const pt::Scene s = load(triangleScene("", "",
        "<Lights><AmbientLight>25 25 25</AmbientLight>"
        "<HeadLight id=\"1\"/><HeadLight id=\"2\"/></Lights>"));
    EXPECT_EQ(s.unsupported, (std::vector<std::string>{"HeadLight lights (ignored)"}));
    EXPECT_TRUE(near3(s.ambientLight, glm::vec3(25.0f))); // for the classic integrator
    EXPECT_TRUE(s.punctualLights.empty());
    const pt::Scene dark = load(triangleScene("", "", "<Lights><AmbientLight>0 0 0</AmbientLight></Lights>"));
    EXPECT_TRUE(dark.unsupported.empty());
}

TEST_F(Ceng795, SpotAndAreaLights) {
    const pt::Scene s = load(triangleScene("", "",
        "<Lights>"
        "<SpotLight id=\"1\"><Position>-0.93 1 0.9</Position><Direction>1 -1 -1</Direction><Intensity>600 600 "
        "600</Intensity>"
        "<CoverageAngle>10</CoverageAngle><FalloffAngle>8</FalloffAngle></SpotLight>"
        "<AreaLight id=\"1\"><Position>0 9.8 2</Position><Normal>0 -2 0</Normal><Size>3</Size><Radiance>15 15 "
        "15</Radiance></AreaLight>"
        "</Lights>"));
    ASSERT_EQ(s.punctualLights.size(), 2u);
    const pt::PunctualLight& spot = s.punctualLights[0];
    EXPECT_EQ(spot.type, pt::PunctualLight::Type::Spot);
    EXPECT_TRUE(near3(spot.direction, glm::normalize(glm::vec3(1, -1, -1))));
    EXPECT_NEAR(spot.cosCoverage, std::cos(glm::radians(5.0f)), 1e-6); // half of the full cone angle
    EXPECT_NEAR(spot.cosFalloff, std::cos(glm::radians(4.0f)), 1e-6);
    const pt::PunctualLight& square = s.punctualLights[1];
    EXPECT_EQ(square.type, pt::PunctualLight::Type::Square);
    EXPECT_TRUE(near3(square.direction, glm::vec3(0, -1, 0)));
    EXPECT_EQ(square.size, 3.0f);
    EXPECT_TRUE(s.unsupported.empty());
    expectError(triangleScene("", "",
                    "<Lights><AreaLight id=\"1\"><Position>0 0 0</Position><Normal>0 0 0</Normal>"
                    "<Size>1</Size><Radiance>1 1 1</Radiance></AreaLight></Lights>"),
        "AreaLight id=1", "non-zero");
}

// SphericalDirectionalLight: the lat-long map named by ImageId, read from <Textures><Images>.
TEST_F(Ceng795, SphericalDirectionalLightLoadsItsMap) {
    pt::Image map;
    map.width = 4;
    map.height = 2;
    map.rgba.assign(4 * 2 * 4, 0.5f);
    fs::create_directories(dir_ / "textures");
    pt::writeExr(dir_ / "textures" / "sky.exr", map, {});
    const std::string lights =
        "<Textures><Images><Image id=\"3\">textures/sky.exr</Image></Images></Textures>"
        "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>3</ImageId></SphericalDirectionalLight></Lights>";
    const pt::Scene s = load(triangleScene("", "", lights));
    ASSERT_TRUE(s.environment.has_value());
    EXPECT_EQ(s.environment->image.width, 4);
    EXPECT_EQ(s.environment->image.height, 2);
    EXPECT_FLOAT_EQ(s.environment->image.rgba[0], 0.5f);
    expectError(
        triangleScene("", "",
            "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>9</ImageId></SphericalDirectionalLight></Lights>"),
        "SphericalDirectionalLight id=1: ImageId", "unknown image");
    expectError(
        triangleScene("", "",
            "<Textures><Images><Image id=\"3\">textures/none.exr</Image></Images></Textures>"
            "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>3</ImageId></SphericalDirectionalLight></Lights>"),
        "SphericalDirectionalLight id=1", "none.exr");
}

} // namespace
} // namespace pt::test
