// The hard-case suite (issue 7): scenes that break renderers numerically, each checked against
// an independent expectation (an analytic value, brute force, the same scene at another scale,
// an energy bound), with tolerances from the Monte Carlo error, and each rendered with zero
// dropped non-finite samples. Every scene is a file of scenes/hard/ (README there: what each
// holds, what a test sets that its file cannot say, how to render it by hand), loaded by the
// loaders `pt render` uses; each test first checks that the file holds what it expects.
#include "support/hard_case_support.h"

#include "scene/default_scene.h"
#include "scene/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace pt::test {
namespace {

// glTF cannot hold a sky: the tests of glTF scenes add theirs (`--env-colour` by hand).
void addSky(Scene& scene, float radiance) {
    Environment sky;
    sky.colour = glm::vec3(radiance);
    scene.environment = sky;
}

// The radiance of the course scenes' sky (scenes/hard/white-sky.hdr), or -1 when the scene has
// none or it is not one constant colour.
double skyRadiance(const Scene& scene) {
    if (!scene.environment || scene.environment->image.rgba.empty()) return -1;
    const std::vector<float>& rgba = scene.environment->image.rgba;
    for (size_t i = 0; i < rgba.size(); ++i)
        if (i % 4 != 3 && rgba[i] != rgba[0]) return -1;
    return rgba[0] * scene.environment->scale;
}

// A sphere's centre and radius (the unit sphere mapped by translate(centre) scale(radius));
// the radius in double is exactly the float the file gave.
glm::vec3 centreOf(const Sphere& s) { return glm::vec3(s.objectToWorld[3]); }
double radiusOf(const Sphere& s) { return glm::length(glm::dvec3(glm::vec3(s.objectToWorld[0]))); }

// Clear glass of ior 1.5: a smooth dielectric, untinted, not absorbing.
bool isClearGlass(const Material& m) {
    return m.type == MaterialType::Dielectric && m.ior == 1.5f && m.baseColor == glm::vec3(1.0f) &&
           m.roughness == 0.0f && std::isinf(m.attenuationDistance);
}

// ---- Scale: the Cornell box at 1e-3, 1 and 1e3, and moved to (1e4, 1e4, 1e4) ----
TEST_F(HardCases, CornellBoxMeanRadianceIsTheSameAtEveryScaleAndPlace) {
    IntegratorSettings s = independentSettings();
    s.maxDepth = 8;
    struct Case {
        const char* name;
        const char* file;
        float scale;
        glm::vec3 offset;
    };
    const Case cases[] = {{"scale 1", "cornell-box-scale-1.gltf", 1.0f, glm::vec3(0.0f)},
        {"scale 1e-3", "cornell-box-scale-1e-3.gltf", 1e-3f, glm::vec3(0.0f)},
        {"scale 1e3", "cornell-box-scale-1e3.gltf", 1e3f, glm::vec3(0.0f)},
        {"moved by 1e4", "cornell-box-moved-1e4.gltf", 1.0f, glm::vec3(1e4f)}};
    const Scene box = loadDefaultScene();
    ImageStats reference;
    for (const Case& c : cases) {
        const Scene scene = loadHardScene(c.file, s);
        // The file is the built-in box mapped by p -> scale p + offset.
        const Scene expected = scaledScene(box, c.scale, c.offset);
        ASSERT_EQ(scene.meshes.size(), expected.meshes.size()) << c.file;
        for (size_t m = 0; m < scene.meshes.size(); ++m) {
            ASSERT_EQ(scene.meshes[m].positions.size(), expected.meshes[m].positions.size()) << c.file;
            for (size_t v = 0; v < scene.meshes[m].positions.size(); ++v)
                EXPECT_LE(glm::length(scene.meshes[m].positions[v] - expected.meshes[m].positions[v]),
                    1e-6f * (c.scale + c.offset.x))
                    << c.file;
        }
        EXPECT_LE(glm::length(scene.cameras.at(0).position - expected.cameras.at(0).position),
            1e-6f * (c.scale + c.offset.x));
        const auto r = renderScene(scene, s, scene.cameras.at(0), 48, 48, 32);
        EXPECT_EQ(r.droppedSamples, 0u) << c.name;
        const ImageStats st = imageStats(r, 0);
        std::printf("[          ] %-12s mean %.5f +- %.5f\n", c.name, st.mean, st.standardError);
        if (c.scale == 1.0f && c.offset == glm::vec3(0.0f))
            reference = st;
        else
            EXPECT_NEAR(st.mean, reference.mean, 4.0 * std::hypot(st.standardError, reference.standardError)) << c.name;
        // Bidirectional path tracing's MIS sums hold squared lengths and area densities, which
        // scale by 1e6 and 1e-6 here: the same mean at every scale and place.
        IntegratorSettings bidirectional = s;
        bidirectional.estimator = Estimator::Bidirectional;
        const auto b = renderScene(scene, bidirectional, scene.cameras.at(0), 48, 48, 16);
        EXPECT_EQ(b.droppedSamples, 0u) << c.name << ", bdpt";
        const ImageStats bs = imageStats(b, 0);
        std::printf("[          ] %-12s bdpt mean %.5f +- %.5f\n", c.name, bs.mean, bs.standardError);
        EXPECT_NEAR(bs.mean, reference.mean, 4.0 * std::hypot(bs.standardError, reference.standardError))
            << c.name << ", bdpt";
    }
}

// ---- Contacts: a room closed by a box resting on a floor, a 1e-4-thick lid whose underside
// coincides with the walls' top face; bright light only outside. Inside, every pixel is 0. ----
TEST_F(HardCases, NoLightLeaksIntoASealedRoomThroughContactsAndAThinLid) {
    const std::pair<float, const char*> cases[] = {{1.0f, "sealed-room-scale-1.gltf"},
        {1e-3f, "sealed-room-scale-1e-3.gltf"}, {1e3f, "sealed-room-scale-1e3.gltf"}};
    for (auto [scale, file] : cases) {
        IntegratorSettings s = independentSettings();
        s.maxDepth = 8;
        Scene scene = loadHardScene(file, s);
        // Floor, walls without a bottom (10 triangles), lid; double-sided, so that light
        // entering through any gap is reflected, not absorbed; the light outside, above the lid.
        ASSERT_EQ(scene.meshes.size(), 3u) << file;
        EXPECT_EQ(scene.meshes[1].triangles.size(), 10u) << file;
        for (const Material& m : scene.materials) EXPECT_TRUE(m.doubleSided) << file;
        ASSERT_EQ(scene.punctualLights.size(), 1u) << file;
        EXPECT_GT(scene.punctualLights[0].position.y, 1.0001f * scale) << file;
        float top = 0, lidBottom = INFINITY, lidTop = 0;
        for (const glm::vec3& p : scene.meshes[1].positions) top = std::max(top, p.y);
        for (const glm::vec3& p : scene.meshes[2].positions)
            lidBottom = std::min(lidBottom, p.y), lidTop = std::max(lidTop, p.y);
        EXPECT_EQ(lidBottom, top) << file; // coincident faces, exactly
        EXPECT_NEAR(top, scale, 1e-6f * scale) << file;
        EXPECT_NEAR(lidTop - lidBottom, 1e-4f * scale, 1e-2f * 1e-4f * scale) << file;
        addSky(scene, 10.0f);
        const auto r = renderAllModes(scene, s, scene.cameras.at(0), 32, 32, "sealed room");
        const ImageStats st = imageStats(r, 0);
        std::printf("[          ] sealed room at scale %g: brightest pixel %g\n", scale, st.highest);
        EXPECT_EQ(st.highest, 0.0) << "light leaked in at scale " << scale;
        // Light subpaths from the lamp land on the lid; no connection may pass through it.
        IntegratorSettings bidirectional = s;
        bidirectional.estimator = Estimator::Bidirectional;
        const ImageStats b = imageStats(renderScene(scene, bidirectional, scene.cameras.at(0), 32, 32, 16), 0);
        EXPECT_EQ(b.highest, 0.0) << "light leaked in through a BDPT connection at scale " << scale;
    }
}

// ---- Watertightness: a closed, one-sided emissive cube of 32 x 32 grids per face. Pinhole
// rays with the pixel jitter forced to 0 (1 - 2^-24) pass through the grid's vertices and
// edges (to within rounding); each must find a front face (radiance 1), never slip through to
// the inside of the far face (0) or the bright sky (5). ----
TEST_F(HardCases, RaysThroughSharedVerticesAndEdgesOfAClosedMeshNeverSlipThrough) {
    IntegratorSettings s = independentSettings();
    s.maxDepth = 1;
    Scene scene = loadHardScene("watertight-cube.gltf", s);
    ASSERT_EQ(scene.meshes.size(), 6u);
    for (const Mesh& m : scene.meshes) EXPECT_EQ(m.triangles.size(), 2u * 32 * 32) << m.name;
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].emission, glm::vec3(1.0f));
    EXPECT_FALSE(scene.materials[0].doubleSided);
    addSky(scene, 5.0f);
    // Camera 0 sees the face z = 1 from z = 2 with tan(yfov / 2) = 1/2: the image spans
    // [-1/2, 1/2]^2 of it, so the corners of its 32 x 32 pixels (x, y multiples of 1/32) fall on
    // the grid's vertices (spacing 1/16), on its edges and on its diagonals.
    ASSERT_EQ(scene.cameras.size(), 2u);
    Camera camera = scene.cameras[0];
    EXPECT_EQ(camera.position, glm::vec3(0, 0, 2));
    EXPECT_EQ(camera.forward, glm::vec3(0, 0, -1));
    EXPECT_EQ(camera.yfov, 2.0f * std::atan(0.5f));
    for (uint32_t forced : kForcedModes) {
        const auto r = renderForced(scene, s, camera, 32, 32, 1, forced);
        EXPECT_EQ(r.droppedSamples, 0u);
        const ImageStats st = imageStats(r, 0);
        EXPECT_EQ(st.lowest, 1.0) << "a ray slipped through (forced " << forced << ")";
        EXPECT_EQ(st.highest, 1.0) << "a ray slipped through (forced " << forced << ")";
    }
    // Camera 1 is turned, so that the rays meet vertices and edges at general angles.
    camera = scene.cameras[1];
    const auto r = renderScene(scene, s, camera, 64, 64, 16);
    EXPECT_EQ(r.droppedSamples, 0u);
    const ImageStats inner =
        imageStats(r, 0, [](int x, int y) { return std::abs(x - 32) < 14 && std::abs(y - 32) < 14; });
    EXPECT_EQ(inner.lowest, 1.0);
    EXPECT_EQ(inner.highest, 1.0);
}

