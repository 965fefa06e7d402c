// Host tests for the binned SAH BVH builder: structural invariants, closest-hit traversal against
// brute force (including axis-aligned rays, origins on box planes, flat and duplicated geometry),
// determinism across thread counts, degenerate inputs and a SAH sanity check.
#include "accel/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

namespace {

using pt::Aabb;
using pt::Bvh;
using pt::BvhBuildOptions;
using pt::BvhNode;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint32_t kNoPrim = std::numeric_limits<uint32_t>::max();

struct Tri {
    glm::vec3 v0, v1, v2;
};

Aabb triBounds(const Tri& t) {
    Aabb b;
    b.grow(t.v0);
    b.grow(t.v1);
    b.grow(t.v2);
    return b;
}

std::vector<Aabb> boundsOf(const std::vector<Tri>& tris) {
    std::vector<Aabb> b(tris.size());
    for (size_t i = 0; i < tris.size(); ++i) b[i] = triBounds(tris[i]);
    return b;
}

// Small triangles (vertex offsets within +-size) with centres uniform in [0,1]^3.
std::vector<Tri> randomTris(size_t n, uint32_t seed, float size) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), o(-size, size);
    std::vector<Tri> tris(n);
    for (Tri& t : tris) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        t.v0 = c + glm::vec3(o(rng), o(rng), o(rng));
        t.v1 = c + glm::vec3(o(rng), o(rng), o(rng));
        t.v2 = c + glm::vec3(o(rng), o(rng), o(rng));
    }
    return tris;
}

bool sameBox(const glm::vec3& alo, const glm::vec3& ahi, const Aabb& b) { return alo == b.lo && ahi == b.hi; }

