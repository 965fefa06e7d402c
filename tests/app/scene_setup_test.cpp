// The camera a scene without one gets (framingCamera, src/app/scene_setup.cpp): the scene fills
// most of the image in its limiting dimension, centred and uncut, whatever its shape and the image's
// aspect. On the CPU, through the renderer's projection (toGpuCamera in src/render/renderer.cpp).
// The shapes are the bounding boxes of three glTF samples: in a square image the camera before this
// one filled 49% (DamagedHelmet), 61% (StainedGlassLamp) and 55% (SheenChair) of the limiting
// dimension with these boxes, and a third of the width with the models themselves.
#include "app/scene_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace pt {
namespace {

// The eight corners of a box, as one mesh of its twelve triangles.
Mesh boxMesh(glm::vec3 lo, glm::vec3 hi) {
    Mesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    m.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 7, 5}, {4, 6, 7}, {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6}, {0, 2, 6},
        {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
    return m;
}

Scene boxScene(glm::vec3 lo, glm::vec3 hi) {
    Scene scene;
    scene.source = "box.gltf";
    scene.meshes.push_back(boxMesh(lo, hi));
    return scene;
}

// Where the points land in the image, as fractions of its half-width and half-height.
struct Projection {
    float xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    float nearestDepth = INFINITY;
    float fill() const { return std::max(xmax - xmin, ymax - ymin) / 2.0f; } // of the limiting dimension
};

Projection project(const Camera& c, float aspect, const std::vector<glm::vec3>& points) {
    const glm::vec3 forward = glm::normalize(c.forward);
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float t = std::tan(0.5f * c.yfov), r = t * aspect;
    Projection p;
    for (const glm::vec3& point : points) {
        const glm::vec3 d = point - c.position;
        const float depth = glm::dot(d, forward);
        const float x = glm::dot(d, right) / (depth * r), y = glm::dot(d, up) / (depth * t);
        p.xmin = std::min(p.xmin, x), p.xmax = std::max(p.xmax, x);
        p.ymin = std::min(p.ymin, y), p.ymax = std::max(p.ymax, y);
        p.nearestDepth = std::min(p.nearestDepth, depth);
    }
    return p;
}

std::vector<glm::vec3> vertices(const Scene& scene) {
    std::vector<glm::vec3> points;
    for (const Mesh& m : scene.meshes) points.insert(points.end(), m.positions.begin(), m.positions.end());
    return points;
}

// Fills 85-95% of the limiting dimension (kFramingFill is 90%), centred, nothing outside the image.
void expectFramed(const std::string& what, const Camera& c, float aspect, const std::vector<glm::vec3>& points,
    float lowestFill = 0.85f) {
    SCOPED_TRACE(what + ", aspect " + std::to_string(aspect));
    const Projection p = project(c, aspect, points);
    EXPECT_GT(p.nearestDepth, 0.0f) << "a point behind the camera";
    EXPECT_GE(p.fill(), lowestFill);
    EXPECT_LE(p.fill(), 0.95f);
    for (float edge : {p.xmin, p.xmax, p.ymin, p.ymax}) EXPECT_LE(std::abs(edge), kFramingFill + 1e-3f) << "cut off";
    const bool widthLimits = p.xmax - p.xmin >= p.ymax - p.ymin;
    EXPECT_NEAR(p.xmin + p.xmax, 0.0f, widthLimits ? 0.02f : 0.1f) << "not centred across";
    EXPECT_NEAR(p.ymin + p.ymax, 0.0f, widthLimits ? 0.1f : 0.02f) << "not centred up and down";
    std::printf("%-24s aspect %.2f: fills %.0f%% of the %s (x %.3f..%.3f, y %.3f..%.3f)\n", what.c_str(), aspect,
        100.0f * p.fill(), widthLimits ? "width" : "height", p.xmin, p.xmax, p.ymin, p.ymax);
}

struct Shape {
    const char* name;
    glm::vec3 lo, hi;
};
// Bounding boxes of three glTF samples (scene units, as their loader places them).
const Shape kShapes[] = {
    {"StainedGlassLamp (tall)", {-0.22f, 0.0f, -0.22f}, {0.22f, 0.689f, 0.22f}},
    {"SheenChair (wide)", {-16.30f, -0.003f, -10.89f}, {16.24f, 27.01f, 11.56f}},
    {"DamagedHelmet (deep)", {-0.947f, -0.901f, -1.187f}, {0.942f, 0.901f, 0.813f}},
    {"far from the origin", {1e3f - 2.0f, 5e2f, -3e3f - 1.0f}, {1e3f + 2.0f, 5e2f + 1.0f, -3e3f + 1.0f}},
};

TEST(FramingCamera, FillsMostOfTheImageForEveryShapeAndAspect) {
    for (const Shape& shape : kShapes) {
        const Scene scene = boxScene(shape.lo, shape.hi);
        for (float aspect : {1.0f, 16.0f / 9.0f, 0.5f}) {
            const Camera c = framingCamera(scene, aspect);
            EXPECT_EQ(c.forward, glm::vec3(0, 0, -1)) << shape.name << ": glTF's front view";
            expectFramed(shape.name, c, aspect, vertices(scene));
        }
    }
}

TEST(FramingCamera, FlatScenesAreNotSeenEdgeOn) {
    // A floor (flat in y) from 45 degrees above the front; a panel facing +z from the front; a wall
    // facing x from +x. Each fills the image as a solid would.
    const Scene floor = boxScene({-1, 0, -1}, {1, 0, 1});
    const Camera above = framingCamera(floor, 1.0f);
    EXPECT_LT(above.forward.y, -0.5f);
    EXPECT_LT(above.forward.z, -0.5f);
    expectFramed("floor", above, 1.0f, vertices(floor));

    const Scene panel = boxScene({-2, -1, 0}, {2, 1, 0});
    const Camera front = framingCamera(panel, 1.0f);
    EXPECT_EQ(front.forward, glm::vec3(0, 0, -1));
    expectFramed("panel facing +z", front, 1.0f, vertices(panel));

    const Scene wall = boxScene({0, -1, -2}, {0, 1, 2});
    const Camera side = framingCamera(wall, 1.0f);
    EXPECT_EQ(side.forward, glm::vec3(-1, 0, 0));
    expectFramed("wall facing +x", side, 1.0f, vertices(wall));
}

TEST(FramingCamera, FramesEllipsoidsByTheirSilhouette) {
    Scene scene;
    Sphere s;
    s.objectToWorld = glm::mat4(1.0f);
    s.objectToWorld[0] = glm::vec4(2, 0, 0, 0); // an ellipsoid 4 wide, 2 high, 2 deep at (1, 2, 3)
    s.objectToWorld[3] = glm::vec4(1, 2, 3, 1);
    scene.spheres.push_back(s);
    const Camera c = framingCamera(scene, 1.0f);
    // Its silhouette, densely: the sampled points bound it within 5%, so it may reach a little
    // past kFramingFill but never out of the image.
    std::vector<glm::vec3> surface;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j <= 32; ++j) {
            const float phi = 2.0f * 3.14159265f * i / 64, theta = 3.14159265f * j / 32;
            const glm::vec3 unit(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            surface.push_back(glm::vec3(s.objectToWorld * glm::vec4(unit, 1.0f)));
        }
    const Projection p = project(c, 1.0f, surface);
    EXPECT_GE(p.fill(), 0.8f);
    EXPECT_LE(p.fill(), 0.97f);
    EXPECT_GT(p.nearestDepth, 0.0f);
}

TEST(FramingCamera, ChooseCamerasFramesForTheImageSizeGiven) {
    const Scene scene = boxScene(kShapes[0].lo, kShapes[0].hi);
    for (auto [width, height] : {std::pair{400, 200}, std::pair{200, 400}, std::pair{512, 512}}) {
        RenderOptions o;
        o.width = width;
        o.height = height;
        const std::vector<Camera> cameras = chooseCameras(scene, o, false);
        ASSERT_EQ(cameras.size(), 1u);
        EXPECT_EQ(cameras[0].name, "framing camera");
        expectFramed(std::to_string(width) + "x" + std::to_string(height), cameras[0],
            static_cast<float>(width) / static_cast<float>(height), vertices(scene));
    }
}

} // namespace
} // namespace pt
