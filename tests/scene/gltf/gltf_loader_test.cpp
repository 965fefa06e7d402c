// The glTF loader on the reference scenes, on tiny hand-written documents (mirroring and node
// hierarchies) and on the malformed corpus (tests/data/malformed_gltf/README.md).
#include "support/malformed_corpus.h"
#include "scene/default_scene.h"
#include "scene/gltf/gltf_loader.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kTests = PT_TEST_DATA_DIR;
const fs::path kCorpus = kTests / "data" / "malformed_gltf";
const fs::path kDiffuse = kTests / "references" / "cbox-diffuse" / "scene.gltf";
const fs::path kGlassMirror = kTests / "references" / "cbox-glass-mirror" / "scene.gltf";

::testing::AssertionResult near3(const glm::vec3& a, const glm::vec3& b, float tol) {
    if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tol)))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") != (" << b.x << ", " << b.y
                                         << ", " << b.z << ") within " << tol;
}

const pt::Material* findMaterial(const pt::Scene& s, const std::string& name) {
    for (const auto& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

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
// Tiny hand-written documents: one triangle (plus per-vertex normals) in a base64 data: URI.

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= uint32_t(bytes[i + 2]);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

// The local triangle: normal (-1, 0, 1)/sqrt(2), counter-clockwise seen from that side.
const glm::vec3 kP[3] = {{0, 0, 0}, {1, 0, 1}, {0, 1, 0}};
const glm::vec3 kN = glm::normalize(glm::vec3(-1, 0, 1));

std::string vec3Json(const glm::vec3& v) {
    std::ostringstream s;
    s << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return s.str();
}

// `nodes` is the JSON array of nodes; the mesh is mesh 0, the camera camera 0; the scene's roots
// are `roots`.
std::string triangleDocument(const std::string& nodes, const std::string& roots) {
    std::vector<unsigned char> bytes(72);
    for (int i = 0; i < 3; ++i) {
        std::memcpy(bytes.data() + 12 * i, &kP[i], 12);
        std::memcpy(bytes.data() + 36 + 12 * i, &kN, 12);
    }
    std::ostringstream d;
    d << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" << roots << R"(}],
  "nodes": )"
      << nodes << R"(,
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "material": 0}]}],
  "materials": [{"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0},
                 "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}],
  "extensionsUsed": ["KHR_materials_specular"],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01}}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
  "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)"
      << base64(bytes) << R"("}]})";
    return d.str();
}

pt::Scene loadText(const std::string& text) { return pt::loadGltfText(text, "test.gltf", fs::temp_directory_path()); }

struct WorldTriangle {
    glm::vec3 p[3];
    glm::vec3 n[3]; // shading normals at p[0..2]
    glm::vec3 geometricNormal() const { return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0])); }
};

WorldTriangle onlyTriangle(const pt::Scene& s) {
    WorldTriangle w{};
    EXPECT_EQ(s.triangleCount(), 1u);
    if (s.meshes.size() != 1 || s.meshes[0].triangles.size() != 1) {
        ADD_FAILURE() << "expected one mesh with one triangle";
        return w;
    }
    const pt::Mesh& m = s.meshes[0];
    EXPECT_EQ(m.normals.size(), m.positions.size());
    for (int k = 0; k < 3; ++k) {
        w.p[k] = m.positions[m.triangles[0][k]];
        w.n[k] = m.normals.empty() ? glm::vec3(0) : m.normals[m.triangles[0][k]];
    }
    return w;
}

// The triangle transformed by `scale`: its vertex set is the scaled local vertices, and its front
// face (geometric normal, by winding) is the transformed local front face, as are its shading normals.
void expectScaledTriangle(const glm::vec3& scale) {
    SCOPED_TRACE("scale " + vec3Json(scale));
    const WorldTriangle w =
        onlyTriangle(loadText(triangleDocument(R"([{"mesh": 0, "scale": )" + vec3Json(scale) + "}]", "[0]")));
    // The same three points (in whichever order).
    for (const glm::vec3& local : kP) {
        const glm::vec3 expected = local * scale;
        bool found = false;
        for (const auto& p : w.p) found |= glm::all(glm::lessThanEqual(glm::abs(p - expected), glm::vec3(1e-6f)));
        EXPECT_TRUE(found) << "vertex " << vec3Json(expected) << " missing";
    }
    // Normals transform with the inverse transpose: for a diagonal scale, divide by it.
    const glm::vec3 front = glm::normalize(kN / scale);
    EXPECT_TRUE(near3(w.geometricNormal(), front, 1e-5f)) << "front face flipped";
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.n[k], front, 1e-5f)) << "shading normal " << k;
}

