// The CENG795 loader's cameras: near planes, lookAt cameras, handedness, tone mapping settings,
// RendererParams as integrator switches, and camera errors.
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Cameras

std::string cameraScene(const std::string& cameras) {
    return triangleScene("", "", "<Cameras>" + cameras + "</Cameras>");
}

TEST_F(Ceng795, SimpleCameraWithNearPlane) {
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"7\"><Position>0 5 25</Position><Gaze>0 0 -2</Gaze><Up>0 1 0.5</Up>"
        "<NearPlane>-1 1 -0.5 0.75</NearPlane><NearDistance>2</NearDistance><ImageResolution>800 400</ImageResolution>"
        "<NumSamples>16</NumSamples><ImageName>spheres.png</ImageName>"
        "<FocusDistance>21</FocusDistance><ApertureSize>1.5</ApertureSize></Camera>"));
    ASSERT_EQ(s.cameras.size(), 1u);
    const pt::Camera& c = s.cameras[0];
    EXPECT_EQ(c.name, "camera 7");
    EXPECT_TRUE(near3(c.position, glm::vec3(0, 5, 25)));
    EXPECT_TRUE(near3(c.forward, glm::vec3(0, 0, -1)));
    EXPECT_TRUE(near3(c.up, glm::vec3(0, 1, 0))); // re-orthogonalised against the gaze
    ASSERT_TRUE(c.window.has_value());
    EXPECT_TRUE(near4(*c.window, glm::vec4(-0.5f, 0.5f, -0.25f, 0.375f)));
    EXPECT_NEAR(c.yfov, std::atan(0.375f) + std::atan(0.25f), 1e-6f);
    EXPECT_FLOAT_EQ(c.aspectRatio, 2.0f);
    EXPECT_FLOAT_EQ(c.apertureSize, 1.5f);
    EXPECT_FLOAT_EQ(c.focusDistance, 21.0f);
    EXPECT_EQ(c.settings.width, std::optional<int>(800));
    EXPECT_EQ(c.settings.height, std::optional<int>(400));
    EXPECT_EQ(c.settings.spp, std::optional<uint32_t>(16));
    EXPECT_EQ(c.settings.imageName, "spheres.png");
    EXPECT_EQ(c.id, 7);
    // The course has no scene-wide resolution: each camera carries its own.
    EXPECT_FALSE(s.hints.width.has_value());
}

TEST_F(Ceng795, LookAtCameraWithGazePointOrGazeAndFovY) {
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"1\" type=\"lookAt\"><Position>1 1 1</Position><GazePoint>1 1 -3</GazePoint><Up>0 1 0</Up>"
        "<FovY>60</FovY><NearDistance>1.7</NearDistance><ImageResolution>1280 720</ImageResolution></Camera>"
        // The official HW6 Cornell files: type="lookAt" with a Gaze direction.
        "<Camera id=\"2\" type=\"lookAt\" handedness=\"right\"><Position>0 -4 0</Position><Gaze>0 2 0</Gaze><Up>0 0 "
        "1</Up>"
        "<FovY>45</FovY><NearDistance>0.1</NearDistance></Camera>"));
    ASSERT_EQ(s.cameras.size(), 2u);
    EXPECT_TRUE(near3(s.cameras[0].forward, glm::vec3(0, 0, -1)));
    EXPECT_FALSE(s.cameras[0].window.has_value());
    EXPECT_NEAR(s.cameras[0].yfov, glm::radians(60.0f), 1e-6f);
    EXPECT_NEAR(s.cameras[0].aspectRatio, 1280.0f / 720.0f, 1e-6f);
    EXPECT_TRUE(near3(s.cameras[1].forward, glm::vec3(0, 1, 0)));
    EXPECT_TRUE(near3(s.cameras[1].up, glm::vec3(0, 0, 1)));
    EXPECT_EQ(s.cameras[1].name, "camera 2");
    EXPECT_EQ(s.cameras[1].id, 2);
}

