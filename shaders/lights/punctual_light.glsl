// Point and directional lights: delta distributions, reached by light sampling only.
#ifndef PT_LIGHTS_PUNCTUAL_LIGHT_GLSL
#define PT_LIGHTS_PUNCTUAL_LIGHT_GLSL
#include "lights/light_common.glsl"
#include "common/math.glsl"

LightSample samplePointLight(GpuLight light, vec3 x) {
    LightSample s = noLightSample();
    vec3 d = light.position - x;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) return s;
    s.distance = sqrt(dist2);
    s.wi = d / s.distance;
    s.point = light.position;
    s.radiance = light.intensity / dist2; // inverse-square falloff of radiant intensity
    s.pdf = light.pmf;
    s.isDelta = true;
    return s;
}

LightSample sampleDirectionalLight(GpuLight light, vec3 x) {
    LightSample s = noLightSample();
    s.wi = -light.direction;
    s.distance = FLOAT_MAX;
    s.point = x + s.wi; // unused: the shadow ray runs to infinity
    s.radiance = light.intensity;
    s.pdf = light.pmf;
    s.isDelta = true;
    return s;
}

// A point light limited to a cone, with a smooth band between the falloff and the coverage
// angle: ((cos a - cos coverage) / (cos falloff - cos coverage))^e, e = 4 for the course's
// spots and 2 for glTF's (KHR_lights_punctual's squared edge), stored in `area`.
float spotFalloff(GpuLight light, float cosAngle) {
    float band = max(light.cosFalloff - light.cosCoverage, 1e-7);
    float t = clamp((cosAngle - light.cosCoverage) / band, 0.0, 1.0);
    float t2 = t * t;
    return light.area == 2.0 ? t2 : (light.area == 4.0 ? t2 * t2 : pow(t, light.area));
}

LightSample sampleSpotLight(GpuLight light, vec3 x) {
    LightSample s = samplePointLight(light, x);
    s.radiance *= spotFalloff(light, dot(-s.wi, light.direction));
    return s;
}

// The course's AreaLight: a square of edge `radius` centred at `position` (normal `direction`),
// emitting radiance `intensity` from both faces: the course's estimate uses |n_l . w_i|, and its
// official images show the ceiling above such a light lit. No ray can hit it, so it is found
// by light sampling only (a uniform point on the square, pdf dist^2 / (area |cos|) per solid angle).
LightSample sampleSquareLight(GpuLight light, vec3 x, vec2 u) {
    LightSample s = noLightSample();
    vec3 t, b;
    buildBasis(light.direction, t, b);
    s.point = light.position + light.radius * ((u.x - 0.5) * t + (u.y - 0.5) * b);
    s.normal = light.direction;
    vec3 d = s.point - x;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) return s;
    s.distance = sqrt(dist2);
    s.wi = d / s.distance;
    float cosLight = abs(dot(light.direction, s.wi));
    if (cosLight <= 0.0) return s;
    s.radiance = light.intensity;
    s.pdf = light.pmf * dist2 / (light.area * cosLight);
    s.isDelta = true;
    return s;
}

#endif