TEST(GltfLoader, UnmirroredTriangleKeepsItsWinding) {
    const WorldTriangle w = onlyTriangle(loadText(triangleDocument(R"([{"mesh": 0}])", "[0]")));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.p[k], kP[k], 0.0f)) << k;
    EXPECT_TRUE(near3(w.geometricNormal(), kN, 1e-6f));
    expectScaledTriangle(glm::vec3(2.0f, 3.0f, 0.5f));
}

TEST(GltfLoader, NegativeDeterminantScaleKeepsFrontFaces) {
    expectScaledTriangle(glm::vec3(-1.0f, 1.0f, 1.0f));
    expectScaledTriangle(glm::vec3(1.0f, 1.0f, -2.0f));
    expectScaledTriangle(glm::vec3(-1.0f, -1.0f, -1.0f));
    // Two mirrors make a rotation: nothing to swap.
    expectScaledTriangle(glm::vec3(-1.0f, -1.0f, 1.0f));
}

TEST(GltfLoader, MirrorInheritedFromAParentNode) {
    // Parent mirrors x, child mirrors nothing: the child's triangle is still mirrored.
    const WorldTriangle w = onlyTriangle(loadText(
        triangleDocument(R"([{"scale": [-1, 1, 1], "children": [1]}, {"mesh": 0, "translation": [0, 0, 5]}])", "[0]")));
    const glm::vec3 front = glm::normalize(kN * glm::vec3(-1, 1, 1));
    EXPECT_TRUE(near3(w.geometricNormal(), front, 1e-5f));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.n[k], front, 1e-5f)) << k;
}

TEST(GltfLoader, NodeHierarchyTransformsAreComposed) {
    // Parent: translation (1, 2, 3). Child 1: 90 degrees about +z, holds the mesh. Child 2: 90
    // degrees about +y, holds the camera. World = parent * child (child applied first).
    const float h = std::sqrt(0.5f);
    std::ostringstream nodes;
    nodes << R"([{"translation": [1, 2, 3], "children": [1, 2]},
      {"mesh": 0, "rotation": [0, 0, )"
          << h << ", " << h << R"(]},
      {"camera": 0, "rotation": [0, )"
          << h << ", 0, " << h << R"(]}])";
    const pt::Scene s = loadText(triangleDocument(nodes.str(), "[0]"));
    const WorldTriangle w = onlyTriangle(s);
    // Rz(90): (x, y, z) -> (-y, x, z); then + (1, 2, 3).
    auto world = [](glm::vec3 p) { return glm::vec3(-p.y, p.x, p.z) + glm::vec3(1, 2, 3); };
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.p[k], world(kP[k]), 1e-5f)) << "vertex " << k;
    const glm::vec3 n = glm::vec3(-kN.y, kN.x, kN.z);
    EXPECT_TRUE(near3(w.geometricNormal(), n, 1e-5f));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.n[k], n, 1e-5f)) << "shading normal " << k;

    ASSERT_EQ(s.cameras.size(), 1u);
    const pt::Camera& c = s.cameras[0];
    EXPECT_TRUE(near3(c.position, glm::vec3(1, 2, 3), 1e-5f));
    // Ry(90) turns the camera's -z view direction to -x; up stays +y.
    EXPECT_TRUE(near3(c.forward, glm::vec3(-1, 0, 0), 1e-5f));
    EXPECT_TRUE(near3(c.up, glm::vec3(0, 1, 0), 1e-5f));
    EXPECT_FLOAT_EQ(c.yfov, 0.5f);
    EXPECT_EQ(c.aspectRatio, 0.0f);
}

