// Device tests of the production BVH traversal (shaders/geometry/traverse.glsl): every query is
// run twice through shaders/tests/test_kernels.comp, once through the BVH and once against all
// triangles with the same watertight intersector, and the answers must be identical. Because
// both sides share the intersector, any difference is the traversal's fault (a box culled too
// eagerly, a wrong child order, a stack overflow, tMax mishandled), not floating-point noise.
#include "accel/quantized_bvh.h"
#include "support/gpu_test_support.h"
#include "support/test_rays.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace {

using pt::gpu::GpuTestRay;
using pt::test::makeRay;
using pt::test::randomIn;
using pt::test::randomUnit;

// A scene flattened (triangles in BVH order) and uploaded for the test kernel.
struct TestScene {
    pt::FlatScene flat;
    std::unique_ptr<pt::GpuScene> gpu;
};

// Whether the trees of the current test are stored quantised (the suite runs once with each
// node format: TraversalTest's parameter).
bool quantizedTrees = false;

TestScene uploadMeshes(std::vector<pt::Mesh> meshes) {
    pt::Scene scene;
    scene.source = "traversal test";
    scene.materials.push_back(pt::Material{});
    scene.meshes = std::move(meshes);
    TestScene s;
    pt::BvhBuildOptions options;
    options.quantizeOverBytes = quantizedTrees ? 0 : std::numeric_limits<size_t>::max();
    s.flat = pt::flattenScene(scene, options);
    EXPECT_EQ(s.flat.quantizedNodes.empty(), !quantizedTrees);
    s.gpu = std::make_unique<pt::GpuScene>(pt::test::sharedContext(), s.flat, pt::gpu::GpuSceneParams{}, 0);
    return s;
}

// Directions with components exactly zero (both signs of zero and of the others): the slab
// test divides by them and the shear picks its axes from them.
std::vector<glm::vec3> axisAlignedDirections() {
    std::vector<glm::vec3> dirs;
    for (int axis = 0; axis < 3; ++axis)
        for (float s : {1.0f, -1.0f}) {
            glm::vec3 d(0.0f);
            d[axis] = s;
            dirs.push_back(d);
            glm::vec3 negZero(-0.0f);
            negZero[axis] = s;
            dirs.push_back(negZero);
        }
    // One zero component: diagonals within the coordinate planes.
    for (int zero = 0; zero < 3; ++zero)
        for (float a : {1.0f, -1.0f})
            for (float b : {1.0f, -1.0f}) {
                glm::vec3 d(0.0f);
                d[(zero + 1) % 3] = a * 0.70710678f;
                d[(zero + 2) % 3] = b * 0.70710678f;
                dirs.push_back(d);
            }
    return dirs;
}

struct TraceResult {
    bool hit = false;
    bool anyClosestDisagree = false; // the kernel's -2: traceAny and traceClosest disagreed
    float t = 0.0f;
    uint32_t triangle = 0;
    glm::vec2 bary{0.0f};
};

std::vector<TraceResult> trace(uint32_t mode, const TestScene& scene, const std::vector<GpuTestRay>& rays) {
    std::vector<glm::vec4> out = pt::test::runTestKernel(
        mode, static_cast<uint32_t>(rays.size()), scene.gpu.get(), std::as_bytes(std::span<const GpuTestRay>(rays)));
    std::vector<TraceResult> results(out.size());
    for (size_t i = 0; i < out.size(); ++i) {
        TraceResult& r = results[i];
        r.anyClosestDisagree = out[i].x == -2.0f;
        r.hit = out[i].x >= 0.0f;
        if (r.hit) {
            r.t = out[i].x;
            r.triangle = std::bit_cast<uint32_t>(out[i].y);
            r.bary = glm::vec2(out[i].z, out[i].w);
        }
    }
    return results;
}

std::string str(float x) {
    std::ostringstream s;
    s.precision(9);
    s << x;
    return s.str();
}

