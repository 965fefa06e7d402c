// Emissive triangles: one table over all of them, chosen by emitted power through a CDF
// (built on the host, src/lights/light_table.cpp), then a uniform point on the chosen triangle.
// Every pdf here is with respect to solid angle at the shading point.
#ifndef PT_LIGHTS_TRIANGLE_LIGHTS_GLSL
#define PT_LIGHTS_TRIANGLE_LIGHTS_GLSL
#include "common/buffers.glsl"
#include "common/sampling.glsl"

struct LightSample {
    vec3 point;
    vec3 normal;   // geometric normal of the emitter at point (its front side)
    vec3 radiance; // emitted toward the shading point; zero if that is the emitter's back
    vec3 wi;       // unit direction from the shading point to the light point
    float distance;
    float pdf;     // solid angle; 0 when the sample is unusable
};

// Index of the light whose CDF interval holds u (binary search over numLights + 1 entries).
uint selectLight(float u) {
    uint lo = 0u;
    uint hi = scene.numLights; // cdf[numLights] == 1
    while (lo + 1u < hi) {
        uint mid = (lo + hi) >> 1u;
        if (sceneLightCdf.v[mid] <= u) lo = mid;
        else hi = mid;
    }
    return lo;
}

vec3 emittedRadiance(GpuMaterial mat, bool frontFace) {
    return (frontFace || (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u) ? mat.emission : vec3(0.0);
}

// Solid-angle pdf of reaching light `lightIndex` at distance `dist` with cosine `cosLight`
// between the emitter normal and the direction: pmf / area * dist^2 / |cos|.
float lightPdf(uint lightIndex, float dist, float cosLight) {
    GpuLight light = sceneLights.v[lightIndex];
    float c = abs(cosLight);
    return c > 0.0 ? light.pmf * dist * dist / (light.area * c) : 0.0;
}

LightSample sampleLight(vec3 x, float uSelect, vec2 uPoint) {
    LightSample s;
    uint index = selectLight(uSelect);
    GpuLight light = sceneLights.v[index];
    GpuTriangle tri = sceneTriangles.v[light.triangleIndex];
    vec2 b = sampleUniformTriangle(uPoint);
    s.point = (1.0 - b.x - b.y) * tri.p0 + b.x * tri.p1 + b.y * tri.p2;
    vec3 cr = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
    s.normal = normalize(cr);
    vec3 toLight = s.point - x;
    float dist2 = dot(toLight, toLight);
    s.distance = sqrt(dist2);
    s.wi = toLight / s.distance;
    float cosLight = dot(s.normal, -s.wi);
    GpuMaterial mat = sceneMaterials.v[tri.materialIndex];
    s.radiance = emittedRadiance(mat, cosLight > 0.0);
    s.pdf = (dist2 > 0.0 && cosLight != 0.0) ? light.pmf * dist2 / (light.area * abs(cosLight)) : 0.0;
    return s;
}

#endif
