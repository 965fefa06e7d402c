// The CENG795 loader on whole documents: malformed XML, a missing or empty file, text loaded
// against a base directory, unknown elements; and the scene-wide settings (BackgroundColor,
// MaxRecursionDepth).
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Documents

TEST_F(Ceng795, MalformedDocumentsAreErrors) {
    expectError("<Scene><Objects></Scene>", "", "malformed XML at offset");
    expectError("<World></World>", "", "root element is <World>, expected <Scene>");
    const fs::path missing = dir_ / "missing.xml";
    EXPECT_THROW(pt::loadCeng795File(missing), pt::SceneError);
    try {
        pt::loadCeng795File(missing);
    } catch (const pt::SceneError& e) {
        EXPECT_EQ(std::string(e.what()), missing.string() + ": file not found");
    }
    const fs::path empty = write("empty.xml", "");
    EXPECT_THROW(pt::loadCeng795File(empty), pt::SceneError);
    EXPECT_THROW(pt::loadCeng795File(dir_), pt::SceneError);
}

TEST_F(Ceng795, LoadFromTextResolvesAgainstBaseDir) {
    write("m/quad.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n");
    const pt::Scene s = pt::loadCeng795Text(
        sceneXml(kOneMaterial +
                 "<Objects><Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"m/quad.ply\"/></Mesh></Objects>"),
        "inline.xml", dir_);
    EXPECT_EQ(s.source, "inline.xml");
    EXPECT_EQ(s.triangleCount(), 1u);
}

TEST_F(Ceng795, UnknownElementsAreNoted) {
    const pt::Scene s = load(sceneXml(
        kOneMaterial + kSquare +
        "<Integrator>PathTracing</Integrator><ShadowRayEpsilon>1e-3</ShadowRayEpsilon>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh><Plane id=\"1\"/></Objects>"));
    EXPECT_TRUE(contains(s.unsupported, "element <Integrator> (ignored)"));
    EXPECT_TRUE(contains(s.unsupported, "Plane objects (ignored)"));
    EXPECT_EQ(s.unsupported.size(), 2u); // ShadowRayEpsilon is known and deliberately ignored
}

// ---------------------------------------------------------------------------------------------
// Scene settings

TEST_F(Ceng795, BackgroundColour) {
    const pt::Scene black = load(triangleScene("", "", "<BackgroundColor>0 0 0</BackgroundColor>"));
    EXPECT_TRUE(near3(black.background, glm::vec3(0)));
    EXPECT_TRUE(black.unsupported.empty());
    const pt::Scene grey = load(triangleScene("", "", "<BackgroundColor>0.1 0.2 0.3</BackgroundColor>"));
    EXPECT_TRUE(near3(grey.background, glm::vec3(0.1f, 0.2f, 0.3f)));
    EXPECT_TRUE(contains(grey.unsupported, "background seen only by primary rays"));
}

TEST_F(Ceng795, MaxRecursionDepthCountsBouncesAfterTheCameraRay) {
    const std::string cameras =
        "<Cameras><Camera id=\"1\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Renderer>PathTracing</Renderer><RendererParams>NextEventEstimation</RendererParams></Camera>"
        "<Camera id=\"2\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Renderer>PathTracing</Renderer><RendererParams>RussianRoulette</RendererParams></Camera></Cameras>";
    const pt::Scene s = load(triangleScene("", "", "<MaxRecursionDepth>3</MaxRecursionDepth>" + cameras));
    ASSERT_TRUE(s.hints.maxDepth.has_value());
    EXPECT_EQ(*s.hints.maxDepth, 4); // camera ray + 3 bounces
    EXPECT_EQ(s.cameras[0].settings.maxDepth, std::optional<int>(4));
    // docs/ceng795-format.md §8: the official references apply Russian roulette without the depth cap.
    EXPECT_FALSE(s.cameras[1].settings.maxDepth.has_value());
    // Absent: no depth from the file at all.
    const pt::Scene none = load(triangleScene("", "", cameras));
    EXPECT_FALSE(none.hints.maxDepth.has_value());
    EXPECT_FALSE(none.cameras[0].settings.maxDepth.has_value());
    expectError(
        triangleScene("", "", "<MaxRecursionDepth>-1</MaxRecursionDepth>"), "MaxRecursionDepth", "out of range");
}

} // namespace
} // namespace pt::test
