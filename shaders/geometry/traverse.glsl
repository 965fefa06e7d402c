// Stack-based traversal of the binary BVH: closest hit for path segments, any hit for shadow rays.
// Both children's boxes are tested before descending and the nearer one is visited first.
#ifndef PT_GEOMETRY_TRAVERSE_GLSL
#define PT_GEOMETRY_TRAVERSE_GLSL
#include "common/buffers.glsl"
#include "common/math.glsl"
#include "geometry/triangle.glsl"
#include "geometry/sphere.glsl"
#include "shared/features.glsl"
#include "textures/alpha.glsl"
#include "geometry/motion.glsl"

// Depth of the traversal stack (shared/layout.h). The builder caps tree depth below this
// (src/accel/bvh.cpp).
const int TRAVERSAL_STACK_SIZE = MAX_TRAVERSAL_DEPTH;

// Slab tests round in both directions; growing the far distance by 1 + 2 gamma(3) makes them
// conservative (Ize, "Robust BVH Ray Traversal", JCGT 2013), so a triangle lying on a box face
// is never culled.
const float BOX_FAR_SCALE = 1.0000003576;
// Direction components below this are treated as parallel to the slab (exact zeros included).
const float TINY_DIRECTION = 1e-20;
const float MISS = -1.0;

struct Hit {
    float t;
    uint primitive; // triangle index, or sphere index | SPHERE_BIT; valid only when t < tMax of the query
    vec2 bary;      // triangles: barycentrics of vertices 1 and 2
};

// What the slab test needs of a ray, computed once per traversal.
struct BoxRay {
    vec3 origin;
    vec3 invDir;
    bvec3 parallel; // direction component (almost) zero: the slab is crossed never or always
    bool anyParallel;
};

BoxRay makeBoxRay(Ray ray) {
    BoxRay r;
    r.origin = ray.origin;
    r.parallel = lessThan(abs(ray.direction), vec3(TINY_DIRECTION));
    r.anyParallel = any(r.parallel);
    vec3 tiny = mix(vec3(TINY_DIRECTION), vec3(-TINY_DIRECTION), lessThan(ray.direction, vec3(0.0)));
    r.invDir = vec3(1.0) / mix(ray.direction, tiny, r.parallel);
    return r;
}

// Entry distance into the box (>= 0), or MISS when the ray misses it within (0, tMax).
float boxEntry(vec3 lo, vec3 hi, BoxRay r, float tMax) {
    vec3 t0 = (lo - r.origin) * r.invDir;
    vec3 t1 = (hi - r.origin) * r.invDir;
    vec3 tNear = min(t0, t1);
    vec3 tFar = max(t0, t1);
    if (r.anyParallel) {
        // A ray parallel to a slab is inside it for every t (origin between the planes, on them
        // included) or for none; 0 * (1/d) would otherwise give an empty interval on the hi plane.
        bvec3 inside = bvec3(uvec3(greaterThanEqual(r.origin, lo)) & uvec3(lessThanEqual(r.origin, hi)));
        tNear = mix(tNear, mix(vec3(FLOAT_MAX), vec3(-FLOAT_MAX), inside), r.parallel);
        tFar = mix(tFar, mix(vec3(-FLOAT_MAX), vec3(FLOAT_MAX), inside), r.parallel);
    }
    float entry = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax)) * BOX_FAR_SCALE;
    return entry <= exit ? entry : MISS;
}

// Nodes visited by this invocation's traversals, counted only for the viewer's BVH-cost view
// (the increment is removed by specialization otherwise). debug_view.glsl resets and reads it.
uint traversalNodeVisits = 0u;

