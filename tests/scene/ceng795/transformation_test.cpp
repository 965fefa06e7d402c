// The CENG795 loader's transformations: the order of a Transformations list, Composite, Rotation
// and mirroring; MeshInstance on top of its base or reset to it, in any order and long chains;
// MotionBlur, each object's translation over the shutter.
#include "ceng795_fixture.h"

namespace pt::test {
namespace {

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
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 0), glm::vec3(2, 0, 0))); // (0,0,0) -> (0,0,0) -> (1,0,0) -> (2,0,0)
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 1), glm::vec3(2, 1, 0))); // (1,0,0)
    EXPECT_TRUE(near3(corner(s.meshes[0], 0, 2), glm::vec3(0, 1, 0))); // (1,1,0) -> (-1,1,0) -> (0,1,0) -> (0,1,0)

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
    // docs/ceng795-format.md §10: normals map with the inverse transpose, which for Scaling -1 1 1 keeps +z.
    // The mirrored winding would face -z, so the loader swaps two corners.
    const std::string transforms = "<Transformations><Scaling id=\"1\">-1 1 1</Scaling></Transformations>";
    const pt::Scene s =
        load(triangleScene(" shadingMode=\"smooth\"", "<Transformations>s1</Transformations>", transforms));
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
    expectError(
        triangleScene("", "",
            "<Transformations><Composite id=\"1\">1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1</Composite></Transformations>"),
        "Composite id=1", "last row");
    expectError(triangleScene("", "", "<Transformations><Translation id=\"1\">1 2</Translation></Transformations>"),
        "Translation id=1", "expected 3 numbers");
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
    const std::string xml = (sceneXml(
        kTwoMaterials + kSquare + kInstanceTransforms +
        "<Objects>"
        "<Mesh id=\"1\"><Material>1</Material><Transformations>t1</Transformations><Faces>2 3 4</Faces></Mesh>"
        // on top of the base: (1,0,0) -> t1 -> (2,0,0) -> t2 -> (2,10,0)
        "<MeshInstance id=\"2\" baseMeshId=\"1\"><Transformations>t2</Transformations></MeshInstance>"
        // raw base geometry: (1,0,0) -> s1 -> (2,0,0)
        "<MeshInstance id=\"3\" baseMeshId=\"1\" "
        "resetTransform=\"true\"><Material>2</Material><Transformations>s1</Transformations></MeshInstance>"
        // a chain: on top of instance 2: (2,10,0) -> s1 -> (4,20,0)
        "<MeshInstance id=\"4\" baseMeshId=\"2\" "
        "resetTransform=\"false\"><Transformations>s1</Transformations></MeshInstance>"
        // reset in a chain still starts from the root mesh's raw geometry: (1,0,0) -> t2
        "<MeshInstance id=\"5\" baseMeshId=\"4\" "
        "resetTransform=\"true\"><Transformations>t2</Transformations></MeshInstance>"
        "</Objects>"));
    // The Mesh and its instances are one mesh kept once, in object space, and five placements;
    // Material 2 needs nothing of its own there (an instance names its material).
    const pt::Scene kept = load(xml);
    EXPECT_TRUE(kept.meshes.empty());
    ASSERT_EQ(kept.sharedMeshes.size(), 1u);
    EXPECT_EQ(kept.instances.size(), 5u);
    EXPECT_TRUE(near3(corner(kept.sharedMeshes[0].parts[0], 0, 0), glm::vec3(1, 0, 0))); // the raw geometry
    const pt::Scene s = loadExpanded(xml);
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
    const pt::Scene s = loadExpanded(
        sceneXml(kOneMaterial + kSquare + kInstanceTransforms +
                 "<Objects>"
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
    const pt::Scene s = loadExpanded(sceneXml(
        kOneMaterial + kSquare + kInstanceTransforms +
        "<Objects>"
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
    const pt::Scene s =
        loadExpanded(sceneXml(kOneMaterial + kSquare + kInstanceTransforms + "<Objects>" + objects + "</Objects>"));
    ASSERT_EQ(s.meshes.size(), 3000u);
    EXPECT_TRUE(near3(corner(s.meshes.back(), 0, 0), glm::vec3(2999, 0, 0), 1e-2f));
}

TEST_F(Ceng795, CyclicOrDanglingInstancesAreErrors) {
    const std::string base =
        kOneMaterial + kSquare + "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>";
    expectError(
        sceneXml(base + "<MeshInstance id=\"2\" baseMeshId=\"3\"/><MeshInstance id=\"3\" baseMeshId=\"2\"/></Objects>"),
        "MeshInstance id=2", "baseMeshId chain is cyclic (2 -> 3 -> 2)");
    expectError(sceneXml(base + "<MeshInstance id=\"7\" baseMeshId=\"7\"/></Objects>"), "MeshInstance id=7", "cyclic");
    expectError(sceneXml(base + "<MeshInstance id=\"2\" baseMeshId=\"9\"/></Objects>"), "MeshInstance id=2",
        "baseMeshId 9 is neither a Mesh nor a MeshInstance");
    expectError(sceneXml(base + "<MeshInstance id=\"2\"/></Objects>"), "MeshInstance id=2", "missing baseMeshId");
    expectError(sceneXml(base + "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=1", "duplicate id");
}

// ---------------------------------------------------------------------------------------------
// Motion blur

TEST_F(Ceng795, MotionBlurIsEachObjectsTranslation) {
    const pt::Scene s = loadExpanded(
        sceneXml(kOneMaterial + kSquare +
                 "<Objects><Mesh id=\"1\"><Material>1</Material>"
                 "<MotionBlur>0 0 1</MotionBlur><Faces>1 2 3</Faces></Mesh>"
                 "<MeshInstance id=\"2\" baseMeshId=\"1\"></MeshInstance>"
                 "<MeshInstance id=\"3\" baseMeshId=\"1\"><MotionBlur>2 0 0</MotionBlur></MeshInstance>"
                 "<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius><MotionBlur>0 3 "
                 "0</MotionBlur></Sphere>"
                 "</Objects>"));
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_TRUE(near3(s.meshes[0].motion, glm::vec3(0, 0, 1)));
    EXPECT_TRUE(near3(s.meshes[1].motion, glm::vec3(0, 0, 1))); // the base's
    EXPECT_TRUE(near3(s.meshes[2].motion, glm::vec3(2, 0, 0))); // its own
    ASSERT_EQ(s.spheres.size(), 1u);
    EXPECT_TRUE(near3(s.spheres[0].motion, glm::vec3(0, 3, 0)));
    // The instances take their base's material, and say so (the course's instances name their own).
    EXPECT_EQ(s.unsupported, std::vector<std::string>{"MeshInstances without a Material (their base's assumed)"});
    expectError(sceneXml(kOneMaterial + kSquare +
                         "<Objects><Mesh id=\"1\"><Material>1</Material>"
                         "<MotionBlur>0 0</MotionBlur><Faces>1 2 3</Faces></Mesh></Objects>"),
        "Mesh id=1: MotionBlur", "");
}

} // namespace
} // namespace pt::test