TEST(GltfLoader, NodeTrsAppliesScaleThenRotationThenTranslation) {
    const float h = std::sqrt(0.5f);
    std::ostringstream nodes;
    nodes << R"([{"mesh": 0, "translation": [1, 2, 3], "rotation": [0, 0, )" << h << ", " << h
          << R"(], "scale": [2, 1, 1]}])";
    const WorldTriangle w = onlyTriangle(loadText(triangleDocument(nodes.str(), "[0]")));
    // T * R * S: scale x by 2, Rz(90): (x, y, z) -> (-y, x, z), then + (1, 2, 3).
    auto world = [](glm::vec3 p) {
        p.x *= 2;
        return glm::vec3(-p.y, p.x, p.z) + glm::vec3(1, 2, 3);
    };
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.p[k], world(kP[k]), 1e-5f)) << "vertex " << k;
}

TEST(GltfLoader, NodeMatrixIsColumnMajor) {
    // translation (4, 5, 6) as a column-major matrix: elements 12..14.
    const WorldTriangle w = onlyTriangle(
        loadText(triangleDocument(R"([{"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 4,5,6,1]}])", "[0]")));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(near3(w.p[k], kP[k] + glm::vec3(4, 5, 6), 1e-6f)) << k;
}

TEST(GltfLoader, NodeUsedTwiceIsInstancedTwice) {
    // Two parents share one child: the mesh appears twice, once under each parent's transform.
    const pt::Scene s = loadText(triangleDocument(
        R"([{"translation": [10, 0, 0], "children": [2]}, {"translation": [-10, 0, 0], "children": [2]}, {"mesh": 0}])",
        "[0, 1]"));
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_TRUE(near3(s.meshes[0].positions[0], glm::vec3(10, 0, 0), 0.0f));
    EXPECT_TRUE(near3(s.meshes[1].positions[0], glm::vec3(-10, 0, 0), 0.0f));
}

// ---------------------------------------------------------------------------------------------
// Material factors, KHR_materials_* and KHR_lights_punctual: one triangle per material, lights
// on their own nodes.

// `materials` and `lights` are JSON arrays; `lightNodes` are extra nodes (after the mesh nodes).
std::string materialDocument(const std::string& materials, int materialCount, const std::string& lights = "[]",
    const std::string& lightNodes = "") {
    std::vector<unsigned char> bytes(36);
    for (int i = 0; i < 3; ++i) std::memcpy(bytes.data() + 12 * i, &kP[i], 12);
    std::ostringstream nodes, meshes, roots;
    for (int i = 0; i < materialCount; ++i) {
        nodes << (i ? ", " : "") << R"({"mesh": )" << i << "}";
        meshes << (i ? ", " : "") << R"({"primitives": [{"attributes": {"POSITION": 0}, "material": )" << i << "}]}";
        roots << (i ? ", " : "") << i;
    }
    int next = materialCount;
    if (!lightNodes.empty()) {
        nodes << ", " << lightNodes;
        for (size_t c = 0, depth = 0; c < lightNodes.size(); ++c) {
            // Count the top-level objects of the node list.
            if (lightNodes[c] == '{' && depth++ == 0) roots << ", " << next++;
            if (lightNodes[c] == '}') --depth;
        }
    }
    std::ostringstream d;
    d << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)" << roots.str() << R"(]}],
  "nodes": [)"
      << nodes.str() << R"(], "meshes": [)" << meshes.str() << R"(],
  "materials": )"
      << materials << R"(,
  "extensions": {"KHR_lights_punctual": {"lights": )"
      << lights << R"(}},
  "extensionsUsed": ["KHR_materials_specular", "KHR_materials_ior", "KHR_materials_transmission",
                     "KHR_materials_volume", "KHR_materials_emissive_strength", "KHR_lights_punctual"],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
      << base64(bytes) << R"("}]})";
    return d.str();
}