TEST_F(Ceng795, LeftHandedCameraMirrorsTheWindow) {
    // Course left-handed u = w x v = -(pt's right): columns run the other way, so the window's
    // left and right are negated (left > right).
    const pt::Scene s = load(
        cameraScene("<Camera id=\"1\" handedness=\"left\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                    "<NearPlane>-1 3 -1 1</NearPlane><NearDistance>2</NearDistance></Camera>"
                    "<Camera id=\"2\" type=\"lookAt\" handedness=\"left\"><Position>0 0 0</Position><GazePoint>0 0 "
                    "-1</GazePoint><Up>0 1 0</Up>"
                    "<FovY>90</FovY><ImageResolution>200 100</ImageResolution></Camera>"));
    EXPECT_TRUE(near4(*s.cameras[0].window, glm::vec4(0.5f, -1.5f, -0.5f, 0.5f)));
    ASSERT_TRUE(s.cameras[1].window.has_value());
    EXPECT_TRUE(near4(*s.cameras[1].window, glm::vec4(2.0f, -2.0f, -1.0f, 1.0f), 1e-5f));
}

TEST_F(Ceng795, TonemapSettings) {
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Tonemap><TMO>Photographic</TMO><TMOOptions>0.18 "
        "1</TMOOptions><Saturation>0.8</Saturation><Gamma>2.2</Gamma></Tonemap></Camera>"
        "<Camera id=\"2\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Tonemap><TMO>Photographic</TMO><TMOOptions>0.0018 0</TMOOptions><Gamma>sRGB</Gamma></Tonemap></Camera>"
        "<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY></Camera>"));
    const pt::TonemapSettings& a = *s.cameras[0].settings.tonemap;
    EXPECT_EQ(a.op, pt::TonemapSettings::Operator::Photographic);
    EXPECT_FLOAT_EQ(a.key, 0.18f);
    EXPECT_FLOAT_EQ(a.burnPercent, 1.0f);
    EXPECT_FLOAT_EQ(a.saturation, 0.8f);
    EXPECT_FLOAT_EQ(a.gamma, 2.2f);
    EXPECT_FALSE(a.srgb);
    const pt::TonemapSettings& b = *s.cameras[1].settings.tonemap;
    EXPECT_TRUE(b.srgb);
    EXPECT_FLOAT_EQ(b.key, 0.0018f);
    // No Tonemap: the course clamps with no gamma.
    const pt::TonemapSettings& c = *s.cameras[2].settings.tonemap;
    EXPECT_EQ(c.op, pt::TonemapSettings::Operator::Clamp);
    EXPECT_FALSE(c.srgb);
    EXPECT_FLOAT_EQ(c.gamma, 1.0f);
    EXPECT_FALSE(s.cameras[2].settings.spp.has_value());
}

// A Tonemap that leaves out its options, and a camera without an id: each value the loader fills
// in is named in a note (the "values assumed" warning; the CLI tests check its file name).
TEST_F(Ceng795, TonemapWithoutOptionsAndCameraWithoutIdSayWhatIsAssumed) {
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Tonemap><TMO>Photographic</TMO></Tonemap></Camera>"
        "<Camera><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<GammaCorrection>sRGB</GammaCorrection><Tonemap><TMO>Photographic</TMO><TMOOptions>0.18 1</TMOOptions>"
        "<Saturation>1</Saturation></Tonemap></Camera>"));
    const std::vector<std::string> expected = {"Camera id=1: Tonemap without TMOOptions (key 0.18, burn 0% assumed)",
        "Camera id=1: Tonemap without Saturation (1 assumed)",
        "Camera id=1: Tonemap without Gamma (1, no gamma correction, assumed)",
        "Camera without an id (the name 'camera 2' from its position assumed)"};
    EXPECT_EQ(s.unsupported, expected); // camera 2's gamma comes from GammaCorrection: nothing assumed
    const pt::TonemapSettings& a = *s.cameras[0].settings.tonemap;
    EXPECT_FLOAT_EQ(a.key, 0.18f);
    EXPECT_FLOAT_EQ(a.burnPercent, 0.0f);
    EXPECT_FLOAT_EQ(a.gamma, 1.0f);
    EXPECT_FALSE(a.srgb);
    EXPECT_TRUE(s.cameras[1].settings.tonemap->srgb);
    EXPECT_EQ(s.cameras[1].id, -1);
}

