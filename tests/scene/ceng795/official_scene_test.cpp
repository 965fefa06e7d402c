// The CENG795 loader on three official course scenes copied into tests/data/ceng795/
// (provenance in its README.md).
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

const fs::path kData = fs::path(PT_TEST_DATA_DIR) / "data" / "ceng795";

// ---------------------------------------------------------------------------------------------
// Official course scenes (tests/data/ceng795/README.md)

TEST(Ceng795Official, CornellPathDiffuseCameras) {
    const pt::Scene s = pt::loadCeng795File(kData / "cornellbox_jaroslav_path_diffuse.xml");
    ASSERT_EQ(s.cameras.size(), 8u);
    const std::vector<std::string> names = {"diffuse_next.exr", "diffuse_next_russian.exr",
        "diffuse_next_importance.exr", "diffuse_next_importance_russian.exr", "diffuse.exr", "diffuse_russian.exr",
        "diffuse_importance.exr", "diffuse_importance_russian.exr"};
    for (size_t i = 0; i < names.size(); ++i) {
        const pt::Camera& c = s.cameras[i];
        EXPECT_EQ(c.name, "camera " + std::to_string(i + 1));
        EXPECT_EQ(c.settings.imageName, names[i]);
        const bool russian = names[i].find("russian") != std::string::npos;
        EXPECT_EQ(c.settings.nee, std::optional<bool>(names[i].find("next") != std::string::npos)) << names[i];
        EXPECT_EQ(c.settings.russianRoulette, std::optional<bool>(russian)) << names[i];
        // diffuse.exr's camera says ImportanceSampling in the official file (docs/ceng795-format.md §8 quirk).
        const bool importance = names[i].find("importance") != std::string::npos || names[i] == "diffuse.exr";
        EXPECT_EQ(c.settings.importanceSampling, std::optional<bool>(importance)) << names[i];
        EXPECT_EQ(c.settings.maxDepth, russian ? std::nullopt : std::optional<int>(4)) << names[i];
        EXPECT_EQ(c.settings.width, std::optional<int>(512));
        EXPECT_EQ(c.settings.spp, std::optional<uint32_t>(100));
        ASSERT_TRUE(c.settings.tonemap.has_value());
        EXPECT_EQ(c.settings.tonemap->op, pt::TonemapSettings::Operator::Photographic);
        EXPECT_FLOAT_EQ(c.settings.tonemap->key, 0.18f);
        EXPECT_FLOAT_EQ(c.settings.tonemap->burnPercent, 1.0f);
        EXPECT_FLOAT_EQ(c.settings.tonemap->gamma, 2.2f);
        EXPECT_FALSE(c.window.has_value());
        EXPECT_NEAR(c.yfov, glm::radians(45.0f), 1e-6f);
        EXPECT_TRUE(near3(c.forward, glm::normalize(glm::vec3(0.00688625f, 0.998505f, -0.0542161f))));
        EXPECT_NEAR(glm::dot(c.forward, c.up), 0.0f, 1e-6f);
    }
    EXPECT_EQ(s.hints.maxDepth, std::optional<int>(4));
    EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
    // "50 Watts / (4 * PI)" at (0, -0.5, 1).
    ASSERT_EQ(s.punctualLights.size(), 1u);
    EXPECT_TRUE(near3(s.punctualLights[0].position, glm::vec3(0, -0.5f, 1)));
    EXPECT_TRUE(near3(s.punctualLights[0].intensity, glm::vec3(3.9788735772973833f)));
}

TEST(Ceng795Official, CornellPathDiffuseGeometryAndLight) {
    const pt::Scene s = pt::loadCeng795File(kData / "cornellbox_jaroslav_path_diffuse.xml");
    ASSERT_EQ(s.meshes.size(), 6u);
    EXPECT_EQ(s.triangleCount(), 20u);
    const pt::Mesh* floor = findMesh(s, "Mesh 1");
    ASSERT_NE(floor, nullptr);
    // vertexOffset="1" with "0 4 5": vertices 1, 5, 6.
    EXPECT_TRUE(near3(corner(*floor, 0, 0), glm::vec3(-1.27029f, 1.30455f, -1.28002f)));
    EXPECT_TRUE(near3(corner(*floor, 0, 1), glm::vec3(-1.27029f, -1.25549f, -1.28002f)));
    EXPECT_TRUE(near3(geometricNormal(*floor, 0), glm::vec3(0, 0, 1))); // faces up into the box
    EXPECT_TRUE(near3(s.materials[floor->material].baseColor, glm::vec3(0.803922f)));

    const pt::Mesh* light = findMesh(s, "LightMesh 1");
    ASSERT_NE(light, nullptr);
    EXPECT_EQ(light->triangles.size(), 10u);
    const pt::Material& lm = s.materials[light->material];
    EXPECT_TRUE(near3(lm.emission, glm::vec3(31.831f)));
    EXPECT_TRUE(near3(lm.baseColor, glm::vec3(0.0f)));
    // The small box light's faces point outwards (vertexOffset="11": vertices 11..18).
    const glm::vec3 centre(0.0f, 0.0f, 1.22002f);
    for (size_t t = 0; t < light->triangles.size(); ++t) {
        const glm::vec3 mid = (corner(*light, t, 0) + corner(*light, t, 1) + corner(*light, t, 2)) / 3.0f;
        EXPECT_GT(glm::dot(geometricNormal(*light, t), mid - centre), 0.0f) << t;
    }

    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_TRUE(near3(glm::vec3(s.spheres[0].objectToWorld[3]), glm::vec3(-0.53885f, 0.02453f, -0.78002f)));
    EXPECT_NEAR(s.spheres[0].objectToWorld[0][0], 0.5f, 1e-6f);
    EXPECT_TRUE(near3(s.materials[s.spheres[0].material].baseColor, glm::vec3(0.803922f, 0.803922f, 0.152941f)));
}

