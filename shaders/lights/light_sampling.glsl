// Light sampling over the one table of all emitters (a light chosen by the light tree or the power
// CDF, lights/light_tree.glsl), and the pdf that MIS needs when a BSDF-sampled ray hits an emitter.
#ifndef PT_LIGHTS_LIGHT_SAMPLING_GLSL
#define PT_LIGHTS_LIGHT_SAMPLING_GLSL
#include "shared/features.glsl"
#include "lights/light_common.glsl"
#include "lights/light_tree.glsl"
#include "lights/triangle_light.glsl"
#include "lights/sphere_light.glsl"
#include "lights/punctual_light.glsl"
#include "lights/environment_light.glsl"

// A point on `light` (its table entry, with `pmf` its selection pmf) as seen from x; the pdf
// includes the pmf.
LightSample sampleLightEntry(GpuLight light, vec3 x, vec2 uPoint) {
    if (HAS_SPHERES && light.type == LIGHT_SPHERE) return sampleSphereLight(light, x, uPoint);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_POINT) return samplePointLight(light, x);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_DIRECTIONAL) return sampleDirectionalLight(light, x);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SPOT) return sampleSpotLight(light, x);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SQUARE) return sampleSquareLight(light, x, uPoint);
    if (HAS_ENVIRONMENT && light.type == LIGHT_ENVIRONMENT) return sampleEnvironment(light, uPoint);
    return sampleTriangleLight(light, x, uPoint);
}

// The same for light `index` of the table, with the table's (power) pmf: the classic ray
// tracer's sum over lights, the light-visibility probe.
LightSample sampleLightIndex(uint index, vec3 x, vec2 uPoint) {
    return sampleLightEntry(sceneLights.v[index], x, uPoint);
}

// The light that light sampling chooses for shading point x with normal n (by the tree where the
// scene uses one, else by power): its index and its table entry with `pmf` the probability of
// the choice, each loaded once. False where the tree finds no light that can reach x.
bool chooseLightEntry(vec3 x, vec3 n, float uSelect, out uint index, out GpuLight light) {
    if (!choosesInTree(uSelect)) {
        index = selectLight(uSelect);
        light = sceneLights.v[index];
        return true;
    }
    LightChoice c = chooseTreeLight(x, n, uSelect);
    index = c.index;
    if (c.index == NO_LIGHT) return false;
    light = sceneLights.v[c.index];
    light.pmf = c.pmf;
    return true;
}

// A light sample for shading point x with normal n (0 where there is none).
LightSample sampleLight(vec3 x, vec3 n, float uSelect, vec2 uPoint) {
    uint index;
    GpuLight light;
    if (!chooseLightEntry(x, n, uSelect, index, light)) return noLightSample();
    return sampleLightEntry(light, x, uPoint);
}

// Solid-angle pdf with which light sampling from x would have produced the point p on `light`
// (its table entry, with `pmf` its selection pmf), reached at distance t along unit direction dir
// with geometric normal ng there.
float lightPdfOf(GpuLight light, vec3 x, vec3 p, vec3 ng, float t, vec3 dir) {
    if (HAS_SPHERES && light.type == LIGHT_SPHERE) return sphereLightPdf(light, x, p);
    if (!SPHERICAL_TRIANGLE_LIGHTS) return areaSampledPdf(light, t, dot(ng, dir));
    return triangleLightPdf(light, placedTriangle(loadTriangle(light.primitive)), x, t, dot(ng, dir));
}

// The same for sampleLight from x with normal n (its selection included).
float lightPdf(uint lightIndex, vec3 x, vec3 n, vec3 p, vec3 ng, float t, vec3 dir) {
    GpuLight light = sceneLights.v[lightIndex];
    light.pmf = lightSelectionPmf(lightIndex, light, x, n);
    return lightPdfOf(light, x, p, ng, t, dir);
}

// Solid-angle pdf of light sampling the environment in direction dir (0 without one).
float environmentPdf(vec3 dir) {
    if (!HAS_ENVIRONMENT || scene.envLightIndex == NO_LIGHT) return 0.0;
    return envPdf(sceneLights.v[scene.envLightIndex].pmf, dir);
}

#endif