std::string describe(const GpuTestRay& r) {
    std::ostringstream s;
    s.precision(9);
    s << "origin (" << r.origin.x << ", " << r.origin.y << ", " << r.origin.z << ") direction (" << r.direction.x
      << ", " << r.direction.y << ", " << r.direction.z << ") tMax " << r.tMax;
    return s.str();
}

// Whether `result`'s barycentrics put its hit point on the ray at its t, inside its triangle.
bool liesOnItsTriangle(const pt::FlatScene& flat, const GpuTestRay& ray, const TraceResult& result) {
    if (result.triangle >= flat.triangles.size()) return false;
    const pt::gpu::GpuTriangle& tri = flat.triangles[result.triangle];
    const glm::dvec3 p0(tri.p0), p1(tri.p1), p2(tri.p2);
    const glm::dvec3 onTriangle = p0 + double(result.bary.x) * (p1 - p0) + double(result.bary.y) * (p2 - p0);
    const glm::dvec3 onRay = glm::dvec3(ray.origin) + double(result.t) * glm::dvec3(ray.direction);
    const double scale = 1.0 + glm::length(glm::dvec3(ray.origin)) + glm::length(onRay);
    const float b0 = 1.0f - result.bary.x - result.bary.y;
    const float eps = 1e-4f;
    return glm::length(onTriangle - onRay) < 1e-4 * scale && result.bary.x >= -eps && result.bary.y >= -eps &&
           b0 >= -eps;
}

// A BVH answer naming a different triangle than brute force at the same t is still right if it
// is a genuine tie: brute force keeps the lowest index among equal t, so the BVH's must be
// higher, and its hit must lie on its triangle.
bool isGenuineTie(const pt::FlatScene& flat, const GpuTestRay& ray, const TraceResult& bvh, const TraceResult& brute) {
    return bvh.triangle > brute.triangle && liesOnItsTriangle(flat, ray, bvh);
}

// A BVH answer farther than brute force's by no more than the intersector's rounding is a tie
// too: two triangles meeting the ray at the same point (coplanar faces along a shared edge)
// whose computed t differ in their last bits, where the traversal reached the other one first
// and the box of brute force's triangle was (rightly) not entered beyond the found t. A culled
// closer surface lies farther off than this by orders of magnitude.
bool isRoundingTie(const pt::FlatScene& flat, const GpuTestRay& ray, const TraceResult& bvh, const TraceResult& brute) {
    if (!(bvh.t > brute.t)) return false;
    const glm::dvec3 onRay = glm::dvec3(ray.origin) + double(bvh.t) * glm::dvec3(ray.direction);
    const double scale = 1.0 + glm::length(glm::dvec3(ray.origin)) + glm::length(onRay);
    const bool withinRounding = double(bvh.t) - double(brute.t) <= 4.0 * std::numeric_limits<float>::epsilon() * scale;
    return withinRounding && liesOnItsTriangle(flat, ray, bvh);
}

struct Comparison {
    std::vector<TraceResult> bvh, brute;
    size_t hits = 0, ties = 0;
};