TEST(Ceng795Official, CornellPathGlass) {
    const pt::Scene s = pt::loadCeng795File(kData / "cornellbox_jaroslav_path_glass.xml");
    ASSERT_EQ(s.cameras.size(), 8u);
    EXPECT_EQ(s.cameras[4].settings.imageName, "glass.exr");
    EXPECT_EQ(s.cameras[4].settings.nee, std::optional<bool>(false)); // the empty RendererParams
    EXPECT_EQ(s.cameras[4].settings.importanceSampling, std::optional<bool>(false));
    ASSERT_EQ(s.spheres.size(), 2u);
    const pt::Material& glass = s.materials[s.spheres[0].material];
    EXPECT_EQ(glass.type, pt::MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(glass.ior, 1.5f);
    EXPECT_TRUE(near3(glass.attenuationColor, glm::vec3(std::exp(-0.01f))));
    EXPECT_EQ(s.materials[s.spheres[1].material].type, pt::MaterialType::Diffuse);
}

TEST(Ceng795Official, MetalGlassPlatesTransformsAndInstance) {
    pt::Scene s = pt::loadCeng795File(kData / "metal_glass_plates.xml");
    EXPECT_EQ(s.instances.size(), 2u); // Mesh 3 and MeshInstance 4 place one mesh
    pt::expandInstances(s);
    ASSERT_EQ(s.meshes.size(), 4u);
    ASSERT_EQ(s.spheres.size(), 1u);
    // Vertex 5 (-0.5, -0.5, 0.5) through "s2 s3 r2 t2" (Mesh 3), by hand:
    //   s2 (10,10,10): (-5, -5, 5); s3 (1,1,0.1): (-5, -5, 0.5);
    //   r2 (70 deg about y): x = -5 cos70 + 0.5 sin70 = -1.240252, z = 5 sin70 + 0.5 cos70 = 4.869472;
    //   t2 (20, 5.001, -14): (18.759748, 0.001, -9.130528).
    // MeshInstance 4 (resetTransform="false") adds t3 (0, 0, -10) on top.
    const glm::vec3 inMesh(18.759748f, 0.001f, -9.130528f);
    const glm::vec3 inInstance = inMesh + glm::vec3(0, 0, -10);
    auto hasPoint = [](const pt::Mesh& m, const glm::vec3& p) {
        for (const auto& q : m.positions)
            if (glm::length(q - p) < 1e-4f) return true;
        return false;
    };
    EXPECT_TRUE(hasPoint(*findMesh(s, "Mesh 3"), inMesh));
    EXPECT_TRUE(hasPoint(*findMesh(s, "MeshInstance 4"), inInstance));
    EXPECT_EQ(findMesh(s, "MeshInstance 4")->material, findMesh(s, "Mesh 2")->material); // its own Material 3
    const pt::Material& metal = s.materials[findMesh(s, "Mesh 3")->material];
    EXPECT_EQ(metal.type, pt::MaterialType::Conductor);
    EXPECT_TRUE(near3(metal.conductorEta, glm::vec3(0.135f)));
    EXPECT_TRUE(near3(metal.conductorK, glm::vec3(3.985f)));
    EXPECT_TRUE(near3(metal.baseColor, glm::vec3(0.77f, 0.78f, 0.78f)));
    // The cube's faces are wound outwards in the file and stay so after the transforms.
    const pt::Mesh& cube = *findMesh(s, "Mesh 2");
    glm::vec3 centre(0.0f);
    for (const auto& p : cube.positions) centre += p / static_cast<float>(cube.positions.size());
    for (size_t t = 0; t < cube.triangles.size(); ++t) {
        const glm::vec3 mid = (corner(cube, t, 0) + corner(cube, t, 1) + corner(cube, t, 2)) / 3.0f;
        EXPECT_GT(glm::dot(geometricNormal(cube, t), mid - centre), 0.0f) << t;
    }
    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_TRUE(near4(*s.cameras[0].window, glm::vec4(-1, 1, -1, 1)));
    EXPECT_EQ(s.hints.maxDepth, std::optional<int>(7));
}

} // namespace
} // namespace pt::test
