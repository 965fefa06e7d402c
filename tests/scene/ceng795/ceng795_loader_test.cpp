// The CENG795 course XML loader: one test per element family and per quirk of the format
// (/work/shared/ceng795/FORMAT.md), hostile input, and three official course scenes copied into
// tests/data/ceng795/ (provenance in its README.md).
#include "image/image_io.h"
#include "scene/ceng795/loader.h"
#include "scene/scene_error.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kData = fs::path(PT_TEST_DATA_DIR) / "data" / "ceng795";

::testing::AssertionResult near3(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
    if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tol)))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") != (" << b.x << ", " << b.y
                                         << ", " << b.z << ") within " << tol;
}

::testing::AssertionResult near4(const glm::vec4& a, const glm::vec4& b, float tol = 1e-6f) {
    if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(tol)))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ", " << a.w << ") != (" << b.x
                                         << ", " << b.y << ", " << b.z << ", " << b.w << ")";
}

bool contains(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

glm::vec3 geometricNormal(const pt::Mesh& m, size_t triangle) {
    const glm::uvec3 t = m.triangles[triangle];
    return glm::normalize(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
}

// World position of corner `corner` of triangle `triangle`.
glm::vec3 corner(const pt::Mesh& m, size_t triangle, int corner) { return m.positions[m.triangles[triangle][corner]]; }

const pt::Mesh* findMesh(const pt::Scene& s, const std::string& name) {
    for (const auto& m : s.meshes)
        if (m.name == name) return &m;
    return nullptr;
}

// Pieces of small scenes. Vertex ids 1..4 are the unit square in z = 0.
const std::string kOneMaterial =
    "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>";
const std::string kSquare = "<VertexData>0 0 0  1 0 0  1 1 0  0 1 0</VertexData>";
const std::string kCamera =
    "<Cameras><Camera id=\"1\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
    "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>8 8</ImageResolution>"
    "<ImageName>out.png</ImageName></Camera></Cameras>";

std::string sceneXml(const std::string& inner) { return "<Scene>" + inner + "</Scene>"; }

// A scene with the square's first triangle as Mesh 1 plus `objects` and `extra` elements.
std::string triangleScene(const std::string& meshAttributes, const std::string& meshChildren, const std::string& extra = "") {
    return sceneXml(kOneMaterial + kSquare + extra + "<Objects><Mesh id=\"1\"" + meshAttributes + "><Material>1</Material>" +
                    meshChildren + "<Faces>1 2 3</Faces></Mesh></Objects>");
}

class Ceng795 : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("pt_ceng795_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const std::string& content) const {
        const fs::path p = dir_ / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }

    fs::path writeBinary(const std::string& name, const std::vector<int32_t>& header, const std::vector<float>& floats,
        const std::vector<int32_t>& ints = {}) const {
        const fs::path p = dir_ / name;
        fs::create_directories(p.parent_path());
        std::ofstream out(p, std::ios::binary);
        out.write(reinterpret_cast<const char*>(header.data()), static_cast<std::streamsize>(header.size() * 4));
        out.write(reinterpret_cast<const char*>(floats.data()), static_cast<std::streamsize>(floats.size() * 4));
        out.write(reinterpret_cast<const char*>(ints.data()), static_cast<std::streamsize>(ints.size() * 4));
        return p;
    }

    pt::Scene load(const std::string& xml) const { return pt::loadCeng795File(write("scene.xml", xml)); }

    // Loading must fail with one line "<file>: <label>: ...<problem>...".
    void expectError(const std::string& xml, const std::string& label, const std::string& problem) const {
        const fs::path file = write("scene.xml", xml);
        std::string message = "(no error)";
        try {
            pt::loadCeng795File(file);
        } catch (const pt::SceneError& e) {
            message = e.what();
        }
        const std::string prefix = file.string() + ": ";
        ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
        const std::string rest = message.substr(prefix.size());
        if (!label.empty()) {
            EXPECT_EQ(rest.rfind(label + ": ", 0), 0u) << message;
        }
        EXPECT_NE(rest.find(problem), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }

    fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// Transformations

TEST_F(Ceng795, TransformationsApplyLeftToRight) {
    // "r1 t1 s2": first rotate (1,0,0) by 90 degrees about z -> (0,1,0), then translate by
    // (1,0,0) -> (1,1,0), then scale x by 2 -> (2,1,0). M = S2 · T1 · R1.
    const std::string transforms =
        "<Transformations><Rotation id=\"1\">90 0 0 1</Rotation><Translation id=\"1\">1 0 0</Translation>"
        "<Scaling id=\"2\">2 1 1</Scaling></Transformations>";
    const pt::Scene s = load(triangleScene("", "<Transformations>r1 t1 s2</Transformations>", transforms));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 0), glm::vec3(2, 0, 0)));  // (0,0,0) -> (0,0,0) -> (1,0,0) -> (2,0,0)
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 1), glm::vec3(2, 1, 0)));  // (1,0,0)
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 2), glm::vec3(0, 1, 0)));  // (1,1,0) -> (-1,1,0) -> (0,1,0) -> (0,1,0)

    // The reverse list is a different map: (1,0,0) -> (2,0,0) -> (3,0,0) -> (0,3,0).
    const pt::Scene r = load(triangleScene("", "<Transformations>s2 t1 r1</Transformations>", transforms));
    EXPECT_TRUE(near3(corner(r.meshes[0], 0, 1), glm::vec3(0, 3, 0)));
}

TEST_F(Ceng795, CompositeIsRowMajor) {
    // Rows: a 90-degree rotation about z and a translation (5, 6, 7) in the last column.
    const std::string transforms =
        "<Transformations><Composite id=\"1\">0 -1 0 5  1 0 0 6  0 0 1 7  0 0 0 1</Composite></Transformations>";
    const pt::Scene s = load(triangleScene("", "<Transformations>c1</Transformations>", transforms));
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 0), glm::vec3(5, 6, 7)));
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 1), glm::vec3(5, 7, 7))); // (1,0,0) -> (0,1,0) + t
}

TEST_F(Ceng795, RotationIsCounterClockwiseAboutAnUnnormalisedAxis) {
    const std::string transforms = "<Transformations><Rotation id=\"1\">90 0 0 3</Rotation></Transformations>";
    const pt::Scene s = load(triangleScene("", "<Transformations>r1</Transformations>", transforms));
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 1), glm::vec3(0, 1, 0)));
}

TEST_F(Ceng795, MirroringTransformKeepsTheFrontSide) {
    // FORMAT.md §10: normals map with the inverse transpose, which for Scaling -1 1 1 keeps +z.
    // The mirrored winding would face -z, so the loader swaps two corners.
    const std::string transforms = "<Transformations><Scaling id=\"1\">-1 1 1</Scaling></Transformations>";
    const pt::Scene s = load(triangleScene(" shadingMode=\"smooth\"", "<Transformations>s1</Transformations>", transforms));
    EXPECT_TRUE(near3(geometricNormal(s.meshes[0], 0), glm::vec3(0, 0, 1)));
    for (const auto& n : s.meshes[0].normals) EXPECT_TRUE(near3(n, glm::vec3(0, 0, 1)));
}

TEST_F(Ceng795, BadTransformationsAreErrors) {
    expectError(triangleScene("", "<Transformations>t9</Transformations>"), "Mesh id=1: Transformations",
        "unknown transformation 't9'");
    expectError(triangleScene("", "<Transformations>x1</Transformations>"), "Mesh id=1: Transformations",
        "is not a transformation reference");
    expectError(triangleScene("", "", "<Transformations><Scaling id=\"1\">1 0 1</Scaling></Transformations>"),
        "Scaling id=1", "non-zero");
    expectError(triangleScene("", "", "<Transformations><Rotation id=\"1\">30 0 0 0</Rotation></Transformations>"),
        "Rotation id=1", "axis");
    expectError(triangleScene("", "", "<Transformations><Composite id=\"1\">1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1</Composite></Transformations>"),
        "Composite id=1", "last row");
    expectError(triangleScene("", "", "<Transformations><Translation id=\"1\">1 2</Translation></Transformations>"),
        "Translation id=1", "expected 3 numbers");
}

// ---------------------------------------------------------------------------------------------
// Meshes, triangles, indexing

TEST_F(Ceng795, InlineFacesAreOneBasedAndShareVertices) {
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare +
        "<Objects><Mesh id=\"4\"><Material>1</Material><Faces>1 2 3  1 3 4</Faces></Mesh></Objects>"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const pt::Mesh& m = s.meshes[0];
    EXPECT_EQ(m.name, "Mesh 4");
    EXPECT_EQ(m.material, 0u);
    EXPECT_EQ(m.positions.size(), 4u); // shared, not 6
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_TRUE(near3(corner(m, 1, 2), glm::vec3(0, 1, 0)));
    EXPECT_TRUE(m.normals.empty()); // flat by default
    EXPECT_TRUE(near3(geometricNormal(m, 0), glm::vec3(0, 0, 1)));
}

