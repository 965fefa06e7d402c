// Stack-based traversal of the four-wide BVHs (GpuBvh4Node, src/accel/wide_bvh.cpp): closest
// hit for path segments, any hit for shadow rays. A node's four child boxes are tested
// together, the children hit are visited nearest first and the others pushed. Triangles are in
// the world tree or in instanced meshes' trees, reached through the tree over the instances
// (two levels: the ray goes into each instance's object space at its leaf); spheres have a tree
// of their own.
#ifndef PT_GEOMETRY_TRAVERSE_GLSL
#define PT_GEOMETRY_TRAVERSE_GLSL
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_vote : require
#include "common/buffers.glsl"
#include "common/math.glsl"
#include "geometry/triangle.glsl"
#include "geometry/sphere.glsl"
#include "shared/features.glsl"
#include "textures/alpha.glsl"
#include "geometry/motion.glsl"
#include "geometry/instance.glsl"

// Slab tests round in both directions; growing the far distance by 1 + 2 gamma(3) makes them
// conservative (Ize, "Robust BVH Ray Traversal", JCGT 2013), so a triangle lying on a box face
// is never culled.
const float BOX_FAR_SCALE = 1.0000003576;
// Direction components below this are treated as parallel to the slab (exact zeros included).
const float TINY_DIRECTION = 1e-20;
// quantizedChildEntries: its distances are exact but for the two roundings of (origin - o) / d
// and the one of the fma (relative, covered by BOX_FAR_SCALE), so each box is widened by this
// many times the largest |(origin - o) / d|, twice the bound.
const float QUANTIZED_SLACK = 4.0 / 16777216.0;
// Rays whose |1 / d| components lie in [2^-40, 2^40] (all but the nearly axis-parallel, and the
// shadow rays of scenes over 2^40 across) use it: scale / d then neither overflows nor flushes to
// zero (scales are 2^-80 or more, src/accel/quantized_bvh.cpp). The others decode the planes.
const float FOLDED_INV_MAX = 1099511627776.0; // 2^40

struct Hit {
    float t;
    uint primitive; // triangle index, or sphere index | SPHERE_BIT; valid only when t < tMax of the query
    vec2 bary;      // triangles: barycentrics of vertices 1 and 2
    uint instance;  // the instance whose mesh the triangle is in (object space), or NO_INSTANCE
};

// What the slab test needs of a ray, computed once per traversal.
struct BoxRay {
    vec3 origin;
    vec3 invDir;
    bvec3 parallel; // direction component (almost) zero: the slab is crossed never or always
    bvec3 negative; // 1 / direction component below zero: a slab's high plane is its near one
    bool anyParallel;
    bool folded; // quantised nodes are tested by quantizedChildEntries
};

BoxRay makeBoxRay(Ray ray) {
    BoxRay r;
    r.origin = ray.origin;
    r.parallel = lessThan(abs(ray.direction), vec3(TINY_DIRECTION));
    r.anyParallel = any(r.parallel);
    vec3 tiny = mix(vec3(TINY_DIRECTION), vec3(-TINY_DIRECTION), lessThan(ray.direction, vec3(0.0)));
    r.invDir = vec3(1.0) / mix(ray.direction, tiny, r.parallel);
    r.negative = lessThan(r.invDir, vec3(0.0));
    vec3 a = abs(r.invDir);
    bool quantized = NODE_FORMAT == BVH_NODES_QUANTIZED ||
                     (NODE_FORMAT == BVH_NODES_FROM_SCENE && scene.nodeFormat == BVH_NODES_QUANTIZED);
    r.folded = quantized && !r.anyParallel && all(lessThanEqual(a, vec3(FOLDED_INV_MAX))) &&
               all(greaterThanEqual(a, vec3(1.0 / FOLDED_INV_MAX)));
    return r;
}

// A ray parallel to a slab is inside it for every t (origin between the planes, on them
// included) or for none; 0 * (1/d) would otherwise give an empty interval on the hi plane.
void parallelSlab(float origin, vec4 lo, vec4 hi, inout vec4 tNear, inout vec4 tFar) {
    bvec4 inside = bvec4(uvec4(greaterThanEqual(vec4(origin), lo)) & uvec4(lessThanEqual(vec4(origin), hi)));
    tNear = mix(vec4(FLOAT_MAX), vec4(-FLOAT_MAX), inside);
    tFar = mix(vec4(-FLOAT_MAX), vec4(FLOAT_MAX), inside);
}