TEST_F(Ceng795, RendererParamsMapToIntegratorSwitches) {
    auto camera = [](int id, const std::string& renderer) {
        return "<Camera id=\"" + std::to_string(id) +
               "\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
               "<FovY>45</FovY>" +
               renderer + "</Camera>";
    };
    const pt::Scene s = load(
        cameraScene(camera(1, "<Renderer>PathTracing</Renderer><RendererParams>NextEventEstimation ImportanceSampling "
                              "RussianRoulette</RendererParams>") +
                    camera(2, "<Renderer>PathTracing</Renderer><RendererParams>ImportanceSampling</RendererParams>") +
                    camera(3, "<Renderer>PathTracing</Renderer><RendererParams></RendererParams>") +
                    camera(4, "<Renderer>PathTracing</Renderer>")));
    const auto& a = s.cameras[0].settings;
    EXPECT_EQ(a.nee, std::optional<bool>(true));
    EXPECT_EQ(a.importanceSampling, std::optional<bool>(true));
    EXPECT_EQ(a.russianRoulette, std::optional<bool>(true));
    const auto& b = s.cameras[1].settings;
    EXPECT_EQ(b.nee, std::optional<bool>(false));
    EXPECT_EQ(b.importanceSampling, std::optional<bool>(true));
    EXPECT_EQ(b.russianRoulette, std::optional<bool>(false));
    for (int i : {2, 3}) {
        const auto& c = s.cameras[i].settings;
        EXPECT_EQ(c.nee, std::optional<bool>(false)) << i;
        EXPECT_EQ(c.importanceSampling, std::optional<bool>(false)) << i;
        EXPECT_EQ(c.russianRoulette, std::optional<bool>(false)) << i;
    }
    EXPECT_EQ(a.classic, std::optional<bool>(false));

    // No Renderer: the course's classic ray tracer, whose images are in 0..255 display units.
    const pt::Scene classic = load(cameraScene(camera(1, "")));
    EXPECT_EQ(classic.cameras[0].settings.classic, std::optional<bool>(true));
    EXPECT_FALSE(classic.cameras[0].settings.nee.has_value());
    EXPECT_FALSE(classic.cameras[0].settings.importanceSampling.has_value());
    EXPECT_FALSE(classic.cameras[0].settings.russianRoulette.has_value());
    ASSERT_TRUE(classic.cameras[0].settings.tonemap.has_value());
    EXPECT_FLOAT_EQ(classic.cameras[0].settings.tonemap->scale, 1.0f / 255.0f);
}

TEST_F(Ceng795, CameraErrors) {
    const std::string view = "<Position>0 0 0</Position><Up>0 1 0</Up><FovY>45</FovY>";
    expectError(cameraScene("<Camera id=\"3\">" + view + "</Camera>"), "Camera id=3", "missing <Gaze> or <GazePoint>");
    expectError(
        cameraScene(
            "<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 1 0</Gaze><Up>0 2 0</Up><FovY>45</FovY></Camera>"),
        "Camera id=3", "Up is zero or parallel to the gaze");
    expectError(
        cameraScene(
            "<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 0</Gaze><Up>0 1 0</Up><FovY>45</FovY></Camera>"),
        "Camera id=3", "gaze direction is zero");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up></Camera>"),
        "Camera id=3", "missing <NearPlane> or <FovY>");
    expectError(
        cameraScene(
            "<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>180</FovY></Camera>"),
        "Camera id=3: FovY", "must be in (0, 180)");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                            "<NearPlane>1 -1 -1 1</NearPlane><NearDistance>1</NearDistance></Camera>"),
        "Camera id=3: NearPlane", "left < right");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                            "<NearPlane>-1 1 -1 1</NearPlane></Camera>"),
        "Camera id=3", "missing <NearDistance>");
    expectError(cameraScene("<Camera id=\"3\"><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY></Camera>"),
        "Camera id=3", "missing <Position>");
    expectError(
        cameraScene("<Camera id=\"3\">" + view + "<Gaze>0 0 -1</Gaze><NumSamples>99999999999</NumSamples></Camera>"),
        "Camera id=3: NumSamples", "out of range");
    expectError(
        cameraScene("<Camera id=\"3\">" + view + "<Gaze>0 0 -1</Gaze><ImageResolution>0 10</ImageResolution></Camera>"),
        "Camera id=3: ImageResolution", "out of range");
    expectError(
        cameraScene("<Camera id=\"3\">" + view + "<Gaze>0 0 -1</Gaze><ImageName>../../x.png</ImageName></Camera>"),
        "Camera id=3: ImageName", "relative path inside");
    expectError(cameraScene("<Camera id=\"3\" handedness=\"up\">" + view + "<Gaze>0 0 -1</Gaze></Camera>"),
        "Camera id=3", "handedness 'up'");
}

} // namespace
} // namespace pt::test
