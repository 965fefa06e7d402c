// Stack-based traversal of the binary BVH: closest hit for path segments, any hit for shadow rays.
// Both children's boxes are tested before descending and the nearer one is visited first.
#ifndef PT_GEOMETRY_TRAVERSE_GLSL
#define PT_GEOMETRY_TRAVERSE_GLSL
#include "common/buffers.glsl"
#include "common/math.glsl"
#include "geometry/triangle.glsl"

// Depth of the traversal stack. The builder caps tree depth below this (src/accel/bvh.cpp).
const int TRAVERSAL_STACK_SIZE = 64;

// Slab tests round in both directions; growing the far distance by 1 + 2 gamma(3) makes them
// conservative (Ize, "Robust BVH Ray Traversal", JCGT 2013), so a triangle lying on a box face
// is never culled.
const float BOX_FAR_SCALE = 1.0000003576;
// Direction components below this are treated as parallel to the slab (exact zeros included).
const float TINY_DIRECTION = 1e-20;
const float MISS = -1.0;

struct Hit {
    float t;
    uint triangle; // BVH-ordered index; valid only when t < tMax of the query
    vec2 bary;     // barycentrics of vertices 1 and 2
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

// Closest hit in (0, tMax). Returns false on a miss.
bool traceClosest(Ray ray, float tMax, out Hit hit) {
    hit.t = tMax;
    hit.triangle = 0u;
    hit.bary = vec2(0.0);
    if (scene.numNodes == 0u) return false;
    WatertightRay wray = makeWatertightRay(ray);
    BoxRay boxRay = makeBoxRay(ray);
    uint stack[TRAVERSAL_STACK_SIZE];
    int stackSize = 0;
    uint nodeIndex = 0u;
    bool found = false;
    GpuBvhNode root = sceneNodes.v[0];
    if (boxEntry(root.lo, root.hi, boxRay, hit.t) == MISS) return false;
    while (true) {
        GpuBvhNode node = sceneNodes.v[nodeIndex];
        if (node.count > 0u) {
            for (uint i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
                GpuTriangle tri = sceneTriangles.v[i];
                float t;
                vec2 bary;
                if (intersectTriangle(wray, tri.p0, tri.p1, tri.p2, hit.t, t, bary)) {
                    hit.t = t;
                    hit.triangle = i;
                    hit.bary = bary;
                    found = true;
                }
            }
        } else {
            uint left = node.leftOrFirst;
            GpuBvhNode a = sceneNodes.v[left];
            GpuBvhNode b = sceneNodes.v[left + 1u];
            float ta = boxEntry(a.lo, a.hi, boxRay, hit.t);
            float tb = boxEntry(b.lo, b.hi, boxRay, hit.t);
            bool hitA = ta != MISS;
            bool hitB = tb != MISS;
            if (hitA || hitB) {
                bool aFirst = hitA && (!hitB || ta <= tb);
                uint near = aFirst ? left : left + 1u;
                uint far = aFirst ? left + 1u : left;
                if (hitA && hitB && stackSize < TRAVERSAL_STACK_SIZE) stack[stackSize++] = far;
                nodeIndex = near;
                continue;
            }
        }
        if (stackSize == 0) break;
        nodeIndex = stack[--stackSize];
    }
    return found;
}

// True if anything lies along the ray in (0, tMax): the shadow-ray query, which stops early.
bool traceAny(Ray ray, float tMax) {
    if (scene.numNodes == 0u) return false;
    WatertightRay wray = makeWatertightRay(ray);
    BoxRay boxRay = makeBoxRay(ray);
    uint stack[TRAVERSAL_STACK_SIZE];
    int stackSize = 0;
    uint nodeIndex = 0u;
    GpuBvhNode root = sceneNodes.v[0];
    if (boxEntry(root.lo, root.hi, boxRay, tMax) == MISS) return false;
    while (true) {
        GpuBvhNode node = sceneNodes.v[nodeIndex];
        if (node.count > 0u) {
            for (uint i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
                GpuTriangle tri = sceneTriangles.v[i];
                float t;
                vec2 bary;
                if (intersectTriangle(wray, tri.p0, tri.p1, tri.p2, tMax, t, bary)) return true;
            }
        } else {
            uint left = node.leftOrFirst;
            GpuBvhNode a = sceneNodes.v[left];
            GpuBvhNode b = sceneNodes.v[left + 1u];
            bool hitA = boxEntry(a.lo, a.hi, boxRay, tMax) != MISS;
            bool hitB = boxEntry(b.lo, b.hi, boxRay, tMax) != MISS;
            if (hitA || hitB) {
                if (hitA && hitB && stackSize < TRAVERSAL_STACK_SIZE) stack[stackSize++] = left + 1u;
                nodeIndex = hitA ? left : left + 1u;
                continue;
            }
        }
        if (stackSize == 0) break;
        nodeIndex = stack[--stackSize];
    }
    return false;
}

#endif