TEST_F(Ceng795, ZeroBasedIndexingAndVertexOffset) {
    // 1-based with vertexOffset 1: "0 1 2" means vertices 1, 2, 3 (the HW6 Cornell files).
    const pt::Scene a = load(sceneXml(kOneMaterial + kSquare +
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces vertexOffset=\"1\">0 1 2</Faces></Mesh></Objects>"));
    EXPECT_TRUE(near3(corner(a.meshes[0], 0, 0), glm::vec3(0, 0, 0)));
    EXPECT_TRUE(near3(corner(a.meshes[0], 0, 2), glm::vec3(1, 1, 0)));
    // ZeroBasedIndexing: "1 2 3" means vertices 2, 3, 4; Triangle and Sphere Center ids too.
    const pt::Scene b = load(sceneXml(kOneMaterial + kSquare + "<ZeroBasedIndexing>true</ZeroBasedIndexing>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>"
        "<Triangle id=\"2\"><Material>1</Material><Indices>0 1 2</Indices></Triangle>"
        "<Sphere id=\"1\"><Material>1</Material><Center>3</Center><Radius>1</Radius></Sphere></Objects>"));
    EXPECT_TRUE(near3(corner(b.meshes[0], 0, 0), glm::vec3(1, 0, 0)));
    EXPECT_TRUE(near3(corner(b.meshes[1], 0, 0), glm::vec3(0, 0, 0)));
    EXPECT_TRUE(near3(glm::vec3(b.spheres[0].objectToWorld[3]), glm::vec3(0, 1, 0)));
    // A negative offset ("can be negative").
    const pt::Scene c = load(sceneXml(kOneMaterial + kSquare +
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces vertexOffset=\"-1\">2 3 4</Faces></Mesh></Objects>"));
    EXPECT_TRUE(near3(corner(c.meshes[0], 0, 0), glm::vec3(0, 0, 0)));
}

TEST_F(Ceng795, CommasSeparateNumbers) {
    const pt::Scene s = load(sceneXml(kOneMaterial + "<VertexData>0, 0, 0,  2, 0, 0,\n 0, 2, 0</VertexData>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1,2,3</Faces></Mesh></Objects>"
        "<Cameras><Camera id=\"1\"><Position>1, 2, 3</Position><Gaze>0,0,-1</Gaze><Up>0, 1, 0</Up>"
        "<NearPlane>-1,1,-1,1</NearPlane><NearDistance>1</NearDistance></Camera></Cameras>"));
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 1), glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(s.cameras[0].position, glm::vec3(1, 2, 3)));
}

TEST_F(Ceng795, TriangleElement) {
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare +
        "<Transformations><Translation id=\"1\">0 0 2</Translation></Transformations>"
        "<Objects><Triangle id=\"7\"><Material>1</Material><Transformations>t1</Transformations><Indices>2 3 4</Indices></Triangle></Objects>"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].name, "Triangle 7");
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 0), glm::vec3(1, 0, 2)));
}

TEST_F(Ceng795, SmoothShadingAveragesFaceNormalsByArea) {
    // Two faces meet at vertex 1 = origin: a unit one in z = 0 (normal +z) and one of four
    // times the area in x = 0 (normal +x). The shared normal leans 4:1 towards +x.
    const pt::Scene s = load(sceneXml(kOneMaterial + "<VertexData>0 0 0  1 0 0  0 1 0  0 2 0  0 0 2</VertexData>"
        "<Objects><Mesh id=\"1\" shadingMode=\"smooth\"><Material>1</Material><Faces>1 2 3  1 4 5</Faces></Mesh>"
        "<Mesh id=\"2\" shadingMode=\"flat\"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>"));
    const pt::Mesh& m = s.meshes[0];
    ASSERT_EQ(m.normals.size(), m.positions.size());
    EXPECT_TRUE(near3(m.normals[0], glm::normalize(glm::vec3(4, 0, 1))));
    EXPECT_TRUE(near3(m.normals[1], glm::vec3(0, 0, 1)));
    EXPECT_TRUE(near3(m.normals[3], glm::vec3(1, 0, 0)));
    EXPECT_TRUE(s.meshes[1].normals.empty());
}

TEST_F(Ceng795, SmoothNormalsUseTheInverseTranspose) {
    // A 45-degree slope scaled by 2 in x: the normal of the plane x = y becomes (1, -2)/sqrt(5)
    // direction-wise (inverse transpose), not the scaled (2, -1).
    const std::string transforms = "<Transformations><Scaling id=\"1\">2 1 1</Scaling></Transformations>";
    const pt::Scene s = load(sceneXml(kOneMaterial + "<VertexData>0 0 0  1 1 0  0 0 1</VertexData>" + transforms +
        "<Objects><Mesh id=\"1\" shadingMode=\"smooth\"><Material>1</Material><Transformations>s1</Transformations>"
        "<Faces>1 2 3</Faces></Mesh></Objects>"));
    const glm::vec3 expected = glm::normalize(glm::vec3(1, -2, 0));
    EXPECT_TRUE(near3(s.meshes[0].normals[0], expected));
    EXPECT_TRUE(near3(geometricNormal(s.meshes[0], 0), expected));
}

TEST_F(Ceng795, DegenerateTrianglesAreSkipped) {
    const pt::Scene s = load(sceneXml(kOneMaterial + "<VertexData>0 0 0  1 0 0  0 1 0  0 1 0</VertexData>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3  1 3 4  1 2 1</Faces></Mesh></Objects>"));
    EXPECT_EQ(s.meshes[0].triangles.size(), 1u);
}

TEST_F(Ceng795, BinaryVerticesAndFaces) {
    writeBinary("geometry/v.bin", {4}, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    writeBinary("geometry/f.bin", {2}, {}, {0, 1, 2, 0, 2, 3});
    const pt::Scene s = load(sceneXml(kOneMaterial + "<ZeroBasedIndexing>true</ZeroBasedIndexing>"
        "<VertexData binaryFile=\"geometry/v.bin\"/>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces binaryFile=\"geometry/f.bin\"/></Mesh></Objects>"));
    ASSERT_EQ(s.meshes[0].triangles.size(), 2u);
    EXPECT_TRUE(near3(corner(s.meshes[0], 1, 2), glm::vec3(0, 1, 0)));
}

TEST_F(Ceng795, PlyFacesRelativeToTheSceneFile) {
    write("models/quad.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    const pt::Scene s = load(sceneXml(kOneMaterial +
        "<Transformations><Translation id=\"1\">0 0 3</Translation></Transformations>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"models/quad.ply\"/></Mesh>"
        "<Mesh id=\"2\"><Material>1</Material><Transformations>t1</Transformations><Faces plyFile=\"models/quad.ply\"/></Mesh></Objects>"));
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].triangles.size(), 2u); // the quad split in two
    EXPECT_TRUE(near3(s.meshes[1].positions[2], glm::vec3(1, 1, 3)));
}

// ---------------------------------------------------------------------------------------------
// Instancing

const std::string kInstanceTransforms =
    "<Transformations><Translation id=\"1\">1 0 0</Translation><Translation id=\"2\">0 10 0</Translation>"
    "<Scaling id=\"1\">2 2 2</Scaling></Transformations>";
const std::string kTwoMaterials =
    "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>"
    "<Material id=\"2\"><DiffuseReflectance>0.1 0.2 0.3</DiffuseReflectance></Material></Materials>";

