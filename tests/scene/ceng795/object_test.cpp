// The CENG795 loader's objects: meshes (inline, binary and PLY faces, indexing, shading modes),
// triangles, spheres, LightMesh and LightSphere, and every error an object or a file it names
// can give.
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Meshes, triangles, indexing

TEST_F(Ceng795, InlineFacesAreOneBasedAndShareVertices) {
    const pt::Scene s =
        load(sceneXml(kOneMaterial + kSquare +
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
    const pt::Scene a = load(sceneXml(
        kOneMaterial + kSquare +
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces vertexOffset=\"1\">0 1 2</Faces></Mesh></Objects>"));
    EXPECT_TRUE(near3(corner(a.meshes[0], 0, 0), glm::vec3(0, 0, 0)));
    EXPECT_TRUE(near3(corner(a.meshes[0], 0, 2), glm::vec3(1, 1, 0)));
    // ZeroBasedIndexing: "1 2 3" means vertices 2, 3, 4; Triangle and Sphere Center ids too.
    const pt::Scene b = load(
        sceneXml(kOneMaterial + kSquare +
                 "<ZeroBasedIndexing>true</ZeroBasedIndexing>"
                 "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>"
                 "<Triangle id=\"2\"><Material>1</Material><Indices>0 1 2</Indices></Triangle>"
                 "<Sphere id=\"1\"><Material>1</Material><Center>3</Center><Radius>1</Radius></Sphere></Objects>"));
    EXPECT_TRUE(near3(corner(b.meshes[0], 0, 0), glm::vec3(1, 0, 0)));
    EXPECT_TRUE(near3(corner(b.meshes[1], 0, 0), glm::vec3(0, 0, 0)));
    EXPECT_TRUE(near3(glm::vec3(b.spheres[0].objectToWorld[3]), glm::vec3(0, 1, 0)));
    // A negative offset ("can be negative").
    const pt::Scene c = load(sceneXml(
        kOneMaterial + kSquare +
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces vertexOffset=\"-1\">2 3 4</Faces></Mesh></Objects>"));
    EXPECT_TRUE(near3(corner(c.meshes[0], 0, 0), glm::vec3(0, 0, 0)));
}

TEST_F(Ceng795, CommasSeparateNumbers) {
    const pt::Scene s = load(sceneXml(
        kOneMaterial + "<VertexData>0, 0, 0,  2, 0, 0,\n 0, 2, 0</VertexData>"
                       "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1,2,3</Faces></Mesh></Objects>"
                       "<Cameras><Camera id=\"1\"><Position>1, 2, 3</Position><Gaze>0,0,-1</Gaze><Up>0, 1, 0</Up>"
                       "<NearPlane>-1,1,-1,1</NearPlane><NearDistance>1</NearDistance></Camera></Cameras>"));
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 1), glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(s.cameras[0].position, glm::vec3(1, 2, 3)));
}

TEST_F(Ceng795, TriangleElement) {
    const pt::Scene s = load(
        sceneXml(kOneMaterial + kSquare +
                 "<Transformations><Translation id=\"1\">0 0 2</Translation></Transformations>"
                 "<Objects><Triangle id=\"7\"><Material>1</Material><Transformations>t1</Transformations><Indices>2 3 "
                 "4</Indices></Triangle></Objects>"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].name, "Triangle 7");
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 0), glm::vec3(1, 0, 2)));
}