// Runs `rays` through the BVH and brute force and fails (with the first few rays named) on any
// disagreement; with `mustHit`, also on any miss.
Comparison expectBvhMatchesBruteForce(
    const TestScene& scene, const std::vector<GpuTestRay>& rays, const char* what, bool mustHit = false) {
    Comparison c;
    c.bvh = trace(TEST_MODE_TRACE_BVH, scene, rays);
    c.brute = trace(TEST_MODE_TRACE_BRUTE_FORCE, scene, rays);
    size_t failures = 0;
    auto fail = [&](size_t i, const std::string& why) {
        if (++failures <= 8) ADD_FAILURE() << what << ", ray " << i << ": " << why << "; " << describe(rays[i]);
    };
    for (size_t i = 0; i < rays.size(); ++i) {
        const TraceResult& b = c.bvh[i];
        const TraceResult& f = c.brute[i];
        if (b.anyClosestDisagree) {
            fail(i, "traceAny and traceClosest disagree");
            continue;
        }
        if (b.hit != f.hit) {
            fail(i, std::string("BVH ") + (b.hit ? "hits" : "misses") + ", brute force " + (f.hit ? "hits" : "misses") +
                        " (t " + str(b.hit ? b.t : f.t) + ")");
            continue;
        }
        if (mustHit && !f.hit) {
            fail(i, "missed a closed mesh (not watertight)");
            continue;
        }
        if (!f.hit) continue;
        ++c.hits;
        if (std::bit_cast<uint32_t>(b.t) != std::bit_cast<uint32_t>(f.t)) {
            if (isRoundingTie(scene.flat, rays[i], b, f)) {
                ++c.ties;
                continue;
            }
            fail(i, "t differs: BVH " + str(b.t) + " (triangle " + std::to_string(b.triangle) + "), brute force " +
                        str(f.t) + " (triangle " + std::to_string(f.triangle) + ")");
        } else if (b.triangle != f.triangle) {
            if (isGenuineTie(scene.flat, rays[i], b, f))
                ++c.ties;
            else
                fail(i, "triangle differs: BVH " + std::to_string(b.triangle) + ", brute force " +
                            std::to_string(f.triangle));
        }
    }
    EXPECT_EQ(failures, 0u) << what << ": " << failures << " of " << rays.size() << " rays disagree";
    return c;
}

// ---- Scenes ----

// Small random triangles (edges up to ~2) with centres in [-10, 10]^3: overlapping, any orientation.
pt::Mesh randomSoup(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> offset(-1.0f, 1.0f);
    pt::Mesh m;
    m.name = "soup";
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 centre = randomIn(rng, glm::vec3(-10.0f), glm::vec3(10.0f));
        const uint32_t base = static_cast<uint32_t>(m.positions.size());
        for (int k = 0; k < 3; ++k) m.positions.push_back(centre + glm::vec3(offset(rng), offset(rng), offset(rng)));
        m.triangles.push_back({base, base + 1, base + 2});
    }
    return m;
}

