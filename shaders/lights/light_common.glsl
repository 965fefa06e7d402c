// What every light-sampling routine returns, and the light-table lookup shared by all of them.
#ifndef PT_LIGHTS_LIGHT_COMMON_GLSL
#define PT_LIGHTS_LIGHT_COMMON_GLSL
#include "common/buffers.glsl"
#include "shared/features.glsl"

struct LightSample {
    vec3 point;     // on the emitter (point lights: their position)
    vec3 normal;    // emitter normal at point, facing the side it was sampled from (0 for punctual)
    vec3 radiance;  // arriving at the shading point (point lights: I / d^2; directional: irradiance)
    vec3 wi;        // unit direction from the shading point to the light
    float distance; // FLOAT_MAX for directional lights
    float pdf;      // solid angle, times the selection pmf; for delta lights the pmf alone
    bool isDelta;   // no BSDF sample can hit this light (delta or invisible), so no MIS
};

LightSample noLightSample() {
    LightSample s;
    s.point = vec3(0.0);
    s.normal = vec3(0.0);
    s.radiance = vec3(0.0);
    s.wi = vec3(0.0, 0.0, 1.0);
    s.distance = 0.0;
    s.pdf = 0.0;
    s.isDelta = false;
    return s;
}

// Index of the light whose CDF interval holds u (binary search over numLights + 1 entries).
uint selectLight(float u) {
    uint lo = 0u;
    uint hi = scene.numLights; // cdf[numLights] == 1
    while (lo + 1u < hi) {
        uint mid = (lo + hi) >> 1u;
        if (sceneLightCdf.v[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

// The environment or a directional light: no place, so no bounds (the light tree leaves them to
// the power CDF) and light subpaths start on a disc outside the scene.
bool isInfiniteLight(GpuLight light) {
    return (HAS_ENVIRONMENT && light.type == LIGHT_ENVIRONMENT) ||
           (HAS_PUNCTUAL_LIGHTS && light.type == LIGHT_DIRECTIONAL);
}

vec3 emittedRadiance(GpuMaterial mat, bool frontFace) {
    return (frontFace || (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u) ? mat.emission : vec3(0.0);
}

#endif