// ---- Spheres ----
// A sphere of radius 1e5 as the ground under a uniform white sky: a diffuse point on it sees
// the sky over its whole hemisphere, so every pixel is the albedo (1 - 1e-5 for the curvature);
// acne (rays hitting the ground they leave) darkens pixels.
TEST_F(HardCases, HugeGroundSphereHasNoAcne) {
    IntegratorSettings s = independentSettings();
    s.maxDepth = 8;
    const Scene scene = loadHardScene("ground-sphere.xml", s);
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(radiusOf(scene.spheres[0]), 1e5);
    EXPECT_EQ(centreOf(scene.spheres[0]), glm::vec3(0, -1e5f, 0));
    EXPECT_EQ(scene.materials.at(scene.spheres[0].material).baseColor, glm::vec3(0.5f));
    EXPECT_EQ(skyRadiance(scene), 1.0);
    const auto r = renderAllModes(scene, s, scene.cameras.at(0), 32, 128, "ground sphere");
    const ImageStats st = imageStats(r, 0);
    std::printf("[          ] ground sphere: mean %.5f +- %.5f, lowest %.4f\n", st.mean, st.standardError, st.lowest);
    EXPECT_NEAR(st.mean, 0.5, 4.0 * st.standardError + 1e-4);
}

// Camera inside emissive diffuse spheres of radius 1e-3 to 1e4, off-centre: L = Le sum rho^k.
// (The small ones near the origin were too bright, +0.025% at radius 1e-2 and +0.24% at 1e-3,
// while the ray offset there was a fixed 1/65536; it now scales with the primitive, see
// shaders/common/ray_offset.glsl.)
TEST_F(HardCases, CameraInsideSpheresOfEverySizeSeesTheAnalyticRadiance) {
    const std::pair<float, const char*> cases[] = {{1e-3f, "inside-sphere-r1e-3.xml"},
        {1e-2f, "inside-sphere-r1e-2.xml"}, {1.0f, "inside-sphere-r1.xml"}, {1e4f, "inside-sphere-r1e4.xml"}};
    for (auto [radius, file] : cases) {
        IntegratorSettings s = independentSettings();
        s.maxDepth = 6;
        s.rr = false;
        const Scene scene = loadHardScene(file, s);
        ASSERT_EQ(scene.spheres.size(), 1u) << file;
        const Sphere& sphere = scene.spheres[0];
        EXPECT_EQ(radiusOf(sphere), double(radius)) << file;
        const Material& m = scene.materials.at(sphere.material);
        EXPECT_EQ(m.baseColor, glm::vec3(0.5f)) << file;
        EXPECT_EQ(m.emission, glm::vec3(1.0f)) << file;
        EXPECT_TRUE(m.doubleSided) << file;
        const Camera& camera = scene.cameras.at(0);
        EXPECT_LT(glm::length(camera.position - centreOf(sphere)), 0.9f * radius) << file; // inside, off centre
        const auto r = renderAllModes(scene, s, camera, 24, 32, "inside a sphere");
        const ImageStats st = imageStats(r, 0);
        const double expected = (1.0 - std::pow(0.5, 6)) / 0.5;
        std::printf("[          ] inside a sphere of radius %g: mean %.5f +- %.5f (expected %.5f)\n", radius, st.mean,
            st.standardError, expected);
        EXPECT_NEAR(st.mean, expected, 4.0 * st.standardError + 1e-4 * expected) << "radius " << radius;
    }
}