TEST_F(Ceng795, SmoothShadingAveragesFaceNormalsByArea) {
    // Two faces meet at vertex 1 = origin: a unit one in z = 0 (normal +z) and one of four
    // times the area in x = 0 (normal +x). The shared normal leans 4:1 towards +x.
    const pt::Scene s = load(sceneXml(
        kOneMaterial +
        "<VertexData>0 0 0  1 0 0  0 1 0  0 2 0  0 0 2</VertexData>"
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
    const pt::Scene s = load(sceneXml(
        kOneMaterial + "<VertexData>0 0 0  1 1 0  0 0 1</VertexData>" + transforms +
        "<Objects><Mesh id=\"1\" shadingMode=\"smooth\"><Material>1</Material><Transformations>s1</Transformations>"
        "<Faces>1 2 3</Faces></Mesh></Objects>"));
    const glm::vec3 expected = glm::normalize(glm::vec3(1, -2, 0));
    EXPECT_TRUE(near3(s.meshes[0].normals[0], expected));
    EXPECT_TRUE(near3(geometricNormal(s.meshes[0], 0), expected));
}

TEST_F(Ceng795, DegenerateTrianglesAreSkipped) {
    const pt::Scene s = load(
        sceneXml(kOneMaterial +
                 "<VertexData>0 0 0  1 0 0  0 1 0  0 1 0</VertexData>"
                 "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3  1 3 4  1 2 1</Faces></Mesh></Objects>"));
    EXPECT_EQ(s.meshes[0].triangles.size(), 1u);
}

TEST_F(Ceng795, BinaryVerticesAndFaces) {
    writeBinary("geometry/v.bin", {4}, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    writeBinary("geometry/f.bin", {2}, {}, {0, 1, 2, 0, 2, 3});
    const pt::Scene s = load(sceneXml(
        kOneMaterial +
        "<ZeroBasedIndexing>true</ZeroBasedIndexing>"
        "<VertexData binaryFile=\"geometry/v.bin\"/>"
        "<Objects><Mesh id=\"1\"><Material>1</Material><Faces binaryFile=\"geometry/f.bin\"/></Mesh></Objects>"));
    ASSERT_EQ(s.meshes[0].triangles.size(), 2u);
    EXPECT_TRUE(near3(corner(s.meshes[0], 1, 2), glm::vec3(0, 1, 0)));
}

TEST_F(Ceng795, PlyFacesRelativeToTheSceneFile) {
    write("models/quad.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    const pt::Scene s = load(sceneXml(
        kOneMaterial + "<Transformations><Translation id=\"1\">0 0 3</Translation></Transformations>"
                       "<Objects><Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"models/quad.ply\"/></Mesh>"
                       "<Mesh id=\"2\"><Material>1</Material><Transformations>t1</Transformations><Faces "
                       "plyFile=\"models/quad.ply\"/></Mesh></Objects>"));
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].triangles.size(), 2u); // the quad split in two
    EXPECT_TRUE(near3(s.meshes[1].positions[2], glm::vec3(1, 1, 3)));
    EXPECT_TRUE(s.unsupported.empty());
}

// Faces of one or two vertices make no triangle: dropped, and said so, naming the PLY file.
TEST_F(Ceng795, PlyFacesWithFewerThanThreeVerticesAreDroppedWithANote) {
    write("models/short.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 3\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n2 0 1\n1 "
        "2\n");
    const pt::Scene s = load(sceneXml(kOneMaterial + "<Objects><Mesh id=\"4\"><Material>1</Material>"
                                                     "<Faces plyFile=\"models/short.ply\"/></Mesh></Objects>"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].triangles.size(), 1u);
    EXPECT_EQ(s.unsupported, std::vector<std::string>{"Mesh id=4: Faces: plyFile 'models/short.ply': 2 faces with "
                                                      "fewer than 3 vertices (dropped)"});
}

// ---------------------------------------------------------------------------------------------
// Spheres and object lights