// The slab test's end, shared by both node formats: from each child's slab intervals, its entry
// distance (>= 0), or FLOAT_MAX where the ray misses it within (0, tMax) or the slot is unused
// (so that misses sort last). `slack` widens every box by that distance at both ends. The
// distances are never NaN (finite planes and origin, a finite nonzero 1 / direction), so the
// compare-and-select min and max serve.
vec4 enteredChildren(
    vec4 nearX, vec4 farX, vec4 nearY, vec4 farY, vec4 nearZ, vec4 farZ, float tMax, float slack, uvec4 child) {
    vec4 entry = maxOfNumbers(maxOfNumbers(maxOfNumbers(nearX, nearY), nearZ) - slack, vec4(0.0));
    vec4 exit = minOfNumbers(minOfNumbers(farX, farY), minOfNumbers(farZ, vec4(tMax))) * BOX_FAR_SCALE + slack;
    bvec4 hit = bvec4(uvec4(lessThanEqual(entry, exit)) & uvec4(notEqual(child, uvec4(BVH4_EMPTY))));
    return mix(vec4(FLOAT_MAX), entry, hit);
}

// Entry distances into a wide node's four child boxes (enteredChildren). Each slab's near plane
// is the low one where 1 / direction is positive, the high one where it is negative (Williams et
// al., "An Efficient and Robust Ray-Box Intersection Algorithm", 2005): the same distances as the
// min and max of both, bit for bit (rounding keeps the order of (plane - origin) * invDir), without
// them.
vec4 childEntries(GpuBvh4Node node, BoxRay r, float tMax) {
    vec4 nearX = ((r.negative.x ? node.hiX : node.loX) - r.origin.x) * r.invDir.x;
    vec4 farX = ((r.negative.x ? node.loX : node.hiX) - r.origin.x) * r.invDir.x;
    vec4 nearY = ((r.negative.y ? node.hiY : node.loY) - r.origin.y) * r.invDir.y;
    vec4 farY = ((r.negative.y ? node.loY : node.hiY) - r.origin.y) * r.invDir.y;
    vec4 nearZ = ((r.negative.z ? node.hiZ : node.loZ) - r.origin.z) * r.invDir.z;
    vec4 farZ = ((r.negative.z ? node.loZ : node.hiZ) - r.origin.z) * r.invDir.z;
    if (r.anyParallel) {
        if (r.parallel.x) parallelSlab(r.origin.x, node.loX, node.hiX, nearX, farX);
        if (r.parallel.y) parallelSlab(r.origin.y, node.loY, node.hiY, nearY, farY);
        if (r.parallel.z) parallelSlab(r.origin.z, node.loZ, node.hiZ, nearZ, farZ);
    }
    return enteredChildren(nearX, farX, nearY, farY, nearZ, farZ, tMax, 0.0, node.child);
}

// childEntries for quantised node `index` (GpuBvh4QNode), its planes folded into the distances:
// plane q of an axis lies at t = q * (scale / d) + (origin - o) / d, one fma a plane, where
// decoding and then subtracting and scaling took three operations (the 1 M-triangle mesh: 3%
// faster, the same image; bench/RESULTS.md). Exact planes (the encoder's origin is a multiple of
// the scale) and QUANTIZED_SLACK keep it conservative. The near plane of each slab is chosen by
// the direction's sign, as in childEntries. For r.folded rays only.
vec4 quantizedChildEntries(uint index, BoxRay r, float tMax, out uvec4 child) {
    QuantizedNodeWords q = loadTriangleTreeQuantizedWords(index);
    child = q.child;
    vec3 s = q.scale * r.invDir, b = (q.origin - r.origin) * r.invDir;
    uvec3 nearBytes =
        uvec3(r.negative.x ? q.hi.x : q.lo.x, r.negative.y ? q.hi.y : q.lo.y, r.negative.z ? q.hi.z : q.lo.z);
    uvec3 farBytes =
        uvec3(r.negative.x ? q.lo.x : q.hi.x, r.negative.y ? q.lo.y : q.hi.y, r.negative.z ? q.lo.z : q.hi.z);
    vec4 nearX = planeSteps(nearBytes.x) * s.x + b.x, farX = planeSteps(farBytes.x) * s.x + b.x;
    vec4 nearY = planeSteps(nearBytes.y) * s.y + b.y, farY = planeSteps(farBytes.y) * s.y + b.y;
    vec4 nearZ = planeSteps(nearBytes.z) * s.z + b.z, farZ = planeSteps(farBytes.z) * s.z + b.z;
    vec3 absB = abs(b);
    float slack = QUANTIZED_SLACK * maxOfNumbers(maxOfNumbers(absB.x, absB.y), absB.z);
    return enteredChildren(nearX, farX, nearY, farY, nearZ, farZ, tMax, slack, child);
}