TEST_F(Ceng795, InstancesComposeOrResetTheBaseTransform) {
    const pt::Scene s = load(sceneXml(kTwoMaterials + kSquare + kInstanceTransforms + "<Objects>"
        "<Mesh id=\"1\"><Material>1</Material><Transformations>t1</Transformations><Faces>2 3 4</Faces></Mesh>"
        // on top of the base: (1,0,0) -> t1 -> (2,0,0) -> t2 -> (2,10,0)
        "<MeshInstance id=\"2\" baseMeshId=\"1\"><Transformations>t2</Transformations></MeshInstance>"
        // raw base geometry: (1,0,0) -> s1 -> (2,0,0)
        "<MeshInstance id=\"3\" baseMeshId=\"1\" resetTransform=\"true\"><Material>2</Material><Transformations>s1</Transformations></MeshInstance>"
        // a chain: on top of instance 2: (2,10,0) -> s1 -> (4,20,0)
        "<MeshInstance id=\"4\" baseMeshId=\"2\" resetTransform=\"false\"><Transformations>s1</Transformations></MeshInstance>"
        // reset in a chain still starts from the root mesh's raw geometry: (1,0,0) -> t2
        "<MeshInstance id=\"5\" baseMeshId=\"4\" resetTransform=\"true\"><Transformations>t2</Transformations></MeshInstance>"
        "</Objects>"));
    ASSERT_EQ(s.meshes.size(), 5u);
    EXPECT_TRUE(near3(corner(*findMesh(s, "Mesh 1"), 0, 0), glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(corner(*findMesh(s, "MeshInstance 2"), 0, 0), glm::vec3(2, 10, 0)));
    EXPECT_TRUE(near3(corner(*findMesh(s, "MeshInstance 3"), 0, 0), glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(corner(*findMesh(s, "MeshInstance 4"), 0, 0), glm::vec3(4, 20, 0)));
    EXPECT_TRUE(near3(corner(*findMesh(s, "MeshInstance 5"), 0, 0), glm::vec3(1, 10, 0)));
    // Own material, else the base's.
    EXPECT_EQ(findMesh(s, "MeshInstance 2")->material, 0u);
    EXPECT_EQ(findMesh(s, "MeshInstance 3")->material, 1u);
}

TEST_F(Ceng795, InstanceMayPrecedeItsBaseAndInheritsShading) {
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare + kInstanceTransforms + "<Objects>"
        "<MeshInstance id=\"2\" baseMeshId=\"1\"><Transformations>t2</Transformations></MeshInstance>"
        "<MeshInstance id=\"3\" baseMeshId=\"1\" shadingMode=\"flat\"/>"
        "<Mesh id=\"1\" shadingMode=\"smooth\"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>"));
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_EQ(s.meshes[0].name, "MeshInstance 2"); // file order
    EXPECT_EQ(s.meshes[0].normals.size(), 3u);
    EXPECT_TRUE(s.meshes[1].normals.empty());
}

TEST_F(Ceng795, BaseMeshIdPrefersMeshesOverInstancesWithTheSameId) {
    // veach-ajar: MeshInstance 1 coexists with Mesh 1; baseMeshId="1" is the Mesh, not itself.
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare + kInstanceTransforms + "<Objects>"
        "<Mesh id=\"1\"><Material>1</Material><Faces>2 3 4</Faces></Mesh>"
        "<MeshInstance id=\"1\" baseMeshId=\"1\"><Transformations>t2</Transformations></MeshInstance>"
        "<MeshInstance id=\"2\" baseMeshId=\"1\"><Transformations>t1</Transformations></MeshInstance></Objects>"));
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_TRUE(near3(corner(s.meshes[1], 0, 0), glm::vec3(1, 10, 0)));
    EXPECT_TRUE(near3(corner(s.meshes[2], 0, 0), glm::vec3(2, 0, 0))); // Mesh 1 + t1, not instance 1
}

TEST_F(Ceng795, LongInstanceChainsResolve) {
    std::string objects = "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>";
    for (int i = 2; i <= 3000; ++i)
        objects += "<MeshInstance id=\"" + std::to_string(i) + "\" baseMeshId=\"" + std::to_string(i - 1) +
                   "\"><Transformations>t1</Transformations></MeshInstance>";
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare + kInstanceTransforms + "<Objects>" + objects + "</Objects>"));
    ASSERT_EQ(s.meshes.size(), 3000u);
    EXPECT_TRUE(near3(corner(s.meshes.back(), 0, 0), glm::vec3(2999, 0, 0), 1e-2f));
}

TEST_F(Ceng795, CyclicOrDanglingInstancesAreErrors) {
    const std::string base = kOneMaterial + kSquare + "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>";
    expectError(sceneXml(base + "<MeshInstance id=\"2\" baseMeshId=\"3\"/><MeshInstance id=\"3\" baseMeshId=\"2\"/></Objects>"),
        "MeshInstance id=2", "baseMeshId chain is cyclic (2 -> 3 -> 2)");
    expectError(sceneXml(base + "<MeshInstance id=\"7\" baseMeshId=\"7\"/></Objects>"), "MeshInstance id=7", "cyclic");
    expectError(sceneXml(base + "<MeshInstance id=\"2\" baseMeshId=\"9\"/></Objects>"), "MeshInstance id=2",
        "baseMeshId 9 is neither a Mesh nor a MeshInstance");
    expectError(sceneXml(base + "<MeshInstance id=\"2\"/></Objects>"), "MeshInstance id=2", "missing baseMeshId");
    expectError(sceneXml(base + "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>"), "Mesh id=1",
        "duplicate id");
}

// ---------------------------------------------------------------------------------------------
// Spheres and object lights

TEST_F(Ceng795, SphereMapsTheUnitSphereThroughCentreRadiusAndTransform) {
    // objectToWorld = M · translate(centre) · scale(radius), M = "s1 t1" = T1 · S1.
    const pt::Scene s = load(sceneXml(kOneMaterial + "<VertexData>1 2 3</VertexData>"
        "<Transformations><Scaling id=\"1\">5 1 1</Scaling><Translation id=\"1\">0 0 10</Translation></Transformations>"
        "<Objects><Sphere id=\"3\"><Material>1</Material><Center>1</Center><Radius>0.5</Radius>"
        "<Transformations>s1 t1</Transformations></Sphere></Objects>"));
    ASSERT_EQ(s.spheres.size(), 1u);
    const pt::Sphere& sp = s.spheres[0];
    EXPECT_EQ(sp.name, "Sphere 3");
    EXPECT_EQ(sp.material, 0u);
    const glm::vec3 centre = glm::vec3(sp.objectToWorld * glm::vec4(0, 0, 0, 1));
    const glm::vec3 east = glm::vec3(sp.objectToWorld * glm::vec4(1, 0, 0, 1));
    const glm::vec3 north = glm::vec3(sp.objectToWorld * glm::vec4(0, 1, 0, 1));
    EXPECT_TRUE(near3(centre, glm::vec3(5, 2, 13)));   // (1,2,3) scaled then moved
    EXPECT_TRUE(near3(east, glm::vec3(7.5f, 2, 13)));  // (1.5,2,3) -> (7.5,2,3) -> +z10
    EXPECT_TRUE(near3(north, glm::vec3(5, 2.5f, 13)));
}

TEST_F(Ceng795, LightMeshAndLightSphereEmitTheirRadiance) {
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare + "<Objects>"
        "<LightMesh id=\"1\"><Material>1</Material><Radiance>31.831 31.831 31.831</Radiance><Faces>1 2 3</Faces></LightMesh>"
        "<LightSphere id=\"1\"><Material>1</Material><Center>4</Center><Radius>0.2</Radius><Radiance>1 2 3</Radiance></LightSphere>"
        "<Mesh id=\"1\"><Material>1</Material><Faces>1 3 4</Faces></Mesh></Objects>"));
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_FALSE(s.materials[0].emissive()); // the referenced material itself stays as it was
    const pt::Mesh& light = *findMesh(s, "LightMesh 1");
    const pt::Material& lm = s.materials[light.material];
    EXPECT_TRUE(near3(lm.emission, glm::vec3(31.831f)));
    EXPECT_TRUE(near3(lm.baseColor, glm::vec3(0.5f)));
    EXPECT_TRUE(lm.doubleSided);
    const pt::Material& sm = s.materials[s.spheres[0].material];
    EXPECT_TRUE(near3(sm.emission, glm::vec3(1, 2, 3)));
    EXPECT_EQ(sm.name, "LightSphere 1");
    EXPECT_EQ(findMesh(s, "Mesh 1")->material, 0u);
}

