// Device tests of the two-level traversal (shaders/geometry/traverse.glsl, traverseInstances):
// meshes kept once and placed by instances with scale, rotation, mirroring and translations up
// to 1e4, traced through the instance tree and each mesh's tree, against brute force over every
// triangle of every instance with the same transformed ray and the same intersector
// (shaders/tests/test_kernels.comp). Any difference is then the trees' fault: an instance box
// too small, a ray taken into the wrong space, a hit recorded with the wrong instance.
#include "accel/quantized_bvh.h"
#include "scene/mesh_placement.h"
#include "support/gpu_test_support.h"
#include "support/test_rays.h"

#include <glm/gtc/matrix_transform.hpp>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace pt::test {
namespace {

using gpu::GpuTestRay;

struct Uploaded {
    FlatScene flat;
    std::unique_ptr<GpuScene> gpu;
};

Uploaded upload(const Scene& scene, bool quantized) {
    BvhBuildOptions options;
    options.instancing = Instancing::Keep;
    options.quantizeOverBytes = quantized ? 0 : std::numeric_limits<size_t>::max();
    Uploaded u;
    u.flat = flattenScene(scene, options);
    u.gpu = std::make_unique<GpuScene>(sharedContext(), u.flat, gpu::GpuSceneParams{}, 0);
    return u;
}

struct TraceHit {
    bool hit = false;
    bool disagree = false; // traceAny and traceClosest disagreed (the kernel's -2)
    float t = 0;
    uint32_t triangle = 0;
    uint32_t instance = NO_INSTANCE;
};

std::vector<TraceHit> trace(uint32_t mode, const Uploaded& u, const std::vector<GpuTestRay>& rays) {
    const std::vector<glm::vec4> out = runTestKernel(
        mode, static_cast<uint32_t>(rays.size()), u.gpu.get(), std::as_bytes(std::span<const GpuTestRay>(rays)));
    std::vector<TraceHit> hits(out.size());
    for (size_t i = 0; i < out.size(); ++i) {
        TraceHit& h = hits[i];
        h.disagree = out[i].x == -2.0f;
        h.hit = out[i].x >= 0.0f;
        if (!h.hit) continue;
        h.t = out[i].x;
        const uint32_t primitive = std::bit_cast<uint32_t>(out[i].y);
        h.triangle = primitive & ~TEST_HIT_INSTANCE_BIT;
        if (primitive & TEST_HIT_INSTANCE_BIT) h.instance = std::bit_cast<uint32_t>(out[i].w);
    }
    return hits;
}

// Small random triangles around the origin, any orientation (a mesh with inner structure).
Mesh soup(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    Mesh m;
    m.name = "soup";
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 centre = randomIn(rng, glm::vec3(-1.0f), glm::vec3(1.0f));
        const uint32_t base = static_cast<uint32_t>(m.positions.size());
        for (int k = 0; k < 3; ++k)
            m.positions.push_back(centre + 0.3f * randomIn(rng, glm::vec3(-1.0f), glm::vec3(1.0f)));
        m.triangles.push_back({base, base + 1, base + 2});
    }
    return m;
}

// A placement: rotation about a random axis, a scale (uniform or not, mirrored when asked),
// then a translation.
glm::mat4 randomPlacement(std::mt19937& rng, glm::vec3 at, bool mirrored) {
    std::uniform_real_distribution<float> angle(0.0f, 6.2831853f), scale(0.3f, 2.5f);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
    m = glm::rotate(m, angle(rng), randomUnit(rng));
    glm::vec3 s(scale(rng), scale(rng), scale(rng));
    if (mirrored) s.y = -s.y;
    return glm::scale(m, s);
}