// A sphere of radius 1e-3 at distance 1e4 straight ahead, emitting 1: the image integrates to
// its solid angle, pi r^2 / d^2 (to 1e-14), and nothing lights up away from it. (It used to
// vanish: see toSphereObject and the discriminant in shaders/geometry/sphere.glsl.) Along a
// diagonal the float ray directions themselves are spaced 6e-8 rad apart, more than half the
// angular radius 1e-7 of that sphere, so there the sphere has radius 1e-2 (0.2% of its radius
// per direction step) and the same 1% tolerance holds.
TEST_F(HardCases, TinySphereFarAwayCoversItsSolidAngle) {
    for (const char* file : {"tiny-far-sphere-ahead.xml", "tiny-far-sphere-diagonal.xml"}) {
        IntegratorSettings s = independentSettings();
        s.maxDepth = 2;
        const Scene scene = loadHardScene(file, s);
        ASSERT_EQ(scene.spheres.size(), 1u) << file;
        const Sphere& sphere = scene.spheres[0];
        EXPECT_EQ(scene.materials.at(sphere.material).emission, glm::vec3(1.0f)) << file;
        const double r = radiusOf(sphere), d = glm::length(glm::dvec3(centreOf(sphere)));
        const glm::dvec3 dir = glm::dvec3(centreOf(sphere)) / d;
        const Camera& camera = scene.cameras.at(0);
        EXPECT_EQ(camera.position, glm::vec3(0.0f)) << file;
        EXPECT_NEAR(d, 1e4, 1e-2) << file;
        const int size = 32;
        const float halfAngle = 0.5f * camera.yfov;
        EXPECT_NEAR(halfAngle, 4.0 * r / d, 1e-6 * halfAngle) << file; // the disc spans a quarter of the image
        const auto rb = renderAllModes(scene, s, camera, size, 64, "tiny far sphere");
        const ImageStats st = imageStats(rb, 0);
        const double pixelSolidAngle = std::pow(2.0 * std::tan(halfAngle) / size, 2.0); // narrow field: cos^3 = 1
        const double measured = st.mean * st.pixels * pixelSolidAngle;
        const double error = st.standardError * st.pixels * pixelSolidAngle;
        const double expected = M_PI * r * r / (d * d);
        std::printf("[          ] tiny sphere along (%.2f %.2f %.2f): solid angle %.4e +- %.1e, expected %.4e\n", dir.x,
            dir.y, dir.z, measured, error, expected);
        EXPECT_NEAR(measured, expected, 4.0 * error + 0.01 * expected);
        // Clean silhouette: nothing lit beyond 1.5 radii from the centre pixel.
        const ImageStats outside = imageStats(
            rb, 0, [&](int x, int y) { return std::hypot(x + 0.5 - size / 2.0, y + 0.5 - size / 2.0) > 6.0 * 1.5; });
        EXPECT_EQ(outside.highest, 0.0);
    }
}