TEST_F(Ceng795, ObjectErrors) {
    const std::string head = kOneMaterial + kSquare + "<Objects>";
    expectError(sceneXml(head + "<LightMesh id=\"2\"><Material>1</Material><Radiance>1 1 1</Radiance><Faces>1 2 2</Faces></LightMesh></Objects>"),
        "LightMesh id=2", "all triangles are degenerate (zero area)");
    expectError(sceneXml(head + "<LightMesh id=\"2\"><Material>1</Material><Faces>1 2 3</Faces></LightMesh></Objects>"),
        "LightMesh id=2", "missing <Radiance>");
    expectError(sceneXml(head + "<Sphere id=\"4\"><Material>1</Material><Center>1</Center><Radius>-1</Radius></Sphere></Objects>"),
        "Sphere id=4: Radius", "must be positive");
    expectError(sceneXml(head + "<Sphere id=\"4\"><Material>1</Material><Center>1</Center><Radius>0</Radius></Sphere></Objects>"),
        "Sphere id=4: Radius", "must be positive");
    expectError(sceneXml(head + "<Sphere id=\"4\"><Material>1</Material><Center>5</Center><Radius>1</Radius></Sphere></Objects>"),
        "Sphere id=4: Center", "vertex 5 out of range (4 vertices, 1-based)");
    expectError(sceneXml(head + "<Sphere id=\"4\"><Center>1</Center><Radius>1</Radius></Sphere></Objects>"), "Sphere id=4",
        "missing <Material>");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>9</Material><Faces>1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=3: Material", "unknown material 9");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material></Mesh></Objects>"), "Mesh id=3", "missing <Faces>");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>1 2 3 2 3 12</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "face index 12 out of range (4 vertices, 1-based)");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>9223372036854775807 1 2</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "face index 9223372036854775807 out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces vertexOffset=\"9223372036854775807\">1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "vertexOffset is out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>99999999999999999999 1 2</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "'99999999999999999999' is out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>0 1 2</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "face index 0 out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>1 2 3 4</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "not a whole number of triangles");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>1 2 3.5</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "'3.5' is not an integer");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces></Faces></Mesh></Objects>"), "Mesh id=3: Faces",
        "no faces");
    expectError(sceneXml(head + "<Triangle id=\"8\"><Material>1</Material><Indices>1 2 99</Indices></Triangle></Objects>"),
        "Triangle id=8: Indices", "face index 99 out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\" shadingMode=\"glossy\"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=3", "shadingMode 'glossy'");
    expectError(sceneXml(kOneMaterial + kSquare), "", "no objects to render");
}

TEST_F(Ceng795, MissingOrHostileExternalFilesAreErrors) {
    const std::string head = kOneMaterial + kSquare + "<Objects>";
    expectError(sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces plyFile=\"ply/none.ply\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "plyFile 'ply/none.ply' not found");
    write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\nnot-a-number\n");
    expectError(sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces plyFile=\"bad.ply\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "bad.ply");
    expectError(sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces binaryFile=\"none.bin\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "binaryFile 'none.bin' not found");
    // A count far beyond what the file holds must not be allocated.
    writeBinary("huge.bin", {0x7fffffff}, {}, {1, 2, 3});
    expectError(sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces binaryFile=\"huge.bin\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "count 2147483647 needs");
    writeBinary("negative.bin", {-5}, {});
    expectError(sceneXml(kOneMaterial + "<VertexData binaryFile=\"negative.bin\"/>" + "<Objects></Objects>"), "VertexData",
        "negative count");
}

// ---------------------------------------------------------------------------------------------
// Materials

std::string materialScene(const std::string& material, const std::string& extra = "") {
    return sceneXml("<Materials>" + material + "</Materials>" + extra + kSquare +
                    "<Objects><Mesh id=\"1\"><Material>5</Material><Faces>1 2 3</Faces></Mesh></Objects>");
}

TEST_F(Ceng795, DefaultMaterialIsDiffuse) {
    const pt::Scene s = load(materialScene("<Material id=\"5\"><AmbientReflectance>1 1 1</AmbientReflectance>"
        "<DiffuseReflectance>0.2 0.4 0.6</DiffuseReflectance><SpecularReflectance>0 0 0</SpecularReflectance>"
        "<PhongExponent>10</PhongExponent></Material>"));
    ASSERT_EQ(s.materials.size(), 1u);
    const pt::Material& m = s.materials[0];
    EXPECT_EQ(m.type, pt::MaterialType::Diffuse);
    EXPECT_EQ(m.name, "material 5");
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(0.2f, 0.4f, 0.6f)));
    EXPECT_FALSE(m.doubleSided);
    EXPECT_FALSE(contains(s.unsupported, "course BRDF specular lobes (rendered diffuse)"));
}

TEST_F(Ceng795, BrdfsBecomeGlossyMaterials) {
    const std::string brdfs = "<BRDFs><ModifiedPhong id=\"1\" normalized=\"true\"><Exponent>90</Exponent></ModifiedPhong>"
        "<TorranceSparrow id=\"2\" kdfresnel=\"true\"><Exponent>50</Exponent></TorranceSparrow></BRDFs>";
    const pt::Scene used = load(materialScene("<Material id=\"5\" BRDF=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
        "<SpecularReflectance>0.3 0.3 0.3</SpecularReflectance></Material>", brdfs));
    EXPECT_TRUE(used.unsupported.empty()) << used.unsupported.front();
    EXPECT_EQ(used.materials[0].type, pt::MaterialType::Glossy);
    EXPECT_EQ(used.materials[0].glossyModel, pt::GlossyModel::ModifiedPhong);
    EXPECT_EQ(used.materials[0].exponent, 90.0f);
    EXPECT_TRUE(used.materials[0].normalized);
    const pt::Scene ts = load(materialScene("<Material id=\"5\" BRDF=\"2\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
        "<SpecularReflectance>1 0.86 0.57</SpecularReflectance><RefractionIndex>0.37</RefractionIndex>"
        "<AbsorptionIndex>2.82</AbsorptionIndex></Material>", brdfs));
    EXPECT_EQ(ts.materials[0].glossyModel, pt::GlossyModel::TorranceSparrow);
    EXPECT_TRUE(ts.materials[0].kdFresnel);
    EXPECT_FLOAT_EQ(ts.materials[0].conductorK.x, 2.82f);
    // Without a BRDF, a specular colour means the course's default Blinn-Phong with PhongExponent.
    const pt::Scene classic = load(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>"
        "<SpecularReflectance>0.3 0.3 0.3</SpecularReflectance><PhongExponent>40</PhongExponent></Material>"));
    EXPECT_EQ(classic.materials[0].glossyModel, pt::GlossyModel::OriginalBlinnPhong);
    EXPECT_EQ(classic.materials[0].exponent, 40.0f);
    // The HW6 Cornell files carry unused leftovers (e.g. a <Transparency> material): no warning.
    const pt::Scene unused = load(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>"
        "<Material id=\"6\"><SpecularReflectance>0.3 0.3 0.3</SpecularReflectance><Transparency>0.99 0.99 0.99</Transparency></Material>"));
    EXPECT_TRUE(unused.unsupported.empty() || !contains(unused.unsupported, "course BRDF specular lobes (rendered diffuse)"));
    expectError(materialScene("<Material id=\"5\" BRDF=\"4\"/>", brdfs), "Material id=5", "unknown BRDF '4'");
}

TEST_F(Ceng795, MirrorMaterial) {
    const pt::Scene s = load(materialScene("<Material id=\"5\" type=\"mirror\"><DiffuseReflectance>0.1 0.1 0.1</DiffuseReflectance>"
        "<MirrorReflectance>0.9 0.8 0.7</MirrorReflectance></Material>"));
    EXPECT_EQ(s.materials[0].type, pt::MaterialType::Mirror);
    EXPECT_TRUE(near3(s.materials[0].baseColor, glm::vec3(0.9f, 0.8f, 0.7f)));
    EXPECT_TRUE(contains(s.unsupported, "mirror with diffuse layer"));
    expectError(materialScene("<Material id=\"5\" type=\"mirror\"/>"), "Material id=5", "missing <MirrorReflectance>");
}

TEST_F(Ceng795, DielectricMaterialWithBeerAbsorption) {
    const pt::Scene s = load(materialScene("<Material id=\"5\" type=\"dielectric\"><AbsorptionCoefficient>0.01 0.5 2</AbsorptionCoefficient>"
        "<RefractionIndex>1.5</RefractionIndex></Material>"));
    const pt::Material& m = s.materials[0];
    EXPECT_EQ(m.type, pt::MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(m.ior, 1.5f);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1.0f)));
    EXPECT_FLOAT_EQ(m.attenuationDistance, 1.0f);
    EXPECT_TRUE(near3(m.attenuationColor, glm::vec3(std::exp(-0.01f), std::exp(-0.5f), std::exp(-2.0f))));
    // No absorption: no attenuation at all.
    const pt::Scene clear = load(materialScene("<Material id=\"5\" type=\"dielectric\"><RefractionIndex>1.3</RefractionIndex></Material>"));
    EXPECT_TRUE(std::isinf(clear.materials[0].attenuationDistance));
    expectError(materialScene("<Material id=\"5\" type=\"dielectric\"><RefractionIndex>0</RefractionIndex></Material>"),
        "Material id=5: RefractionIndex", "must be positive");
    expectError(materialScene("<Material id=\"5\" type=\"dielectric\"><RefractionIndex>1.5</RefractionIndex>"
        "<AbsorptionCoefficient>-1 0 0</AbsorptionCoefficient></Material>"), "Material id=5: AbsorptionCoefficient",
        "must not be negative");
}

