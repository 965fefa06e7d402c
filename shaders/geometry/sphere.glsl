// Ray against the unit sphere in object space, for spheres and ellipsoids under any affine map.
// The quadratic is solved in the numerically stable form of Haines et al., "Precision
// Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7 (2019): the discriminant
// from the closest-approach vector, and the two roots without cancellation.
#ifndef PT_GEOMETRY_SPHERE_GLSL
#define PT_GEOMETRY_SPHERE_GLSL
#include "common/buffers.glsl"
#include "geometry/ray.glsl"

vec3 transformPoint(vec4 rows[3], vec3 p) {
    return vec3(dot(rows[0].xyz, p) + rows[0].w, dot(rows[1].xyz, p) + rows[1].w, dot(rows[2].xyz, p) + rows[2].w);
}
vec3 transformVector(vec4 rows[3], vec3 v) { return vec3(dot(rows[0].xyz, v), dot(rows[1].xyz, v), dot(rows[2].xyz, v)); }

// A world point in the sphere's object space, taken relative to the centre first and mapped by
// the linear part only: origin and direction then share one rounded matrix. The inverse's own
// translation column is rounded separately (1e7 * (1 - 1e-7) against a scale of 1000 * (1 - 6e-8)
// for a sphere of radius 1e-3 at distance 1e4), and that mismatch alone moved the closest
// approach by half a radius, so small spheres far away vanished (tests/gpu/hard_cases_test.cpp).
vec3 toSphereObject(GpuSphere sphere, vec3 p) {
    vec3 centre = vec3(sphere.objectToWorld[0].w, sphere.objectToWorld[1].w, sphere.objectToWorld[2].w);
    return transformVector(sphere.worldToObject, p - centre);
}

// The ray parameter t is shared by world and object space (the map is affine), so the result
// compares directly with triangle hits.
bool intersectSphere(GpuSphere sphere, Ray ray, float tMax, out float t) {
    vec3 o = toSphereObject(sphere, ray.origin);
    vec3 d = transformVector(sphere.worldToObject, ray.direction);
    t = 0.0;
    float a = dot(d, d);
    float b = dot(o, d); // half the linear coefficient
    vec3 f = o - (b / a) * d;
    float disc = a * (1.0 - dot(f, f));
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