double nodeArea(const BvhNode& n) {
    const glm::dvec3 d = glm::dvec3(n.hi) - glm::dvec3(n.lo);
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// Same definition as documented for Bvh::sahCost.
double sahOf(const pt::BvhNodeArray& nodes, size_t primCount, const BvhBuildOptions& o) {
    double sum = 0.0;
    size_t interior = 0;
    for (const BvhNode& n : nodes) {
        if (n.count == 0) {
            sum += o.traversalCost * nodeArea(n);
            ++interior;
        } else {
            sum += o.intersectCost * double(n.count) * nodeArea(n);
        }
    }
    const double root = nodeArea(nodes[0]);
    return root > 0 ? sum / root : o.traversalCost * double(interior) + o.intersectCost * double(primCount);
}

// Checks every structural property of the tree; returns the number of leaves.
size_t checkStructure(const Bvh& bvh, const std::vector<Aabb>& prims, const BvhBuildOptions& opt) {
    const size_t n = prims.size();
    if (n == 0) {
        EXPECT_TRUE(bvh.nodes.empty());
        EXPECT_TRUE(bvh.primOrder.empty());
        return 0;
    }
    EXPECT_FALSE(bvh.nodes.empty());
    EXPECT_EQ(bvh.primOrder.size(), n);
    if (bvh.nodes.empty() || bvh.primOrder.size() != n) return 0;

    // primOrder is a permutation of [0, N).
    std::vector<uint8_t> seenPrim(n, 0);
    size_t dupPrims = 0;
    for (uint32_t p : bvh.primOrder) {
        EXPECT_LT(p, n);
        if (p < n && seenPrim[p]++) ++dupPrims;
    }
    EXPECT_EQ(dupPrims, 0u) << "primitive listed twice in primOrder";

    std::vector<uint8_t> covered(n, 0), visited(bvh.nodes.size(), 0);
    std::vector<std::pair<uint32_t, int>> stack{{0u, 0}};
    size_t leaves = 0, failures = 0;
    uint32_t nextPair = 1; // depth-first layout: children pairs in preorder of their parents
    int maxDepth = 0;
    const size_t maxLeaf = size_t(std::max(opt.maxLeafSize, 1));
    while (!stack.empty() && failures < 10) {
        const auto [idx, depth] = stack.back();
        stack.pop_back();
        if (visited[idx]++) {
            ADD_FAILURE() << "node " << idx << " reached twice";
            ++failures;
            continue;
        }
        const BvhNode& nd = bvh.nodes[idx];
        if (nd.count == 0) {
            const uint32_t l = nd.leftOrFirst;
            if (!(l > idx && size_t(l) + 1 < bvh.nodes.size())) {
                ADD_FAILURE() << "bad child index " << l << " at node " << idx;
                ++failures;
                continue;
            }
            if (l != nextPair) {
                ADD_FAILURE() << "node " << idx << ": children at " << l << ", depth-first order expects " << nextPair;
                ++failures;
            }
            nextPair = l + 2;
            Aabb u;
            u.grow(Aabb{bvh.nodes[l].lo, bvh.nodes[l].hi});
            u.grow(Aabb{bvh.nodes[l + 1].lo, bvh.nodes[l + 1].hi});
            if (!sameBox(nd.lo, nd.hi, u)) {
                ADD_FAILURE() << "interior node " << idx << " is not the tight union of its children";
                ++failures;
            }
            stack.push_back({l + 1, depth + 1});
            stack.push_back({l, depth + 1});
        } else {
            ++leaves;
            maxDepth = std::max(maxDepth, depth);
            if (nd.count > maxLeaf) {
                ADD_FAILURE() << "leaf " << idx << " has " << nd.count << " > maxLeafSize prims";
                ++failures;
            }
            if (size_t(nd.leftOrFirst) + nd.count > n) {
                ADD_FAILURE() << "leaf range out of bounds at node " << idx;
                ++failures;
                continue;
            }
            Aabb u;
            for (uint32_t i = nd.leftOrFirst; i < nd.leftOrFirst + nd.count; ++i) {
                if (covered[i]++) {
                    ADD_FAILURE() << "primOrder slot " << i << " in two leaves";
                    ++failures;
                }
                u.grow(prims[bvh.primOrder[i]]);
            }
            if (!sameBox(nd.lo, nd.hi, u)) {
                ADD_FAILURE() << "leaf " << idx << " is not the tight box of its primitives";
                ++failures;
            }
        }
    }
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), std::ptrdiff_t(n)) << "leaves do not cover [0,N)";
    EXPECT_EQ(std::count(visited.begin(), visited.end(), 1), std::ptrdiff_t(bvh.nodes.size())) << "unreachable nodes";
    EXPECT_EQ(bvh.nodes.size(), 2 * leaves - 1);
    EXPECT_EQ(bvh.maxDepth, maxDepth);
    EXPECT_NEAR(bvh.sahCost, sahOf(bvh.nodes, n, opt), 1e-9 * std::max(1.0, bvh.sahCost));
    return leaves;
}

// ---- CPU reference traversal ------------------------------------------------------------------

struct Ray {
    glm::vec3 o, d;
};

struct Hit {
    float t = kInf;
    uint32_t prim = kNoPrim;
};

