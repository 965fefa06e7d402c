// Emissive triangles: a uniform point on the triangle (pbrt's square-root warp).
#ifndef PT_LIGHTS_TRIANGLE_LIGHT_GLSL
#define PT_LIGHTS_TRIANGLE_LIGHT_GLSL
#include "lights/light_common.glsl"
#include "common/sampling.glsl"
#include "textures/texture.glsl"

// Solid-angle pdf of a point at distance dist whose emitter normal makes cosine cosLight with
// the direction: pmf / area * dist^2 / |cos|.
float triangleLightPdf(GpuLight light, float dist, float cosLight) {
    float c = abs(cosLight);
    return c > 0.0 ? light.pmf * dist * dist / (light.area * c) : 0.0;
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

LightSample sampleTriangleLight(GpuLight light, vec3 x, vec2 u) {
    LightSample s = noLightSample();
    GpuTriangle tri = loadTriangle(light.primitive);
    vec2 b = sampleUniformTriangle(u);
    s.point = (1.0 - b.x - b.y) * tri.p0 + b.x * tri.p1 + b.y * tri.p2;
    s.normal = normalize(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
    vec3 toLight = s.point - x;
    float dist2 = dot(toLight, toLight);
    s.distance = sqrt(dist2);
    s.wi = toLight / s.distance;
    float cosLight = dot(s.normal, -s.wi);
    GpuMaterial mat = sceneMaterials.v[tri.materialIndex];
    s.radiance = triangleEmission(light.primitive, mat, b, s.point, cosLight > 0.0);
    s.pdf = dist2 > 0.0 ? triangleLightPdf(light, s.distance, cosLight) : 0.0;
    return s;
}

#endif
