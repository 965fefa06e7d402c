// The glTF node hierarchy: transforms (TRS, matrices, parents), mirroring transforms that keep
// front faces and shading normals, and nodes used twice instanced twice.
#include "gltf_test_documents.h"
#include "scene/mesh_placement.h"

#include <cmath>
#include <sstream>

namespace pt::test::gltf {
namespace {

// ---------------------------------------------------------------------------------------------
// Tiny hand-written documents: one triangle (plus per-vertex normals) in a base64 data: URI.

std::string vec3Json(const glm::vec3& v) {
    std::ostringstream s;
    s << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return s.str();
}

// `nodes` is the JSON array of nodes; the mesh is mesh 0, the camera camera 0; the scene's roots
// are `roots`; every vertex has the shading normal `normal`.
std::string triangleDocument(const std::string& nodes, const std::string& roots, const glm::vec3& normal = kN) {
    std::vector<unsigned char> bytes(72);
    for (int i = 0; i < 3; ++i) {
        std::memcpy(bytes.data() + 12 * i, &kP[i], 12);
        std::memcpy(bytes.data() + 36 + 12 * i, &normal, 12);
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
    // The mesh is read once, in object space, and placed by two instances.
    pt::Scene s = loadText(triangleDocument(
        R"([{"translation": [10, 0, 0], "children": [2]}, {"translation": [-10, 0, 0], "children": [2]}, {"mesh": 0}])",
        "[0, 1]"));
    EXPECT_TRUE(s.meshes.empty());
    ASSERT_EQ(s.sharedMeshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_TRUE(near3(s.sharedMeshes[0].parts[0].positions[0], glm::vec3(0, 0, 0), 0.0f));
    pt::expandInstances(s);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_TRUE(near3(s.meshes[0].positions[0], glm::vec3(10, 0, 0), 0.0f));
    EXPECT_TRUE(near3(s.meshes[1].positions[0], glm::vec3(-10, 0, 0), 0.0f));
}
// What the file leaves to the application, or gives malformed, is taken with a note: with two
// scenes and no default, scene 0; extras of the wrong type ignored, fractional ones rounded down;
// zero shading normals replaced by the geometric normal.
TEST(GltfLoader, ChoicesTheFileLeavesOpenAreNoted) {
    std::string doc = triangleDocument(R"([{"mesh": 0}])", "[0]", glm::vec3(0.0f));
    const std::string scenes = R"("scene": 0, "scenes": [{"nodes": [0]}])";
    ASSERT_NE(doc.find(scenes), std::string::npos);
    doc.replace(doc.find(scenes), scenes.size(),
        R"("scenes": [{"nodes": [0], "extras": {"width": "wide", "height": 64.5}}, {"nodes": [0]}])");
    const pt::Scene s = loadText(doc);
    EXPECT_FALSE(s.hints.width.has_value());
    EXPECT_EQ(s.hints.height, std::optional<int>(64));
    EXPECT_EQ(onlyTriangle(s).n[0], glm::vec3(0.0f));
    const std::vector<std::string> expected = {"no default scene among 2 (scene 0 assumed)",
        "scene extras: height 64.5 is not an integer (64 assumed)",
        "scene extras: width that is not a number (ignored)",
        "zero or non-finite NORMAL vectors (the geometric normal used there)"};
    EXPECT_EQ(s.unsupported, expected);
}

} // namespace
} // namespace pt::test::gltf