TEST_F(Ceng795, ConductorMaterialAndRoughness) {
    const pt::Scene s = load(materialScene("<Material id=\"5\" type=\"conductor\"><MirrorReflectance>1 0.86 0.57</MirrorReflectance>"
        "<RefractionIndex>0.370</RefractionIndex><AbsorptionIndex>2.820</AbsorptionIndex><Roughness>0.2</Roughness></Material>"));
    const pt::Material& m = s.materials[0];
    EXPECT_EQ(m.type, pt::MaterialType::Conductor);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1, 0.86f, 0.57f)));
    EXPECT_TRUE(near3(m.conductorEta, glm::vec3(0.37f)));
    EXPECT_TRUE(near3(m.conductorK, glm::vec3(2.82f)));
    // The course's Roughness r as GGX alpha r / 5 (perceptual roughness sqrt(alpha)).
    EXPECT_NEAR(m.roughness * m.roughness, 0.2f * 0.2f, 1e-6f);
    EXPECT_FALSE(contains(s.unsupported, "rough specular (rendered smooth)"));
}

TEST_F(Ceng795, DegammaLinearisesColours) {
    const pt::Scene s = load(materialScene("<Material id=\"5\" degamma=\"true\"><DiffuseReflectance>0.5 1 0</DiffuseReflectance></Material>"));
    EXPECT_TRUE(near3(s.materials[0].baseColor, glm::vec3(std::pow(0.5f, 2.2f), 1.0f, 0.0f)));
}

TEST_F(Ceng795, MaterialErrors) {
    expectError(materialScene("<Material id=\"5\"><DiffuseReflectance>nan 0 0</DiffuseReflectance></Material>"),
        "Material id=5: DiffuseReflectance", "'nan' is not a finite number");
    expectError(materialScene("<Material id=\"5\"><DiffuseReflectance>1e999 0 0</DiffuseReflectance></Material>"),
        "Material id=5: DiffuseReflectance", "'1e999' is out of range");
    expectError(materialScene("<Material id=\"5\"><DiffuseReflectance>0.5 0.5</DiffuseReflectance></Material>"),
        "Material id=5: DiffuseReflectance", "expected 3 numbers, found 2");
    expectError(materialScene("<Material id=\"5\"/><Material id=\"5\"/>"), "Material id=5", "duplicate id");
    expectError(materialScene("<Material><DiffuseReflectance>1 1 1</DiffuseReflectance></Material>"), "Materials: Material",
        "missing id attribute");
}

TEST_F(Ceng795, MotionBlurIsEachObjectsTranslation) {
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare + "<Objects><Mesh id=\"1\"><Material>1</Material>"
        "<MotionBlur>0 0 1</MotionBlur><Faces>1 2 3</Faces></Mesh>"
        "<MeshInstance id=\"2\" baseMeshId=\"1\"></MeshInstance>"
        "<MeshInstance id=\"3\" baseMeshId=\"1\"><MotionBlur>2 0 0</MotionBlur></MeshInstance>"
        "<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius><MotionBlur>0 3 0</MotionBlur></Sphere>"
        "</Objects>"));
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_TRUE(near3(s.meshes[0].motion, glm::vec3(0, 0, 1)));
    EXPECT_TRUE(near3(s.meshes[1].motion, glm::vec3(0, 0, 1))); // the base's
    EXPECT_TRUE(near3(s.meshes[2].motion, glm::vec3(2, 0, 0))); // its own
    ASSERT_EQ(s.spheres.size(), 1u);
    EXPECT_TRUE(near3(s.spheres[0].motion, glm::vec3(0, 3, 0)));
    EXPECT_TRUE(s.unsupported.empty());
    expectError(sceneXml(kOneMaterial + kSquare + "<Objects><Mesh id=\"1\"><Material>1</Material>"
        "<MotionBlur>0 0</MotionBlur><Faces>1 2 3</Faces></Mesh></Objects>"), "Mesh id=1: MotionBlur", "");
}

// ---------------------------------------------------------------------------------------------
// Lights and scene settings

TEST_F(Ceng795, PointAndDirectionalLightsArePunctualLights) {
    const pt::Scene s = load(triangleScene("", "", "<Lights>"
        "<PointLight id=\"1\"><Position>0 30 50</Position><Intensity>1000 2000 3000</Intensity></PointLight>"
        "<DirectionalLight id=\"1\"><Direction>0 -2 0</Direction><Radiance>2 2 2</Radiance></DirectionalLight></Lights>"));
    ASSERT_EQ(s.punctualLights.size(), 2u);
    EXPECT_EQ(s.punctualLights[0].type, pt::PunctualLight::Type::Point);
    EXPECT_TRUE(near3(s.punctualLights[0].position, glm::vec3(0, 30, 50)));
    EXPECT_TRUE(near3(s.punctualLights[0].intensity, glm::vec3(1000, 2000, 3000)));
    EXPECT_EQ(s.punctualLights[1].type, pt::PunctualLight::Type::Directional);
    EXPECT_TRUE(near3(s.punctualLights[1].direction, glm::vec3(0, -1, 0)));
    EXPECT_TRUE(near3(s.punctualLights[1].intensity, glm::vec3(2)));
    EXPECT_TRUE(s.unsupported.empty());
    expectError(triangleScene("", "", "<Lights><PointLight id=\"4\"><Position>0 0 0</Position></PointLight></Lights>"),
        "PointLight id=4", "missing <Intensity>");
    expectError(triangleScene("", "", "<Lights><DirectionalLight id=\"2\"><Direction>0 0 0</Direction><Radiance>1 1 1</Radiance>"
        "</DirectionalLight></Lights>"), "DirectionalLight id=2: Direction", "non-zero");
}

TEST_F(Ceng795, OtherLightsAreNamedOnce) {
    const pt::Scene s = load(triangleScene("", "", "<Lights><AmbientLight>25 25 25</AmbientLight>"
        "<HeadLight id=\"1\"/><HeadLight id=\"2\"/></Lights>"));
    EXPECT_EQ(s.unsupported, (std::vector<std::string>{"HeadLight lights (ignored)"}));
    EXPECT_TRUE(near3(s.ambientLight, glm::vec3(25.0f))); // for the classic integrator
    EXPECT_TRUE(s.punctualLights.empty());
    const pt::Scene dark = load(triangleScene("", "", "<Lights><AmbientLight>0 0 0</AmbientLight></Lights>"));
    EXPECT_TRUE(dark.unsupported.empty());
}

TEST_F(Ceng795, SpotAndAreaLights) {
    const pt::Scene s = load(triangleScene("", "", "<Lights>"
        "<SpotLight id=\"1\"><Position>-0.93 1 0.9</Position><Direction>1 -1 -1</Direction><Intensity>600 600 600</Intensity>"
        "<CoverageAngle>10</CoverageAngle><FalloffAngle>8</FalloffAngle></SpotLight>"
        "<AreaLight id=\"1\"><Position>0 9.8 2</Position><Normal>0 -2 0</Normal><Size>3</Size><Radiance>15 15 15</Radiance></AreaLight>"
        "</Lights>"));
    ASSERT_EQ(s.punctualLights.size(), 2u);
    const pt::PunctualLight& spot = s.punctualLights[0];
    EXPECT_EQ(spot.type, pt::PunctualLight::Type::Spot);
    EXPECT_TRUE(near3(spot.direction, glm::normalize(glm::vec3(1, -1, -1))));
    EXPECT_NEAR(spot.cosCoverage, std::cos(glm::radians(5.0f)), 1e-6); // half of the full cone angle
    EXPECT_NEAR(spot.cosFalloff, std::cos(glm::radians(4.0f)), 1e-6);
    const pt::PunctualLight& square = s.punctualLights[1];
    EXPECT_EQ(square.type, pt::PunctualLight::Type::Square);
    EXPECT_TRUE(near3(square.direction, glm::vec3(0, -1, 0)));
    EXPECT_EQ(square.size, 3.0f);
    EXPECT_TRUE(s.unsupported.empty());
    expectError(triangleScene("", "", "<Lights><AreaLight id=\"1\"><Position>0 0 0</Position><Normal>0 0 0</Normal>"
        "<Size>1</Size><Radiance>1 1 1</Radiance></AreaLight></Lights>"), "AreaLight id=1", "non-zero");
}

TEST_F(Ceng795, BackgroundColour) {
    const pt::Scene black = load(triangleScene("", "", "<BackgroundColor>0 0 0</BackgroundColor>"));
    EXPECT_TRUE(near3(black.background, glm::vec3(0)));
    EXPECT_TRUE(black.unsupported.empty());
    const pt::Scene grey = load(triangleScene("", "", "<BackgroundColor>0.1 0.2 0.3</BackgroundColor>"));
    EXPECT_TRUE(near3(grey.background, glm::vec3(0.1f, 0.2f, 0.3f)));
    EXPECT_TRUE(contains(grey.unsupported, "background seen only by primary rays"));
}