// Möller-Trumbore without epsilons (det == 0 is the only rejection), accepting t > 0. Brute force
// and BVH traversal use this same function, so equal inputs give bit-equal t.
bool intersectTri(const Ray& r, const Tri& tri, float& t) {
    const glm::vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    const glm::vec3 p = glm::cross(r.d, e2);
    const float det = glm::dot(e1, p);
    if (det == 0.0f) return false;
    const float inv = 1.0f / det;
    const glm::vec3 s = r.o - tri.v0;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return false;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(r.d, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return false;
    t = glm::dot(e2, q) * inv;
    return t > 0.0f;
}

// Closest hit, ties on t broken towards the smaller primitive index (so the answer is unique).
void consider(const Ray& r, const std::vector<Tri>& tris, uint32_t prim, Hit& h) {
    float t;
    if (intersectTri(r, tris[prim], t) && (t < h.t || (t == h.t && prim < h.prim))) {
        h.t = t;
        h.prim = prim;
    }
}

Hit bruteForce(const Ray& r, const std::vector<Tri>& tris) {
    Hit h;
    for (uint32_t i = 0; i < tris.size(); ++i) consider(r, tris, i, h);
    return h;
}

// Slab test over [0, tMax]. invD = 1/d, so a zero component gives +-inf (-0 gives -inf). Entry
// and exit planes are chosen by the sign of invD, not by comparing the two t values: when the
// origin lies on a slab plane and d is +-0 on that axis, (plane - o) * inf is 0 * inf = NaN, and
// a comparison-based swap would then put the other plane's +-inf on the wrong side. Every
// comparison with NaN is false, so a NaN bound is simply ignored, which is right: the ray runs
// inside the (closed) slab. A ray parallel to and outside a slab gets t0 = +inf or t1 = -inf.
// The interval is compared with a small relative slack so that rounding differences between the
// box test and the triangle test cannot drop a hit that lies on a box face (the structure test
// separately checks that the boxes are exact).
bool slab(const BvhNode& n, const Ray& r, const glm::vec3& invD, float tMax, float& tNear) {
    float t0 = 0.0f, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        float tn = (n.lo[a] - r.o[a]) * invD[a];
        float tf = (n.hi[a] - r.o[a]) * invD[a];
        if (invD[a] < 0.0f) std::swap(tn, tf);
        if (tn > t0) t0 = tn;
        if (tf < t1) t1 = tf;
    }
    tNear = t0;
    return t0 <= t1 + 1e-5f * std::fabs(t1) + 1e-6f;
}

Hit traverse(const Bvh& bvh, const std::vector<Tri>& tris, const Ray& r, size_t* nodesVisited = nullptr) {
    Hit h;
    if (bvh.nodes.empty()) return h;
    const glm::vec3 invD = 1.0f / r.d;
    float tn;
    if (!slab(bvh.nodes[0], r, invD, kInf, tn)) return h;
    uint32_t stack[256];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const BvhNode& nd = bvh.nodes[stack[--sp]];
        if (nodesVisited) ++*nodesVisited;
        if (nd.count > 0) {
            for (uint32_t i = nd.leftOrFirst; i < nd.leftOrFirst + nd.count; ++i)
                consider(r, tris, bvh.primOrder[i], h);
            continue;
        }
        float ta, tb;
        const bool ha = slab(bvh.nodes[nd.leftOrFirst], r, invD, h.t, ta);
        const bool hb = slab(bvh.nodes[nd.leftOrFirst + 1], r, invD, h.t, tb);
        // Push the farther child first so the nearer one is visited first.
        if (ha && hb) {
            const bool aFirst = ta <= tb;
            stack[sp++] = nd.leftOrFirst + (aFirst ? 1 : 0);
            stack[sp++] = nd.leftOrFirst + (aFirst ? 0 : 1);
        } else if (ha) {
            stack[sp++] = nd.leftOrFirst;
        } else if (hb) {
            stack[sp++] = nd.leftOrFirst + 1;
        }
        if (sp > 250) {
            ADD_FAILURE() << "traversal stack overflow";
            return h;
        }
    }
    return h;
}

