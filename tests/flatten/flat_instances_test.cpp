// The flattener's instances (src/flatten/flat_instances.h): which placements stay instances and
// which are copied into world space, the trees they get, the instance tree's boxes, and the
// placements it drops.
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "scene/mesh_placement.h"
#include "scene/scene_error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pt {
namespace {

// A unit cube's 12 triangles, in object space.
Mesh cube(uint32_t material) {
    Mesh m;
    m.name = "cube";
    for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? 1.0f : 0.0f, k & 2 ? 1.0f : 0.0f, k & 4 ? 1.0f : 0.0f});
    m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3}, {0, 4, 6},
        {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    m.material = material;
    return m;
}

// A cube placed `count` times along x, materials 0 (diffuse) and 1 (emissive) available.
Scene placedCubes(int count) {
    Scene scene;
    scene.source = "cubes";
    Material lamp;
    lamp.emission = glm::vec3(1.0f);
    scene.materials = {Material{}, lamp};
    scene.sharedMeshes.push_back(SharedMesh{"cube", {cube(0)}});
    for (int i = 0; i < count; ++i)
        scene.instances.push_back(MeshInstance{
            "cube " + std::to_string(i), 0, glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * i, 0, 0)), {}, {}});
    return scene;
}

BvhBuildOptions with(Instancing mode) {
    BvhBuildOptions o;
    o.instancing = mode;
    return o;
}

TEST(FlatInstances, KeptInstancesShareOneTreeAndTheirTrianglesOnce) {
    const Scene scene = placedCubes(100);
    const FlatScene flat = flattenScene(scene, with(Instancing::Keep));
    EXPECT_EQ(flat.triangles.size(), 12u);
    EXPECT_EQ(flat.worldNodes, 0u);
    ASSERT_EQ(flat.instances.size(), 100u);
    for (const gpu::GpuInstance& i : flat.instances) {
        EXPECT_EQ(i.root, flat.instances[0].root);
        EXPECT_EQ(i.firstTriangle, 0u);
        EXPECT_EQ(i.triangleCount, 12u);
    }
    EXPECT_FALSE(flat.instanceNodes.empty());
    // The instance tree's root box holds every placed cube: x from 0 to 199, y and z 0 to 1.
    const Aabb bounds = sceneBounds(flat);
    EXPECT_NEAR(bounds.lo.x, 0.0f, 1e-4f);
    EXPECT_NEAR(bounds.hi.x, 199.0f, 1e-3f);
    EXPECT_NEAR(bounds.hi.y, 1.0f, 1e-4f);
    EXPECT_NE(flat.instancing.find("100 instances of 1 meshes kept"), std::string::npos) << flat.instancing;
    EXPECT_TRUE(computeFeatures(flat, IntegratorSettings{}).instances);
}

TEST(FlatInstances, AutoCopiesFewTrianglesAndKeepsMany) {
    Scene scene = placedCubes(100); // 1200 triangles once copied
    BvhBuildOptions options;
    options.expandInstancesUpTo = 1200;
    FlatScene flat = flattenScene(scene, options);
    EXPECT_TRUE(flat.instances.empty());
    EXPECT_EQ(flat.triangles.size(), 1200u);
    EXPECT_NE(flat.instancing.find("copied into world space"), std::string::npos) << flat.instancing;
    EXPECT_FALSE(computeFeatures(flat, IntegratorSettings{}).instances);
    options.expandInstancesUpTo = 1199;
    flat = flattenScene(scene, options);
    EXPECT_EQ(flat.instances.size(), 100u);
    EXPECT_EQ(flat.triangles.size(), 12u);
}