// ---- Sphere lights: irradiance on a diffuse plane (albedo 1, so radiance = E / pi) from a
// sphere light wholly above it is E = pi L sin^2(theta_max) cos(alpha) = pi L r^2 cos(alpha) / d^2,
// exactly. A sun-sized sphere (0.53 degrees across) and one 1e-3 above the plane. ----
TEST_F(HardCases, SphereLightIrradianceMatchesPiLSinSquaredThetaMax) {
    const std::pair<const char*, const char*> cases[] = {
        {"sun", "sphere-light-sun.xml"}, {"almost touching", "sphere-light-almost-touching.xml"}};
    for (auto [name, file] : cases) {
        IntegratorSettings s = independentSettings();
        s.maxDepth = 2; // direct light only
        Scene scene = loadHardScene(file, s);
        // A white floor at y = 0 (to 20 either way) and one sphere light wholly above it.
        ASSERT_EQ(scene.meshes.size(), 1u) << file;
        for (const glm::vec3& p : scene.meshes[0].positions)
            EXPECT_TRUE(p.y == 0.0f && std::abs(p.x) == 20.0f && std::abs(p.z) == 20.0f);
        EXPECT_EQ(scene.materials.at(scene.meshes[0].material).baseColor, glm::vec3(1.0f)) << file;
        ASSERT_EQ(scene.spheres.size(), 1u) << file;
        const glm::vec3 lampCentre = centreOf(scene.spheres[0]);
        const float radius = float(radiusOf(scene.spheres[0]));
        const Material& lamp = scene.materials.at(scene.spheres[0].material);
        EXPECT_EQ(lamp.baseColor, glm::vec3(0.0f)) << file;
        const float radiance = lamp.emission.x;
        EXPECT_EQ(lamp.emission, glm::vec3(radiance)) << file;
        EXPECT_GT(lampCentre.y, radius) << file;
        // The course format makes every emitter double-sided, and pt samples a sphere that may be
        // seen from inside by its area. This test is about a sphere light seen from outside,
        // sampled by its cone of directions (exact for the sun), so the lamp is made one-sided
        // here, as a glTF emitter is. (Rendered by hand: the same image, noisier.)
        scene.materials[scene.spheres[0].material].doubleSided = false;
        const int size = 32;
        const Camera& camera = scene.cameras.at(0);
        const auto r = renderAllModes(scene, s, camera, size, 64, name);
        // Expected radiance per pixel: E / pi averaged over 4 x 4 points in the pixel; pixels
        // where any of them sees the sphere itself are left out.
        const gpu::GpuCamera gc = toGpuCamera(camera, size, size);
        double measured = 0, expected = 0, variance = 0;
        int used = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                double sum = 0;
                bool clean = true;
                for (int k = 0; k < 16 && clean; ++k) {
                    const glm::dvec3 d = pixelDirection(gc, size, size, x + (k % 4 + 0.5) / 4, y + (k / 4 + 0.5) / 4);
                    const glm::dvec3 o = camera.position, centre = lampCentre;
                    const glm::dvec3 toCentre = centre - o;
                    const double along = glm::dot(toCentre, d);
                    if (glm::length(toCentre - along * d) < radius * 1.01 && along > 0) clean = false;
                    if (d.y >= 0) clean = false;
                    const glm::dvec3 p = o - (o.y / d.y) * d;
                    if (std::max(std::abs(p.x), std::abs(p.z)) > 15.0) clean = false; // beyond the floor's edge
                    const glm::dvec3 toLight = centre - p;
                    const double dist = glm::length(toLight);
                    sum += double(radiance) * radius * radius * (toLight.y / dist) / (dist * dist);
                }
                if (!clean) continue;
                measured += r.mean.at(x, y)[0];
                variance += r.varianceOfMean.at(x, y)[0];
                expected += sum / 16;
                ++used;
            }
        const double error = std::sqrt(variance);
        std::printf("[          ] %s: mean radiance %.5f +- %.5f over %d pixels, expected %.5f\n", name,
            measured / used, error / used, used, expected / used);
        ASSERT_GT(used, size * size / 4);
        EXPECT_NEAR(measured, expected, 4.0 * error + 0.005 * expected) << name;
    }
}