// Returns how many rays hit something; every ray must match brute force exactly. The brute force
// reference runs on all cores (it dominates the test time).
size_t expectSameHits(const Bvh& bvh, const std::vector<Tri>& tris, const std::vector<Ray>& rays) {
    std::vector<Hit> reference(rays.size());
    const size_t workers = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (size_t w = 0; w < workers; ++w)
        pool.emplace_back([&, w] {
            for (size_t i = w; i < rays.size(); i += workers) reference[i] = bruteForce(rays[i], tris);
        });
    for (std::thread& t : pool) t.join();

    size_t hits = 0, mismatches = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Hit a = traverse(bvh, tris, rays[i]);
        const Hit& b = reference[i];
        if (b.prim != kNoPrim) ++hits;
        if (a.prim != b.prim || !(a.t == b.t || (std::isinf(a.t) && std::isinf(b.t)))) {
            if (++mismatches <= 5)
                ADD_FAILURE() << "ray " << i << " o=(" << rays[i].o.x << "," << rays[i].o.y << "," << rays[i].o.z
                              << ") d=(" << rays[i].d.x << "," << rays[i].d.y << "," << rays[i].d.z << "): bvh prim "
                              << a.prim << " t " << a.t << ", brute prim " << b.prim << " t " << b.t;
        }
    }
    EXPECT_EQ(mismatches, 0u);
    return hits;
}

std::vector<Ray> randomRays(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), wide(-0.5f, 1.5f);
    std::vector<Ray> rays(n);
    for (Ray& r : rays) {
        r.o = glm::vec3(wide(rng), wide(rng), wide(rng));
        const glm::vec3 target(u(rng), u(rng), u(rng));
        r.d = target - r.o;
        if (glm::dot(r.d, r.d) == 0.0f) r.d = glm::vec3(0, 0, 1);
    }
    return rays;
}

// The 6 axis directions, written with signed zeros so that 1/d covers +inf and -inf.
const glm::vec3 kAxisDirs[] = {
    {1.0f, 0.0f, 0.0f},
    {-1.0f, -0.0f, 0.0f},
    {0.0f, 1.0f, -0.0f},
    {-0.0f, -1.0f, 0.0f},
    {0.0f, -0.0f, 1.0f},
    {-0.0f, 0.0f, -1.0f},
};

// ---- Tests ------------------------------------------------------------------------------------

TEST(Aabb, BasicOperations) {
    Aabb b;
    EXPECT_TRUE(b.empty());
    EXPECT_EQ(b.surfaceArea(), 0.0f);
    b.grow(glm::vec3(1, 2, 3));
    EXPECT_FALSE(b.empty());
    EXPECT_EQ(b.surfaceArea(), 0.0f); // a point
    b.grow(glm::vec3(2, 4, 6));
    EXPECT_EQ(b.surfaceArea(), 2.0f * (1 * 2 + 2 * 3 + 3 * 1));
    EXPECT_EQ(b.centroid(), glm::vec3(1.5f, 3.0f, 4.5f));
    Aabb c;
    c.grow(b);
    c.grow(Aabb{}); // growing by an empty box changes nothing
    EXPECT_EQ(c.lo, b.lo);
    EXPECT_EQ(c.hi, b.hi);
}

TEST(Bvh, ZeroPrimitives) {
    const Bvh bvh = pt::buildBvh({});
    EXPECT_TRUE(bvh.nodes.empty());
    EXPECT_TRUE(bvh.primOrder.empty());
    EXPECT_EQ(bvh.sahCost, 0.0);
    EXPECT_EQ(bvh.maxDepth, 0);
    EXPECT_EQ(traverse(bvh, {}, Ray{glm::vec3(0), glm::vec3(1, 0, 0)}).prim, kNoPrim);
}

TEST(Bvh, OnePrimitive) {
    const std::vector<Tri> tris{Tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
    const std::vector<Aabb> prims = boundsOf(tris);
    const Bvh bvh = pt::buildBvh(prims);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.nodes[0].count, 1u);
    EXPECT_EQ(bvh.nodes[0].leftOrFirst, 0u);
    EXPECT_EQ(bvh.primOrder, std::vector<uint32_t>{0});
    EXPECT_EQ(bvh.maxDepth, 0);
    EXPECT_DOUBLE_EQ(bvh.sahCost, 1.0);
    checkStructure(bvh, prims, {});
    const Hit h = traverse(bvh, tris, Ray{{0.25f, 0.25f, 1.0f}, {0, 0, -1}});
    EXPECT_EQ(h.prim, 0u);
    EXPECT_EQ(h.t, 1.0f);

    // A single point primitive: zero root area.
    const std::vector<Aabb> point{Aabb{glm::vec3(1), glm::vec3(1)}};
    const Bvh p = pt::buildBvh(point);
    ASSERT_EQ(p.nodes.size(), 1u);
    EXPECT_EQ(p.nodes[0].count, 1u);
    checkStructure(p, point, {});
}