// A grid of n x n unit quads in the plane z = 0 centred on the origin: every triangle, and so
// every BVH box, is flat in z, and the quads share edges and vertices.
pt::Mesh flatGrid(int n) {
    pt::Mesh m;
    m.name = "grid";
    const float half = 0.5f * float(n);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.push_back({float(i) - half, float(j) - half, 0.0f});
    auto at = [&](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

// A closed axis-aligned box, 12 outward-facing triangles.
pt::Mesh box(glm::vec3 lo, glm::vec3 hi) {
    pt::Mesh m;
    m.name = "box";
    for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3}, {0, 4, 6},
        {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    return m;
}

// ---- Ray sets ----

std::vector<GpuTestRay> randomRays(size_t count, std::mt19937& rng, glm::vec3 lo, glm::vec3 hi) {
    std::vector<GpuTestRay> rays;
    for (size_t i = 0; i < count; ++i) rays.push_back(makeRay(randomIn(rng, lo, hi), randomUnit(rng)));
    return rays;
}

std::vector<GpuTestRay> axisAlignedRays(size_t perDirection, std::mt19937& rng, glm::vec3 lo, glm::vec3 hi) {
    std::vector<GpuTestRay> rays;
    for (glm::vec3 d : axisAlignedDirections())
        for (size_t i = 0; i < perDirection; ++i) rays.push_back(makeRay(randomIn(rng, lo, hi), d));
    return rays;
}

// Origins exactly on a plane of a BVH node's box (the rest of the origin inside, or a little
// outside, the box), going in random and in axis-aligned directions. A direction component of
// zero with the origin on that slab makes the slab test compute 0 * (1/0).
std::vector<GpuTestRay> nodePlaneRays(const pt::FlatScene& flat, size_t count, std::mt19937& rng) {
    std::vector<GpuTestRay> rays;
    std::uniform_int_distribution<size_t> pickNode(0, std::max(flat.nodes.size(), flat.quantizedNodes.size()) - 1);
    std::uniform_int_distribution<int> pickAxis(0, 2), pickSide(0, 1);
    const std::vector<glm::vec3> axisDirs = axisAlignedDirections();
    std::uniform_int_distribution<size_t> pickDir(0, axisDirs.size() - 1);
    for (size_t i = 0; i < count; ++i) {
        // A child box of a random wide node as the kernel decodes it (every box the traversal
        // tests is one of these).
        const pt::gpu::GpuBvh4Node wide =
            flat.nodes.empty() ? pt::decodeWideNode(flat.quantizedNodes[pickNode(rng)]) : flat.nodes[pickNode(rng)];
        int slot = int(rng() % 4);
        while (wide.child[slot] == BVH4_EMPTY) slot = (slot + 1) % 4;
        struct {
            glm::vec3 lo, hi;
        } node{{wide.loX[slot], wide.loY[slot], wide.loZ[slot]}, {wide.hiX[slot], wide.hiY[slot], wide.hiZ[slot]}};
        const glm::vec3 margin = 0.1f * (node.hi - node.lo) + 1e-3f;
        glm::vec3 origin = randomIn(rng, node.lo - margin, node.hi + margin);
        const int axis = pickAxis(rng);
        origin[axis] = pickSide(rng) ? node.hi[axis] : node.lo[axis];
        // Pin a second coordinate too now and then: origins on box edges.
        if (i % 4 == 0) origin[(axis + 1) % 3] = pickSide(rng) ? node.hi[(axis + 1) % 3] : node.lo[(axis + 1) % 3];
        rays.push_back(makeRay(origin, i % 2 ? randomUnit(rng) : axisDirs[pickDir(rng)]));
    }
    return rays;
}

// Axis-aligned rays through every vertex of `flat`'s triangles exactly (only one coordinate of
// the origin differs from the vertex's), from both sides: shared vertices and, on axis-aligned
// faces, shared edges.
std::vector<GpuTestRay> raysThroughVertices(const pt::FlatScene& flat, float distance) {
    std::set<std::tuple<float, float, float>> seen;
    std::vector<GpuTestRay> rays;
    for (const pt::gpu::GpuTriangle& tri : flat.triangles)
        for (glm::vec3 v : {tri.p0, tri.p1, tri.p2}) {
            if (!seen.insert({v.x, v.y, v.z}).second) continue;
            for (int axis = 0; axis < 3; ++axis)
                for (float s : {1.0f, -1.0f}) {
                    glm::vec3 origin = v, dir(0.0f);
                    origin[axis] += s * distance;
                    dir[axis] = -s;
                    rays.push_back(makeRay(origin, dir));
                }
        }
    return rays;
}

std::vector<GpuTestRay> concat(std::vector<std::vector<GpuTestRay>> parts) {
    std::vector<GpuTestRay> all;
    for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    return all;
}

// Every traversal test runs with float nodes and with quantised ones (GpuBvh4QNode), each read
// through buffer addresses and through texel buffers (TEXEL_LOADS).
class TraversalTest : public pt::test::GpuTest, public ::testing::WithParamInterface<std::tuple<bool, bool>> {
protected:
    void SetUp() override {
        pt::test::GpuTest::SetUp();
        quantizedTrees = std::get<0>(GetParam());
        pt::test::setTestKernelTexelLoads(std::get<1>(GetParam()));
    }
    void TearDown() override {
        pt::test::setTestKernelTexelLoads(false);
        pt::test::GpuTest::TearDown();
    }
};

INSTANTIATE_TEST_SUITE_P(NodeFormats, TraversalTest, ::testing::Combine(::testing::Bool(), ::testing::Bool()),
    [](const ::testing::TestParamInfo<std::tuple<bool, bool>>& info) {
        return std::string(std::get<0>(info.param) ? "Quantized" : "Float") +
               (std::get<1>(info.param) ? "Texels" : "Addresses");
    });

TEST_P(TraversalTest, RandomRaysAgainstTriangleSoupMatchBruteForce) {
    const TestScene scene = uploadMeshes({randomSoup(3000, 7)});
    ASSERT_EQ(scene.flat.triangles.size(), 3000u);
    std::mt19937 rng(12345);
    // Origins both inside the soup and outside it; a few finite tMax values among the rays.
    std::vector<GpuTestRay> rays = randomRays(110000, rng, glm::vec3(-14.0f), glm::vec3(14.0f));
    std::uniform_real_distribution<float> shortT(0.5f, 20.0f);
    for (size_t i = 0; i < rays.size(); i += 5) rays[i].tMax = shortT(rng);
    const Comparison c = expectBvhMatchesBruteForce(scene, rays, "random rays / soup");
    // The test only means something if a good share of rays hit.
    EXPECT_GT(c.hits, rays.size() / 4);
    std::printf("[          ] %zu rays, %zu hits, %zu ties, %zu wide BVH nodes, depth %d (binary %d)\n", rays.size(),
        c.hits, c.ties, scene.flat.nodes.size(), scene.flat.wideBvhDepth, scene.flat.bvhDepth);
}

// The same soup moved far out and shrunk (a box of 2e-3 at 3e4, where a float's step is 2e-3 /
// 1000): quantised nodes there have coarse steps and origins far from the rays' (the kernel's
// folded decode, shaders/geometry/traverse.glsl), and both formats must still find every hit.
TEST_P(TraversalTest, FarSmallSoupMatchesBruteForce) {
    pt::Mesh soup = randomSoup(3000, 21);
    const glm::vec3 far(3e4f, -3e4f, 1e4f);
    for (glm::vec3& p : soup.positions) p = far + p * 1e-4f;
    const TestScene scene = uploadMeshes({soup});
    std::mt19937 rng(77);
    std::vector<GpuTestRay> rays = randomRays(40000, rng, far - glm::vec3(1.4e-3f), far + glm::vec3(1.4e-3f));
    const std::vector<GpuTestRay> planes = nodePlaneRays(scene.flat, 20000, rng);
    rays.insert(rays.end(), planes.begin(), planes.end());
    const Comparison c = expectBvhMatchesBruteForce(scene, rays, "random and node-plane rays / far small soup");
    EXPECT_GT(c.hits, rays.size() / 8);
}

TEST_P(TraversalTest, AxisAlignedRaysAndOriginsOnNodePlanesMatchBruteForce) {
    const TestScene scene = uploadMeshes({randomSoup(2000, 99)});
    std::mt19937 rng(2024);
    const std::vector<GpuTestRay> rays = concat(
        {axisAlignedRays(1000, rng, glm::vec3(-12.0f), glm::vec3(12.0f)), nodePlaneRays(scene.flat, 20000, rng)});
    const Comparison c = expectBvhMatchesBruteForce(scene, rays, "axis-aligned / node-plane rays, soup");
    EXPECT_GT(c.hits, rays.size() / 10);
}

TEST_P(TraversalTest, FlatGridInPlaneZeroMatchesBruteForce) {
    const TestScene scene = uploadMeshes({flatGrid(24)});
    std::vector<pt::gpu::GpuBvh4Node> nodes = scene.flat.nodes;
    for (const pt::gpu::GpuBvh4QNode& q : scene.flat.quantizedNodes) nodes.push_back(pt::decodeWideNode(q));
    for (const pt::gpu::GpuBvh4Node& n : nodes) {
        for (int slot = 0; slot < 4; ++slot) {
            if (n.child[slot] == BVH4_EMPTY) continue;
            ASSERT_EQ(n.loZ[slot], 0.0f);
            ASSERT_EQ(n.hiZ[slot], 0.0f);
        }
    }
    std::mt19937 rng(31);
    std::vector<GpuTestRay> rays =
        concat({randomRays(15000, rng, glm::vec3(-14.0f, -14.0f, -5.0f), glm::vec3(14.0f, 14.0f, 5.0f)),
            axisAlignedRays(500, rng, glm::vec3(-14.0f, -14.0f, -3.0f), glm::vec3(14.0f, 14.0f, 3.0f)),
            nodePlaneRays(scene.flat, 10000, rng), raysThroughVertices(scene.flat, 4.0f)});
    // Rays lying in the plane itself, and rays grazing it.
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 o = randomIn(rng, glm::vec3(-14.0f, -14.0f, 0.0f), glm::vec3(14.0f, 14.0f, 0.0f));
        glm::vec3 d = randomUnit(rng);
        d.z = i % 2 ? 0.0f : d.z * 1e-4f;
        rays.push_back(makeRay(o, glm::normalize(d)));
    }
    const Comparison c = expectBvhMatchesBruteForce(scene, rays, "flat grid z = 0");
    EXPECT_GT(c.hits, rays.size() / 5);
}

// The smallest case of a ray lying in the plane of a BVH box face: one quad, whose box is flat
// in z, and rays with direction x exactly 0 running down through its edges x = 0 and x = 1.
// Both edges belong to the quad (the intersector is edge-inclusive), so each ray must hit,
// whichever face of the box (lo or hi) its origin lies on.
TEST_P(TraversalTest, RaysInTheFacePlanesOfABoxAreNotCulled) {
    const TestScene scene =
        uploadMeshes({pt::test::makeQuad(glm::vec3(0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0)});
    std::vector<GpuTestRay> rays;
    for (float x : {0.0f, 1.0f})
        for (float y : {0.25f, 0.5f, 0.75f}) {
            rays.push_back(makeRay({x, y, 1.0f}, {0.0f, 0.0f, -1.0f}));                    // straight down the edge
            rays.push_back(makeRay({x, y - 0.5f, 1.0f}, {0.0f, 0.4472136f, -0.8944272f})); // slanted within x = const
        }
    expectBvhMatchesBruteForce(
        scene, rays, "rays in the planes x = lo.x, x = hi.x of the quad's box", /*mustHit=*/true);
}

TEST_P(TraversalTest, AxisAlignedBoxesMatchBruteForce) {
    // A 3 x 3 x 3 lattice of closed boxes; neighbours along x touch (shared face planes), the
    // rest are separated by gaps, so node boxes and triangles share planes everywhere.
    std::vector<pt::Mesh> boxes;
    std::mt19937 sizes(5);
    std::uniform_real_distribution<float> extent(0.5f, 1.5f);
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                const glm::vec3 lo(2.0f * float(i), 3.0f * float(j), 3.0f * float(k));
                boxes.push_back(box(lo, lo + glm::vec3(2.0f, extent(sizes), extent(sizes))));
            }
    const TestScene scene = uploadMeshes(std::move(boxes));
    std::mt19937 rng(77);
    const std::vector<GpuTestRay> rays = concat({randomRays(15000, rng, glm::vec3(-3.0f), glm::vec3(10.0f)),
        axisAlignedRays(800, rng, glm::vec3(-1.0f), glm::vec3(7.0f, 9.0f, 9.0f)), nodePlaneRays(scene.flat, 15000, rng),
        raysThroughVertices(scene.flat, 5.0f)});
    const Comparison c = expectBvhMatchesBruteForce(scene, rays, "axis-aligned boxes");
    EXPECT_GT(c.hits, rays.size() / 4);
}

// Rays aimed exactly at the vertices and edge midpoints of a closed icosphere must all hit it
// (watertightness: no ray slips between triangles sharing an edge or a vertex), and the BVH must
// agree with brute force.
TEST_P(TraversalTest, IcosphereVerticesAndEdgesAreWatertight) {
    const glm::vec3 centre(0.3f, -0.2f, 0.1f);
    const float radius = 1.5f;
    const pt::Mesh sphere = pt::test::makeIcosphere(3, centre, radius, 0);
    const TestScene scene = uploadMeshes({sphere});
    ASSERT_EQ(scene.flat.triangles.size(), 1280u);

    std::vector<glm::vec3> targets = sphere.positions;
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (glm::uvec3 t : sphere.triangles)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    ASSERT_EQ(edges.size(), 1920u);
    for (auto [a, b] : edges) targets.push_back(0.5f * (sphere.positions[a] + sphere.positions[b]));

    std::mt19937 rng(4242);
    std::vector<GpuTestRay> rays;
    for (const glm::vec3& target : targets) {
        const glm::vec3 outward = glm::normalize(target - centre);
        // From random points outside that see the target from its front (not grazing).
        for (int k = 0; k < 3;) {
            const glm::vec3 origin = centre + radius * (2.0f + 2.0f * float(k)) * randomUnit(rng);
            const glm::vec3 toTarget = target - origin;
            if (glm::dot(-toTarget, outward) < 0.3f * glm::length(toTarget)) continue;
            // Unnormalised direction: the ray reaches the target at t = 1 (up to rounding).
            rays.push_back(makeRay(origin, k == 1 ? glm::normalize(toTarget) : toTarget));
            ++k;
        }
        // Axis-aligned through the target exactly: only one origin coordinate differs from it.
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (std::abs(outward[a]) > std::abs(outward[axis])) axis = a;
        const float s = outward[axis] > 0.0f ? 1.0f : -1.0f;
        glm::vec3 origin = target, dir(0.0f);
        origin[axis] += s * 3.0f * radius;
        dir[axis] = -s;
        rays.push_back(makeRay(origin, dir));
    }
    const Comparison c = expectBvhMatchesBruteForce(scene, rays, "icosphere vertices and edges", /*mustHit=*/true);
    // Every target is visible from its ray's origin, so the first hit is at the target itself.
    size_t farFromTarget = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (!c.brute[i].hit) continue;
        const size_t target = i / 4;
        const glm::vec3 p = rays[i].origin + c.brute[i].t * rays[i].direction;
        if (glm::length(p - targets[target]) > 1e-4f * radius && ++farFromTarget <= 5)
            ADD_FAILURE() << "ray " << i << " hits " << glm::length(p - targets[target]) << " away from its target";
    }
    EXPECT_EQ(farFromTarget, 0u);
}

