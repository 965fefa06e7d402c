// Smooth conductor: perfect specular reflection with the Fresnel reflectance of a complex index
// of refraction eta + i k (per colour channel), tinted by the base colour.
#ifndef PT_BSDF_CONDUCTOR_GLSL
#define PT_BSDF_CONDUCTOR_GLSL
#include "bsdf/fresnel.glsl"
#include "bsdf/bsdf_sample.glsl"

BsdfSample conductorSample(vec3 tint, vec3 eta, vec3 k, Frame frame, vec3 woLocal) {
    BsdfSample s = invalidBsdfSample();
    if (woLocal.z <= 0.0) return s;
    s.wi = toWorld(frame, vec3(-woLocal.xy, woLocal.z));
    s.weight = tint * fresnelConductor(woLocal.z, eta, k);
    s.pdf = 1.0;
    s.isDelta = true;
    s.valid = true;
    return s;
}

#endif