// World triangles (a soup), two shared meshes (a closed icosphere, a soup) placed 40 times at
// random in [-20, 20]^3, and four placements near (1e4, 1e4, 1e4).
Scene instancedScene() {
    Scene scene;
    scene.source = "instancing test";
    scene.materials.push_back(Material{});
    Mesh world = soup(300, 3);
    for (glm::vec3& p : world.positions) p *= 12.0f;
    scene.meshes.push_back(world);
    SharedMesh ball{"ball", {makeIcosphere(2, glm::vec3(0.0f), 1.0f, 0)}};
    SharedMesh crumbs{"crumbs", {soup(200, 5)}};
    scene.sharedMeshes = {ball, crumbs};
    std::mt19937 rng(77);
    for (int i = 0; i < 40; ++i) {
        MeshInstance inst;
        inst.mesh = uint32_t(i % 2);
        inst.objectToWorld = randomPlacement(rng, randomIn(rng, glm::vec3(-20.0f), glm::vec3(20.0f)), i % 3 == 0);
        scene.instances.push_back(inst);
    }
    for (int i = 0; i < 4; ++i) {
        MeshInstance inst;
        inst.mesh = uint32_t(i % 2);
        inst.objectToWorld = randomPlacement(rng, glm::vec3(1e4f) + glm::vec3(6.0f * float(i), 0.0f, 0.0f), i == 1);
        scene.instances.push_back(inst);
    }
    return scene;
}

glm::vec3 placedCentre(const Scene& scene, size_t instance) {
    return glm::vec3(scene.instances[instance].objectToWorld[3]);
}

// BVH and brute force must agree on every ray: hit or miss, t to the bit, and the triangle and
// instance unless another primitive lies at exactly the same t (rays through shared vertices and
// edges; elsewhere such ties are rare, at most `tieShare` of the hits).
void expectTreesMatchBruteForce(const Uploaded& u, const std::vector<GpuTestRay>& rays, const char* what,
    bool mustHit = false, double tieShare = 0.01) {
    const std::vector<TraceHit> bvh = trace(TEST_MODE_TRACE_BVH, u, rays);
    const std::vector<TraceHit> brute = trace(TEST_MODE_TRACE_BRUTE_FORCE, u, rays);
    size_t failures = 0, hits = 0, instanced = 0, ties = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const TraceHit& b = bvh[i];
        const TraceHit& f = brute[i];
        std::string why;
        if (b.disagree)
            why = "traceAny and traceClosest disagree";
        else if (b.hit != f.hit)
            why = std::string("BVH ") + (b.hit ? "hits" : "misses") + ", brute force " + (f.hit ? "hits" : "misses");
        else if (mustHit && !f.hit)
            why = "missed a closed mesh";
        else if (f.hit && std::bit_cast<uint32_t>(b.t) != std::bit_cast<uint32_t>(f.t))
            why = "t differs: BVH " + std::to_string(b.t) + ", brute force " + std::to_string(f.t);
        if (f.hit && why.empty()) {
            ++hits;
            if (f.instance != NO_INSTANCE) ++instanced;
            if (b.triangle != f.triangle || b.instance != f.instance) ++ties; // same t: equally right
        }
        if (!why.empty() && ++failures <= 8) {
            const GpuTestRay& r = rays[i];
            ADD_FAILURE() << what << ", ray " << i << ": " << why << "; origin (" << r.origin.x << ", " << r.origin.y
                          << ", " << r.origin.z << ") direction (" << r.direction.x << ", " << r.direction.y << ", "
                          << r.direction.z << ")";
        }
    }
    EXPECT_EQ(failures, 0u) << what << ": " << failures << " of " << rays.size() << " rays disagree";
    EXPECT_GT(instanced, hits / 4) << what << ": too few hits in instances for the test to mean much";
    EXPECT_LE(double(ties), tieShare * double(hits)) << what;
    std::printf(
        "[          ] %s: %zu rays, %zu hits (%zu in instances), %zu ties\n", what, rays.size(), hits, instanced, ties);
}

class InstancingTest : public GpuTest, public ::testing::WithParamInterface<bool> {};

INSTANTIATE_TEST_SUITE_P(NodeFormats, InstancingTest, ::testing::Values(false, true),
    [](const ::testing::TestParamInfo<bool>& info) { return info.param ? "Quantized" : "Float"; });

