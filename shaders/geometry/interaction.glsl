// What the integrator needs to know about a closest hit.
#ifndef PT_GEOMETRY_INTERACTION_GLSL
#define PT_GEOMETRY_INTERACTION_GLSL
#include "common/buffers.glsl"
#include "geometry/traverse.glsl"
#include "geometry/motion.glsl"
#include "shared/features.glsl"

struct SurfaceInteraction {
    vec3 p;          // hit point from barycentrics (more accurate than origin + t * direction)
    vec3 ng;         // unit geometric normal, front side = counter-clockwise winding
    vec3 ns;         // unit shading normal, on the same side as ng
    vec3 nSurface;   // the surface's own normal: ns before any normal map (the interpolated vertex normal, or ng)
    vec3 pSmooth;    // origin for shadow rays leaving on the side of nSurface: on the smooth surface (Hanika)
    float magnitude; // largest coordinate magnitude of the primitive hit: scales the ray offset
    bool frontFace;  // the ray arrived from the front side
    uint materialIndex;
    uint lightIndex;
    // Texture coordinates and their derivatives; filled only when the kernel has textures.
    vec2 uv;
    vec3 dpdu;
    vec3 dpdv;
};

// A double-sided opaque surface seen from behind: its normals turn to the viewer's side, and the
// smooth surface (Hanika's offset), which bulges towards the front, no longer applies.
void turnToBackSide(inout SurfaceInteraction si) {
    si.ng = -si.ng;
    si.nSurface = -si.nSurface;
    si.pSmooth = si.p;
}

bool needsSurfaceCoordinates() { return HAS_TEXTURES || HAS_PROCEDURAL || HAS_NORMAL_MAPS || HAS_ANISOTROPY; }

// A tangent basis for surfaces whose uvs are degenerate (absent or collapsed): any frame works
// for colour lookups, and normal maps then rotate about an arbitrary but consistent axis.
void fallbackTangents(inout SurfaceInteraction si) {
    Frame f = makeFrame(si.ng);
    si.dpdu = f.t;
    si.dpdv = f.b;
}

SurfaceInteraction makeSphereInteraction(Ray ray, Hit hit) {
    SurfaceInteraction si;
    si.uv = vec2(0.0);
    si.dpdu = si.dpdv = vec3(0.0);
    GpuSphere sphere = SphereRef(scene.spheres).v[hit.primitive & ~SPHERE_BIT];
    // Recompute the hit in object space and project it onto the unit sphere: the world point
    // then lies on the surface to within the map's rounding, whatever the distance travelled.
    vec3 offset = (HAS_MOTION && sphere.motion != NO_MOTION) ? motionOffset(sphere.motion) : vec3(0.0);
    vec3 o = toSphereObject(sphere, ray.origin - offset);
    vec3 d = transformVector(sphere.worldToObject, ray.direction);
    vec3 po = normalize(o + hit.t * d);
    si.p = transformPoint(sphere.objectToWorld, po) + offset;
    // Normals map with the inverse transpose of objectToWorld, i.e. the transpose of worldToObject.
    si.ng = normalize(
        sphere.worldToObject[0].xyz * po.x + sphere.worldToObject[1].xyz * po.y + sphere.worldToObject[2].xyz * po.z);
    si.ns = si.nSurface = si.ng;
    si.pSmooth = si.p;
    si.magnitude = sphereMagnitude(sphere, offset);
    si.frontFace = dot(ray.direction, si.ng) < 0.0;
    si.materialIndex = sphere.materialIndex;
    si.lightIndex = sphere.lightIndex;
    if (needsSurfaceCoordinates()) {
        // The course's sphere mapping in the untransformed sphere: u = (pi - atan2(z, x)) / 2pi,
        // v = acos(y) / pi (v = 0 at the north pole, the image's top row).
        float phi = atan(po.z, po.x);
        float theta = acos(clamp(po.y, -1.0, 1.0));
        si.uv = vec2((PI - phi) / (2.0 * PI), theta / PI);
        vec3 dpduObject = 2.0 * PI * vec3(po.z, 0.0, -po.x);
        vec3 dpdvObject = PI * vec3(cos(theta) * cos(phi), -sin(theta), cos(theta) * sin(phi));
        si.dpdu = transformVector(sphere.objectToWorld, dpduObject);
        si.dpdv = transformVector(sphere.objectToWorld, dpdvObject);
        // At the poles dp/du vanishes.
        if (dot(si.dpdu, si.dpdu) < 1e-20 * dot(si.dpdv, si.dpdv)) fallbackTangents(si);
    }
    return si;
}