// One traversal loop for both trees (triangles, spheres): `sphereTree` is a literal at every
// call, so the compiler keeps only one kind of leaf test in each inlined copy. `anyHit` stops
// at the first hit (shadow rays).
bool traverseTree(bool sphereTree, bool anyHit, Ray ray, WatertightRay wray, BoxRay boxRay, inout Hit hit) {
    NodeRef nodes = sphereTree ? NodeRef(scene.sphereNodes) : sceneNodes;
    uint numNodes = sphereTree ? scene.numSphereNodes : scene.numNodes;
    if (numNodes == 0u) return false;
    GpuBvhNode root = nodes.v[0];
    if (boxEntry(root.lo, root.hi, boxRay, hit.t) == MISS) return false;
    uint stack[TRAVERSAL_STACK_SIZE];
    int stackSize = 0;
    uint nodeIndex = 0u;
    bool found = false;
    while (true) {
        // Inner nodes first, down to a leaf: the lanes of a SIMD group then test their leaves
        // together instead of paying for inner-node and leaf steps in every iteration
        // (Aila and Laine's "while-while" traversal, 2009).
        if (DEBUG_VIEW == DEBUG_VIEW_BVH_COST) ++traversalNodeVisits;
        GpuBvhNode node = nodes.v[nodeIndex];
        while (node.count == 0u) {
            uint left = node.leftOrFirst;
            GpuBvhNode a = nodes.v[left];
            GpuBvhNode b = nodes.v[left + 1u];
            float ta = boxEntry(a.lo, a.hi, boxRay, hit.t);
            float tb = boxEntry(b.lo, b.hi, boxRay, hit.t);
            bool hitA = ta != MISS;
            bool hitB = tb != MISS;
            if (hitA || hitB) {
                bool aFirst = hitA && (!hitB || ta <= tb);
                if (hitA && hitB && stackSize < TRAVERSAL_STACK_SIZE) stack[stackSize++] = aFirst ? left + 1u : left;
                nodeIndex = aFirst ? left : left + 1u;
                node = aFirst ? a : b;
            } else {
                if (stackSize == 0) return found;
                nodeIndex = stack[--stackSize];
                node = nodes.v[nodeIndex];
            }
            if (DEBUG_VIEW == DEBUG_VIEW_BVH_COST) ++traversalNodeVisits;
        }
        for (uint i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
            float t;
            vec2 bary = vec2(0.0);
            bool hitPrimitive;
            if (sphereTree) {
                GpuSphere sphere = SphereRef(scene.spheres).v[i];
                Ray r = ray;
                // A moving sphere: move the ray the other way (t is unchanged).
                if (HAS_MOTION && sphere.motion != NO_MOTION) r.origin -= motionOffset(sphere.motion);
                hitPrimitive = intersectSphere(sphere, r, hit.t, t);
            } else {
                GpuTriangle tri = placedTriangle(sceneTriangles.v[i]);
                hitPrimitive = intersectTriangle(wray, tri.p0, tri.p1, tri.p2, hit.t, t, bary);
                if (HAS_ALPHA && hitPrimitive && (tri.flags & TRIANGLE_FLAG_ALPHA_TESTED) != 0u)
                    hitPrimitive = !alphaCutsOut(tri, i, bary, ray);
            }
            if (hitPrimitive) {
                hit.t = t;
                hit.primitive = sphereTree ? (i | SPHERE_BIT) : i;
                hit.bary = bary;
                found = true;
                if (anyHit) return true;
            }
        }
        if (stackSize == 0) break;
        nodeIndex = stack[--stackSize];
    }
    return found;
}

// Closest hit in (0, tMax). Returns false on a miss.
bool traceClosest(Ray ray, float tMax, out Hit hit) {
    hit.t = tMax;
    hit.primitive = 0u;
    hit.bary = vec2(0.0);
    WatertightRay wray = makeWatertightRay(ray);
    BoxRay boxRay = makeBoxRay(ray);
    bool found = false;
    if (HAS_TRIANGLES) found = traverseTree(false, false, ray, wray, boxRay, hit);
    if (HAS_SPHERES) found = traverseTree(true, false, ray, wray, boxRay, hit) || found;
    return found;
}

// True if anything lies along the ray in (0, tMax): the shadow-ray query, which stops early.
bool traceAny(Ray ray, float tMax) {
    Hit hit;
    hit.t = tMax;
    hit.primitive = 0u;
    hit.bary = vec2(0.0);
    WatertightRay wray = makeWatertightRay(ray);
    BoxRay boxRay = makeBoxRay(ray);
    if (HAS_TRIANGLES && traverseTree(false, true, ray, wray, boxRay, hit)) return true;
    return HAS_SPHERES && traverseTree(true, true, ray, wray, boxRay, hit);
}

#endif