TEST_F(Ceng795, MaxRecursionDepthCountsBouncesAfterTheCameraRay) {
    const std::string cameras =
        "<Cameras><Camera id=\"1\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Renderer>PathTracing</Renderer><RendererParams>NextEventEstimation</RendererParams></Camera>"
        "<Camera id=\"2\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Renderer>PathTracing</Renderer><RendererParams>RussianRoulette</RendererParams></Camera></Cameras>";
    const pt::Scene s = load(triangleScene("", "", "<MaxRecursionDepth>3</MaxRecursionDepth>" + cameras));
    ASSERT_TRUE(s.hints.maxDepth.has_value());
    EXPECT_EQ(*s.hints.maxDepth, 4); // camera ray + 3 bounces
    EXPECT_EQ(s.cameras[0].settings.maxDepth, std::optional<int>(4));
    // FORMAT.md §8: the official references apply Russian roulette without the depth cap.
    EXPECT_FALSE(s.cameras[1].settings.maxDepth.has_value());
    // Absent: no depth from the file at all.
    const pt::Scene none = load(triangleScene("", "", cameras));
    EXPECT_FALSE(none.hints.maxDepth.has_value());
    EXPECT_FALSE(none.cameras[0].settings.maxDepth.has_value());
    expectError(triangleScene("", "", "<MaxRecursionDepth>-1</MaxRecursionDepth>"), "MaxRecursionDepth", "out of range");
}

// ---------------------------------------------------------------------------------------------
// Cameras

std::string cameraScene(const std::string& cameras) { return triangleScene("", "", "<Cameras>" + cameras + "</Cameras>"); }

TEST_F(Ceng795, SimpleCameraWithNearPlane) {
    const pt::Scene s = load(cameraScene("<Camera id=\"7\"><Position>0 5 25</Position><Gaze>0 0 -2</Gaze><Up>0 1 0.5</Up>"
        "<NearPlane>-1 1 -0.5 0.75</NearPlane><NearDistance>2</NearDistance><ImageResolution>800 400</ImageResolution>"
        "<NumSamples>16</NumSamples><ImageName>spheres.png</ImageName>"
        "<FocusDistance>21</FocusDistance><ApertureSize>1.5</ApertureSize></Camera>"));
    ASSERT_EQ(s.cameras.size(), 1u);
    const pt::Camera& c = s.cameras[0];
    EXPECT_EQ(c.name, "camera 7");
    EXPECT_TRUE(near3(c.position, glm::vec3(0, 5, 25)));
    EXPECT_TRUE(near3(c.forward, glm::vec3(0, 0, -1)));
    EXPECT_TRUE(near3(c.up, glm::vec3(0, 1, 0))); // re-orthogonalised against the gaze
    ASSERT_TRUE(c.window.has_value());
    EXPECT_TRUE(near4(*c.window, glm::vec4(-0.5f, 0.5f, -0.25f, 0.375f)));
    EXPECT_NEAR(c.yfov, std::atan(0.375f) + std::atan(0.25f), 1e-6f);
    EXPECT_FLOAT_EQ(c.aspectRatio, 2.0f);
    EXPECT_FLOAT_EQ(c.apertureSize, 1.5f);
    EXPECT_FLOAT_EQ(c.focusDistance, 21.0f);
    EXPECT_EQ(c.settings.width, std::optional<int>(800));
    EXPECT_EQ(c.settings.height, std::optional<int>(400));
    EXPECT_EQ(c.settings.spp, std::optional<uint32_t>(16));
    EXPECT_EQ(c.settings.imageName, "spheres.png");
    EXPECT_EQ(c.id, 7);
    // The course has no scene-wide resolution: each camera carries its own.
    EXPECT_FALSE(s.hints.width.has_value());
}

TEST_F(Ceng795, LookAtCameraWithGazePointOrGazeAndFovY) {
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"1\" type=\"lookAt\"><Position>1 1 1</Position><GazePoint>1 1 -3</GazePoint><Up>0 1 0</Up>"
        "<FovY>60</FovY><NearDistance>1.7</NearDistance><ImageResolution>1280 720</ImageResolution></Camera>"
        // The official HW6 Cornell files: type="lookAt" with a Gaze direction.
        "<Camera id=\"2\" type=\"lookAt\" handedness=\"right\"><Position>0 -4 0</Position><Gaze>0 2 0</Gaze><Up>0 0 1</Up>"
        "<FovY>45</FovY><NearDistance>0.1</NearDistance></Camera>"));
    ASSERT_EQ(s.cameras.size(), 2u);
    EXPECT_TRUE(near3(s.cameras[0].forward, glm::vec3(0, 0, -1)));
    EXPECT_FALSE(s.cameras[0].window.has_value());
    EXPECT_NEAR(s.cameras[0].yfov, glm::radians(60.0f), 1e-6f);
    EXPECT_NEAR(s.cameras[0].aspectRatio, 1280.0f / 720.0f, 1e-6f);
    EXPECT_TRUE(near3(s.cameras[1].forward, glm::vec3(0, 1, 0)));
    EXPECT_TRUE(near3(s.cameras[1].up, glm::vec3(0, 0, 1)));
    EXPECT_EQ(s.cameras[1].name, "camera 2");
    EXPECT_EQ(s.cameras[1].id, 2);
}

TEST_F(Ceng795, LeftHandedCameraMirrorsTheWindow) {
    // Course left-handed u = w x v = -(pt's right): columns run the other way, so the window's
    // left and right are negated (left > right).
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"1\" handedness=\"left\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
        "<NearPlane>-1 3 -1 1</NearPlane><NearDistance>2</NearDistance></Camera>"
        "<Camera id=\"2\" type=\"lookAt\" handedness=\"left\"><Position>0 0 0</Position><GazePoint>0 0 -1</GazePoint><Up>0 1 0</Up>"
        "<FovY>90</FovY><ImageResolution>200 100</ImageResolution></Camera>"));
    EXPECT_TRUE(near4(*s.cameras[0].window, glm::vec4(0.5f, -1.5f, -0.5f, 0.5f)));
    ASSERT_TRUE(s.cameras[1].window.has_value());
    EXPECT_TRUE(near4(*s.cameras[1].window, glm::vec4(2.0f, -2.0f, -1.0f, 1.0f), 1e-5f));
}

TEST_F(Ceng795, TonemapSettings) {
    const pt::Scene s = load(cameraScene(
        "<Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Tonemap><TMO>Photographic</TMO><TMOOptions>0.18 1</TMOOptions><Saturation>0.8</Saturation><Gamma>2.2</Gamma></Tonemap></Camera>"
        "<Camera id=\"2\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY>"
        "<Tonemap><TMO>Photographic</TMO><TMOOptions>0.0018 0</TMOOptions><Gamma>sRGB</Gamma></Tonemap></Camera>"
        "<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY></Camera>"));
    const pt::TonemapSettings& a = *s.cameras[0].settings.tonemap;
    EXPECT_EQ(a.op, pt::TonemapSettings::Operator::Photographic);
    EXPECT_FLOAT_EQ(a.key, 0.18f);
    EXPECT_FLOAT_EQ(a.burnPercent, 1.0f);
    EXPECT_FLOAT_EQ(a.saturation, 0.8f);
    EXPECT_FLOAT_EQ(a.gamma, 2.2f);
    EXPECT_FALSE(a.srgb);
    const pt::TonemapSettings& b = *s.cameras[1].settings.tonemap;
    EXPECT_TRUE(b.srgb);
    EXPECT_FLOAT_EQ(b.key, 0.0018f);
    // No Tonemap: the course clamps with no gamma.
    const pt::TonemapSettings& c = *s.cameras[2].settings.tonemap;
    EXPECT_EQ(c.op, pt::TonemapSettings::Operator::Clamp);
    EXPECT_FALSE(c.srgb);
    EXPECT_FLOAT_EQ(c.gamma, 1.0f);
    EXPECT_FALSE(s.cameras[2].settings.spp.has_value());
}