// A triangle hit, in the space its vertices are in (world space, or an instance's object space
// with the ray taken there).
SurfaceInteraction makeTriangleInteraction(Ray ray, Hit hit) {
    SurfaceInteraction si;
    si.uv = vec2(0.0);
    si.dpdu = si.dpdv = vec3(0.0);
    GpuTriangle tri = placedTriangle(loadTriangle(hit.primitive));
    float b0 = 1.0 - hit.bary.x - hit.bary.y;
    // The per-vertex record, read once: for shading normals and for texture coordinates.
    bool smoothNormals = HAS_SHADING_NORMALS && (tri.flags & TRIANGLE_FLAG_SHADING_NORMALS) != 0u;
    GpuTriangleShading sh;
    if (smoothNormals || needsSurfaceCoordinates()) sh = sceneShading.v[hit.primitive];
    si.p = b0 * tri.p0 + hit.bary.x * tri.p1 + hit.bary.y * tri.p2;
    si.ng = normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
    si.ns = si.ng;
    si.pSmooth = si.p;
    si.magnitude = maxComponent(max(max(abs(tri.p0), abs(tri.p1)), abs(tri.p2)));
    if (smoothNormals) {
        vec3 n = b0 * sh.n0 + hit.bary.x * sh.n1 + hit.bary.y * sh.n2;
        float len2 = dot(n, n);
        // Degenerate interpolated normals fall back to the geometric one.
        if (len2 > 0.0 && !isinf(len2)) {
            n *= inversesqrt(len2);
            float side = dot(n, si.ng) < 0.0 ? -1.0 : 1.0;
            si.ns = side * n;
            si.pSmooth = shadowTerminatorPoint(si.p, tri.p0, tri.p1, tri.p2, side * sh.n0, side * sh.n1, side * sh.n2,
                vec3(b0, hit.bary.x, hit.bary.y));
            if (!allFinite(si.pSmooth)) si.pSmooth = si.p;
        }
    }
    si.nSurface = si.ns;
    si.frontFace = dot(ray.direction, si.ng) < 0.0;
    si.materialIndex = tri.materialIndex;
    si.lightIndex = tri.lightIndex;
    if (needsSurfaceCoordinates()) {
        vec2 uv0 = vec2(sh.u0, sh.v.x), uv1 = vec2(sh.u1, sh.v.y), uv2 = vec2(sh.u2, sh.v.z);
        si.uv = b0 * uv0 + hit.bary.x * uv1 + hit.bary.y * uv2;
        // Solve p - p0 = (u - u0) dpdu + (v - v0) dpdv over the triangle's two edges.
        vec2 duv1 = uv1 - uv0, duv2 = uv2 - uv0;
        vec3 dp1 = tri.p1 - tri.p0, dp2 = tri.p2 - tri.p0;
        float det = duv1.x * duv2.y - duv1.y * duv2.x;
        if (abs(det) > 1e-20) {
            float inv = 1.0 / det;
            si.dpdu = (duv2.y * dp1 - duv1.y * dp2) * inv;
            si.dpdv = (duv1.x * dp2 - duv2.x * dp1) * inv;
        }
        if (!(abs(det) > 1e-20) || !allFinite(si.dpdu) || !allFinite(si.dpdv)) fallbackTangents(si);
        if ((HAS_NORMAL_MAPS || HAS_ANISOTROPY) && (tri.flags & TRIANGLE_FLAG_TANGENTS) != 0u) {
            // The file's tangent frame (glTF TANGENT): dp/du along the tangent, and dp/dv down
            // the image, i.e. against the bitangent cross(n, t) * w, as normal maps read it.
            GpuTriangleTangents tg = TangentRef(scene.tangents).v[hit.primitive];
            vec3 t = b0 * tg.t0.xyz + hit.bary.x * tg.t1.xyz + hit.bary.y * tg.t2.xyz;
            if (dot(t, t) > 0.0) {
                si.dpdu = t;
                si.dpdv = -cross(si.ns, t) * tg.t0.w;
            }
        }
    }
    return si;
}

// An interaction found in an instance's object space, brought to world space: points and
// tangents by the map, normals by its inverse transpose. The front side stays the object's
// (dot products of mapped directions with mapped normals keep their sign), so a mirroring
// placement keeps its front faces.
void placeInWorld(inout SurfaceInteraction si, GpuInstance instance) {
    si.p = transformPoint(instance.objectToWorld, si.p);
    si.pSmooth = transformPoint(instance.objectToWorld, si.pSmooth);
    si.ng = normalize(transformNormal(instance.worldToObject, si.ng));
    si.ns = normalize(transformNormal(instance.worldToObject, si.ns));
    si.nSurface = normalize(transformNormal(instance.worldToObject, si.nSurface));
    si.magnitude = instanceMagnitude(instance, si.magnitude);
    if (needsSurfaceCoordinates()) {
        si.dpdu = transformVector(instance.objectToWorld, si.dpdu);
        si.dpdv = transformVector(instance.objectToWorld, si.dpdv);
    }
}

SurfaceInteraction makeInteraction(Ray ray, Hit hit) {
    if (HAS_SPHERES && (hit.primitive & SPHERE_BIT) != 0u) return makeSphereInteraction(ray, hit);
    if (HAS_INSTANCES && hit.instance != NO_INSTANCE) {
        GpuInstance instance = loadInstance(hit.instance);
        SurfaceInteraction si = makeTriangleInteraction(toInstanceSpace(instance, ray), hit);
        placeInWorld(si, instance);
        return si;
    }
    return makeTriangleInteraction(ray, hit);
}

#endif