TEST(GltfLoaderMaterials, MetallicRoughnessFactorsAndExtensions) {
    const pt::Scene s = loadText(materialDocument(R"([
      {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.5}},
      {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.3, 1], "metallicFactor": 1, "roughnessFactor": 0.3}},
      {"name": "half", "pbrMetallicRoughness": {"metallicFactor": 0.25, "roughnessFactor": 0.7}},
      {"name": "tinted-spec", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.4},
       "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 0.25]},
                      "KHR_materials_ior": {"ior": 1.33}}},
      {"name": "frosted-glass", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 1, 0.9, 1], "metallicFactor": 0, "roughnessFactor": 0.2},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                      "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationColor": [0.5, 0.8, 1], "attenuationDistance": 2}}},
      {"name": "thin-film", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.3},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.6}}},
      {"name": "partly-clear", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}, "KHR_materials_volume": {"thicknessFactor": 1}}},
      {"name": "lambert", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 0.8},
       "extensions": {"KHR_materials_specular": {"specularFactor": 0}}},
      {"name": "chrome", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0}},
      {"name": "lamp", "emissiveFactor": [1, 0.5, 0.25], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}
    ])",
        10));
    auto get = [&](const char* name) {
        const pt::Material* m = findMaterial(s, name);
        EXPECT_NE(m, nullptr) << name;
        return m ? *m : pt::Material{};
    };
    const pt::Material plastic = get("plastic");
    EXPECT_EQ(plastic.type, pt::MaterialType::Pbr);
    EXPECT_TRUE(near3(plastic.baseColor, glm::vec3(0.2f, 0.4f, 0.6f), 1e-6f));
    EXPECT_FLOAT_EQ(plastic.metallic, 0.0f);
    EXPECT_FLOAT_EQ(plastic.roughness, 0.5f);
    EXPECT_FLOAT_EQ(plastic.specularWeight, 1.0f);
    EXPECT_TRUE(near3(plastic.specular, glm::vec3(1.0f), 0.0f));
    EXPECT_FLOAT_EQ(plastic.ior, 1.5f);
    EXPECT_FLOAT_EQ(plastic.transmission, 0.0f);

    const pt::Material gold = get("gold");
    EXPECT_EQ(gold.type, pt::MaterialType::Pbr) << "rough metal is the PBR metal lobe, not a mirror";
    EXPECT_FLOAT_EQ(gold.metallic, 1.0f);
    EXPECT_FLOAT_EQ(gold.roughness, 0.3f);

    const pt::Material half = get("half");
    EXPECT_EQ(half.type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(half.metallic, 0.25f);
    EXPECT_FLOAT_EQ(half.roughness, 0.7f);
    EXPECT_TRUE(near3(half.baseColor, glm::vec3(1.0f), 0.0f)) << "baseColorFactor defaults to white";

    const pt::Material tinted = get("tinted-spec");
    EXPECT_EQ(tinted.type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(tinted.specularWeight, 0.5f);
    EXPECT_TRUE(near3(tinted.specular, glm::vec3(1.0f, 0.5f, 0.25f), 1e-6f));
    EXPECT_FLOAT_EQ(tinted.ior, 1.33f);

    // Full transmission with a volume and default specular is exactly a (rough) dielectric,
    // which keeps its Beer-Lambert absorption.
    const pt::Material glass = get("frosted-glass");
    EXPECT_EQ(glass.type, pt::MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(glass.roughness, 0.2f);
    EXPECT_FALSE(glass.thinWalled);
    EXPECT_TRUE(near3(glass.baseColor, glm::vec3(0.9f, 1.0f, 0.9f), 1e-6f));
    EXPECT_TRUE(near3(glass.attenuationColor, glm::vec3(0.5f, 0.8f, 1.0f), 1e-6f));
    EXPECT_FLOAT_EQ(glass.attenuationDistance, 2.0f);

    // No volume: thin-walled transmission, partly.
    const pt::Material thin = get("thin-film");
    EXPECT_EQ(thin.type, pt::MaterialType::Pbr);
    EXPECT_TRUE(thin.thinWalled);
    EXPECT_FLOAT_EQ(thin.transmission, 0.6f);
    const pt::Material partly = get("partly-clear");
    EXPECT_EQ(partly.type, pt::MaterialType::Pbr);
    EXPECT_FALSE(partly.thinWalled);
    EXPECT_FLOAT_EQ(partly.transmission, 0.5f);

    // The exact special cases the Mitsuba references rely on.
    EXPECT_EQ(get("lambert").type, pt::MaterialType::Diffuse);
    EXPECT_TRUE(near3(get("lambert").baseColor, glm::vec3(0.5f), 1e-6f));
    EXPECT_EQ(get("chrome").type, pt::MaterialType::Mirror);
    EXPECT_TRUE(near3(get("lamp").emission, glm::vec3(8.0f, 4.0f, 2.0f), 1e-5f));

    // All of it is modelled: nothing in the "not supported" warning.
    EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

TEST(GltfLoaderMaterials, PrimitivesWithoutMaterialGetTheGltfDefault) {
    std::string doc = materialDocument(R"([{"name": "unused"}])", 1);
    const std::string withMaterial = R"(, "material": 0)";
    doc.erase(doc.find(withMaterial), withMaterial.size());
    const pt::Scene s = loadText(doc);
    ASSERT_EQ(s.meshes.size(), 1u);
    const pt::Material& m = s.materials[s.meshes[0].material];
    EXPECT_EQ(m.type, pt::MaterialType::Pbr);
    EXPECT_FLOAT_EQ(m.metallic, 1.0f);
    EXPECT_FLOAT_EQ(m.roughness, 1.0f);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1.0f), 0.0f));
}

