#include "support/hard_case_support.h"

#include "app/scene_setup.h"
#include "scene/scene_loader.h"

#include <algorithm>
#include <cmath>

namespace pt::test {

Renderer::Readback renderForced(const Scene& scene, const IntegratorSettings& settings, const Camera& camera, int width,
    int height, uint32_t spp, uint32_t forcedRandom) {
    FlatScene flat = flattenScene(scene);
    FeatureSet features = suiteFeatures(flat, settings);
    features.forcedRandom = forcedRandom;
    Renderer renderer(sharedContext(), flat, features, settings, camera, FilmSettings{width, height, scene.background});
    renderer.addSamples(spp);
    return renderer.read();
}

Renderer::Readback renderAllModes(const Scene& scene, const IntegratorSettings& settings, const Camera& camera,
    int size, uint32_t spp, const char* what) {
    // The forced modes by bidirectional path tracing too, wherever it can render the scene: its
    // light subpaths and MIS sums meet the same extremes.
    IntegratorSettings bidirectional = settings;
    bidirectional.estimator = Estimator::Bidirectional;
    const bool bdpt = computeFeatures(flattenScene(scene), bidirectional).bdpt;
    for (uint32_t forced : kForcedModes) {
        const char* value = forced == FORCED_RANDOM_ZERO ? "0" : "1 - 2^-24";
        const auto r = renderForced(scene, settings, camera, size, size, 1, forced);
        EXPECT_EQ(r.droppedSamples, 0u) << what << ": random numbers forced to " << value;
        if (!bdpt) continue;
        const auto b = renderForced(scene, bidirectional, camera, size, size, 1, forced);
        EXPECT_EQ(b.droppedSamples, 0u) << what << ": BDPT, random numbers forced to " << value;
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

namespace {

// Spheres, punctual lights and cameras mapped by `map` (a rotation, a uniform scale, mirrored or
// not, and a translation); radiance is unchanged by it.
void mapAllButMeshes(Scene& scene, const glm::mat4& map) {
    const glm::mat3 linear(map);
    const float scale = std::cbrt(std::abs(glm::determinant(linear)));
    auto point = [&](glm::vec3 p) { return glm::vec3(map * glm::vec4(p, 1.0f)); };
    auto direction = [&](glm::vec3 d) { return glm::normalize(linear * d); };
    for (Sphere& s : scene.spheres) s.objectToWorld = map * s.objectToWorld;
    for (PunctualLight& l : scene.punctualLights) {
        l.position = point(l.position);
        l.direction = direction(l.direction);
        l.size *= scale;
        // Point and spot intensities fall off with distance squared: keep their irradiance.
        if (l.type == PunctualLight::Type::Point || l.type == PunctualLight::Type::Spot) l.intensity *= scale * scale;
    }
    for (Camera& c : scene.cameras) {
        c.position = point(c.position);
        c.forward = direction(c.forward);
        c.up = direction(c.up);
        c.focusDistance *= scale;
        c.apertureSize *= scale;
    }
}

} // namespace

Scene scaledScene(Scene scene, float scale, glm::vec3 offset) {
    for (Mesh& m : scene.meshes)
        for (glm::vec3& p : m.positions) p = scale * p + offset;
    glm::mat4 map(scale);
    map[3] = glm::vec4(offset, 1.0f);
    mapAllButMeshes(scene, map);
    return scene;
}

Scene placedAsInstances(Scene scene, const glm::mat4& map) {
    for (Mesh& m : scene.meshes) {
        scene.instances.push_back(
            MeshInstance{m.name, uint32_t(scene.sharedMeshes.size()), map, std::nullopt, m.motion});
        m.motion = glm::vec3(0.0f);
        scene.sharedMeshes.push_back(SharedMesh{m.name, {std::move(m)}});
    }
    scene.meshes.clear();
    mapAllButMeshes(scene, map);
    return scene;
}

BvhBuildOptions keepInstances() {
    BvhBuildOptions options;
    options.instancing = Instancing::Keep;
    return options;
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

std::filesystem::path hardScenePath(const char* fileName) {
    return testDataDir().parent_path() / "scenes" / "hard" / fileName;
}

Scene loadHardScene(const char* file, const IntegratorSettings& s) {
    Scene scene = loadScene(hardScenePath(file));
    EXPECT_FALSE(scene.cameras.empty()) << file;
    // A depth the file states is the one the test renders at, as `pt render` reads it (a course
    // camera's MaxRecursionDepth + 2 with NEE, + 1 without; Russian roulette cameras are uncapped,
    // so their tests give the depth).
    const bool course = hardScenePath(file).extension() == ".xml";
    for (const Camera& c : scene.cameras) {
        const CameraRenderSettings& cs = c.settings;
        if ((scene.hints.maxDepth || cs.maxDepth) && !cs.russianRoulette.value_or(false))
            EXPECT_EQ(chooseMaxDepth(scene, c, RenderOptions{}, course).depth, int(s.maxDepth)) << file;
        if (cs.nee) EXPECT_EQ(*cs.nee, s.nee) << file;
        if (cs.importanceSampling) EXPECT_EQ(*cs.importanceSampling, s.sampling == DirectionSampling::Cosine) << file;
        if (cs.russianRoulette) EXPECT_EQ(*cs.russianRoulette, s.rr) << file;
        if (cs.classic) EXPECT_FALSE(*cs.classic) << file;
    }
    return scene;
}

} // namespace pt::test