TEST_F(Ceng795, RendererParamsMapToIntegratorSwitches) {
    auto camera = [](int id, const std::string& renderer) {
        return "<Camera id=\"" + std::to_string(id) + "\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
               "<FovY>45</FovY>" + renderer + "</Camera>";
    };
    const pt::Scene s = load(cameraScene(
        camera(1, "<Renderer>PathTracing</Renderer><RendererParams>NextEventEstimation ImportanceSampling RussianRoulette</RendererParams>") +
        camera(2, "<Renderer>PathTracing</Renderer><RendererParams>ImportanceSampling</RendererParams>") +
        camera(3, "<Renderer>PathTracing</Renderer><RendererParams></RendererParams>") +
        camera(4, "<Renderer>PathTracing</Renderer>")));
    const auto& a = s.cameras[0].settings;
    EXPECT_EQ(a.nee, std::optional<bool>(true));
    EXPECT_EQ(a.importanceSampling, std::optional<bool>(true));
    EXPECT_EQ(a.russianRoulette, std::optional<bool>(true));
    const auto& b = s.cameras[1].settings;
    EXPECT_EQ(b.nee, std::optional<bool>(false));
    EXPECT_EQ(b.importanceSampling, std::optional<bool>(true));
    EXPECT_EQ(b.russianRoulette, std::optional<bool>(false));
    for (int i : {2, 3}) {
        const auto& c = s.cameras[i].settings;
        EXPECT_EQ(c.nee, std::optional<bool>(false)) << i;
        EXPECT_EQ(c.importanceSampling, std::optional<bool>(false)) << i;
        EXPECT_EQ(c.russianRoulette, std::optional<bool>(false)) << i;
    }
    EXPECT_EQ(a.classic, std::optional<bool>(false));

    // No Renderer: the course's classic ray tracer, whose images are in 0..255 display units.
    const pt::Scene classic = load(cameraScene(camera(1, "")));
    EXPECT_EQ(classic.cameras[0].settings.classic, std::optional<bool>(true));
    EXPECT_FALSE(classic.cameras[0].settings.nee.has_value());
    EXPECT_FALSE(classic.cameras[0].settings.importanceSampling.has_value());
    EXPECT_FALSE(classic.cameras[0].settings.russianRoulette.has_value());
    ASSERT_TRUE(classic.cameras[0].settings.tonemap.has_value());
    EXPECT_FLOAT_EQ(classic.cameras[0].settings.tonemap->scale, 1.0f / 255.0f);
}

TEST_F(Ceng795, CameraErrors) {
    const std::string view = "<Position>0 0 0</Position><Up>0 1 0</Up><FovY>45</FovY>";
    expectError(cameraScene("<Camera id=\"3\">" + view + "</Camera>"), "Camera id=3", "missing <Gaze> or <GazePoint>");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 1 0</Gaze><Up>0 2 0</Up><FovY>45</FovY></Camera>"),
        "Camera id=3", "Up is zero or parallel to the gaze");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 0</Gaze><Up>0 1 0</Up><FovY>45</FovY></Camera>"),
        "Camera id=3", "gaze direction is zero");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up></Camera>"),
        "Camera id=3", "missing <NearPlane> or <FovY>");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>180</FovY></Camera>"),
        "Camera id=3: FovY", "must be in (0, 180)");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
        "<NearPlane>1 -1 -1 1</NearPlane><NearDistance>1</NearDistance></Camera>"),
        "Camera id=3: NearPlane", "left < right");
    expectError(cameraScene("<Camera id=\"3\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
        "<NearPlane>-1 1 -1 1</NearPlane></Camera>"), "Camera id=3", "missing <NearDistance>");
    expectError(cameraScene("<Camera id=\"3\"><Gaze>0 0 -1</Gaze><Up>0 1 0</Up><FovY>45</FovY></Camera>"),
        "Camera id=3", "missing <Position>");
    expectError(cameraScene("<Camera id=\"3\">" + view + "<Gaze>0 0 -1</Gaze><NumSamples>99999999999</NumSamples></Camera>"),
        "Camera id=3: NumSamples", "out of range");
    expectError(cameraScene("<Camera id=\"3\">" + view + "<Gaze>0 0 -1</Gaze><ImageResolution>0 10</ImageResolution></Camera>"),
        "Camera id=3: ImageResolution", "out of range");
    expectError(cameraScene("<Camera id=\"3\">" + view + "<Gaze>0 0 -1</Gaze><ImageName>../../x.png</ImageName></Camera>"),
        "Camera id=3: ImageName", "relative path inside");
    expectError(cameraScene("<Camera id=\"3\" handedness=\"up\">" + view + "<Gaze>0 0 -1</Gaze></Camera>"),
        "Camera id=3", "handedness 'up'");
}

// ---------------------------------------------------------------------------------------------
// Documents

TEST_F(Ceng795, MalformedDocumentsAreErrors) {
    expectError("<Scene><Objects></Scene>", "", "malformed XML at offset");
    expectError("<World></World>", "", "root element is <World>, expected <Scene>");
    const fs::path missing = dir_ / "missing.xml";
    EXPECT_THROW(pt::loadCeng795File(missing), pt::SceneError);
    try {
        pt::loadCeng795File(missing);
    } catch (const pt::SceneError& e) {
        EXPECT_EQ(std::string(e.what()), missing.string() + ": file not found");
    }
    const fs::path empty = write("empty.xml", "");
    EXPECT_THROW(pt::loadCeng795File(empty), pt::SceneError);
    EXPECT_THROW(pt::loadCeng795File(dir_), pt::SceneError);
}

TEST_F(Ceng795, LoadFromTextResolvesAgainstBaseDir) {
    write("m/quad.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n");
    const pt::Scene s = pt::loadCeng795Text(
        sceneXml(kOneMaterial + "<Objects><Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"m/quad.ply\"/></Mesh></Objects>"),
        "inline.xml", dir_);
    EXPECT_EQ(s.source, "inline.xml");
    EXPECT_EQ(s.triangleCount(), 1u);
}

TEST_F(Ceng795, UnknownElementsAreNoted) {
    const pt::Scene s = load(sceneXml(kOneMaterial + kSquare + "<Integrator>PathTracing</Integrator><ShadowRayEpsilon>1e-3</ShadowRayEpsilon>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh><Plane id=\"1\"/></Objects>"));
    EXPECT_TRUE(contains(s.unsupported, "element <Integrator> (ignored)"));
    EXPECT_TRUE(contains(s.unsupported, "Plane objects (ignored)"));
    EXPECT_EQ(s.unsupported.size(), 2u); // ShadowRayEpsilon is known and deliberately ignored
}

// ---------------------------------------------------------------------------------------------
// Official course scenes (tests/data/ceng795/README.md)

