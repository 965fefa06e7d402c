// Emissive triangles. Seen under a solid angle between SPHERICAL_SAMPLING_MIN (shared/layout.h)
// and SPHERICAL_SAMPLING_MAX, a direction uniform in that solid angle (Arvo 1995): no samples are
// wasted on the foreshortened or distant part of a big, near emitter, where a uniform point
// would carry a pdf that varies with distance squared over cosine (23x the variance under a
// square 1.5 across 0.4 above a floor). Smaller triangles get a uniform point on the triangle
// (pbrt's square-root warp): there the two differ little and the point is cheaper (pbrt-v4's
// 3e-4 sr made the Cornell box 4% worse at equal time); nearly hemispherical ones too, as the
// spherical construction loses precision there (pbrt-v4's 6.22).
#ifndef PT_LIGHTS_TRIANGLE_LIGHT_GLSL
#define PT_LIGHTS_TRIANGLE_LIGHT_GLSL
#include "lights/light_common.glsl"
#include "common/sampling.glsl"
#include "textures/texture.glsl"
#include "geometry/motion.glsl"

const float SPHERICAL_SAMPLING_MAX = 6.22; // steradians

// The triangle's solid angle from x when light sampling picks directions in it, else 0 (points
// by area). The one decision both sampling and the pdf of a BSDF ray that hits the light use;
// `corners` are the unit directions to the corners when the answer is not 0.
float sphericalSamplingArea(GpuTriangle tri, vec3 x, out vec3 corners[3]) {
    corners[0] = corners[1] = corners[2] = vec3(0.0);
    if (!SPHERICAL_TRIANGLE_LIGHTS) return 0.0;
    vec3 a = tri.p0 - x, b = tri.p1 - x, c = tri.p2 - x;
    // Cheap first: the solid angle is at most area / h^2, h the distance to the triangle's plane,
    // i.e. |n|^3 / (2 (a . n)^2) with n = e1 x e2 (|n| = 2 area).
    vec3 n = cross(b - a, c - a);
    float nn = dot(n, n), an = dot(a, n);
    if (nn * sqrt(nn) < 2.0 * SPHERICAL_SAMPLING_MIN * an * an) return 0.0;
    float la = dot(a, a), lb = dot(b, b), lc = dot(c, c);
    if (!(la > 0.0 && lb > 0.0 && lc > 0.0)) return 0.0;
    corners[0] = a * inversesqrt(la);
    corners[1] = b * inversesqrt(lb);
    corners[2] = c * inversesqrt(lc);
    float omega = sphericalTriangleArea(corners[0], corners[1], corners[2]);
    return omega >= SPHERICAL_SAMPLING_MIN && omega <= SPHERICAL_SAMPLING_MAX ? omega : 0.0;
}

// Solid-angle pdf, from x, of a point at distance dist whose emitter normal makes cosine
// cosLight with the direction: pmf / omega for a triangle sampled by solid angle, else
// pmf / area * dist^2 / |cos|.
float areaSampledPdf(GpuLight light, float dist, float cosLight) {
    float c = abs(cosLight);
    return c > 0.0 ? light.pmf * dist * dist / (light.area * c) : 0.0;
}
float triangleLightPdf(GpuLight light, GpuTriangle tri, vec3 x, float dist, float cosLight) {
    vec3 corners[3];
    float omega = sphericalSamplingArea(tri, x, corners);
    return omega > 0.0 ? light.pmf / omega : areaSampledPdf(light, dist, cosLight);
}

// The radiance a triangle emitter sends from barycentrics b (point p) to its side `frontFace`:
// the emission factor times its texture, the texel a ray hitting that point would see. (The
// light table's power uses the factor alone, which only changes how often the light is picked.)
vec3 triangleEmission(uint triangle, GpuMaterial mat, vec2 b, vec3 p, bool frontFace) {
    vec3 Le = emittedRadiance(mat, frontFace);
    if ((HAS_TEXTURES || HAS_PROCEDURAL) && mat.emissiveTexture != NO_TEXTURE) {
        GpuTriangleShading sh = sceneShading.v[triangle];
        vec2 uv = (1.0 - b.x - b.y) * vec2(sh.u0, sh.v.x) + b.x * vec2(sh.u1, sh.v.y) + b.y * vec2(sh.u2, sh.v.z);
        Le *= evalTexture(mat.emissiveTexture, uv, p).rgb;
    }
    return Le;
}

// Barycentrics (of p1, p2) of a point p in the triangle's plane.
vec2 triangleBarycentrics(GpuTriangle tri, vec3 p) {
    vec3 e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0, d = p - tri.p0;
    vec3 n = cross(e1, e2);
    float inv = 1.0 / dot(n, n);
    vec2 b = clamp(vec2(dot(cross(d, e2), n), dot(cross(e1, d), n)) * inv, 0.0, 1.0);
    return b.x + b.y > 1.0 ? b / (b.x + b.y) : b;
}

LightSample sampleTriangleLight(GpuLight light, vec3 x, vec2 u) {
    LightSample s = noLightSample();
    GpuTriangle tri = placedTriangle(loadTriangle(light.primitive)); // where it is at the path's time
    s.normal = normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
    vec3 corners[3];
    float omega = sphericalSamplingArea(tri, x, corners);
    vec2 b;
    if (omega > 0.0) {
        vec3 w = sampleSphericalTriangle(corners[0], corners[1], corners[2], omega, u);
        float along = dot(w, s.normal);
        if (along == 0.0) return s; // no sample: a degenerate construction or a ray in the plane
        // Where the direction meets the triangle's plane.
        float t = dot(tri.p0 - x, s.normal) / along;
        if (!(t > 0.0)) return s;
        // Onto the triangle itself: lavapipe's trigonometry is approximate enough to put a
        // direction near an edge a little outside it, where a shadow ray would miss the light.
        b = triangleBarycentrics(tri, x + t * w);
        s.point = (1.0 - b.x - b.y) * tri.p0 + b.x * tri.p1 + b.y * tri.p2;
    } else {
        b = sampleUniformTriangle(u);
        s.point = (1.0 - b.x - b.y) * tri.p0 + b.x * tri.p1 + b.y * tri.p2;
    }
    vec3 toLight = s.point - x;
    float dist2 = dot(toLight, toLight);
    if (!(dist2 > 0.0)) return s;
    s.distance = sqrt(dist2);
    s.wi = toLight / s.distance;
    float cosLight = dot(s.normal, -s.wi);
    GpuMaterial mat = sceneMaterials.v[tri.materialIndex];
    s.radiance = triangleEmission(light.primitive, mat, b, s.point, cosLight > 0.0);
    s.pdf = omega > 0.0 ? light.pmf / omega : areaSampledPdf(light, s.distance, cosLight);
    return s;
}

#endif