// ---- Dielectrics ----
// Camera inside a glass sphere (radius 1, ior 1.5) under a white sky. Along a chord of a sphere
// the angle of incidence never changes: rays whose line passes the centre closer than 1 / 1.5
// leave (after any number of Fresnel reflections) carrying eta^2 = 2.25, the radiance of the
// sky inside glass; farther out they are totally internally reflected forever, and end at the
// depth limit with 0.
TEST_F(HardCases, TotalInternalReflectionInsideAGlassSphere) {
    IntegratorSettings s = independentSettings();
    s.maxDepth = 64;
    const Scene scene = loadHardScene("glass-sphere-from-inside.xml", s);
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(centreOf(scene.spheres[0]), glm::vec3(0.0f));
    EXPECT_EQ(radiusOf(scene.spheres[0]), 1.0);
    EXPECT_TRUE(isClearGlass(scene.materials.at(scene.spheres[0].material)));
    EXPECT_EQ(skyRadiance(scene), 1.0);
    const int size = 32;
    const Camera& camera = scene.cameras.at(0); // from the centre direction to 90 degrees off it
    const auto r = renderAllModes(scene, s, camera, size, 16, "camera inside glass");
    const gpu::GpuCamera gc = toGpuCamera(camera, size, size);
    int leaving = 0, trapped = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double lo = 1e9, hi = 0; // distance of the ray's line from the centre, over the pixel
            for (int k = 0; k < 9; ++k) {
                const glm::vec3 d = pixelDirection(gc, size, size, x + (k % 3) / 2.0, y + (k / 3) / 2.0);
                const double dist = glm::length(glm::cross(camera.position, d));
                lo = std::min(lo, dist);
                hi = std::max(hi, dist);
            }
            const float v = r.mean.at(x, y)[0];
            if (hi < 1.0 / 1.5 - 0.04) {
                EXPECT_NEAR(v, 2.25f, 1e-3f) << "pixel " << x << ", " << y;
                ++leaving;
            } else if (lo > 1.0 / 1.5 + 0.005) {
                EXPECT_EQ(v, 0.0f) << "pixel " << x << ", " << y;
                ++trapped;
            }
        }
    std::printf("[          ] inside glass: %d pixels leave (2.25), %d are trapped (0)\n", leaving, trapped);
    EXPECT_GT(leaving, 50);
    EXPECT_GT(trapped, 50);
}

