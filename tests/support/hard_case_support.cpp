#include "support/hard_case_support.h"

#include <algorithm>
#include <cmath>

namespace pt::test {

Renderer::Readback renderForced(const Scene& scene, const IntegratorSettings& settings, const Camera& camera, int width,
    int height, uint32_t spp, uint32_t forcedRandom) {
    FlatScene flat = flattenScene(scene);
    FeatureSet features = computeFeatures(flat, settings);
    features.forcedRandom = forcedRandom;
    Renderer renderer(sharedContext(), flat, features, settings, camera, FilmSettings{width, height, scene.background});
    renderer.addSamples(spp);
    return renderer.read();
}

Renderer::Readback renderAllModes(const Scene& scene, const IntegratorSettings& settings, const Camera& camera, int size,
    uint32_t spp, const char* what) {
    for (uint32_t forced : kForcedModes) {
        const auto r = renderForced(scene, settings, camera, size, size, 1, forced);
        EXPECT_EQ(r.droppedSamples, 0u) << what << ": random numbers forced to " << (forced == FORCED_RANDOM_ZERO ? "0" : "1 - 2^-24");
    }
    auto r = renderScene(scene, settings, camera, size, size, spp);
    EXPECT_EQ(r.droppedSamples, 0u) << what;
    return r;
}

ImageStats imageStats(const Renderer::Readback& r, int channel, const std::function<bool(int, int)>& use) {
    ImageStats s;
    double sum = 0, variance = 0;
    s.lowest = 1e300;
    s.highest = -1e300;
    for (int y = 0; y < r.mean.height; ++y)
        for (int x = 0; x < r.mean.width; ++x) {
            if (use && !use(x, y)) continue;
            const double v = r.mean.at(x, y)[channel];
            sum += v;
            variance += r.varianceOfMean.at(x, y)[channel];
            s.lowest = std::min(s.lowest, v);
            s.highest = std::max(s.highest, v);
            ++s.pixels;
        }
    if (s.pixels == 0) return s;
    s.mean = sum / double(s.pixels);
    s.standardError = std::sqrt(variance) / double(s.pixels);
    return s;
}

Scene scaledScene(Scene scene, float scale, glm::vec3 offset) {
    const glm::mat4 map = glm::mat4(glm::mat3(scale)) + glm::mat4(glm::vec4(0), glm::vec4(0), glm::vec4(0), glm::vec4(offset, 0));
    for (Mesh& m : scene.meshes)
        for (glm::vec3& p : m.positions) p = scale * p + offset;
    for (Sphere& s : scene.spheres) s.objectToWorld = map * s.objectToWorld;
    for (PunctualLight& l : scene.punctualLights) {
        l.position = scale * l.position + offset;
        l.size *= scale;
        // Point and spot intensities fall off with distance squared: keep their irradiance.
        if (l.type == PunctualLight::Type::Point || l.type == PunctualLight::Type::Spot) l.intensity *= scale * scale;
    }
    for (Camera& c : scene.cameras) {
        c.position = scale * c.position + offset;
        c.focusDistance *= scale;
        c.apertureSize *= scale;
    }
    return scene;
}

Sphere sphereAt(glm::vec3 centre, float radius, uint32_t material) {
    Sphere s;
    s.objectToWorld = glm::mat4(glm::mat3(radius));
    s.objectToWorld[3] = glm::vec4(centre, 1.0f);
    s.material = material;
    return s;
}

Camera lookAt(glm::vec3 from, glm::vec3 to, float yfov, glm::vec3 up) {
    Camera c;
    c.position = from;
    c.forward = glm::normalize(to - from);
    c.up = glm::normalize(glm::cross(glm::cross(c.forward, up), c.forward));
    c.yfov = yfov;
    return c;
}

glm::vec3 pixelDirection(const gpu::GpuCamera& c, int width, int height, double x, double y) {
    const float fx = float(x / width), fy = float(y / height);
    const float u = c.window.x + (c.window.y - c.window.x) * fx, v = c.window.w + (c.window.z - c.window.w) * fy;
    return glm::normalize(c.forward + u * c.right + v * c.up);
}

std::filesystem::path hardScenePath(const char* fileName) { return testDataDir().parent_path() / "scenes" / "hard" / fileName; }

Mesh makeBox(glm::vec3 lo, glm::vec3 hi, uint32_t material, bool inward) {
    Mesh m;
    m.name = "box";
    for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    // Outward-facing (counter-clockwise seen from outside) quads: -x, +x, -y, +y, -z, +z.
    const glm::uvec4 faces[] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (glm::uvec4 f : faces) {
        if (inward) std::swap(f.y, f.w);
        m.triangles.push_back({f.x, f.y, f.z});
        m.triangles.push_back({f.x, f.z, f.w});
    }
    m.material = material;
    return m;
}

Mesh makeGrid(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, int n, uint32_t material) {
    Mesh m;
    m.name = "grid";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.push_back(corner + edgeU * (float(i) / n) + edgeV * (float(j) / n));
    auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            // Alternate the diagonal so that vertices are shared by 4, 6 and 8 triangles.
            if ((i + j) % 2) {
                m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            } else {
                m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
                m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        }
    m.material = material;
    return m;
}

} // namespace pt::test