TEST(Ceng795Official, CornellPathDiffuseCameras) {
    const pt::Scene s = pt::loadCeng795File(kData / "cornellbox_jaroslav_path_diffuse.xml");
    ASSERT_EQ(s.cameras.size(), 8u);
    const std::vector<std::string> names = {"diffuse_next.exr", "diffuse_next_russian.exr", "diffuse_next_importance.exr",
        "diffuse_next_importance_russian.exr", "diffuse.exr", "diffuse_russian.exr", "diffuse_importance.exr",
        "diffuse_importance_russian.exr"};
    for (size_t i = 0; i < names.size(); ++i) {
        const pt::Camera& c = s.cameras[i];
        EXPECT_EQ(c.name, "camera " + std::to_string(i + 1));
        EXPECT_EQ(c.settings.imageName, names[i]);
        const bool russian = names[i].find("russian") != std::string::npos;
        EXPECT_EQ(c.settings.nee, std::optional<bool>(names[i].find("next") != std::string::npos)) << names[i];
        EXPECT_EQ(c.settings.russianRoulette, std::optional<bool>(russian)) << names[i];
        // diffuse.exr's camera says ImportanceSampling in the official file (FORMAT.md §8 quirk).
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
    const pt::Scene s = pt::loadCeng795File(kData / "metal_glass_plates.xml");
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

namespace {

// SphericalDirectionalLight: the lat-long map named by ImageId, read from <Textures><Images>.
TEST_F(Ceng795, SphericalDirectionalLightLoadsItsMap) {
    pt::Image map;
    map.width = 4;
    map.height = 2;
    map.rgba.assign(4 * 2 * 4, 0.5f);
    fs::create_directories(dir_ / "textures");
    pt::writeExr(dir_ / "textures" / "sky.exr", map, {});
    const std::string lights = "<Textures><Images><Image id=\"3\">textures/sky.exr</Image></Images></Textures>"
                               "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>3</ImageId></SphericalDirectionalLight></Lights>";
    const pt::Scene s = load(triangleScene("", "", lights));
    ASSERT_TRUE(s.environment.has_value());
    EXPECT_EQ(s.environment->image.width, 4);
    EXPECT_EQ(s.environment->image.height, 2);
    EXPECT_FLOAT_EQ(s.environment->image.rgba[0], 0.5f);
    expectError(triangleScene("", "", "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>9</ImageId></SphericalDirectionalLight></Lights>"),
        "SphericalDirectionalLight id=1: ImageId", "unknown image");
    expectError(triangleScene("", "", "<Textures><Images><Image id=\"3\">textures/none.exr</Image></Images></Textures>"
        "<Lights><SphericalDirectionalLight id=\"1\"><ImageId>3</ImageId></SphericalDirectionalLight></Lights>"),
        "SphericalDirectionalLight id=1", "none.exr");
}

} // namespace

namespace {

// ---------------------------------------------------------------------------------------------
// Textures (HW4): TextureMaps, decal modes, images, per-object material variants

// A 2x1 binary PPM (stb_image reads PNM like PNG and JPEG): red then green.
std::string tinyPpm() { return std::string("P6\n2 1\n255\n") + std::string("\xff\x00\x00\x00\xff\x00", 6); }

const std::string kTextureMaps =
    "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image></Images>"
    "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode>"
    "<Interpolation>nearest</Interpolation><Normalizer>127.5</Normalizer></TextureMap>"
    "<TextureMap id=\"2\" type=\"image\"><ImageId>1</ImageId><DecalMode>bump_normal</DecalMode><BumpFactor>0.25</BumpFactor></TextureMap>"
    "<TextureMap id=\"3\" type=\"checkerboard\"><DecalMode>blend_kd</DecalMode><BlackColor>0 0 0.5</BlackColor>"
    "<WhiteColor>1 1 1</WhiteColor><Scale>4</Scale><Offset>0.5</Offset></TextureMap>"
    "<TextureMap id=\"4\" type=\"perlin\"><DecalMode>replace_normal</DecalMode><NoiseConversion>absval</NoiseConversion>"
    "<NoiseScale>3</NoiseScale></TextureMap>"
    "<TextureMap id=\"5\" type=\"image\" degamma=\"true\"><ImageId>1</ImageId><DecalMode>replace_all</DecalMode></TextureMap>"
    "</Textures>";

TEST_F(Ceng795, TextureMapsBecomeTexturesAndDecalModesMaterialSlots) {
    write("tex/tiny.ppm", tinyPpm());
    const pt::Scene s = load(triangleScene("", "<Textures>1 2</Textures>", kTextureMaps));
    ASSERT_EQ(s.meshes.size(), 1u);
    const pt::Material& m = s.materials.at(s.meshes[0].material);
    ASSERT_TRUE(m.baseColorTexture && m.normalTexture);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(1.0f))); // replace_kd: the texel is kd
    EXPECT_FALSE(m.blendBaseColor);
    EXPECT_TRUE(m.bumpMap);
    EXPECT_FLOAT_EQ(m.normalScale, 0.25f);
    const pt::Texture& kd = s.textures.at(*m.baseColorTexture);
    EXPECT_EQ(kd.type, pt::Texture::Type::Image);
    EXPECT_FALSE(kd.bilinear);
    EXPECT_FLOAT_EQ(kd.valueScale, 2.0f); // 255 / Normalizer
    const pt::Texture& bump = s.textures.at(*m.normalTexture);
    EXPECT_TRUE(bump.bilinear); // Interpolation omitted: bilinear
    EXPECT_EQ(kd.image, bump.image); // one image, read once
    ASSERT_EQ(s.textureImages.size(), 1u);
    EXPECT_EQ(s.textureImages[0].width, 2);
    EXPECT_EQ(s.textureImages[0].rgba8.at(0), 0xff0000ffu); // red, opaque
    EXPECT_EQ(s.textureImages[0].rgba8.at(1), 0xff00ff00u); // green
    // The untextured material is left as it was.
    EXPECT_TRUE(near3(s.materials.at(0).baseColor, glm::vec3(0.5f)));
    EXPECT_FALSE(s.materials.at(0).baseColorTexture);
}

TEST_F(Ceng795, ProceduralTexturesAndTheOtherDecalModes) {
    write("tex/tiny.ppm", tinyPpm());
    const pt::Scene s = load(triangleScene("", "<Textures>3 4</Textures>", kTextureMaps));
    const pt::Material& m = s.materials.at(s.meshes[0].material);
    const pt::Texture& checker = s.textures.at(*m.baseColorTexture);
    EXPECT_EQ(checker.type, pt::Texture::Type::Checkerboard);
    EXPECT_TRUE(m.blendBaseColor);
    EXPECT_TRUE(near3(m.baseColor, glm::vec3(0.5f))); // blend_kd keeps kd to average with
    EXPECT_TRUE(near3(checker.black, glm::vec3(0, 0, 0.5f)));
    EXPECT_FLOAT_EQ(checker.scale, 4.0f);
    EXPECT_FLOAT_EQ(checker.offset, 0.5f);
    const pt::Texture& perlin = s.textures.at(*m.normalTexture);
    EXPECT_EQ(perlin.type, pt::Texture::Type::Perlin);
    EXPECT_TRUE(perlin.perlinAbs);
    EXPECT_FLOAT_EQ(perlin.scale, 3.0f);
    EXPECT_FALSE(m.bumpMap);
    EXPECT_TRUE(s.textureImages.empty()); // no image map used, none loaded

    const pt::Scene all = load(triangleScene("", "<Textures>5</Textures>", kTextureMaps));
    const pt::Material& unlit = all.materials.at(all.meshes[0].material);
    EXPECT_TRUE(unlit.unlit);
    EXPECT_EQ(all.textures.at(*unlit.baseColorTexture).encoding, pt::Texture::Encoding::Gamma22);
}

TEST_F(Ceng795, ObjectsWithTheSameTexturesShareOneMaterialVariant) {
    write("tex/tiny.ppm", tinyPpm());
    const std::string xml = sceneXml(kOneMaterial + kSquare + kTextureMaps +
        "<Objects><Mesh id=\"1\"><Material>1</Material><Textures>1</Textures><Faces>1 2 3</Faces></Mesh>"
        "<Mesh id=\"2\"><Material>1</Material><Textures>1</Textures><Faces>1 3 4</Faces></Mesh>"
        "<MeshInstance id=\"3\" baseMeshId=\"1\"><Textures>3</Textures></MeshInstance>"
        "<MeshInstance id=\"4\" baseMeshId=\"1\"></MeshInstance></Objects>");
    const pt::Scene s = load(xml);
    ASSERT_EQ(s.meshes.size(), 4u);
    EXPECT_EQ(s.meshes[0].material, s.meshes[1].material);
    EXPECT_NE(s.meshes[2].material, s.meshes[0].material); // its own Textures
    EXPECT_EQ(s.meshes[3].material, s.meshes[0].material); // inherits the base's
    EXPECT_EQ(s.materials.size(), 3u);
}

TEST_F(Ceng795, ReplaceBackgroundBecomesTheSceneBackgroundTexture) {
    write("tex/tiny.ppm", tinyPpm());
    const std::string bg = "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image></Images>"
                           "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_background</DecalMode></TextureMap></Textures>";
    const pt::Scene s = load(triangleScene("", "", bg));
    ASSERT_TRUE(s.backgroundTexture.has_value());
    EXPECT_EQ(s.textures.at(*s.backgroundTexture).type, pt::Texture::Type::Image);
    EXPECT_TRUE(std::none_of(s.unsupported.begin(), s.unsupported.end(),
        [](const std::string& n) { return n.find("texture") != std::string::npos; }));
}

TEST_F(Ceng795, BadTexturesAreNamedErrors) {
    write("tex/tiny.ppm", tinyPpm());
    write("tex/broken.png", "\x89PNG\r\n\x1a\n truncated");
    expectError(triangleScene("", "<Textures>9</Textures>", kTextureMaps), "Mesh id=1: Textures", "unknown TextureMap 9");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>paint_it</DecalMode></TextureMap></Textures>"),
        "TextureMap id=1: DecalMode", "unknown decal mode");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><TextureMap id=\"1\" type=\"marble\"><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "TextureMap id=1", "unknown TextureMap type");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><TextureMap id=\"1\" type=\"image\"><ImageId>4</ImageId><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "TextureMap id=1: ImageId", "unknown image 4");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><Images><Image id=\"1\">tex/missing.png</Image></Images>"
                    "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "Image id=1", "missing.png");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><Images><Image id=\"1\">tex/broken.png</Image></Images>"
                    "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode></TextureMap></Textures>"),
        "Image id=1", "cannot decode image");
    expectError(triangleScene("", "<Textures>1</Textures>",
                    "<Textures><Images><Image id=\"1\">tex/tiny.ppm</Image></Images>"
                    "<TextureMap id=\"1\" type=\"image\"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode><Normalizer>0</Normalizer></TextureMap></Textures>"),
        "TextureMap id=1: Normalizer", "must be positive");
}

} // namespace