TEST(FlatInstances, CopiesMatchTheMeshPlacedInWorldSpace) {
    Scene scene = placedCubes(3);
    scene.instances[1].objectToWorld =
        glm::scale(glm::rotate(scene.instances[1].objectToWorld, 0.5f, glm::vec3(0, 1, 0)),
            glm::vec3(1.0f, -2.0f, 1.0f)); // mirrored
    const FlatScene copied = flattenScene(scene, with(Instancing::Expand));
    Scene expanded = scene;
    expandInstances(expanded);
    const FlatScene reference = flattenScene(expanded, with(Instancing::Expand));
    ASSERT_EQ(copied.triangles.size(), reference.triangles.size());
    for (size_t i = 0; i < copied.triangles.size(); ++i) {
        EXPECT_EQ(copied.triangles[i].p0, reference.triangles[i].p0);
        EXPECT_EQ(copied.triangles[i].p1, reference.triangles[i].p1);
        EXPECT_EQ(copied.triangles[i].p2, reference.triangles[i].p2);
    }
    // The mirrored copy keeps the object's front: its winding was swapped, so the geometric
    // normal of each copied face still points out of the cube.
    const Mesh placed = placeInstance(scene, scene.instances[1])[0];
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : placed.positions) centre += p / 8.0f;
    for (const glm::uvec3& t : placed.triangles) {
        const glm::vec3 a = placed.positions[t.x], b = placed.positions[t.y], c = placed.positions[t.z];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre), 0.0f);
    }
}

// Light sampling and motion blur work on world-space triangles: an emitting or moving placement
// is copied (each copy a light of its own), the others stay instances.
TEST(FlatInstances, EmittingAndMovingPlacementsAreCopied) {
    Scene scene = placedCubes(4);
    scene.instances[1].material = 1u; // emissive
    scene.instances[2].motion = glm::vec3(0, 1, 0);
    const FlatScene flat = flattenScene(scene, with(Instancing::Keep));
    EXPECT_EQ(flat.instances.size(), 2u);
    EXPECT_EQ(flat.triangles.size(), 12u + 12u + 12u); // two copies, one kept mesh
    EXPECT_EQ(flat.lights.lights.size(), 12u);
    EXPECT_EQ(flat.motions.size(), 1u);
    EXPECT_NE(flat.instancing.find("2 emitting or moving ones copied"), std::string::npos) << flat.instancing;
}

// An instance that replaces the material gets triangle records of its own; one that keeps the
// parts' materials shares them.
TEST(FlatInstances, EachMaterialAnInstanceGivesItsMeshGetsATreeOfItsOwn) {
    Scene scene = placedCubes(6);
    Material red;
    red.baseColor = glm::vec3(1, 0, 0);
    scene.materials.push_back(red);
    scene.instances[2].material = 2u;
    scene.instances[4].material = 2u;
    const FlatScene flat = flattenScene(scene, with(Instancing::Keep));
    EXPECT_EQ(flat.instances.size(), 6u);
    EXPECT_EQ(flat.triangles.size(), 24u);
    size_t redPlacements = 0;
    for (const gpu::GpuInstance& i : flat.instances)
        if (flat.triangles[i.firstTriangle].materialIndex == 2u) ++redPlacements;
    EXPECT_EQ(redPlacements, 2u);
}

TEST(FlatInstances, SingularAndNonFinitePlacementsAreDropped) {
    Scene scene = placedCubes(4);
    scene.instances[0].objectToWorld = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f));
    scene.instances[1].objectToWorld[3][0] = std::numeric_limits<float>::infinity();
    scene.instances[2].objectToWorld = glm::scale(glm::mat4(1.0f), glm::vec3(1e30f)); // its determinant overflows
    for (Instancing mode : {Instancing::Keep, Instancing::Expand}) {
        const FlatScene flat = flattenScene(scene, with(mode));
        EXPECT_EQ(flat.degenerateInstances, 3u);
        EXPECT_EQ(flat.instances.size(), mode == Instancing::Keep ? 1u : 0u);
        EXPECT_EQ(flat.triangles.size(), 12u);
    }
}

TEST(FlatInstances, AnInstanceOfAMissingMeshIsAnError) {
    Scene scene = placedCubes(2);
    scene.instances[1].mesh = 7;
    EXPECT_THROW(flattenScene(scene), std::runtime_error);
}

} // namespace
} // namespace pt
