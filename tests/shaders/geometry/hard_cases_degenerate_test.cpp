// The hard-case suite (issue 7), degenerate input: scenes/hard/degenerate-input.gltf (zero-area
// triangles, zero-length and NaN normals, emitters at exactly 90 degrees, a tiny emitter of
// radiance 1e12 far away) loads, renders with no dropped sample, and lights its floor as
// Lambert's polygon formula says.
#include "support/hard_case_support.h"

#include "scene/scene_loader.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

namespace pt::test {
namespace {

const Mesh& meshNamed(const Scene& scene, const std::string& name) {
    for (const Mesh& m : scene.meshes)
        if (m.name == name) return m;
    throw std::runtime_error("no mesh named " + name);
}

// Irradiance at p (unit normal n) from a one-sided emitter of radiance L: Lambert's formula
// E = L / 2 |sum_i theta_i n . unit(v_i x v_(i+1))| with v_i the polygon's corners seen from p
// (each triangle here, the emitter wholly above p's horizon), 0 behind the emitter. Angles
// through atan2, which keeps the 1e-6 rad of the far emitter's corners accurate.
double irradianceFrom(const Mesh& emitter, double L, glm::dvec3 p, glm::dvec3 n) {
    double e = 0;
    for (const glm::uvec3& t : emitter.triangles) {
        const glm::dvec3 c[3] = {emitter.positions[t.x], emitter.positions[t.y], emitter.positions[t.z]};
        if (glm::dot(p - c[0], glm::cross(c[1] - c[0], c[2] - c[0])) <= 0) continue; // behind it
        double sum = 0;
        for (int i = 0; i < 3; ++i) {
            const glm::dvec3 a = c[i] - p, b = c[(i + 1) % 3] - p, axb = glm::cross(a, b);
            const double len = glm::length(axb);
            if (len == 0) continue;
            sum += std::atan2(len, glm::dot(a, b)) * glm::dot(n, axb / len);
        }
        e += L / 2 * std::abs(sum);
    }
    return e;
}

TEST_F(HardCases, DegenerateInputLoadsAndLightsTheFloorAsLambertsFormulaSays) {
    const Scene scene = loadScene(hardScenePath("degenerate-input.gltf"));
    const Mesh& floor = meshNamed(scene, "floor");
    // Zero-length and NaN normals arrive as zero (the triangle shades with its geometric normal).
    for (const glm::vec3& normal : floor.normals)
        EXPECT_TRUE(normal == glm::vec3(0.0f) || std::abs(glm::length(normal) - 1.0f) < 1e-6f);
    EXPECT_EQ(meshNamed(scene, "zero-area triangles").triangles.size(), 3u);
    const Mesh& wall = meshNamed(scene, "wall lamp");
    const Mesh& edgeOn = meshNamed(scene, "edge-on lamp");
    const Mesh& sun = meshNamed(scene, "far tiny sun");
    const double wallL = scene.materials[wall.material].emission.x, sunL = scene.materials[sun.material].emission.x;
    ASSERT_EQ(sunL, double(1e12f));

    const int size = 32;
    const Camera& camera = scene.cameras.at(0);
    IntegratorSettings s = independentSettings();
    s.maxDepth = 2; // direct light only
    const auto r = renderAllModes(scene, s, camera, size, 64, "degenerate input");
    const ImageStats all = imageStats(r, 0);
    EXPECT_TRUE(std::isfinite(all.mean));

    // Per pixel: the floor's E / pi averaged over 4 x 4 points, for pixels that see only the
    // floor; pixels that see only the edge-on lamp show its radiance, 1.
    const gpu::GpuCamera gc = toGpuCamera(camera, size, size);
    double measured = 0, expected = 0, variance = 0, expectedSun = 0;
    int floorPixels = 0, lampPixels = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double sum = 0, sunSum = 0;
            int onFloor = 0, onLamp = 0;
            for (int k = 0; k < 16; ++k) {
                const glm::dvec3 d = pixelDirection(gc, size, size, x + (k % 4 + 0.5) / 4, y + (k / 4 + 0.5) / 4);
                const glm::dvec3 o = camera.position;
                const glm::dvec3 p = o - (o.y / d.y) * d; // where it meets y = 0
                if (std::max(std::abs(p.x), std::abs(p.z)) < 0.99) {
                    ++onFloor;
                    const double eSun = irradianceFrom(sun, sunL, p, {0, 1, 0});
                    sum +=
                        (eSun + irradianceFrom(wall, wallL, p, {0, 1, 0}) + irradianceFrom(edgeOn, 1.0, p, {0, 1, 0})) /
                        M_PI;
                    sunSum += eSun / M_PI;
                } else if (p.x > 1.21 && p.x < 1.59 && std::abs(p.z) < 0.49) {
                    ++onLamp;
                }
            }
            if (onLamp == 16) {
                EXPECT_NEAR(r.mean.at(x, y)[0], 1.0f, 1e-5f) << "edge-on lamp, pixel " << x << ", " << y;
                ++lampPixels;
            }
            if (onFloor < 16) continue;
            measured += r.mean.at(x, y)[0];
            variance += r.varianceOfMean.at(x, y)[0];
            expected += sum / 16;
            expectedSun += sunSum / 16;
            ++floorPixels;
        }
    const double error = std::sqrt(variance);
    std::printf(
        "[          ] degenerate input: floor mean %.5f +- %.5f over %d pixels, expected %.5f (far sun alone %.5f); "
        "%d lamp pixels\n",
        measured / floorPixels, error / floorPixels, floorPixels, expected / floorPixels, expectedSun / floorPixels,
        lampPixels);
    ASSERT_GT(floorPixels, size * size / 4);
    ASSERT_GT(lampPixels, 10);
    EXPECT_NEAR(measured, expected, 4.0 * error + 0.005 * expected);
}

// A file the loader must refuse says so in one line naming the file: an unreadable scene
// (here one whose zero-area triangle indexes a vertex that does not exist) is not a crash.
TEST_F(HardCases, DegenerateInputThatCannotBeRepairedIsOneLineNamingTheFile) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "pt_hard_degenerate_bad_index.gltf";
    {
        std::ifstream in(hardScenePath("degenerate-input.gltf"));
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        // The first accessor's count (the floor's 4 positions) cut to 3: index 3 is then out of range.
        const std::string from = "\"count\": 4", to = "\"count\": 3";
        const size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos);
        text.replace(at, from.size(), to);
        std::ofstream(path) << text;
    }
    try {
        loadScene(path);
        FAIL() << "loaded a scene with an out-of-range index";
    } catch (const std::exception& e) {
        const std::string message = e.what();
        std::printf("[          ] %s\n", message.c_str());
        EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    std::filesystem::remove(path);
}

} // namespace
} // namespace pt::test