TEST(GltfLoaderMaterials, OutOfRangeFactorsAreErrors) {
    for (const char* bad : {R"({"pbrMetallicRoughness": {"metallicFactor": 1.5}})",
             R"({"pbrMetallicRoughness": {"roughnessFactor": -0.1}})",
             R"({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 2}}})",
             R"({"extensions": {"KHR_materials_specular": {"specularFactor": -1}}})"}) {
        EXPECT_THROW(loadText(materialDocument(std::string("[") + bad + "]", 1)), pt::SceneError) << bad;
    }
}

TEST(GltfLoaderLights, PunctualLightsWithUnitsAndNodeTransforms) {
    const float h = std::sqrt(0.5f);
    std::ostringstream nodes;
    // Point at (1, 2, 3); spot at (0, 5, 0) turned by -90 degrees about x (its -z axis looks
    // down, to -y); directional rotated 90 degrees about y (its -z becomes -x); a light under a
    // translated parent inherits the parent's transform.
    nodes << R"({"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"translation": [0, 5, 0], "rotation": [)"
          << -h << ", 0, 0, " << h << R"(], "extensions": {"KHR_lights_punctual": {"light": 1}}},
      {"rotation": [0, )"
          << h << ", 0, " << h << R"(], "extensions": {"KHR_lights_punctual": {"light": 2}}},
      {"translation": [10, 0, 0], "children": [)"
          << 5 << R"(]})";
    // (The child node 5, listed after these, is not a scene root: the helper makes every
    // top-level object of the list a root, so it is added by hand below.)
    std::string doc = materialDocument(R"([{"name": "grey"}])", 1, R"([
      {"type": "point", "color": [1, 0.5, 0.25], "intensity": 40, "range": 0},
      {"type": "spot", "intensity": 100, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}},
      {"type": "directional", "color": [0.5, 0.5, 1], "intensity": 3},
      {"type": "point", "intensity": 2}
    ])",
        nodes.str());
    // Add node 5 (a point light at the parent's origin plus (0, 1, 0)) without making it a root.
    const std::string lastNode = R"("children": [5]})";
    doc.insert(doc.find(lastNode) + lastNode.size(),
        R"(, {"translation": [0, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 3}}})");
    const pt::Scene s = loadText(doc);
    ASSERT_EQ(s.punctualLights.size(), 4u);
    const pt::PunctualLight& point = s.punctualLights[0];
    EXPECT_EQ(point.type, pt::PunctualLight::Type::Point);
    EXPECT_TRUE(near3(point.position, glm::vec3(1, 2, 3), 1e-6f));
    // Candela read as W/sr, times the colour.
    EXPECT_TRUE(near3(point.intensity, glm::vec3(40.0f, 20.0f, 10.0f), 1e-5f));

    const pt::PunctualLight& spot = s.punctualLights[1];
    EXPECT_EQ(spot.type, pt::PunctualLight::Type::Spot);
    EXPECT_TRUE(near3(spot.position, glm::vec3(0, 5, 0), 1e-6f));
    EXPECT_TRUE(near3(spot.direction, glm::vec3(0, -1, 0), 1e-5f));
    EXPECT_TRUE(near3(spot.intensity, glm::vec3(100.0f), 1e-4f));
    EXPECT_NEAR(spot.cosCoverage, std::cos(0.6f), 1e-6f);
    // glTF's edge exactly: t^2 between the inner and the outer cone.
    EXPECT_NEAR(spot.cosFalloff, std::cos(0.3f), 1e-6f);
    EXPECT_FLOAT_EQ(spot.falloffExponent, 2.0f);

    const pt::PunctualLight& sun = s.punctualLights[2];
    EXPECT_EQ(sun.type, pt::PunctualLight::Type::Directional);
    EXPECT_TRUE(near3(sun.direction, glm::vec3(-1, 0, 0), 1e-5f));
    // Lux read as irradiance (W/m^2), times the colour.
    EXPECT_TRUE(near3(sun.intensity, glm::vec3(1.5f, 1.5f, 3.0f), 1e-5f));

    EXPECT_TRUE(near3(s.punctualLights[3].position, glm::vec3(10, 1, 0), 1e-6f)) << "the parent's transform applies";
    EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