// Whether the ray enters the box within (0, tMax): one child's test of childEntries, with the
// same rule for slabs the ray runs parallel to.
bool rayEntersBox(BoxRay r, vec3 lo, vec3 hi, float tMax) {
    vec3 t0 = (lo - r.origin) * r.invDir, t1 = (hi - r.origin) * r.invDir;
    vec3 near = min(t0, t1), far = max(t0, t1);
    if (r.anyParallel) {
        for (int axis = 0; axis < 3; ++axis) {
            if (!r.parallel[axis]) continue;
            vec4 n, f;
            parallelSlab(r.origin[axis], vec4(lo[axis]), vec4(hi[axis]), n, f);
            near[axis] = n.x;
            far[axis] = f.x;
        }
    }
    float entry = max(max(near.x, near.y), max(near.z, 0.0));
    float exit = min(min(far.x, far.y), min(far.z, tMax)) * BOX_FAR_SCALE;
    return entry <= exit;
}

// Node `index` of the triangle tree, in the format the pipeline was specialised for, or (not
// specialised) the scene's. If-else on one constant at a time: only one loader survives
// specialization, and neither load is made speculatively beside the other.
GpuBvh4Node loadTriangleTreeNode(uint index) {
    if (NODE_FORMAT == BVH_NODES_QUANTIZED) return loadTriangleTreeQNode(index);
    if (NODE_FORMAT == BVH_NODES_FLOAT) return loadTriangleTreeFloatNode(index);
    if (scene.nodeFormat == BVH_NODES_QUANTIZED) return loadTriangleTreeQNode(index);
    return loadTriangleTreeFloatNode(index);
}

// Orders (distance, child) pairs a and b so that a is the nearer; misses count as farthest.
void orderPair(inout float da, inout uint ca, inout float db, inout uint cb) {
    bool swap = db < da;
    float d = da;
    uint c = ca;
    da = swap ? db : da;
    ca = swap ? cb : ca;
    db = swap ? d : db;
    cb = swap ? c : cb;
}

// A node's four (entry distance, child word) pairs sorted nearest first, misses (FLOAT_MAX) last:
// a network of five compare-exchanges. Nearest first, so that the hits a child yields shorten
// the rest; shadow rays find occluders sooner this way too (measured: unordered was slower for
// them).
void orderChildren(inout vec4 d, inout uvec4 c) {
    orderPair(d.x, c.x, d.y, c.y);
    orderPair(d.z, c.z, d.w, c.w);
    orderPair(d.x, c.x, d.z, c.z);
    orderPair(d.y, c.y, d.w, c.w);
    orderPair(d.y, c.y, d.z, c.z);
}

// The node's children the ray enters within (0, tMax), nearest first: entry distances in d,
// child words in c, misses last (at FLOAT_MAX).
void orderedChildren(GpuBvh4Node node, BoxRay boxRay, float tMax, out vec4 d, out uvec4 c) {
    d = childEntries(node, boxRay, tMax);
    c = node.child;
    orderChildren(d, c);
}

// Nodes visited by this invocation's traversals, counted only for the viewer's BVH-cost view
// (the increment is removed by specialization otherwise). debug_view.glsl resets and reads it.
uint traversalNodeVisits = 0u;

// The traversal stack's two operations (macros: GLSL passes arrays by value). A pop skips the
// children entered beyond the closest hit found since they were pushed, without loading them;
// the far-distance scale keeps that as conservative as the box test that admitted them.
#define PUSH_CHILD(child, entry)                                                                                       \
    {                                                                                                                  \
        stackT[stackSize] = entry;                                                                                     \
        stack[stackSize++] = child;                                                                                    \
    }
#define POP_CHILD()                                                                                                    \
    {                                                                                                                  \
        do {                                                                                                           \
            if (stackSize == 0) return found;                                                                          \
            --stackSize;                                                                                               \
        } while (stackT[stackSize] > hit.t * BOX_FAR_SCALE);                                                           \
        current = stack[stackSize];                                                                                    \
    }