// A ray whose tMax ends before its first hit must miss in both traversals (hits count only in
// (0, tMax), open at tMax), and one whose tMax is a little past the hit must find the same hit.
TEST_P(TraversalTest, TMaxIsRespected) {
    const TestScene scene = uploadMeshes({randomSoup(2000, 3)});
    std::mt19937 rng(8);
    const std::vector<GpuTestRay> probe = randomRays(20000, rng, glm::vec3(-12.0f), glm::vec3(12.0f));
    const std::vector<TraceResult> first = trace(TEST_MODE_TRACE_BRUTE_FORCE, scene, probe);
    std::vector<GpuTestRay> shortRays, longRays;
    std::vector<float> hitT;
    for (size_t i = 0; i < probe.size(); ++i) {
        if (!first[i].hit) continue;
        const float t = first[i].t;
        for (float tMax : {0.25f * t, 0.999f * t, t})
            shortRays.push_back(makeRay(probe[i].origin, probe[i].direction, tMax));
        longRays.push_back(makeRay(probe[i].origin, probe[i].direction, 1.001f * t));
        hitT.push_back(t);
    }
    ASSERT_GT(hitT.size(), 5000u);
    const Comparison shortC = expectBvhMatchesBruteForce(scene, shortRays, "tMax before the first hit");
    EXPECT_EQ(shortC.hits, 0u) << "hits at or beyond tMax were reported";
    const Comparison longC = expectBvhMatchesBruteForce(scene, longRays, "tMax just past the first hit");
    size_t wrong = 0;
    for (size_t i = 0; i < longRays.size(); ++i)
        if (!longC.bvh[i].hit || longC.bvh[i].t != hitT[i]) ++wrong;
    EXPECT_EQ(wrong, 0u) << "a tMax just past the hit changed the closest hit";
}

} // namespace