TEST(GltfLoaderLights, RangeIsNotedAndBadLightsAreErrors) {
    const std::string node = R"({"extensions": {"KHR_lights_punctual": {"light": 0}}})";
    const pt::Scene ranged =
        loadText(materialDocument(R"([{}])", 1, R"([{"type": "point", "intensity": 1, "range": 5}])", node));
    ASSERT_EQ(ranged.punctualLights.size(), 1u);
    ASSERT_EQ(ranged.unsupported.size(), 1u);
    EXPECT_NE(ranged.unsupported[0].find("range"), std::string::npos) << ranged.unsupported[0];

    EXPECT_THROW(
        loadText(materialDocument(R"([{}])", 1, R"([{"type": "point", "intensity": -1}])", node)), pt::SceneError);
    EXPECT_THROW(loadText(materialDocument(R"([{}])", 1,
                     R"([{"type": "spot", "spot": {"innerConeAngle": 0.8, "outerConeAngle": 0.5}}])", node)),
        pt::SceneError);
    EXPECT_THROW(loadText(materialDocument(R"([{}])", 1, R"([{"type": "point"}])",
                     R"({"extensions": {"KHR_lights_punctual": {"light": 3}}})")),
        pt::SceneError);
}

// ---------------------------------------------------------------------------------------------
// Malformed corpus: every file throws pt::SceneError "<file>: <problem>" with the README's
// substring in <problem>.

using pt::test::trim;
std::map<std::string, std::string> expectedSubstrings() { return pt::test::malformedCorpusExpectations(); }
std::vector<std::string> corpusFiles() { return pt::test::malformedCorpusFiles(); }

using pt::test::lower;
using pt::test::removeAll;

TEST(GltfLoaderCorpus, ReadmeTableCoversEveryCorpusFile) {
    const auto expected = expectedSubstrings();
    const auto files = corpusFiles();
    EXPECT_GE(files.size(), 21u);
    for (const auto& f : files) EXPECT_EQ(expected.count(f), 1u) << f << " has no row in README.md";
    for (const auto& [f, sub] : expected) EXPECT_TRUE(fs::exists(kCorpus / f)) << f << " is in README.md but missing";
}

class MalformedGltf : public ::testing::TestWithParam<std::string> {};

TEST_P(MalformedGltf, ThrowsSceneErrorNamingFileAndProblem) {
    const auto expected = expectedSubstrings();
    auto it = expected.find(GetParam());
    ASSERT_NE(it, expected.end()) << GetParam() << " has no expected substring in README.md";
    const fs::path path = kCorpus / GetParam();
    const std::string name = path.string();
    try {
        pt::loadGltfFile(path);
        FAIL() << name << " loaded without an error";
    } catch (const pt::SceneError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(name + ": ", 0), 0u) << "what() does not start with the path: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
        const std::string problem = lower(removeAll(what, name));
        EXPECT_NE(problem.find(it->second), std::string::npos)
            << "expected '" << it->second << "' in the problem: " << what;
        EXPECT_GT(trim(removeAll(problem, ":")).size(), it->second.size()) << "problem text too terse: " << what;
    } catch (const std::exception& e) {
        FAIL() << "threw a " << typeid(e).name() << " that is not a pt::SceneError: " << e.what();
    }
    // Through the extension dispatch too.
    EXPECT_THROW(pt::loadScene(path), pt::SceneError);
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedGltf, ::testing::ValuesIn(corpusFiles()), pt::test::corpusParamName);

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