// One inner node's step: the children the ray enters, the nearest next and the others waiting on
// the stack, farthest deepest, with their entry distances; none entered pops the stack.
#define VISIT_INNER_NODE(node)                                                                                         \
    {                                                                                                                  \
        vec4 d;                                                                                                        \
        uvec4 c;                                                                                                       \
        orderedChildren(node, boxRay, hit.t, d, c);                                                                    \
        if (d.w != FLOAT_MAX) PUSH_CHILD(c.w, d.w);                                                                    \
        if (d.z != FLOAT_MAX) PUSH_CHILD(c.z, d.z);                                                                    \
        if (d.y != FLOAT_MAX) PUSH_CHILD(c.y, d.y);                                                                    \
        if (d.x != FLOAT_MAX)                                                                                          \
            current = c.x;                                                                                             \
        else                                                                                                           \
            POP_CHILD();                                                                                               \
    }

// A tiny scene's triangles without a tree (UNIFORM_TRIANGLE_COUNT > 0): every ray tests every
// triangle, in a loop unrolled at specialization, so each triangle's words are uniform-buffer
// loads at constant offsets (one scalar load for all lanes) and the lanes of a SIMD vector never
// diverge. For the 32 triangles of a Cornell box this was faster on lavapipe than the four-wide
// tree when its nodes were gathered (bench/RESULTS.md, "Tiny scenes without a tree"); since they
// are read as texels the tree is faster, and this path is taken only with `--bvh auto`.
// Ties in t keep the lower index (the tree may keep either).
bool testUniformTriangles(bool anyHit, Ray ray, WatertightRay wray, inout Hit hit) {
    bool found = false;
    [[unroll]] for (uint i = 0u; i < UNIFORM_TRIANGLE_COUNT; ++i) {
        // A shadow ray stops at its first hit: once every lane of the SIMD vector has one, the
        // driver skips the remaining tests (a branch around a block no lane runs).
        if (anyHit && found) continue;
        GpuTriangle tri = placedTriangle(loadUniformTriangle(i));
        float t;
        vec2 bary;
        bool hitTriangle = intersectTriangle(wray, tri.p0, tri.p1, tri.p2, hit.t, t, bary);
        if (HAS_ALPHA && hitTriangle && (tri.flags & TRIANGLE_FLAG_ALPHA_TESTED) != 0u)
            hitTriangle = !alphaCutsOut(tri, i, bary, ray);
        if (hitTriangle) {
            hit.t = t;
            hit.primitive = i;
            hit.bary = bary;
            hit.instance = NO_INSTANCE;
            found = true;
        }
    }
    return found;
}

// Tests the primitives of leaf `leaf` (a child word) against the ray; true if one is hit within
// hit.t (hit updated). `anyHit` returns at the first.
bool testLeaf(bool sphereTree, bool anyHit, Ray ray, WatertightRay wray, uint leaf, inout Hit hit, uint instance) {
    uint first = leaf & BVH4_FIRST_MASK;
    uint end = first + ((leaf >> BVH4_COUNT_SHIFT) & 15u) + 1u;
    bool found = false;
    for (uint i = first; i < end; ++i) {
        float t;
        vec2 bary = vec2(0.0);
        bool hitPrimitive;
        if (sphereTree) {
            GpuSphere sphere = loadSphere(i);
            Ray r = ray;
            // A moving sphere: move the ray the other way (t is unchanged).
            if (HAS_MOTION && sphere.motion != NO_MOTION) r.origin -= motionOffset(sphere.motion);
            hitPrimitive = intersectSphere(sphere, r, hit.t, t);
        } else {
            GpuTriangle tri = placedTriangle(loadTriangle(i));
            hitPrimitive = intersectTriangle(wray, tri.p0, tri.p1, tri.p2, hit.t, t, bary);
            if (HAS_ALPHA && hitPrimitive && (tri.flags & TRIANGLE_FLAG_ALPHA_TESTED) != 0u)
                hitPrimitive = !alphaCutsOut(tri, i, bary, ray);
        }
        if (hitPrimitive) {
            hit.t = t;
            hit.primitive = sphereTree ? (i | SPHERE_BIT) : i;
            hit.bary = bary;
            hit.instance = instance;
            found = true;
            if (anyHit) return true;
        }
    }
    return found;
}