TEST_F(Ceng795, SphereMapsTheUnitSphereThroughCentreRadiusAndTransform) {
    // objectToWorld = M · translate(centre) · scale(radius), M = "s1 t1" = T1 · S1.
    const pt::Scene s = load(sceneXml(
        kOneMaterial +
        "<VertexData>1 2 3</VertexData>"
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
    EXPECT_TRUE(near3(centre, glm::vec3(5, 2, 13)));  // (1,2,3) scaled then moved
    EXPECT_TRUE(near3(east, glm::vec3(7.5f, 2, 13))); // (1.5,2,3) -> (7.5,2,3) -> +z10
    EXPECT_TRUE(near3(north, glm::vec3(5, 2.5f, 13)));
}

TEST_F(Ceng795, LightMeshAndLightSphereEmitTheirRadiance) {
    const pt::Scene s =
        load(sceneXml(kOneMaterial + kSquare +
                      "<Objects>"
                      "<LightMesh id=\"1\"><Material>1</Material><Radiance>31.831 31.831 31.831</Radiance><Faces>1 2 "
                      "3</Faces></LightMesh>"
                      "<LightSphere id=\"1\"><Material>1</Material><Center>4</Center><Radius>0.2</Radius><Radiance>1 2 "
                      "3</Radiance></LightSphere>"
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
    expectError(sceneXml(head + "<LightMesh id=\"2\"><Material>1</Material><Radiance>1 1 1</Radiance><Faces>1 2 "
                                "2</Faces></LightMesh></Objects>"),
        "LightMesh id=2", "all triangles are degenerate (zero area)");
    expectError(sceneXml(head + "<LightMesh id=\"2\"><Material>1</Material><Faces>1 2 3</Faces></LightMesh></Objects>"),
        "LightMesh id=2", "missing <Radiance>");
    expectError(
        sceneXml(
            head + "<Sphere id=\"4\"><Material>1</Material><Center>1</Center><Radius>-1</Radius></Sphere></Objects>"),
        "Sphere id=4: Radius", "must be positive");
    expectError(
        sceneXml(
            head + "<Sphere id=\"4\"><Material>1</Material><Center>1</Center><Radius>0</Radius></Sphere></Objects>"),
        "Sphere id=4: Radius", "must be positive");
    expectError(
        sceneXml(
            head + "<Sphere id=\"4\"><Material>1</Material><Center>5</Center><Radius>1</Radius></Sphere></Objects>"),
        "Sphere id=4: Center", "vertex 5 out of range (4 vertices, 1-based)");
    expectError(sceneXml(head + "<Sphere id=\"4\"><Center>1</Center><Radius>1</Radius></Sphere></Objects>"),
        "Sphere id=4", "missing <Material>");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>9</Material><Faces>1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=3: Material", "unknown material 9");
    expectError(
        sceneXml(head + "<Mesh id=\"3\"><Material>1</Material></Mesh></Objects>"), "Mesh id=3", "missing <Faces>");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>1 2 3 2 3 12</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "face index 12 out of range (4 vertices, 1-based)");
    expectError(
        sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>9223372036854775807 1 2</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "face index 9223372036854775807 out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces vertexOffset=\"9223372036854775807\">1 2 "
                                "3</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "vertexOffset is out of range");
    expectError(
        sceneXml(
            head + "<Mesh id=\"3\"><Material>1</Material><Faces>99999999999999999999 1 2</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "'99999999999999999999' is out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>0 1 2</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "face index 0 out of range");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>1 2 3 4</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "not a whole number of triangles");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces>1 2 3.5</Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "'3.5' is not an integer");
    expectError(sceneXml(head + "<Mesh id=\"3\"><Material>1</Material><Faces></Faces></Mesh></Objects>"),
        "Mesh id=3: Faces", "no faces");
    expectError(
        sceneXml(head + "<Triangle id=\"8\"><Material>1</Material><Indices>1 2 99</Indices></Triangle></Objects>"),
        "Triangle id=8: Indices", "face index 99 out of range");
    expectError(
        sceneXml(
            head + "<Mesh id=\"3\" shadingMode=\"glossy\"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=3", "shadingMode 'glossy'");
    expectError(sceneXml(kOneMaterial + kSquare), "", "no objects to render");
}

TEST_F(Ceng795, MissingOrHostileExternalFilesAreErrors) {
    const std::string head = kOneMaterial + kSquare + "<Objects>";
    expectError(
        sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces plyFile=\"ply/none.ply\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "plyFile 'ply/none.ply' not found");
    write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\nnot-a-number\n");
    expectError(sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces plyFile=\"bad.ply\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "bad.ply");
    expectError(
        sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces binaryFile=\"none.bin\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "binaryFile 'none.bin' not found");
    // A count far beyond what the file holds must not be allocated.
    writeBinary("huge.bin", {0x7fffffff}, {}, {1, 2, 3});
    expectError(
        sceneXml(head + "<Mesh id=\"2\"><Material>1</Material><Faces binaryFile=\"huge.bin\"/></Mesh></Objects>"),
        "Mesh id=2: Faces", "count 2147483647 needs");
    writeBinary("negative.bin", {-5}, {});
    expectError(sceneXml(kOneMaterial + "<VertexData binaryFile=\"negative.bin\"/>" + "<Objects></Objects>"),
        "VertexData", "negative count");
}

} // namespace
} // namespace pt::test