TEST(Bvh, StructureForVariousOptions) {
    const std::vector<Aabb> prims = boundsOf(randomTris(20000, 1, 0.02f));
    for (int bins : {1, 2, 8, 16, 32, 128, 1000}) // 1 and 1000 are clamped to [2, 128]
        for (int maxLeaf : {1, 4, 8})
            for (float isect : {0.25f, 1.0f, 8.0f}) {
                SCOPED_TRACE("bins " + std::to_string(bins) + " maxLeaf " + std::to_string(maxLeaf) + " isect " +
                             std::to_string(isect));
                BvhBuildOptions o;
                o.bins = bins;
                o.maxLeafSize = maxLeaf;
                o.intersectCost = isect;
                o.threads = 2;
                const Bvh bvh = pt::buildBvh(prims, o);
                checkStructure(bvh, prims, o);
                EXPECT_LE(bvh.maxDepth, 64);
            }
}

TEST(Bvh, SmallCountsAllMaxLeafSizes) {
    for (size_t n = 1; n <= 40; ++n)
        for (int maxLeaf : {1, 2, 4, 7}) {
            const std::vector<Aabb> prims = boundsOf(randomTris(n, uint32_t(100 + n), 0.1f));
            BvhBuildOptions o;
            o.maxLeafSize = maxLeaf;
            const Bvh bvh = pt::buildBvh(prims, o);
            checkStructure(bvh, prims, o);
        }
}

TEST(Bvh, ClosestHitMatchesBruteForceOnRandomRays) {
    const std::vector<Tri> tris = randomTris(2000, 7, 0.05f);
    const Bvh bvh = pt::buildBvh(boundsOf(tris));
    const std::vector<Ray> rays = randomRays(100000, 8);
    const size_t hits = expectSameHits(bvh, tris, rays);
    EXPECT_GT(hits, rays.size() / 5) << "too few hits for the test to mean much";
}

TEST(Bvh, ClosestHitAxisAlignedRaysAndOriginsOnBoxPlanes) {
    const std::vector<Tri> tris = randomTris(2000, 11, 0.05f);
    const Bvh bvh = pt::buildBvh(boundsOf(tris));
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(-0.2f, 1.2f);
    std::uniform_int_distribution<size_t> pickNode(0, bvh.nodes.size() - 1);
    std::vector<Ray> rays;
    // Axis-aligned directions with random origins.
    for (int i = 0; i < 12000; ++i) rays.push_back(Ray{glm::vec3(u(rng), u(rng), u(rng)), kAxisDirs[i % 6]});
    // Origins with one, two or three coordinates exactly on a node's box planes; axis-aligned and
    // random directions. These make (plane - o) == 0, i.e. 0 * inf in the slab test.
    for (int i = 0; i < 24000; ++i) {
        const BvhNode& n = bvh.nodes[pickNode(rng)];
        glm::vec3 o(u(rng), u(rng), u(rng));
        const int mask = 1 + i % 7;
        for (int a = 0; a < 3; ++a)
            if (mask & (1 << a)) o[a] = (rng() & 1) ? n.lo[a] : n.hi[a];
        glm::vec3 d = (i % 2) ? kAxisDirs[(i / 2) % 6] : glm::vec3(u(rng), u(rng), u(rng)) - o;
        if (glm::dot(d, d) == 0.0f) d = glm::vec3(1, 0, 0);
        rays.push_back(Ray{o, d});
    }
    const size_t hits = expectSameHits(bvh, tris, rays);
    EXPECT_GT(hits, rays.size() / 20);
}