namespace {

// ---------------------------------------------------------------------------------------------
// Textures: slots, encodings, samplers, KHR_texture_transform, alpha modes

const char* const kOnePixelPng =
    "data:image/"
    "png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==";

// materialDocument plus textures / images / samplers arrays.
std::string texturedDocument(const std::string& materials, int materialCount, const std::string& textures,
    const std::string& images, const std::string& samplers = "[]") {
    std::string d = materialDocument(materials, materialCount);
    const std::string head = R"({"asset": {"version": "2.0"},)";
    const size_t at = d.find(head);
    EXPECT_NE(at, std::string::npos);
    d.insert(at + head.size(),
        R"( "textures": )" + textures + R"(, "images": )" + images + R"(, "samplers": )" + samplers + ",");
    return d;
}

TEST(GltfLoaderTextures, SlotsEncodingsSamplersAndTransforms) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    const pt::Scene s = loadText(texturedDocument(R"([
      {"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1},
                                                   "metallicFactor": 1, "roughnessFactor": 0},
       "normalTexture": {"index": 1, "scale": 0.5}, "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 1, 1],
       "alphaMode": "MASK", "alphaCutoff": 0.3},
      {"name": "moved", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.4],
        "baseColorTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 1.5707963, "scale": [2, 3]}}}},
       "alphaMode": "BLEND"}
    ])",
        2, R"([{"source": 0}, {"source": 0, "sampler": 0}])", images,
        R"([{"magFilter": 9728, "wrapS": 33071, "wrapT": 33648}])"));
    const pt::Material* painted = findMaterial(s, "painted");
    const pt::Material* moved = findMaterial(s, "moved");
    ASSERT_TRUE(painted && moved);
    ASSERT_TRUE(painted->baseColorTexture && painted->metallicRoughnessTexture && painted->normalTexture &&
                painted->emissiveTexture);
    // A metallic-roughness texture can make the factors' mirror rough: the full model is needed.
    EXPECT_EQ(painted->type, pt::MaterialType::Pbr);
    EXPECT_EQ(s.textures.at(*painted->baseColorTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_EQ(s.textures.at(*painted->emissiveTexture).encoding, pt::Texture::Encoding::Srgb);
    EXPECT_EQ(s.textures.at(*painted->metallicRoughnessTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_EQ(s.textures.at(*painted->normalTexture).encoding, pt::Texture::Encoding::Linear);
    EXPECT_FLOAT_EQ(painted->normalScale, 0.5f);
    EXPECT_FALSE(painted->normalMapYDown); // glTF: +y up the image
    EXPECT_EQ(painted->alphaMode, pt::Material::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(painted->alphaCutoff, 0.3f);
    // Sampler 0: nearest, clamp in u, mirror in v; no sampler: bilinear repeat.
    const pt::Texture& sampled = s.textures.at(*painted->metallicRoughnessTexture);
    EXPECT_FALSE(sampled.bilinear);
    EXPECT_EQ(sampled.wrapU, pt::TextureWrap::Clamp);
    EXPECT_EQ(sampled.wrapV, pt::TextureWrap::Mirror);
    const pt::Texture& plain = s.textures.at(*painted->baseColorTexture);
    EXPECT_TRUE(plain.bilinear);
    EXPECT_EQ(plain.wrapU, pt::TextureWrap::Repeat);
    // One image, decoded once, shared by every texture that reads it.
    ASSERT_EQ(s.textureImages.size(), 1u);
    EXPECT_EQ(s.textureImages[0].width, 1);
    EXPECT_EQ(plain.image, sampled.image);
    // KHR_texture_transform: uv' = T R S uv; (1, 0) -> S (2, 0) -> R(90 deg) (0, -2) -> T (0.5, -1.75).
    const pt::Texture& t = s.textures.at(*moved->baseColorTexture);
    const glm::vec2 uv(1, 0);
    EXPECT_NEAR(t.uvRow0.x * uv.x + t.uvRow0.y * uv.y + t.uvRow0.z, 0.5f, 1e-5f);
    EXPECT_NEAR(t.uvRow1.x * uv.x + t.uvRow1.y * uv.y + t.uvRow1.z, -1.75f, 1e-5f);
    EXPECT_EQ(moved->alphaMode, pt::Material::AlphaMode::Blend);
    EXPECT_FLOAT_EQ(moved->opacity, 0.4f);
    EXPECT_TRUE(std::none_of(s.unsupported.begin(), s.unsupported.end(),
        [](const std::string& n) { return n.find("texture") != std::string::npos; }));
}

TEST(GltfLoaderTextures, BadTexturesAreErrors) {
    const std::string images = std::string(R"([{"uri": ")") + kOnePixelPng + R"("}])";
    auto expectError = [&](const std::string& doc, const std::string& problem) {
        try {
            loadText(doc);
            ADD_FAILURE() << "no error for " << problem;
        } catch (const pt::SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
        }
    };
    const std::string base = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}}])";
    expectError(texturedDocument(base, 1, R"([{"source": 0}])", images), "texture 3 does not exist");
    expectError(texturedDocument(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])", 1,
                    R"([{"source": 0, "sampler": 4}])", images),
        "sampler 4 does not exist");
    expectError(texturedDocument(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])", 1,
                    R"([{"source": 0}])", R"([{"uri": "data:image/png;base64,iVBORw0KGgoAAAA"}])"),
        "image 0");
    expectError(texturedDocument(R"([{"alphaMode": "SOMETIMES"}])", 1, "[]", "[]"), "unknown alphaMode");
}

} // namespace

