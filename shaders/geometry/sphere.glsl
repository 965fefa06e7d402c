// Ray against the unit sphere in object space, for spheres and ellipsoids under any affine map.
// The quadratic is solved in the numerically stable form of Haines et al., "Precision
// Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7 (2019): the discriminant
// from the closest-approach distance, and the two roots without cancellation.
#ifndef PT_GEOMETRY_SPHERE_GLSL
#define PT_GEOMETRY_SPHERE_GLSL
#include "common/buffers.glsl"
#include "common/math.glsl"
#include "common/ray.glsl"

vec3 sphereCentre(GpuSphere sphere) {
    return vec3(sphere.objectToWorld[0].w, sphere.objectToWorld[1].w, sphere.objectToWorld[2].w);
}

// Largest coordinate magnitude a point of the sphere (moved by `offset`) can have: scales the
// ray offset (common/ray_offset.glsl).
float sphereMagnitude(GpuSphere sphere, vec3 offset) {
    vec3 axisLengths = vec3(
        length(sphere.objectToWorld[0].xyz), length(sphere.objectToWorld[1].xyz), length(sphere.objectToWorld[2].xyz));
    return maxComponent(abs(sphereCentre(sphere) + offset)) + maxComponent(axisLengths);
}

// A world point in the sphere's object space, taken relative to the centre first and mapped by
// the linear part only, so that origin and direction share one rounded matrix (the inverse's
// translation column is rounded on its own: 1e7 (1 - 1e-7) against a scale of 1000 (1 - 6e-8)
// for a sphere of radius 1e-3 at distance 1e4).
vec3 toSphereObject(GpuSphere sphere, vec3 p) {
    return transformVector(sphere.worldToObject, p - sphereCentre(sphere));
}

vec3 accurateCross(vec3 u, vec3 v) {
    return vec3(differenceOfProducts(u.y, v.z, u.z, v.y), differenceOfProducts(u.z, v.x, u.x, v.z),
        differenceOfProducts(u.x, v.y, u.y, v.x));
}

// The ray parameter t is shared by world and object space (the map is affine), so the result
// compares directly with triangle hits.
bool intersectSphere(GpuSphere sphere, Ray ray, float tMax, out float t) {
    vec3 ow = ray.origin - sphereCentre(sphere);
    vec3 o = transformVector(sphere.worldToObject, ow);
    vec3 d = transformVector(sphere.worldToObject, ray.direction);
    t = 0.0;
    float a = dot(d, d);
    float b = dot(o, d); // half the linear coefficient
    // The discriminant is a (1 - |f|^2), f the closest approach to the centre (Haines et al.),
    // i.e. a - |o x d|^2. For a small sphere far away f = o - (b / a) d cancels (|o| = 1e7 for
    // radius 1e-3 at 1e4: an error of half a radius, so most of the sphere went missing); the
    // world-space cross product with difference-of-products has no cancellation, and maps to
    // object space by (M u) x (M v) = det(M) M^-T (u x v), M = worldToObject, M^-T = objectToWorld^T.
    vec3 cw = accurateCross(ow, ray.direction);
    vec4 m[3] = sphere.worldToObject;
    float detM = dot(m[0].xyz, cross(m[1].xyz, m[2].xyz));
    vec3 co = detM * (sphere.objectToWorld[0].xyz * cw.x + sphere.objectToWorld[1].xyz * cw.y +
                         sphere.objectToWorld[2].xyz * cw.z);
    float disc = a - dot(co, co);
    if (!(disc >= 0.0)) return false;
    float c = dot(o, o) - 1.0;
    float q = -b - (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc);
    float t0 = c / q;
    float t1 = q / a;
    if (t0 > t1) {
        float tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    t = t0 > 0.0 ? t0 : t1;
    return t > 0.0 && t < tMax;
}

#endif
