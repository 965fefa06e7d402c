// Watertight ray/triangle intersection: Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2013. The ray is sheared so it runs along +z; edge functions are then
// evaluated in 2D, and a point on a shared edge is accepted by both triangles, never by neither.
// Each edge function is a difference of two products; for a triangle far off the ray's line
// (1e4 times its own size away, as instances placed far away see) they cancel to rounding noise,
// and three noises of one sign made false hits, far from any surface. So a candidate hit whose
// determinant (their sum) is not clear of its rounding error is evaluated again with exact
// products (Dekker's), whose signs are exact. A true hit lies near the triangle, where the
// determinant is clear of it; rays through edges and vertices keep their exact zeros, so shared
// edges still agree. The paper re-evaluates only zeros, in double
// precision, which lavapipe has but some GPUs do not.
#ifndef PT_GEOMETRY_TRIANGLE_GLSL
#define PT_GEOMETRY_TRIANGLE_GLSL
#include "common/math.glsl"
#include "common/ray.glsl"

// A determinant (the sum of the three edge functions) within this fraction of the largest
// product may be all rounding error: each edge function is two products and a difference, each
// rounded by at most 2^-24 of the largest product, so three of them err by at most 6 x 2^-24.
const float DETERMINANT_ROUNDING = 9.536743164e-7; // 2^-20

// Per-ray constants of the shear transform, computed once per traversal.
struct WatertightRay {
    vec3 origin;
    ivec3 axis; // kx, ky, kz: kz is the dominant direction axis
    vec3 shear; // Sx, Sy, Sz
};

WatertightRay makeWatertightRay(Ray ray) {
    WatertightRay w;
    w.origin = ray.origin;
    vec3 a = abs(ray.direction);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    // Swap kx and ky to keep the winding (and so the sign of the determinant) unchanged.
    if (ray.direction[kz] < 0.0) {
        int t = kx;
        kx = ky;
        ky = t;
    }
    w.axis = ivec3(kx, ky, kz);
    float dz = ray.direction[kz];
    w.shear = vec3(ray.direction[kx] / dz, ray.direction[ky] / dz, 1.0 / dz);
    return w;
}

// Returns true on a hit with 0 < t < tMax; t and barycentrics (b1, b2) of p1 and p2.
bool intersectTriangle(WatertightRay r, vec3 p0, vec3 p1, vec3 p2, float tMax, out float t, out vec2 bary) {
    vec3 a3 = p0 - r.origin;
    vec3 b3 = p1 - r.origin;
    vec3 c3 = p2 - r.origin;
    vec3 a = vec3(a3[r.axis.x], a3[r.axis.y], a3[r.axis.z]);
    vec3 b = vec3(b3[r.axis.x], b3[r.axis.y], b3[r.axis.z]);
    vec3 c = vec3(c3[r.axis.x], c3[r.axis.y], c3[r.axis.z]);
    // `precise` (SPIR-V NoContraction): a shared edge must give the same edge function in both
    // of its triangles, so every compiler must round each product and difference the same way.
    // Left free, NVIDIA's compiler fuses some of them into FMAs and rays slip through edges.
    precise float ax = a.x - r.shear.x * a.z;
    precise float ay = a.y - r.shear.y * a.z;
    precise float bx = b.x - r.shear.x * b.z;
    precise float by = b.y - r.shear.y * b.z;
    precise float cx = c.x - r.shear.x * c.z;
    precise float cy = c.y - r.shear.y * c.z;
    precise float U = cx * by - cy * bx;
    precise float V = ax * cy - ay * cx;
    precise float W = bx * ay - by * ax;
    t = 0.0;
    bary = vec2(0.0);
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    float det = U + V + W;
    if (det == 0.0) return false;
    float az = r.shear.z * a.z;
    float bz = r.shear.z * b.z;
    float cz = r.shear.z * c.z;
    float T = U * az + V * bz + W * cz;
    // Compare T against the range scaled by det without dividing (sign-aware).
    if (det < 0.0 ? (T >= 0.0 || T < tMax * det) : (T <= 0.0 || T > tMax * det)) return false;
    // Checked only here, for a hit within range: most candidates in a dense mesh lie beyond the
    // closest hit found so far.
    if (abs(det) <= DETERMINANT_ROUNDING * maxComponent(abs(vec3(ax, bx, cx))) * maxComponent(abs(vec3(ay, by, cy)))) {
        U = exactSignDifferenceOfProducts(cx, by, cy, bx);
        V = exactSignDifferenceOfProducts(ax, cy, ay, cx);
        W = exactSignDifferenceOfProducts(bx, ay, by, ax);
        if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
        det = U + V + W;
        if (det == 0.0) return false;
        T = U * az + V * bz + W * cz;
        if (det < 0.0 ? (T >= 0.0 || T < tMax * det) : (T <= 0.0 || T > tMax * det)) return false;
    }
    float invDet = 1.0 / det;
    t = T * invDet;
    bary = vec2(V * invDet, W * invDet);
    return t > 0.0 && t < tMax;
}

#endif