// The stack's pop for traverseTree: the next child entered before the closest hit so far, or
// TRAVERSAL_DONE when none is left.
const uint TRAVERSAL_DONE = BVH4_EMPTY; // has the leaf bit: ends the inner-node loop
#define POP_OR_DONE()                                                                                                  \
    {                                                                                                                  \
        current = TRAVERSAL_DONE;                                                                                      \
        while (stackSize > 0) {                                                                                        \
            --stackSize;                                                                                               \
            if (stackT[stackSize] <= hit.t * BOX_FAR_SCALE) {                                                          \
                current = stack[stackSize];                                                                            \
                break;                                                                                                 \
            }                                                                                                          \
        }                                                                                                              \
    }

// One traversal loop for the triangle trees and the sphere tree: `sphereTree` is a literal at
// every call, so the compiler keeps only one kind of leaf test in each inlined copy. `anyHit`
// stops at the first hit (shadow rays). A triangle tree starts at node `root` (0: the world
// tree); `instance` is what a hit records (NO_INSTANCE for world space).
//
// Inner nodes first, down to a leaf: the lanes of a SIMD group then test their leaves together
// instead of paying for inner-node and leaf steps in every iteration (Aila and Laine's
// "while-while" traversal, 2009). A lane that reaches a leaf while others are still descending
// puts it aside and goes on through the inner nodes on its stack (their "speculative" traversal):
// the inner-node loop runs until every lane has a leaf to test, so fewer of its iterations find
// lanes idle. The leaf put aside is tested later than a strict nearest-first order would, which
// can only cost extra work, never change the hit.
bool traverseTree(
    bool sphereTree, bool anyHit, Ray ray, WatertightRay wray, BoxRay boxRay, inout Hit hit, uint root, uint instance) {
    if (sphereTree ? scene.numSphereNodes == 0u : (instance == NO_INSTANCE && scene.numNodes == 0u)) return false;
    uint stack[TRAVERSAL_STACK_SIZE];   // child words
    float stackT[TRAVERSAL_STACK_SIZE]; // their entry distances
    int stackSize = 0;
    uint current = root;           // a child word: the root node
    uint pending = TRAVERSAL_DONE; // a leaf put aside, or none
    bool found = false;
    while (true) {
        while ((current & BVH4_LEAF_BIT) == 0u) {
            if (DEBUG_VIEW == DEBUG_VIEW_BVH_COST) ++traversalNodeVisits;
            vec4 d;
            uvec4 c;
            if (!sphereTree && boxRay.folded) {
                d = quantizedChildEntries(current, boxRay, hit.t, c);
                orderChildren(d, c);
            } else {
                GpuBvh4Node node = sphereTree ? loadSphereTreeNode(current) : loadTriangleTreeNode(current);
                orderedChildren(node, boxRay, hit.t, d, c);
            }
            if (d.w != FLOAT_MAX) PUSH_CHILD(c.w, d.w);
            if (d.z != FLOAT_MAX) PUSH_CHILD(c.z, d.z);
            if (d.y != FLOAT_MAX) PUSH_CHILD(c.y, d.y);
            if (d.x != FLOAT_MAX)
                current = c.x;
            else
                POP_OR_DONE();
            if (current != TRAVERSAL_DONE && (current & BVH4_LEAF_BIT) != 0u && pending == TRAVERSAL_DONE) {
                pending = current;
                POP_OR_DONE();
            }
            if (subgroupAll(pending != TRAVERSAL_DONE)) break;
        }
        if (pending != TRAVERSAL_DONE) {
            if (testLeaf(sphereTree, anyHit, ray, wray, pending, hit, instance)) {
                found = true;
                if (anyHit) return true;
            }
            pending = TRAVERSAL_DONE;
        }
        if (current == TRAVERSAL_DONE) return found;
        if ((current & BVH4_LEAF_BIT) != 0u) {
            if (testLeaf(sphereTree, anyHit, ray, wray, current, hit, instance)) {
                found = true;
                if (anyHit) return true;
            }
            POP_OR_DONE();
            if (current == TRAVERSAL_DONE) return found;
        }
    }
    return found;
}

