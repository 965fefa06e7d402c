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

#endif
