// Scenes bigger than lavapipe's 128 MiB per-binding limit (maxStorageBufferRange) must load
// and render: every array is reached through its buffer device address, not a binding.
#include "support/gpu_test_support.h"

#include <cmath>

namespace pt::test {
namespace {

class LargeScene : public GpuTest {};

TEST_F(LargeScene, TriangleBufferOver128MiBRenders) {
    Scene scene;
    Material floor;
    floor.baseColor = glm::vec3(0.5f);
    floor.doubleSided = true;
    Material light;
    light.baseColor = glm::vec3(0.0f);
    light.emission = glm::vec3(4.0f);
    scene.materials = {floor, light};
    // A 1250 x 1250 grid of quads: 3.125 M triangles, 150 MB of GpuTriangle records.
    const int n = 1250;
    Mesh grid;
    grid.material = 0;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x)
            grid.positions.push_back(glm::vec3(x / float(n) * 2 - 1, 0.0f, y / float(n) * 2 - 1));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const uint32_t i = y * (n + 1) + x;
            grid.triangles.push_back({i, i + n + 1, i + 1});
            grid.triangles.push_back({i + 1, i + n + 1, i + n + 2});
        }
    scene.meshes.push_back(std::move(grid));
    scene.meshes.push_back(makeQuad(glm::vec3(-0.5f, 1.0f, -0.5f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), 1));
    const size_t triangleBytes = scene.triangleCount() * sizeof(gpu::GpuTriangle);
    ASSERT_GT(triangleBytes, size_t(128) << 20);

    Camera camera;
    camera.position = glm::vec3(0.0f, 0.5f, 2.5f);
    camera.forward = glm::normalize(glm::vec3(0.0f, -0.5f, -2.5f));
    camera.up = glm::normalize(glm::cross(glm::cross(camera.forward, glm::vec3(0, 1, 0)), camera.forward));
    IntegratorSettings s;
    s.maxDepth = 2;
    auto r = renderScene(scene, s, camera, 16, 16, 4);
    EXPECT_EQ(r.droppedSamples, 0u);
    // The floor under the light is lit: the centre pixels see it, so the image is not black.
    double centre = r.mean.at(8, 8)[0];
    EXPECT_GT(centre, 0.01);
    EXPECT_TRUE(std::isfinite(centre));
}

} // namespace
} // namespace pt::test