TEST(Bvh, FlatAxisAlignedGeometry) {
    // Every triangle lies in one of a few planes z = const, so every box (leaf and, for the
    // single-plane part, interior) has zero thickness.
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), o(-0.05f, 0.05f);
    const float planes[] = {0.25f, 0.5f, 0.75f};
    std::vector<Tri> tris(2000);
    for (size_t i = 0; i < tris.size(); ++i) {
        const float z = planes[i % 3];
        const glm::vec3 c(u(rng), u(rng), z);
        tris[i] =
            Tri{c + glm::vec3(o(rng), o(rng), 0), c + glm::vec3(o(rng), o(rng), 0), c + glm::vec3(o(rng), o(rng), 0)};
    }
    const std::vector<Aabb> prims = boundsOf(tris);
    BvhBuildOptions opt;
    const Bvh bvh = pt::buildBvh(prims, opt);
    checkStructure(bvh, prims, opt);

    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i) {
        const float z = (i % 4 == 3) ? u(rng) : planes[i % 3];
        const glm::vec3 org(u(rng), u(rng), z);
        switch (i % 3) {
        case 0: rays.push_back(Ray{org, kAxisDirs[i % 6]}); break; // in-plane or through planes
        case 1: rays.push_back(Ray{glm::vec3(org.x, org.y, (i & 1) ? 1.5f : -0.5f), kAxisDirs[(i & 1) ? 5 : 4]}); break;
        default: rays.push_back(Ray{org, glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)}); break;
        }
    }
    const size_t hits = expectSameHits(bvh, tris, rays);
    EXPECT_GT(hits, rays.size() / 10);

    // All in a single plane: every node box, root included, is flat.
    std::vector<Tri> one(tris.begin(), tris.end());
    for (Tri& t : one) t.v0.z = t.v1.z = t.v2.z = 0.5f;
    const std::vector<Aabb> onePrims = boundsOf(one);
    const Bvh flat = pt::buildBvh(onePrims, opt);
    checkStructure(flat, onePrims, opt);
    EXPECT_LE(flat.maxDepth, 40);
    for (const BvhNode& n : flat.nodes) EXPECT_EQ(n.lo.z, n.hi.z);
    expectSameHits(flat, one, rays);
}

TEST(Bvh, DegeneratePointAndLineBounds) {
    // Points on a line: every box has zero area, so all SAH costs tie; depth must stay logarithmic.
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Aabb> line(100000);
    for (Aabb& b : line) b.lo = b.hi = glm::vec3(u(rng), 0.5f, 0.5f);
    BvhBuildOptions opt;
    const Bvh a = pt::buildBvh(line, opt);
    checkStructure(a, line, opt);
    EXPECT_LE(a.maxDepth, 40);

    // Random points (boxes of leaves with one prim are points).
    std::vector<Aabb> pts(20000);
    for (Aabb& b : pts) b.lo = b.hi = glm::vec3(u(rng), u(rng), u(rng));
    const Bvh b = pt::buildBvh(pts, opt);
    checkStructure(b, pts, opt);
}

TEST(Bvh, ManyIdenticalTriangles) {
    // 2000 copies of one triangle plus random ones: all copies are hit at the same t, and the
    // traversal must still report the smallest index, i.e. reach every copy's leaf.
    std::vector<Tri> tris = randomTris(1000, 41, 0.05f);
    const Tri same{{0.3f, 0.3f, 0.5f}, {0.7f, 0.3f, 0.5f}, {0.3f, 0.7f, 0.5f}};
    tris.insert(tris.end(), 2000, same);
    std::mt19937 rng(42);
    std::shuffle(tris.begin(), tris.end(), rng);
    const std::vector<Aabb> prims = boundsOf(tris);
    BvhBuildOptions opt;
    const Bvh bvh = pt::buildBvh(prims, opt);
    checkStructure(bvh, prims, opt);

    std::uniform_real_distribution<float> u(0.3f, 0.5f);
    std::vector<Ray> rays;
    for (int i = 0; i < 5000; ++i) {
        const glm::vec3 p(u(rng), u(rng), 0.5f);
        rays.push_back(Ray{p + glm::vec3(0, 0, (i & 1) ? 1.0f : -1.0f), kAxisDirs[(i & 1) ? 5 : 4]});
    }
    expectSameHits(bvh, tris, rays);
}

