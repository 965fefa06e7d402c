// Light sampling over the one table of all emitters, and the pdf that MIS needs when a
// BSDF-sampled ray hits an emitter.
#ifndef PT_LIGHTS_LIGHT_SAMPLING_GLSL
#define PT_LIGHTS_LIGHT_SAMPLING_GLSL
#include "integrator/features.glsl"
#include "lights/light_common.glsl"
#include "lights/triangle_light.glsl"
#include "lights/sphere_light.glsl"
#include "lights/punctual_light.glsl"

LightSample sampleLight(vec3 x, float uSelect, vec2 uPoint) {
    GpuLight light = sceneLights.v[selectLight(uSelect)];
    if (HAS_SPHERES && light.type == LIGHT_SPHERE) return sampleSphereLight(light, x, uPoint);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_POINT) return samplePointLight(light, x);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_DIRECTIONAL) return sampleDirectionalLight(light, x);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SPOT) return sampleSpotLight(light, x);
    if (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_SQUARE) return sampleSquareLight(light, x, uPoint);
    return sampleTriangleLight(light, x, uPoint);
}

// Solid-angle pdf (selection included) with which light sampling from x would have produced
// the point p on emitter lightIndex, reached at distance t along unit direction dir with
// geometric normal ng there.
float lightPdf(uint lightIndex, vec3 x, vec3 p, vec3 ng, float t, vec3 dir) {
    GpuLight light = sceneLights.v[lightIndex];
    if (HAS_SPHERES && light.type == LIGHT_SPHERE) return sphereLightPdf(light, x, p);
    return triangleLightPdf(light, t, dot(ng, dir));
}

#endif