namespace {

// TANGENT: read as VEC4, mapped with the node's matrix, the bitangent sign flipped by a
// mirroring transform, invalid ones zeroed.
TEST(GltfLoaderTextures, TangentsAreTransformedWithTheirHandedness) {
    const glm::vec3 p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::vec3 n(0, 0, 1);
    const glm::vec4 t[3] = {{1, 0, 0, 1}, {1, 0, 0, 1}, {0, 0, 0, 1}}; // the last one is invalid
    std::vector<unsigned char> bytes(3 * 12 + 3 * 12 + 3 * 16);
    for (int i = 0; i < 3; ++i) {
        std::memcpy(bytes.data() + 12 * i, &p[i], 12);
        std::memcpy(bytes.data() + 36 + 12 * i, &n, 12);
        std::memcpy(bytes.data() + 72 + 16 * i, &t[i], 16);
    }
    auto document = [&](const std::string& scale) {
        return std::string(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
          "nodes": [{"mesh": 0, "scale": )") +
               scale + R"(}],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2}, "material": 0}]}],
          "materials": [{"normalTexture": {"index": 0}}],
          "textures": [{"source": 0}], "images": [{"uri": ")" +
               kOnePixelPng + R"("}],
          "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}],
          "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                          {"buffer": 0, "byteOffset": 72, "byteLength": 48}],
          "buffers": [{"byteLength": 120, "uri": "data:application/octet-stream;base64,)" +
               base64(bytes) + R"("}]})";
    };
    const pt::Scene plain = loadText(document("[2, 1, 1]"));
    ASSERT_EQ(plain.meshes.at(0).tangents.size(), 3u);
    EXPECT_TRUE(near3(glm::vec3(plain.meshes[0].tangents[0]), glm::vec3(1, 0, 0), 1e-6f)); // renormalised after scaling
    EXPECT_EQ(plain.meshes[0].tangents[0].w, 1.0f);
    EXPECT_EQ(plain.meshes[0].tangents[2], glm::vec4(0.0f)); // invalid
    const pt::Scene mirrored = loadText(document("[-1, 1, 1]"));
    EXPECT_TRUE(near3(glm::vec3(mirrored.meshes.at(0).tangents[0]), glm::vec3(-1, 0, 0), 1e-6f));
    EXPECT_EQ(mirrored.meshes[0].tangents[0].w, -1.0f);
}

} // namespace