// The tree over the instances: at each leaf the ray goes into the instance's object space and
// through its mesh's tree. The hit's t needs no conversion (toInstanceSpace keeps t).
bool traverseInstances(bool anyHit, Ray ray, BoxRay boxRay, inout Hit hit) {
    if (scene.numInstanceNodes == 0u) return false;
    uint stack[TRAVERSAL_STACK_SIZE];
    float stackT[TRAVERSAL_STACK_SIZE];
    int stackSize = 0;
    uint current = 0u;
    bool found = false;
    while (true) {
        while ((current & BVH4_LEAF_BIT) == 0u) {
            if (DEBUG_VIEW == DEBUG_VIEW_BVH_COST) ++traversalNodeVisits;
            GpuBvh4Node node = loadBvh4Node(scene.instanceNodes, current);
            VISIT_INNER_NODE(node);
        }
        uint first = current & BVH4_FIRST_MASK;
        uint end = first + ((current >> BVH4_COUNT_SHIFT) & 15u) + 1u;
        for (uint i = first; i < end; ++i) {
            GpuInstance instance = loadInstance(i);
            Ray local = toInstanceSpace(instance, ray);
            if (traverseTree(
                    false, anyHit, local, makeWatertightRay(local), makeBoxRay(local), hit, instance.root, i)) {
                found = true;
                if (anyHit) return true;
            }
        }
        POP_CHILD();
    }
    return found;
}

// Rounding can make a rare false hit far off a sliver triangle (geometry/triangle.glsl); the
// tree never tests a triangle whose box the ray does not enter, so it never sees one. Without a
// tree the hit found is checked once the same way (its triangle's box entered by t, by the tree's
// conservative slab test), and where it fails the tree finds the hit instead (in practice never:
// a branch no lane of the SIMD vector takes costs nothing). Checking each candidate instead cost
// a third of what skipping the tree gains on the Cornell box.
bool uniformHitInItsBox(BoxRay boxRay, Hit hit) {
    GpuTriangle tri = placedTriangle(loadTriangle(hit.primitive));
    return rayEntersBox(boxRay, min(min(tri.p0, tri.p1), tri.p2), max(max(tri.p0, tri.p1), tri.p2), hit.t);
}

// Closest hit in (0, tMax). Returns false on a miss.
bool traceClosest(Ray ray, float tMax, out Hit hit) {
    hit.t = tMax;
    hit.primitive = 0u;
    hit.bary = vec2(0.0);
    hit.instance = NO_INSTANCE;
    WatertightRay wray = makeWatertightRay(ray);
    BoxRay boxRay = makeBoxRay(ray);
    bool found = false;
    if (HAS_TRIANGLES && UNIFORM_TRIANGLE_COUNT > 0u) {
        found = testUniformTriangles(false, ray, wray, hit);
        if (found && !uniformHitInItsBox(boxRay, hit)) {
            hit.t = tMax;
            found = traverseTree(false, false, ray, wray, boxRay, hit, 0u, NO_INSTANCE);
        }
    } else if (HAS_TRIANGLES)
        found = traverseTree(false, false, ray, wray, boxRay, hit, 0u, NO_INSTANCE);
    if (HAS_INSTANCES) found = traverseInstances(false, ray, boxRay, hit) || found;
    if (HAS_SPHERES) found = traverseTree(true, false, ray, wray, boxRay, hit, 0u, NO_INSTANCE) || found;
    return found;
}

// True if anything lies along the ray in (0, tMax): the shadow-ray query, which stops early.
bool traceAny(Ray ray, float tMax) {
    Hit hit;
    hit.t = tMax;
    hit.primitive = 0u;
    hit.bary = vec2(0.0);
    hit.instance = NO_INSTANCE;
    WatertightRay wray = makeWatertightRay(ray);
    BoxRay boxRay = makeBoxRay(ray);
    if (HAS_TRIANGLES && UNIFORM_TRIANGLE_COUNT > 0u) {
        if (testUniformTriangles(true, ray, wray, hit)) {
            if (uniformHitInItsBox(boxRay, hit)) return true;
            hit.t = tMax;
            if (traverseTree(false, true, ray, wray, boxRay, hit, 0u, NO_INSTANCE)) return true;
        }
    } else if (HAS_TRIANGLES && traverseTree(false, true, ray, wray, boxRay, hit, 0u, NO_INSTANCE))
        return true;
    if (HAS_INSTANCES && traverseInstances(true, ray, boxRay, hit)) return true;
    return HAS_SPHERES && traverseTree(true, true, ray, wray, boxRay, hit, 0u, NO_INSTANCE);
}

#endif
