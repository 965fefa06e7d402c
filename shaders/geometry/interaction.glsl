// What the integrator needs to know about a closest hit.
#ifndef PT_GEOMETRY_INTERACTION_GLSL
#define PT_GEOMETRY_INTERACTION_GLSL
#include "common/buffers.glsl"
#include "geometry/traverse.glsl"
#include "integrator/features.glsl"

struct SurfaceInteraction {
    vec3 p;          // hit point from barycentrics (more accurate than origin + t * direction)
    vec3 ng;         // unit geometric normal, front side = counter-clockwise winding
    vec3 ns;         // unit shading normal, on the same side as ng
    bool frontFace;  // the ray arrived from the front side
    uint materialIndex;
    uint lightIndex;
};

SurfaceInteraction makeSphereInteraction(Ray ray, Hit hit) {
    SurfaceInteraction si;
    GpuSphere sphere = SphereRef(scene.spheres).v[hit.primitive & ~SPHERE_BIT];
    // Recompute the hit in object space and project it onto the unit sphere: the world point
    // then lies on the surface to within the map's rounding, whatever the distance travelled.
    vec3 o = transformPoint(sphere.worldToObject, ray.origin);
    vec3 d = transformVector(sphere.worldToObject, ray.direction);
    vec3 po = normalize(o + hit.t * d);
    si.p = transformPoint(sphere.objectToWorld, po);
    // Normals map with the inverse transpose of objectToWorld, i.e. the transpose of worldToObject.
    si.ng = normalize(sphere.worldToObject[0].xyz * po.x + sphere.worldToObject[1].xyz * po.y + sphere.worldToObject[2].xyz * po.z);
    si.ns = si.ng;
    si.frontFace = dot(ray.direction, si.ng) < 0.0;
    si.materialIndex = sphere.materialIndex;
    si.lightIndex = sphere.lightIndex;
    return si;
}

SurfaceInteraction makeInteraction(Ray ray, Hit hit) {
    if (HAS_SPHERES && (hit.primitive & SPHERE_BIT) != 0u) return makeSphereInteraction(ray, hit);
    SurfaceInteraction si;
    GpuTriangle tri = sceneTriangles.v[hit.primitive];
    float b0 = 1.0 - hit.bary.x - hit.bary.y;
    si.p = b0 * tri.p0 + hit.bary.x * tri.p1 + hit.bary.y * tri.p2;
    si.ng = normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
    si.ns = si.ng;
    if (HAS_SHADING_NORMALS && (tri.flags & TRIANGLE_FLAG_SHADING_NORMALS) != 0u) {
        GpuTriangleShading sh = sceneShading.v[hit.primitive];
        vec3 n = b0 * sh.n0 + hit.bary.x * sh.n1 + hit.bary.y * sh.n2;
        float len2 = dot(n, n);
        // Degenerate interpolated normals fall back to the geometric one.
        if (len2 > 0.0 && !isinf(len2)) {
            n *= inversesqrt(len2);
            si.ns = dot(n, si.ng) < 0.0 ? -n : n;
        }
    }
    si.frontFace = dot(ray.direction, si.ng) < 0.0;
    si.materialIndex = tri.materialIndex;
    si.lightIndex = tri.lightIndex;
    return si;
}

#endif
