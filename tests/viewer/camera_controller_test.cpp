// The viewer's camera controls and script parser: pure host code, no window.
#include "viewer/camera_controller.h"
#include "viewer/script.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pt::viewer {
namespace {

Camera cornellCamera() {
    Camera c;
    c.position = glm::vec3(0, 0, 3.9f);
    c.forward = glm::vec3(0, 0, -1);
    c.up = glm::vec3(0, 1, 0);
    c.yfov = 0.686f;
    return c;
}

void expectNear(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(ViewerCamera, OrbitKeepsTargetAndDistance) {
    CameraController c(cornellCamera(), glm::vec3(0.0f), 1.0f);
    const glm::vec3 target = c.target();
    expectNear(target, glm::vec3(0.0f));
    c.orbit(glm::vec2(100, -40));
    expectNear(c.target(), target);
    EXPECT_NEAR(glm::length(c.camera().position - target), 3.9f, 1e-4f);
    const Camera cam = c.camera();
    EXPECT_NEAR(glm::length(cam.forward), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(cam.forward, cam.up), 0.0f, 1e-5f);
    EXPECT_GT(cam.up.y, 0.0f); // still upright
    EXPECT_GT(std::abs(cam.position.x), 0.1f);
}

TEST(ViewerCamera, ElevationStopsShortOfTheUpAxis) {
    CameraController c(cornellCamera(), glm::vec3(0.0f), 1.0f);
    c.orbit(glm::vec2(0, 10000)); // far past the pole
    const Camera cam = c.camera();
    EXPECT_LT(std::abs(glm::dot(cam.forward, glm::vec3(0, 1, 0))), 0.9999f);
    EXPECT_FALSE(std::isnan(cam.up.x));
}

TEST(ViewerCamera, PanMovesCameraAndTargetTogether) {
    CameraController c(cornellCamera(), glm::vec3(0.0f), 1.0f);
    c.pan(glm::vec2(-50, 0), 500); // drag left: the view moves right
    const Camera cam = c.camera();
    EXPECT_GT(cam.position.x, 0.0f);
    expectNear(cam.forward, glm::vec3(0, 0, -1));
    EXPECT_NEAR(c.target().x, cam.position.x, 1e-5f);
}

TEST(ViewerCamera, DollyApproachesAndResetRestores) {
    CameraController c(cornellCamera(), glm::vec3(0.0f), 1.0f);
    c.dolly(3.0f);
    EXPECT_NEAR(c.camera().position.z, 3.9f * std::pow(0.9f, 3.0f), 1e-4f);
    c.fly(glm::vec3(1, 0, 0), 0.5f);
    c.reset();
    expectNear(c.camera().position, glm::vec3(0, 0, 3.9f));
    expectNear(c.camera().forward, glm::vec3(0, 0, -1));
}

TEST(ViewerCamera, SnippetsCarryThePose) {
    CameraController c(cornellCamera(), glm::vec3(0.0f), 1.0f);
    EXPECT_NE(c.gltfSnippet().find("\"translation\": [0, 0, 3.9]"), std::string::npos) << c.gltfSnippet();
    EXPECT_NE(c.gltfSnippet().find("\"rotation\": [0, 0, 0, 1]"), std::string::npos) << c.gltfSnippet();
    const std::string xml = c.courseXmlSnippet(512, 256);
    EXPECT_NE(xml.find("<Position>0 0 3.9</Position>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<GazePoint>0 0 0</GazePoint>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<ImageResolution>512 256</ImageResolution>"), std::string::npos) << xml;
}

TEST(ViewerScript, ParsesCommandsAndComments) {
    auto cmds = parseScript(
        "# a test\nwait 3\norbit 10 -5  # drag\n\nrepeat 4 orbit 1 0\ntoggle nee\nsave out/a.exr\nquit\n", "t");
    ASSERT_EQ(cmds.size(), 6u);
    EXPECT_EQ(cmds[1].name, "orbit");
    EXPECT_EQ(cmds[1].numbers, (std::vector<double>{10, -5}));
    EXPECT_EQ(cmds[1].line, 3);
    EXPECT_EQ(cmds[2].numbers, (std::vector<double>{4}));
    EXPECT_EQ(cmds[4].args[0], "out/a.exr");
}

TEST(ViewerScript, RejectsBadLinesWithTheirNumber) {
    auto message = [](const std::string& text) {
        try {
            parseScript(text, "s.txt");
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message("wait 1\nfly away\n"), "s.txt:2: fly: unknown command (see README.md, \"Viewer\")");
    EXPECT_EQ(message("orbit 1\n"), "s.txt:1: orbit: expected 2 number(s), got 1");
    EXPECT_EQ(message("orbit 1 x\n"), "s.txt:1: orbit: 'x' is not a number");
    EXPECT_EQ(message("toggle warp\n"), "s.txt:1: toggle: unknown argument 'warp'");
    EXPECT_EQ(message("repeat 3 wait 1\n"), "s.txt:1: repeat: repeats one command that is not a wait or a repeat");
    EXPECT_EQ(message("resize 0 10\n"), "s.txt:1: resize: size out of range");
}

} // namespace
} // namespace pt::viewer