TEST(Bvh, MillionIdenticalTriangles) {
    const Tri t{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<Aabb> prims(1000000, triBounds(t));
    BvhBuildOptions opt;
    opt.threads = 2;
    const Bvh bvh = pt::buildBvh(prims, opt);
    checkStructure(bvh, prims, opt);
    EXPECT_LE(bvh.maxDepth, 20); // halving: ceil(log2(1e6 / 4)) = 18
    opt.threads = 1;
    const Bvh one = pt::buildBvh(prims, opt);
    EXPECT_EQ(one.primOrder, bvh.primOrder);
    ASSERT_EQ(one.nodes.size(), bvh.nodes.size());
    EXPECT_EQ(std::memcmp(one.nodes.data(), bvh.nodes.data(), one.nodes.size() * sizeof(BvhNode)), 0);
}

TEST(Bvh, DeterministicAcrossThreadCounts) {
    // Big enough that the top phase bins in parallel and there are many subtree tasks.
    const std::vector<Aabb> prims = boundsOf(randomTris(300000, 51, 0.01f));
    BvhBuildOptions opt;
    opt.threads = 1;
    const Bvh ref = pt::buildBvh(prims, opt);
    checkStructure(ref, prims, opt);
    for (int threads : {2, 3, 4, 0}) {
        SCOPED_TRACE("threads " + std::to_string(threads));
        opt.threads = threads;
        const Bvh b = pt::buildBvh(prims, opt);
        EXPECT_EQ(b.primOrder, ref.primOrder);
        ASSERT_EQ(b.nodes.size(), ref.nodes.size());
        EXPECT_EQ(std::memcmp(b.nodes.data(), ref.nodes.data(), b.nodes.size() * sizeof(BvhNode)), 0);
        EXPECT_EQ(b.sahCost, ref.sahCost);
        EXPECT_EQ(b.maxDepth, ref.maxDepth);
    }
}

TEST(Bvh, BigLeavesAtTheTopLevels) {
    // Leaves bigger than the builder's task size are made by its top (level-by-level) phase:
    // here the root splits two far-apart clusters and each 10,000-primitive cluster is one leaf
    // (splitting costs at least traversalCost = 1, more than 10,000 * intersectCost).
    std::vector<Tri> tris = randomTris(20000, 81, 0.01f);
    for (size_t i = 0; i < tris.size() / 2; ++i) {
        tris[i].v0.x += 100.0f;
        tris[i].v1.x += 100.0f;
        tris[i].v2.x += 100.0f;
    }
    const std::vector<Aabb> prims = boundsOf(tris);
    BvhBuildOptions opt;
    opt.maxLeafSize = 100000;
    opt.intersectCost = 1.0f / 15000.0f;
    opt.threads = 1;
    const Bvh one = pt::buildBvh(prims, opt);
    checkStructure(one, prims, opt);
    ASSERT_EQ(one.nodes.size(), 3u);
    EXPECT_EQ(one.nodes[1].count, 10000u);
    opt.threads = 2;
    const Bvh two = pt::buildBvh(prims, opt);
    EXPECT_EQ(two.primOrder, one.primOrder);
    ASSERT_EQ(two.nodes.size(), one.nodes.size());
    EXPECT_EQ(std::memcmp(two.nodes.data(), one.nodes.data(), one.nodes.size() * sizeof(BvhNode)), 0);
    // And the whole scene as one leaf when that is cheapest.
    opt.intersectCost = 1e-6f;
    const Bvh single = pt::buildBvh(prims, opt);
    checkStructure(single, prims, opt);
    EXPECT_EQ(single.nodes.size(), 1u);
}

// Reference object-median build (split the centroid range at the median of the widest axis).
void medianBuild(pt::BvhNodeArray& nodes, std::vector<uint32_t>& order, const std::vector<Aabb>& prims, uint32_t slot,
    uint32_t begin, uint32_t end, int maxLeaf) {
    Aabb b, cb;
    for (uint32_t i = begin; i < end; ++i) {
        b.grow(prims[order[i]]);
        cb.grow(prims[order[i]].centroid());
    }
    nodes[slot].lo = b.lo;
    nodes[slot].hi = b.hi;
    if (end - begin <= uint32_t(maxLeaf)) {
        nodes[slot].leftOrFirst = begin;
        nodes[slot].count = end - begin;
        return;
    }
    const glm::vec3 e = cb.hi - cb.lo;
    const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
        [&](uint32_t a, uint32_t c) { return prims[a].centroid()[axis] < prims[c].centroid()[axis]; });
    const uint32_t left = uint32_t(nodes.size());
    nodes.push_back({});
    nodes.push_back({});
    nodes[slot].leftOrFirst = left;
    nodes[slot].count = 0;
    medianBuild(nodes, order, prims, left, begin, mid, maxLeaf);
    medianBuild(nodes, order, prims, left + 1, mid, end, maxLeaf);
}