// Clear glass neither absorbs nor emits: under a white sky every path that leaves carries
// exactly 1, so every pixel is 1 whatever the glass's shape (paths still trapped at the depth
// limit can only lower it). A slab seen at 2 degrees, nested spheres, and two blocks 1e-4 apart.
TEST_F(HardCases, ClearGlassInAWhiteSkyIsInvisibleAtGrazingViewsNestedAndAdjacent) {
    const std::pair<const char*, const char*> cases[] = {{"grazing slab", "clear-glass-grazing-slab.xml"},
        {"nested spheres", "clear-glass-nested-spheres.xml"}, {"adjacent blocks", "clear-glass-adjacent-blocks.xml"}};
    for (auto [name, file] : cases) {
        IntegratorSettings s = independentSettings();
        s.maxDepth = 64;
        const Scene scene = loadHardScene(file, s);
        ASSERT_EQ(scene.meshes.size() + scene.spheres.size(), name == std::string("grazing slab") ? 1u : 2u) << file;
        for (const Material& m : scene.materials) EXPECT_TRUE(isClearGlass(m)) << file;
        EXPECT_EQ(skyRadiance(scene), 1.0) << file;
        const auto r = renderAllModes(scene, s, scene.cameras.at(0), 16, 8, name);
        const ImageStats st = imageStats(r, 0);
        std::printf("[          ] %s: mean %.5f, lowest %.4f, highest %.6f\n", name, st.mean, st.lowest, st.highest);
        EXPECT_LE(st.highest, 1.0 + 1e-4) << name << " gains energy";
        EXPECT_GT(st.mean, 0.99) << name;
    }
}

} // namespace
} // namespace pt::test
