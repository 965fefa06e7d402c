// The glTF loader on the reference scenes (geometry, camera, hints, materials), the built-in
// default scene, and paths that are not glTF documents at all.
#include "gltf_test_documents.h"
#include "support/malformed_corpus.h"
#include "scene/default_scene.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>

namespace pt::test::gltf {
namespace {

const fs::path kTests = PT_TEST_DATA_DIR;
const fs::path kDiffuse = kTests / "references" / "cbox-diffuse" / "scene.gltf";
const fs::path kGlassMirror = kTests / "references" / "cbox-glass-mirror" / "scene.gltf";

// ---------------------------------------------------------------------------------------------
// Reference scenes

TEST(GltfLoader, CboxDiffuseGeometryCameraAndHints) {
    const pt::Scene s = pt::loadGltfFile(kDiffuse);
    EXPECT_EQ(s.source, kDiffuse.string());
    size_t triangles = 0;
    for (const auto& m : s.meshes) triangles += m.triangles.size();
    EXPECT_EQ(triangles, 32u);
    EXPECT_EQ(s.triangleCount(), 32u);
    EXPECT_EQ(s.meshes.size(), 8u);
    for (const auto& m : s.meshes) {
        ASSERT_LT(m.material, s.materials.size()) << m.name;
        for (const auto& t : m.triangles)
            EXPECT_TRUE(glm::all(glm::lessThan(t, glm::uvec3(m.positions.size())))) << m.name;
    }

    ASSERT_EQ(s.cameras.size(), 1u);
    const pt::Camera& c = s.cameras[0];
    EXPECT_NEAR(c.yfov, 0.6860f, 1e-4f);
    EXPECT_NEAR(c.yfov, 39.3077 * M_PI / 180.0, 1e-5);
    EXPECT_TRUE(near3(c.position, glm::vec3(0.0f, 0.0f, 3.9f), 1e-6f));
    EXPECT_TRUE(near3(c.forward, glm::vec3(0.0f, 0.0f, -1.0f), 1e-6f));
    EXPECT_TRUE(near3(c.up, glm::vec3(0.0f, 1.0f, 0.0f), 1e-6f));
    EXPECT_FLOAT_EQ(c.aspectRatio, 1.0f);

    ASSERT_TRUE(s.hints.width.has_value());
    ASSERT_TRUE(s.hints.height.has_value());
    ASSERT_TRUE(s.hints.maxDepth.has_value());
    EXPECT_EQ(*s.hints.width, 256);
    EXPECT_EQ(*s.hints.height, 256);
    EXPECT_EQ(*s.hints.maxDepth, 16);
    EXPECT_TRUE(near3(s.background, glm::vec3(0.0f), 0.0f));
    // Everything in the reference scenes is modelled: no "rendered approximately" warning.
    EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

TEST(GltfLoader, CboxDiffuseMaterials) {
    const pt::Scene s = pt::loadGltfFile(kDiffuse);
    ASSERT_EQ(s.materials.size(), 4u);

    const pt::Material* light = findMaterial(s, "light");
    ASSERT_NE(light, nullptr);
    // emissiveFactor x KHR_materials_emissive_strength.
    const glm::vec3 expected = 18.387f * glm::vec3(1.0f, 0.7607168107902321f, 0.36730135421765375f);
    EXPECT_TRUE(near3(light->emission, expected, 1e-4f));
    EXPECT_TRUE(near3(light->emission, glm::vec3(18.387f, 13.9873f, 6.75357f), 1e-3f));
    EXPECT_TRUE(light->emissive());
    EXPECT_FALSE(light->doubleSided);
    EXPECT_EQ(light->type, pt::MaterialType::Diffuse);

    const std::map<std::string, glm::vec3> walls = {{"white", {0.885809f, 0.698859f, 0.666422f}},
        {"red", {0.570068f, 0.0430135f, 0.0443706f}}, {"green", {0.105421f, 0.37798f, 0.076425f}}};
    for (const auto& [name, albedo] : walls) {
        const pt::Material* m = findMaterial(s, name);
        ASSERT_NE(m, nullptr) << name;
        EXPECT_EQ(m->type, pt::MaterialType::Diffuse) << name;
        EXPECT_TRUE(m->doubleSided) << name;
        EXPECT_FALSE(m->emissive()) << name;
        EXPECT_TRUE(near3(m->baseColor, albedo, 1e-6f)) << name;
    }

    // The light mesh uses the light material, two triangles.
    size_t lightTriangles = 0;
    for (const auto& m : s.meshes)
        if (s.materials[m.material].emissive()) lightTriangles += m.triangles.size();
    EXPECT_EQ(lightTriangles, 2u);
}

TEST(GltfLoader, CboxGlassMirrorMaterialsAndSmoothNormals) {
    const pt::Scene s = pt::loadGltfFile(kGlassMirror);
    ASSERT_EQ(s.cameras.size(), 1u);
    int mirrors = 0, dielectrics = 0;
    for (const auto& m : s.materials) {
        if (m.type == pt::MaterialType::Mirror) ++mirrors;
        if (m.type == pt::MaterialType::Dielectric) {
            ++dielectrics;
            EXPECT_FLOAT_EQ(m.ior, 1.5f) << m.name;
        }
    }
    EXPECT_EQ(mirrors, 1);
    EXPECT_EQ(dielectrics, 1);
    const pt::Material* mirror = findMaterial(s, "mirror");
    const pt::Material* glass = findMaterial(s, "glass");
    ASSERT_NE(mirror, nullptr);
    ASSERT_NE(glass, nullptr);
    EXPECT_EQ(mirror->type, pt::MaterialType::Mirror);
    EXPECT_EQ(glass->type, pt::MaterialType::Dielectric);

    // The spheres carry per-vertex normals: present, one per position, unit length, and smooth
    // (more distinct directions than a faceted mesh of the same triangles would need... at least
    // they are not all equal to their faces' geometric normals).
    size_t meshesWithNormals = 0;
    for (const auto& m : s.meshes) {
        if (m.normals.empty()) continue;
        ++meshesWithNormals;
        ASSERT_EQ(m.normals.size(), m.positions.size()) << m.name;
        for (const auto& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f) << m.name;
        size_t differFromFace = 0;
        for (const auto& t : m.triangles) {
            const glm::vec3 g =
                glm::normalize(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
            for (int k = 0; k < 3; ++k)
                if (glm::dot(g, m.normals[t[k]]) < 0.9999f) ++differFromFace;
            // Shading normals lie on the front side of their face.
            for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(g, m.normals[t[k]]), 0.0f) << m.name;
        }
        EXPECT_GT(differFromFace, m.triangles.size()) << m.name << ": normals look faceted";
        // Which material the sphere uses.
        const auto type = s.materials[m.material].type;
        EXPECT_TRUE(type == pt::MaterialType::Mirror || type == pt::MaterialType::Dielectric) << m.name;
    }
    EXPECT_EQ(meshesWithNormals, 2u);
}

TEST(GltfLoader, DefaultSceneEqualsCboxDiffuse) {
    const pt::Scene a = pt::loadDefaultScene();
    const pt::Scene b = pt::loadGltfFile(kDiffuse);
    EXPECT_EQ(pt::loadScene("").triangleCount(), 32u);

    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const pt::Material &x = a.materials[i], &y = b.materials[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.type, y.type) << x.name;
        EXPECT_EQ(x.baseColor, y.baseColor) << x.name;
        EXPECT_EQ(x.emission, y.emission) << x.name;
        EXPECT_EQ(x.doubleSided, y.doubleSided) << x.name;
        EXPECT_EQ(x.ior, y.ior) << x.name;
        EXPECT_EQ(x.attenuationColor, y.attenuationColor) << x.name;
        EXPECT_EQ(x.attenuationDistance, y.attenuationDistance) << x.name;
    }
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        const pt::Mesh &x = a.meshes[i], &y = b.meshes[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.material, y.material) << x.name;
        EXPECT_EQ(x.positions, y.positions) << x.name;
        EXPECT_EQ(x.normals, y.normals) << x.name;
        EXPECT_EQ(x.uvs, y.uvs) << x.name;
        EXPECT_EQ(x.triangles, y.triangles) << x.name;
    }
    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    for (size_t i = 0; i < a.cameras.size(); ++i) {
        EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
        EXPECT_EQ(a.cameras[i].position, b.cameras[i].position);
        EXPECT_EQ(a.cameras[i].forward, b.cameras[i].forward);
        EXPECT_EQ(a.cameras[i].up, b.cameras[i].up);
        EXPECT_EQ(a.cameras[i].yfov, b.cameras[i].yfov);
        EXPECT_EQ(a.cameras[i].aspectRatio, b.cameras[i].aspectRatio);
    }
    EXPECT_EQ(a.hints.width, b.hints.width);
    EXPECT_EQ(a.hints.height, b.hints.height);
    EXPECT_EQ(a.hints.maxDepth, b.hints.maxDepth);
    EXPECT_EQ(a.background, b.background);
    EXPECT_EQ(a.unsupported, b.unsupported);
    EXPECT_EQ(a.source, "built-in Cornell box");
}
// ---------------------------------------------------------------------------------------------
// Files that are not glTF documents at all.

TEST(GltfLoader, MissingFileDirectoryAndUnknownExtension) {
    const fs::path dir = fs::temp_directory_path() / ("pt_gltf_loader_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "folder.gltf");
    std::ofstream(dir / "model.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

    auto expectError = [](const fs::path& p, const std::string& substring) {
        try {
            pt::loadScene(p);
            ADD_FAILURE() << p << " loaded";
        } catch (const pt::SceneError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(p.string() + ": ", 0), 0u) << what;
            EXPECT_NE(lower(removeAll(what, p.string())).find(substring), std::string::npos) << what;
        }
    };
    expectError(dir / "missing.gltf", "not found");
    expectError(dir / "missing.glb", "not found");
    expectError(dir / "folder.gltf", "directory");
    expectError(dir / "model.obj", ".obj");
    fs::remove_all(dir);
}
} // namespace
} // namespace pt::test::gltf