TEST(Bvh, SahNoWorseThanMedianSplit) {
    // Uniform small triangles, and a clustered scene with a few big triangles where SAH matters more.
    std::vector<Tri> uniform = randomTris(50000, 61, 0.01f);
    std::vector<Tri> clustered = randomTris(45000, 62, 0.002f);
    for (Tri& t : clustered) {
        t.v0 *= 0.1f;
        t.v1 *= 0.1f;
        t.v2 *= 0.1f;
    }
    const std::vector<Tri> big = randomTris(5000, 63, 0.3f);
    clustered.insert(clustered.end(), big.begin(), big.end());
    for (const auto* tris : {&uniform, &clustered}) {
        const std::vector<Aabb> prims = boundsOf(*tris);
        BvhBuildOptions opt;
        const Bvh sah = pt::buildBvh(prims, opt);
        Bvh med;
        med.nodes.resize(1);
        med.primOrder.resize(prims.size());
        std::iota(med.primOrder.begin(), med.primOrder.end(), 0u);
        medianBuild(med.nodes, med.primOrder, prims, 0, 0, uint32_t(prims.size()), opt.maxLeafSize);
        const double medCost = sahOf(med.nodes, prims.size(), opt);
        std::printf("  [sah] %zu prims: binned SAH %.2f, median split %.2f\n", prims.size(), sah.sahCost, medCost);
        EXPECT_LE(sah.sahCost, medCost);
    }
}

TEST(Bvh, BuildSpeedMillionRandomTriangles) {
    // Timing print only (no assertion: the machine may be shared). Best of two builds.
    const std::vector<Aabb> prims = boundsOf(randomTris(1000000, 71, 0.01f));
    BvhBuildOptions opt;
    for (int threads : {1, 2}) {
        opt.threads = threads;
        Bvh bvh = pt::buildBvh(prims, opt);
        double best = bvh.buildSeconds;
        if (threads == 2) {
            bvh = pt::buildBvh(prims, opt);
            best = std::min(best, bvh.buildSeconds);
            checkStructure(bvh, prims, opt);
        }
        std::printf(
            "  [speed] 1M random triangles, threads=%d: %.1f ms, %.2f M prims/s, SAH %.2f, %zu nodes, depth %d\n",
            threads, best * 1e3, 1e-6 * double(prims.size()) / best, bvh.sahCost, bvh.nodes.size(), bvh.maxDepth);
    }
}

} // namespace