TEST_P(InstancingTest, TwoLevelTraversalMatchesBruteForceOverEveryPlacement) {
    const Scene scene = instancedScene();
    const Uploaded u = upload(scene, GetParam());
    ASSERT_EQ(u.flat.instances.size(), scene.instances.size());
    EXPECT_FALSE(u.flat.instanceNodes.empty());
    EXPECT_EQ(u.flat.quantizedNodes.empty(), !GetParam());
    std::mt19937 rng(2026);
    std::vector<GpuTestRay> rays;
    // Random rays through the cluster, some with a finite tMax.
    std::uniform_real_distribution<float> shortT(0.5f, 30.0f);
    for (int i = 0; i < 30000; ++i) {
        rays.push_back(makeRay(randomIn(rng, glm::vec3(-25.0f), glm::vec3(25.0f)), randomUnit(rng)));
        if (i % 5 == 0) rays.back().tMax = shortT(rng);
    }
    // Rays aimed at each placement's centre from random points, near ones and far ones (1e4).
    for (size_t k = 0; k < scene.instances.size(); ++k)
        for (int i = 0; i < 400; ++i) {
            const glm::vec3 target = placedCentre(scene, k) + randomIn(rng, glm::vec3(-1.5f), glm::vec3(1.5f));
            const glm::vec3 from = target + randomUnit(rng) * std::uniform_real_distribution<float>(2.0f, 40.0f)(rng);
            rays.push_back(makeRay(from, glm::normalize(target - from)));
        }
    expectTreesMatchBruteForce(u, rays, GetParam() ? "two levels, quantised" : "two levels, float");
}

// A closed icosphere under each kind of placement: rays from its placed centre outwards, and
// rays from outside at the placed vertices facing them, never slip through an edge or a vertex.
TEST_P(InstancingTest, PlacedClosedMeshStaysWatertight) {
    const glm::mat4 id(1.0f);
    const glm::mat4 rotated = glm::rotate(id, 0.7f, glm::normalize(glm::vec3(1, 2, 3)));
    const std::pair<const char*, glm::mat4> placements[] = {{"scaled by 1e-3", glm::scale(id, glm::vec3(1e-3f))},
        {"scaled by 1e3", glm::scale(id, glm::vec3(1e3f))},
        {"rotated and stretched", glm::scale(rotated, glm::vec3(3.0f, 0.5f, 1.0f))},
        {"mirrored", glm::scale(rotated, glm::vec3(1.0f, -1.0f, 1.0f))},
        {"moved by 1e4", glm::translate(id, glm::vec3(1e4f, -1e4f, 1e4f)) * rotated}};
    for (const auto& [name, placement] : placements) {
        Scene scene;
        scene.source = name;
        scene.materials.push_back(Material{});
        scene.sharedMeshes.push_back(SharedMesh{"ball", {makeIcosphere(3, glm::vec3(0.0f), 1.0f, 0)}});
        scene.instances.push_back(MeshInstance{"ball", 0, placement, std::nullopt, glm::vec3(0.0f)});
        const Uploaded u = upload(scene, GetParam());
        ASSERT_EQ(u.flat.instances.size(), 1u) << name;
        std::mt19937 rng(11);
        const glm::vec3 centre(placement[3]);
        std::vector<GpuTestRay> rays;
        for (int i = 0; i < 4000; ++i) rays.push_back(makeRay(centre, randomUnit(rng)));
        // Through the placed vertices, from 4 radii away along the placed normal (plus a tilt).
        const Mesh placed = placeMesh(scene.sharedMeshes[0].parts[0], placement);
        const float size = glm::length(glm::vec3(placement * glm::vec4(1, 0, 0, 0)));
        for (size_t v = 0; v < placed.positions.size(); ++v) {
            const glm::vec3 n = glm::normalize(placed.positions[v] - centre);
            const glm::vec3 from = placed.positions[v] + 4.0f * size * glm::normalize(n + 0.2f * randomUnit(rng));
            rays.push_back(makeRay(from, glm::normalize(placed.positions[v] - from)));
        }
        expectTreesMatchBruteForce(u, rays, name, true, 0.05);
    }
}

} // namespace
} // namespace pt::test
